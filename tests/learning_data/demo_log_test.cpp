// Tests of the demonstration log format v1: round trip, and every rule of the reader.

#include "learning_data/demo_log.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "common/errors.hpp"
#include "kinematics/pose_math.hpp"
#include "tests/learning_data/demo_csv_cases.hpp"
#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::TestFolder;

// A log whose values have full-precision mantissas, negative-w quaternions included.
DemoLog RandomLog(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  DemoLog log;
  log.metadata.theta_deg = 37.123456789012345;
  log.metadata.object_position = Eigen::Vector3d(u(rng), u(rng), u(rng));
  log.metadata.trial = "7b";
  log.metadata.operator_name = "operator with spaces";
  log.metadata.sample_rate_hz = 59.94;
  log.metadata.extra = {{"glove", "5DT Data Glove"}, {"note", "kept: as is"}};
  double t = 0.1 * u(rng);
  for (int i = 0; i < 40; ++i) {
    DemoSample s;
    t += 0.01 + 0.02 * std::abs(u(rng));
    s.t = t;
    s.p_WH = Eigen::Vector3d(u(rng), u(rng), u(rng));
    s.q_WH = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    // every other quaternion with w < 0, which the writer must flip.
    if ((i % 2 == 1) == (s.q_WH.w() > 0.0)) s.q_WH.coeffs() = -s.q_WH.coeffs();
    for (int k = 0; k < kHandDof; ++k) s.f[k] = u(rng) * 1e-3 + u(rng);
    s.event = i == 25 ? DemoEvent::kGrasp : i == 39 ? DemoEvent::kEnd : DemoEvent::kNone;
    s.p_WO = Eigen::Vector3d(u(rng), u(rng), 1e-300 * u(rng));
    log.samples.push_back(s);
  }
  return log;
}

TEST(DemoLog, RoundTripGivesIdenticalValues) {
  const TestFolder folder;
  const DemoLog original = RandomLog(11);
  const auto path = folder.path() / "sub" / "trial.csv";
  WriteDemoLog(path, original);
  const DemoLog read = ReadDemoLog(path);

  EXPECT_EQ(read.source, path.string());
  EXPECT_EQ(read.metadata.format, "graspsynth-demo/1");
  EXPECT_EQ(read.metadata.theta_deg, original.metadata.theta_deg);
  EXPECT_EQ(read.metadata.object_position, original.metadata.object_position);
  EXPECT_EQ(read.metadata.trial, original.metadata.trial);
  EXPECT_EQ(read.metadata.operator_name, original.metadata.operator_name);
  EXPECT_EQ(read.metadata.sample_rate_hz, original.metadata.sample_rate_hz);
  EXPECT_EQ(read.metadata.extra, original.metadata.extra);
  ASSERT_EQ(read.samples.size(), original.samples.size());
  for (size_t i = 0; i < read.samples.size(); ++i) {
    SCOPED_TRACE("sample " + std::to_string(i));
    const DemoSample& a = original.samples[i];
    const DemoSample& b = read.samples[i];
    EXPECT_EQ(b.t, a.t);
    EXPECT_EQ(b.p_WH, a.p_WH);
    // unit to the last bits already, so only the sign changes: bit for bit.
    const Eigen::Vector4d expected =
        a.q_WH.w() < 0.0 ? Eigen::Vector4d(-a.q_WH.coeffs()) : Eigen::Vector4d(a.q_WH.coeffs());
    EXPECT_EQ(b.q_WH.coeffs(), expected);
    EXPECT_GE(b.q_WH.w(), 0.0);
    EXPECT_LT(AngleBetween(a.q_WH, b.q_WH), 1e-12);  // the same orientation
    EXPECT_EQ(b.f, a.f);
    EXPECT_EQ(b.event, a.event);
    EXPECT_EQ(b.p_WO, a.p_WO);
  }
  // writing what was read gives the same bytes.
  EXPECT_EQ(FormatDemoLog(read), FormatDemoLog(original));
}

