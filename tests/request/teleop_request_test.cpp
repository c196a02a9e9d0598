// Tests of the requests of teleop and teleop-client (request/teleop_request.hpp): their options
// are described once with the session's defaults and ranges, a value out of range names the
// option, and a config file sets them.

#include "request/teleop_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/orientation_list.hpp"
#include "teleop/teleop_session.hpp"
#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::request {
namespace {

TEST(TeleopRequest, EveryOptionIsWellDescribed) {
  ExpectWellDescribed(TeleopServerOptions());
  ExpectWellDescribed(TeleopClientOptions());
}

TEST(TeleopRequest, TheDefaultsAreTheSessions) {
  const TeleopRequest r;
  const teleop::TeleopOptions session;
  EXPECT_EQ(r.rate_hz, session.rate_hz);
  EXPECT_EQ(r.timeout_ms * 1e-3, session.timeout_s);
  EXPECT_EQ(r.end_hold_s, session.end_hold_s);
  EXPECT_EQ(ParseOrientationList(r.orientations, "orientations"), session.orientations_deg);
  EXPECT_EQ(r.at.has_value(), session.object_xy.has_value());
  EXPECT_EQ(r.operator_name, session.operator_name);
  EXPECT_EQ(r.port, 9870);
  EXPECT_EQ(r.bind, "127.0.0.1");
  EXPECT_FALSE(r.insecure);
  EXPECT_EQ(r.viewer_port, -1);
  EXPECT_EQ(r.exit_after_s, 0.0);
  // the client talks to a server of the defaults.
  const TeleopClientRequest c;
  EXPECT_EQ(c.host, r.bind);
  EXPECT_EQ(c.port, r.port);
  EXPECT_EQ(c.speed, 1.0);
  EXPECT_EQ(c.linger_s, 2.0);
  // the flags keep their names.
  for (const char* name : {"port", "bind", "insecure", "orientations", "at", "rate", "timeout_ms",
                           "end_hold", "viewer_port", "camera", "operator", "exit_after"}) {
    EXPECT_NE(FindOption(TeleopServerOptions(), name), nullptr) << name;
  }
  EXPECT_EQ(FindOption(TeleopServerOptions(), "timeout_ms")->info.Flag(Value(200.0)),
            "--timeout-ms");
  for (const char* name : {"host", "port", "speed", "linger"}) {
    EXPECT_NE(FindOption(TeleopClientOptions(), name), nullptr) << name;
  }
}

// The ranges of rate, end hold and timeout are the session's (TeleopOptions::IsValid): a value
// the option takes the session takes, and one it refuses the session refuses.
TEST(TeleopRequest, TheRangesAreTheSessions) {
  const auto session_takes = [](const char* name, double v) {
    teleop::TeleopOptions session;
    if (std::string(name) == "rate") session.rate_hz = v;
    if (std::string(name) == "end_hold") session.end_hold_s = v;
    if (std::string(name) == "timeout_ms") session.timeout_s = v * 1e-3;
    return session.IsValid(nullptr);
  };
  for (const char* name : {"rate", "end_hold", "timeout_ms"}) {
    const OptionInfo& info = FindOption(TeleopServerOptions(), name)->info;
    for (double v : {-1.0, 0.0, 0.5, 1.0, 60.0, 61.0, 1000.0, 1000.5}) {
      EXPECT_EQ(CheckValue(info, Value(v)).empty(), session_takes(name, v)) << name << " " << v;
    }
  }
}

TEST(TeleopRequest, AValueOutOfRangeNamesTheOption) {
  TeleopRequest r;
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(TeleopServerOptions(), "rate"), Value(2000.0), "--rate", &r), InputError,
      "--rate: must be [1, 1000] (got 2000)");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(TeleopServerOptions(), "orientations"),
                             Value(std::string("20,abc")), "--orientations", &r),
                       InputError,
                       "--orientations: 'abc' is not a finite number of degrees (in '20,abc')");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(TeleopServerOptions(), "viewer_port"), Value(int64_t{-2}),
                             "--viewer-port", &r),
                       InputError, "--viewer-port: must be [-1, 65535] (got -2)");
  TeleopClientRequest c;
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(TeleopClientOptions(), "speed"), Value(0.0), "--speed", &c), InputError,
      "--speed: must be > 0 (got 0)");
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(TeleopClientOptions(), "port"), Value(int64_t{0}), "--port", &c),
      InputError, "--port: must be [1, 65535] (got 0)");
}

TEST(TeleopRequest, AConfigFileSetsOptionsAndAFlagOverridesIt) {
  TeleopRequest r;
  ApplyConfig(TeleopServerOptions(),
              WriteConfig("teleop.json", R"({"format": "graspsynth-options/1", "orientations":
                  [60, 70], "at": [-0.3, 0.9], "rate": 30, "operator": "ann", "insecure": true})"),
              &r);
  EXPECT_EQ(r.orientations, "60,70");
  ASSERT_TRUE(r.at.has_value());
  EXPECT_EQ(r.at->x(), -0.3);
  EXPECT_EQ(r.rate_hz, 30.0);
  EXPECT_EQ(r.operator_name, "ann");
  EXPECT_TRUE(r.insecure);
  // a flag given beside the file is applied after it (apps/request_flags.hpp).
  const Option<TeleopRequest>& rate = *FindOption(TeleopServerOptions(), "rate");
  Apply(rate, ParseText(rate.info, "50", "--rate"), "--rate", &r);
  EXPECT_EQ(r.rate_hz, 50.0);
  // a value out of range in the file names the file and the field.
  const std::filesystem::path bad = WriteConfig("teleop_bad.json", R"({"timeout_ms": -5})");
  GS_EXPECT_THROW_WITH(ApplyConfig(TeleopServerOptions(), bad, &r), InputError,
                       "field 'timeout_ms': must be > 0 (got -5)");
  TeleopClientRequest c;
  ApplyConfig(TeleopClientOptions(), WriteConfig("client.json", R"({"speed": 0.5, "port": 9871})"),
              &c);
  EXPECT_EQ(c.speed, 0.5);
  EXPECT_EQ(c.port, 9871);
}

}  // namespace
}  // namespace graspsynth::request
