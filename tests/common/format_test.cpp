#include "common/format.hpp"

#include <gtest/gtest.h>

#include <string>

namespace graspsynth {
namespace {

TEST(Format, FormatsLikePrintf) {
  EXPECT_EQ(Format("lifted %.1f mm and held %.2f s", 61.25, 1.0), "lifted 61.2 mm and held 1.00 s");
  EXPECT_EQ(Format("%d of %d", 9, 9), "9 of 9");
  EXPECT_EQ(Format("no conversion"), "no conversion");
}

TEST(Format, KeepsTextOfAnyLength) {
  const std::string long_text(2000, 'x');
  EXPECT_EQ(Format("%s!", long_text.c_str()), long_text + "!");
}

}  // namespace
}  // namespace graspsynth
