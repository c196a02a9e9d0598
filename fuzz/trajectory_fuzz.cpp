// Joint trajectories and grasp files (graspsynth-trajectory/1, graspsynth-grasp/1:
// gate/grasp_file.hpp), with the joint limits of the shipped robot.
#include "fuzz/fuzz_support.hpp"
#include "gate/grasp_file.hpp"
#include "kinematics/robot_description.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  fuzz::RefusedOnlyWithInputError([&] {
    ParseTrajectoryOrGraspFile(fuzz::AsText(data, size), "fuzz_grasp.json", robot.arm, robot.hand);
  });
  return 0;
}
