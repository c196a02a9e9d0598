// The small grammars of command-line values and input lines: orientation lists
// (common/orientation_list.hpp), number lines (common/text_input.hpp, the fk/ik input), the
// viewer camera (viewer/viewer_scene.hpp) and the teleoperation key file
// (teleop/packet_key.hpp, through a file: it is only ever read from one).
#include <unistd.h>

#include <fstream>

#include "common/orientation_list.hpp"
#include "common/text_input.hpp"
#include "fuzz/fuzz_support.hpp"
#include "teleop/packet_key.hpp"
#include "viewer/viewer_scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  const std::string text(fuzz::AsText(data, size));
  fuzz::RefusedOnlyWithInputError([&] { ParseOrientationList(text, "--orientations"); });
  std::string why;
  ParseNumberList(text, 0, &why);
  ParseNumberList(text, 7, &why);
  fuzz::RefusedOnlyWithInputError([&] { viewer::ParseViewerCamera(text, viewer::ViewerCamera{}); });
  // one file per process, removed at its exit.
  static const struct KeyFile {
    std::filesystem::path path = std::filesystem::temp_directory_path() /
                                 ("graspsynth_fuzz_key_" + std::to_string(::getpid()));
    ~KeyFile() { std::filesystem::remove(path); }
  } file;
  const std::filesystem::path& key_file = file.path;
  std::ofstream(key_file, std::ios::binary | std::ios::trunc) << text;
  // owner-only, as a key file must be (a key others can read is refused before it is used).
  std::filesystem::permissions(
      key_file, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  fuzz::RefusedOnlyWithInputError([&] { teleop::PacketKey::Load(key_file); });
  return 0;
}
