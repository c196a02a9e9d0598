// Object files (graspsynth-object/1, scene/object_model.hpp), with mesh files found
// beside the shipped objects (models/objects/meshes/).
#include "common/data_dir.hpp"
#include "fuzz/fuzz_support.hpp"
#include "scene/object_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  static const std::filesystem::path objects = DataDirectory() / "models" / "objects";
  fuzz::RefusedOnlyWithInputError(
      [&] { ParseObjectModel(fuzz::AsText(data, size), "fuzz_object.json", objects); });
  return 0;
}
