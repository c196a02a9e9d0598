// Demonstration logs (graspsynth-demo/1 CSV, learning_data/demo_log.hpp).
#include "fuzz/fuzz_support.hpp"
#include "learning_data/demo_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  fuzz::RefusedOnlyWithInputError([&] { ParseDemoLog(fuzz::AsText(data, size), "fuzz.csv"); });
  return 0;
}
