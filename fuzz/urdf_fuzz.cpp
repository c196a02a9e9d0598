// Robot descriptions (URDF, kinematics/robot_description.hpp): urdfdom's reading, then every
// check graspsynth makes of the PA-10 and the Gifu hand.
#include "fuzz/fuzz_support.hpp"
#include "kinematics/robot_description.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  fuzz::RefusedOnlyWithInputError([&] { ParseRobotModel(fuzz::AsText(data, size), "fuzz.urdf"); });
  return 0;
}
