// Teleoperation calibration files (graspsynth-teleop-config/1, teleop/calibration.hpp).
#include "fuzz/fuzz_support.hpp"
#include "teleop/calibration.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  fuzz::RefusedOnlyWithInputError([&] {
    teleop::ParseTeleopCalibration(fuzz::AsText(data, size), "fuzz_calibration.json");
  });
  return 0;
}
