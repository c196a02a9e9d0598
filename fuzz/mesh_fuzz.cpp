// Triangle meshes (scene/triangle_mesh.hpp): the first byte chooses the reader (even: STL,
// binary or ASCII; odd: OBJ), the rest is the file.
#include "fuzz/fuzz_support.hpp"
#include "scene/triangle_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  if (size == 0) return 0;
  const std::string_view file = fuzz::AsText(data + 1, size - 1);
  fuzz::RefusedOnlyWithInputError([&] {
    if (data[0] % 2 == 0) {
      ParseStl(file, 1.0, "fuzz.stl");
    } else {
      ParseObj(file, 1.0, "fuzz.obj");
    }
  });
  return 0;
}
