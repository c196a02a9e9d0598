// Tests of `graspsynth fk` and `graspsynth ik` through the built binary.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "common/format.hpp"
#include "kinematics/robot_description.hpp"
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

// The shipped robot: the limits and lengths the commands check against.
const ArmModel& Arm() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot.arm;
}

// "x y z qw qx qy qz" of the flange pose that `graspsynth fk` gives for `q` (radians).
std::string FlangeTarget(const std::vector<double>& q) {
  std::ostringstream line;
  line.precision(17);
  for (double v : q) line << v << " ";
  const json pose = json::parse(RunGraspsynth("fk", line.str() + "\n").out);
  std::ostringstream target;
  target.precision(17);
  for (double v : pose["position"]) target << v << " ";
  for (double v : pose["quaternion"]) target << v << " ";
  return target.str();
}

TEST(FkCommand, SaysWhichJointsAreOutsideTheLimitsAndHintsAtDegrees) {
  // S2 30, E1 90 and W1 45 degrees, given as radians: a pose all the same, exit status 0.
  const auto r = RunGraspsynth("fk", "0 30 0 90 0 45 0\n0.3 0.7 0 1.1 0.5 -0.8 0.2\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto lines = JsonLines(r.out);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_TRUE(lines[0].contains("position"));
  EXPECT_FALSE(lines[0]["within_limits"].get<bool>());
  const json& outside = lines[0]["outside_limits"];
  ASSERT_EQ(outside.size(), 3u) << outside.dump();
  const std::vector<std::pair<std::string, int>> expected = {{"S2", 1}, {"E1", 3}, {"W1", 5}};
  for (size_t k = 0; k < expected.size(); ++k) {
    const auto& [name, i] = expected[k];
    EXPECT_EQ(outside[k]["joint"], name);
    EXPECT_EQ(outside[k]["lower"].get<double>(), Arm().lower()[i]);
    EXPECT_EQ(outside[k]["upper"].get<double>(), Arm().upper()[i]);
  }
  EXPECT_EQ(outside[1]["value"].get<double>(), 90.0);
  EXPECT_THAT(r.err, HasSubstr("<stdin>:1: outside the joint limits: S2 = 30 (limits ["));
  EXPECT_THAT(r.err, HasSubstr("E1 = 90 (limits [" + FixedNumber(Arm().lower()[3], 3) + ", " +
                               FixedNumber(Arm().upper()[3], 3) + "] rad"));
  EXPECT_THAT(r.err, HasSubstr("look like degrees"));
  // the second line is within the limits: said so, and nothing on stderr for it.
  EXPECT_TRUE(lines[1]["within_limits"].get<bool>());
  EXPECT_FALSE(lines[1].contains("outside_limits"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("<stdin>:2:")));
}

TEST(FkCommand, ARadianValueJustBeyondALimitGetsNoHintAtDegrees) {
  const double e1 = Arm().upper()[3] + 0.1;
  std::ostringstream line;
  line.precision(17);
  line << "0 0 0 " << e1 << " 0 0 0\n";
  const auto r = RunGraspsynth("fk", line.str());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json out = json::parse(r.out);
  EXPECT_FALSE(out["within_limits"].get<bool>());
  ASSERT_EQ(out["outside_limits"].size(), 1u);
  EXPECT_EQ(out["outside_limits"][0]["joint"], "E1");
  EXPECT_THAT(r.err, HasSubstr("outside the joint limits: E1 = "));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("degrees")));
}

TEST(IkCommand, AnUnreachableTargetIsOutOfReachWithExitStatus1) {
  const auto r = RunGraspsynth("ik", "3 0 0.5 1 0 0 0 0\n");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json out = json::parse(r.out);
  EXPECT_TRUE(out["solutions"].empty());
  EXPECT_TRUE(out["psi_intervals"].empty());
  EXPECT_EQ(out["status"], "out_of_reach");
  // the span is the arm's, d_se + d_ew; the distance is the wrist centre's from the shoulder.
  const SrsLengths& len = Arm().lengths();
  EXPECT_DOUBLE_EQ(out["reach"]["outer"].get<double>(), len.d_se + len.d_ew);
  EXPECT_DOUBLE_EQ(out["reach"]["inner"].get<double>(), std::abs(len.d_se - len.d_ew));
  EXPECT_NEAR(out["reach"]["distance"].get<double>(), std::hypot(3.0, 0.5 - len.d_wt - len.d_bs),
              1e-12);
  EXPECT_THAT(r.err, HasSubstr("<stdin>:1: out of reach: the wrist centre is 3.002 m from the "
                               "shoulder"));
  EXPECT_EQ(out["message"].get<std::string>().rfind("out of reach", 0), 0u);
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("millimetres")));
}

