// Tests of `graspsynth fk` and `graspsynth ik` through the built binary.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "tests/utils/run_command.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using testing::RunGraspsynth;

std::vector<json> JsonLines(const std::string& text) {
  std::vector<json> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(json::parse(line));
  return lines;
}

TEST(FkCommand, PrintsTheFlangePoseOfEachLine) {
  const auto r =
      RunGraspsynth("fk", "0 0 0 0 0 0 0\n# a comment\n\n0,0,0,1.5707963267948966,0,0,0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = JsonLines(r.out);
  ASSERT_EQ(lines.size(), 2u);
  const std::vector<double> p0 = lines[0]["position"];
  EXPECT_NEAR(p0[2], 1.317, 1e-12);
  const std::vector<double> q0 = lines[0]["quaternion"];
  EXPECT_NEAR(q0[0], 1.0, 1e-12);
  const std::vector<double> p1 = lines[1]["position"];
  EXPECT_NEAR(p1[2], 0.767, 1e-12);
  EXPECT_NEAR(std::hypot(p1[0], p1[1]), 0.55, 1e-12);
}

TEST(FkCommand, NamesMalformedLinesAndGoesOn) {
  const auto r =
      RunGraspsynth("fk", "0 0 0 0 0 0\n0 0 0 0 0 0 x\n0 0 0 0 0 0 0\n0 0 nan 0 0 0 0\n");
  EXPECT_EQ(r.exit_code, 1);
  const auto lines = JsonLines(r.out);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_THAT(lines[0]["error"].get<std::string>(), HasSubstr("expected 7 numbers, found 6"));
  EXPECT_THAT(lines[1]["error"].get<std::string>(), HasSubstr("field 7"));
  EXPECT_TRUE(lines[2].contains("position"));
  EXPECT_THAT(lines[3]["error"].get<std::string>(), HasSubstr("'nan'"));
  EXPECT_THAT(r.err, HasSubstr("<stdin>:1:"));
  EXPECT_THAT(r.err, HasSubstr("<stdin>:2:"));
  EXPECT_THAT(r.err, HasSubstr("<stdin>:4:"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("<stdin>:3:")));
}

TEST(IkCommand, SolvesWhatFkProduced) {
  // with S3 = 0 the elbow lies in the reference plane, so the arm angle of q is 0.
  const std::vector<double> q = {0.3, 0.7, 0.0, 1.1, 0.5, -0.8, 0.2};
  std::ostringstream q_line;
  q_line.precision(17);
  for (double v : q) q_line << v << " ";
  const auto fk = RunGraspsynth("fk", q_line.str() + "\n");
  ASSERT_EQ(fk.exit_code, 0);
  const json pose = json::parse(fk.out);
  std::ostringstream target;
  target.precision(17);
  for (double v : pose["position"]) target << v << " ";
  for (double v : pose["quaternion"]) target << v << " ";
  const auto r = RunGraspsynth("ik --branch 1,1,-1", target.str() + "0.0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // the branch from a file of options (--config) is the same as the flag's.
  const testing::TestFolder folder;
  std::ofstream(folder.path() / "ik.json") << R"({"branch": [1, 1, -1]})";
  const auto config =
      RunGraspsynth("ik --config " + (folder.path() / "ik.json").string(), target.str() + "0.0\n");
  ASSERT_EQ(config.exit_code, 0) << config.err;
  EXPECT_EQ(config.out, r.out);
  const json out = json::parse(r.out);
  ASSERT_EQ(out["solutions"].size(), 1u);
  EXPECT_EQ(out["branches"][0], json({1, 1, -1}));
  for (int i = 0; i < 7; ++i) EXPECT_NEAR(out["solutions"][0][i].get<double>(), q[i], 1e-9);
  // psi = 0 lies in one of the reported feasible intervals.
  bool inside = false;
  for (const auto& iv : out["psi_intervals"]) {
    inside |= iv[0].get<double>() <= 0.0 && 0.0 <= iv[1].get<double>();
  }
  EXPECT_TRUE(inside);
  // without --branch, every printed solution is one of the 8 branches and reproduces the pose.
  const json all = json::parse(RunGraspsynth("ik", target.str() + "0.0\n").out);
  EXPECT_GE(all["solutions"].size(), 1u);
  for (const auto& sol : all["solutions"]) {
    std::ostringstream line;
    line.precision(17);
    for (double v : sol) line << v << " ";
    const json back = json::parse(RunGraspsynth("fk", line.str() + "\n").out);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(back["position"][i].get<double>(), pose["position"][i].get<double>(), 1e-9);
    }
  }
}

TEST(IkCommand, UnreachableTargetHasNoSolutionAndNoInterval) {
  const auto r = RunGraspsynth("ik", "3 0 0.5 1 0 0 0 0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json out = json::parse(r.out);
  EXPECT_TRUE(out["solutions"].empty());
  EXPECT_TRUE(out["psi_intervals"].empty());
}

TEST(IkCommand, NamesMalformedLines) {
  const auto r = RunGraspsynth("ik", "0.5 0 0.5 2 0 0 0 0\n0.5 0 0.5 1 0 0 0 7\n0.5 0 0.5 1 0 0\n");
  EXPECT_EQ(r.exit_code, 1);
  const auto lines = JsonLines(r.out);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_THAT(lines[0]["error"].get<std::string>(), HasSubstr("norm 2"));
  EXPECT_THAT(lines[1]["error"].get<std::string>(), HasSubstr("outside [-pi, pi]"));
  EXPECT_THAT(lines[2]["error"].get<std::string>(), HasSubstr("expected 8 numbers, found 6"));
  EXPECT_THAT(r.err, HasSubstr("<stdin>:3:"));
}

TEST(IkCommand, RejectsABadBranchOption) {
  const auto r = RunGraspsynth("ik --branch 1,2,1", "0.5 0 0.5 1 0 0 0 0\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--branch takes three signs"));
}

TEST(FkCommand, MissingInputFileIsAnError) {
  const auto r = RunGraspsynth("fk /nonexistent/file.txt");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("/nonexistent/file.txt"));
}

}  // namespace
}  // namespace graspsynth
