// Grasp libraries (graspsynth-library/1, learning_data/grasp_library.hpp).
#include "fuzz/fuzz_support.hpp"
#include "learning_data/grasp_library.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  fuzz::RefusedOnlyWithInputError(
      [&] { ParseGraspLibrary(fuzz::AsText(data, size), "fuzz_library.json"); });
  return 0;
}