TEST(IkCommand, ATargetInMillimetresIsOutOfReachWithAHint) {
  // README's example target, 0.5 0.2 0.6 m, given in millimetres.
  const auto r = RunGraspsynth("ik", "500 200 600 0 1 0 0 0.3\n0.5 0.2 0.6 0 1 0 0 0.3\n");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto lines = JsonLines(r.out);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0]["status"], "out_of_reach");
  EXPECT_THAT(r.err, HasSubstr("<stdin>:1: out of reach"));
  EXPECT_THAT(r.err, HasSubstr("looks like millimetres: ik takes metres"));
  // in metres it has solutions.
  EXPECT_EQ(lines[1]["status"], "ok");
  EXPECT_FALSE(lines[1]["solutions"].empty());
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("<stdin>:2:")));
}

TEST(IkCommand, AReachableTargetWithoutASolutionAtThatArmAngleFails) {
  // a configuration near the shoulder's limit: on its branch only some arm angles are feasible.
  const std::string target = FlangeTarget({0.0, 1.5, 0.0, 1.0, 0.0, 1.0, 0.0});
  const auto ok = RunGraspsynth("ik --branch 1,1,1", target + "0\n");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const json feasible = json::parse(ok.out)["psi_intervals"];
  ASSERT_EQ(feasible.size(), 1u) << feasible.dump();
  const double psi = feasible[0][1].get<double>() + 0.5;
  ASSERT_LT(psi, M_PI);
  std::ostringstream line;
  line.precision(17);
  line << target << psi << "\n";
  const auto r = RunGraspsynth("ik --branch 1,1,1", line.str());
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json out = json::parse(r.out);
  EXPECT_TRUE(out["solutions"].empty());
  EXPECT_EQ(out["status"], "no_solution");
  EXPECT_EQ(out["psi_intervals"], feasible);
  EXPECT_THAT(r.err, HasSubstr("no solution within the joint limits at psi = "));
  EXPECT_THAT(r.err, HasSubstr("feasible arm angles: ["));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("out of reach")));
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

std::string IiwaRobotFile() {
  return std::string(::testing::SourceDir()) + "/models/iiwa14_allegro.robot.json";
}

