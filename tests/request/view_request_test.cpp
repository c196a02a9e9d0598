// Tests of the request of view (request/view_request.hpp): its options are described once with
// the command's defaults, a port out of range names the option, and a config file sets them.

#include "request/view_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::request {
namespace {

TEST(ViewRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(ViewOptions()); }

TEST(ViewRequest, TheDefaultsAreTheCommands) {
  const ViewRequest r;
  EXPECT_FALSE(r.at.has_value());
  EXPECT_EQ(r.address, "127.0.0.1");
  EXPECT_EQ(r.port, 8765);
  EXPECT_EQ(r.rate_hz, 60.0);
  EXPECT_EQ(r.hold_s, 1.0);
  EXPECT_NE(FindOption(ViewOptions(), "no_wait"), nullptr);
  EXPECT_EQ(FindOption(ViewOptions(), "no_wait")->info.Flag(Value(false)), "--no-wait");
}

TEST(ViewRequest, APortOutOfRangeNamesTheOptionAndAConfigFileSetsOptions) {
  ViewRequest r;
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(ViewOptions(), "port"), Value(int64_t{70000}), "--port", &r), InputError,
      "--port: must be [0, 65535] (got 70000)");
  ApplyConfig(ViewOptions(),
              WriteConfig("view.json", R"({"port": 0, "loop": true, "at": [-0.3, 0.9]})"), &r);
  EXPECT_EQ(r.port, 0);
  EXPECT_TRUE(r.loop);
  ASSERT_TRUE(r.at.has_value());
  EXPECT_EQ(r.at->x(), -0.3);
}

}  // namespace
}  // namespace graspsynth::request
