#include "tests/utils/paths.hpp"

namespace testing {

const char* SourceDir() { return GRASPSYNTH_SOURCE_DIR; }
const char* GraspsynthBinary() { return GRASPSYNTH_BINARY; }

}  // namespace testing