TEST(FkCommand, TakesARobotFilesArm) {
  // the iiwa straight up: the flange 0.36 + 0.42 + 0.40 + 0.126 m above the base, unturned.
  const auto r = RunGraspsynth("fk --robot " + IiwaRobotFile(), "0 0 0 0 0 0 0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json pose = json::parse(r.out);
  EXPECT_NEAR(pose["position"][0].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(pose["position"][1].get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(pose["position"][2].get<double>(), 1.306, 1e-12);
  EXPECT_NEAR(pose["quaternion"][0].get<double>(), 1.0, 1e-12);
  // A4 = +90 deg bends the forearm toward -x (A4 turns about -y at q = 0; the PA-10's E1 about
  // +y bends it toward +x).
  const auto bent =
      RunGraspsynth("fk --robot " + IiwaRobotFile(), "0 0 0 1.5707963267948966 0 0 0\n");
  ASSERT_EQ(bent.exit_code, 0) << bent.err;
  const json p = json::parse(bent.out)["position"];
  EXPECT_NEAR(p[0].get<double>(), -(0.40 + 0.126), 1e-12);
  EXPECT_NEAR(p[2].get<double>(), 0.36 + 0.42, 1e-12);
  // a joint beyond the iiwa's limit (A2 +-120 deg) is named by the URDF's joint name.
  const auto off = RunGraspsynth("fk --robot " + IiwaRobotFile(), "0 2.2 0 0 0 0 0\n");
  EXPECT_THAT(off.out, HasSubstr("A2"));
}

TEST(FkCommand, TakesAShippedRobotsName) {
  const std::string q = "0.3 0.7 -0.2 1.1 0.5 -0.8 0.2\n";
  const auto by_name = RunGraspsynth("fk --robot iiwa14_allegro", q);
  ASSERT_EQ(by_name.exit_code, 0) << by_name.err;
  EXPECT_EQ(by_name.out, RunGraspsynth("fk --robot " + IiwaRobotFile(), q).out);
  // the PA-10 by its robot file: the same bytes as the default URDF.
  const auto pa10 = RunGraspsynth("fk --robot pa10_gifu3", q);
  ASSERT_EQ(pa10.exit_code, 0) << pa10.err;
  EXPECT_EQ(pa10.out, RunGraspsynth("fk", q).out);
  const auto unknown = RunGraspsynth("fk --robot panda", q);
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("found \"panda\""));
  EXPECT_THAT(unknown.err, HasSubstr("graspsynth robots"));
}

TEST(RobotsCommand, ListsTheShippedRobots) {
  const auto text = RunGraspsynth("robots");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, HasSubstr("pa10_gifu3 (default)\n  models/pa10_gifu3.robot.json\n"));
  EXPECT_THAT(text.out, HasSubstr("iiwa14_allegro\n  models/iiwa14_allegro.robot.json\n"));
  const auto listed = RunGraspsynth("robots --json");
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  const json robots = json::parse(listed.out);
  ASSERT_EQ(robots.size(), 2u);
  EXPECT_EQ(robots[0]["name"], "iiwa14_allegro");
  EXPECT_EQ(robots[0]["default"], false);
  EXPECT_EQ(robots[1]["name"], "pa10_gifu3");
  EXPECT_EQ(robots[1]["default"], true);
  EXPECT_EQ(robots[1]["file"], "models/pa10_gifu3.robot.json");
}

TEST(IkCommand, SolvesARobotFilesArmOnItsDhBranches) {
  const std::vector<double> q = {0.3, 0.7, 0.0, 1.1, 0.5, -0.8, 0.2};
  std::ostringstream q_line;
  q_line.precision(17);
  for (double v : q) q_line << v << " ";
  const auto fk = RunGraspsynth("fk --robot " + IiwaRobotFile(), q_line.str() + "\n");
  ASSERT_EQ(fk.exit_code, 0) << fk.err;
  const json pose = json::parse(fk.out);
  std::ostringstream target;
  target.precision(17);
  for (double v : pose["position"]) target << v << " ";
  for (double v : pose["quaternion"]) target << v << " ";
  // with S3 = 0 the elbow lies in the reference plane: arm angle 0, as on the PA-10.
  const auto r = RunGraspsynth("ik --robot " + IiwaRobotFile(), target.str() + "0.0\n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json out = json::parse(r.out);
  bool found = false;
  for (size_t k = 0; k < out["solutions"].size(); ++k) {
    double err = 0.0;
    for (int i = 0; i < 7; ++i)
      err = std::max(err, std::abs(out["solutions"][k][i].get<double>() - q[i]));
    if (err < 1e-9) {
      found = true;
      // A4 = +1.1 is DH E1 = -1.1: GC4 = -1.
      EXPECT_EQ(out["branches"][k], json({1, -1, -1}));
    }
  }
  EXPECT_TRUE(found) << r.out;
}

TEST(FkCommand, ABadRobotFileIsNamed) {
  const testing::TestFolder folder;
  const std::string path = (folder.path() / "bad.robot.json").string();
  std::ofstream(path) << R"({"format": "graspsynth-robot/1", "name": "x", "urdf": ")"
                      << std::string(::testing::SourceDir())
                      << R"(/models/iiwa14_allegro.urdf", "arm": {"base_link": "base_link",
                             "flange_link": "A6_link", "ik": "srs"}})";
  const auto r = RunGraspsynth("fk --robot " + path, "0 0 0 0 0 0 0\n");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr(path));
  EXPECT_THAT(r.err, HasSubstr("expected 7 revolute joints"));
}

}  // namespace
}  // namespace graspsynth
