// Synthetic operator files (graspsynth-operator/1, learning_data/operator_options.hpp).
#include "fuzz/fuzz_support.hpp"
#include "learning_data/operator_options.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  fuzz::RefusedOnlyWithInputError(
      [&] { ParseOperatorOptions(fuzz::AsText(data, size), "fuzz_operator.json"); });
  return 0;
}
