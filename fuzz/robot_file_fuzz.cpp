// Robot files (graspsynth-robot/1, kinematics/robot_file.hpp): the JSON, then the arm it names
// in a URDF beside the shipped robot files (models/): the chain between two links, the SRS
// checks and the DH map.
#include "common/data_dir.hpp"
#include "fuzz/fuzz_support.hpp"
#include "kinematics/robot_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  static const std::filesystem::path models = DataDirectory() / "models";
  fuzz::RefusedOnlyWithInputError([&] {
    const RobotFile file = ParseRobotFile(fuzz::AsText(data, size), "fuzz_robot.json", models);
    ArmFromRobotFile(file);
  });
  return 0;
}