TEST(DemoLog, WriterNormalizesNearUnitQuaternions) {
  DemoLog log = RandomLog(5);
  log.samples[2].q_WH = Eigen::Quaterniond(-0.6 * 1.0005, 0.0, 0.8 * 1.0005, 0.0);
  const DemoLog read = ParseDemoLog(FormatDemoLog(log), "n.csv");
  EXPECT_NEAR(read.samples[2].q_WH.norm(), 1.0, 1e-15);
  EXPECT_TRUE(testing::MatricesNear(read.samples[2].q_WH.coeffs(),
                                    Eigen::Vector4d(0.0, -0.8, 0.0, 0.6), 1e-15));
  EXPECT_EQ(FormatDemoLog(read), FormatDemoLog(log));
}

TEST(DemoLog, WriterRefusesWhatTheReaderWouldReject) {
  const TestFolder folder;
  DemoLog log = RandomLog(3);
  log.samples[10].t = log.samples[9].t;
  GS_EXPECT_THROW_WITH(WriteDemoLog(folder.path() / "bad.csv", log), InputError,
                       "bad.csv:", "does not increase");
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "bad.csv"));

  log = RandomLog(3);
  log.samples[4].q_WH.coeffs() *= 1.5;
  GS_EXPECT_THROW_WITH(FormatDemoLog(log), InputError, "sample 4", "norm 1.5");
  log = RandomLog(3);
  log.samples[25].event = DemoEvent::kNone;
  GS_EXPECT_THROW_WITH(FormatDemoLog(log), InputError, "no grasp event");
}

TEST(DemoLog, ParsesAGoodLogExactly) {
  const DemoLog log = ParseDemoLog(testing::GoodDemoText(), "good.csv");
  EXPECT_EQ(log.source, "good.csv");
  EXPECT_EQ(log.metadata.theta_deg, 40.0);
  EXPECT_EQ(log.metadata.object_position, Eigen::Vector3d(-0.25, 0.85, 0.025));
  EXPECT_FALSE(log.metadata.trial.has_value());
  ASSERT_EQ(log.samples.size(), 4u);
  EXPECT_EQ(log.samples[1].t, 0.1);
  EXPECT_EQ(log.samples[2].event, DemoEvent::kGrasp);
  EXPECT_EQ(log.samples[3].event, DemoEvent::kEnd);
  EXPECT_EQ(log.samples[3].p_WO.z(), 0.2);
  EXPECT_EQ(log.samples[0].f, HandVector::Constant(0.1));
  EXPECT_EQ(FindEvent(log, DemoEvent::kGrasp), std::optional<size_t>(2));
  EXPECT_EQ(FindEvent(log, DemoEvent::kEnd), std::optional<size_t>(3));
}

TEST(DemoLog, AcceptsBlanksCrlfByteOrderMarkUnknownKeysAndNearUnitQuaternions) {
  std::string text =
      "\n# format: graspsynth-demo/1\n#theta_deg:40\n\n# colour: red, green\n"
      "# object_position: -0.25,0.85,0.025\n" +
      testing::DemoHeader() + testing::DemoRow("0", "0", 0.1, "1.0009") +
      testing::DemoRow("0.1", "1") + testing::DemoRow("0.2", "2") + "\n\n";
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  for (const std::string& variant : {text, crlf, "\xEF\xBB\xBF" + text}) {
    const DemoLog log = ParseDemoLog(variant, "ok.csv");
    ASSERT_EQ(log.samples.size(), 3u);
    EXPECT_EQ(log.metadata.theta_deg, 40.0);
    ASSERT_EQ(log.metadata.extra.size(), 1u);
    EXPECT_EQ(log.metadata.extra[0].first, "colour");
    EXPECT_EQ(log.metadata.extra[0].second, "red, green");
    EXPECT_EQ(log.samples[0].q_WH.w(), 1.0009);  // kept as written, not normalized
  }
}

TEST(DemoLog, RejectsEveryMalformedCaseNamingFileLineAndColumn) {
  for (const testing::MalformedCase& c : testing::MalformedDemoCases()) {
    SCOPED_TRACE(c.name);
    const std::string source = c.name + ".csv";
    try {
      ParseDemoLog(c.text, source);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(source + ":", 0), 0u) << message;
      for (const std::string& part : c.message) EXPECT_THAT(message, HasSubstr(part));
    }
  }
}

TEST(DemoLog, ReadNamesAMissingFile) {
  GS_EXPECT_THROW_WITH(ReadDemoLog("/nonexistent/folder/trial.csv"), InputError,
                       "/nonexistent/folder/trial.csv");
}

}  // namespace
}  // namespace graspsynth
