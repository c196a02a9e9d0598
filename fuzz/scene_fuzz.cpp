// Scene files (graspsynth-scene/1 and /2, scene/scene_model.hpp), with their object
// files found beside the shipped scene (models/objects/).
#include "common/data_dir.hpp"
#include "fuzz/fuzz_support.hpp"
#include "scene/scene_model.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  static const std::filesystem::path models = DataDirectory() / "models";
  fuzz::RefusedOnlyWithInputError(
      [&] { ParseSceneModel(fuzz::AsText(data, size), "fuzz_scene.json", models); });
  return 0;
}
