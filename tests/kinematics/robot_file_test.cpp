// Tests of kinematics/robot_file.hpp: the shipped robot files, the KUKA LBR iiwa's arm loaded
// from its robot file (FK against the published joint positions, IK round trips on its DH
// branches, feasible arm angles against a scan), the PA-10's arm unchanged, and bad files.

#include "kinematics/robot_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/robot_description.hpp"
#include "tests/utils/data_dir_override.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/paths.hpp"
#include "tests/utils/robot_fixtures.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

using testing::NearSingular;
using testing::PoseError;
using testing::RandomConfiguration;

namespace fs = std::filesystem;

fs::path Models() { return fs::path(::testing::SourceDir()) / "models"; }
fs::path IiwaFile() { return Models() / "iiwa14_allegro.robot.json"; }
fs::path Pa10File() { return Models() / "pa10_gifu3.robot.json"; }

// The iiwa 14 R820's flange from its published figures, independent of the URDF and of the DH
// table: the joints stacked straight up at q = 0 (0.1575, 0.2025, 0.2045, 0.2155, 0.1845,
// 0.2155, 0.081 m; the flange 0.045 m beyond A7, parallel to the base), axes z, y, z, -y, z,
// y, z; a product of exponentials.
Eigen::Isometry3d PublishedIiwaFlange(const Vector7d& q) {
  const double offsets[kArmDof] = {0.1575, 0.2025, 0.2045, 0.2155, 0.1845, 0.2155, 0.081};
  const Eigen::Vector3d axes[kArmDof] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(),
                                         Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitY(),
                                         Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(),
                                         Eigen::Vector3d::UnitZ()};
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  double height = 0.0;
  for (int i = 0; i < kArmDof; ++i) {
    height += offsets[i];
    const Eigen::Vector3d p(0.0, 0.0, height);
    // a turn by q_i about the line through p along the axis.
    Eigen::Isometry3d turn = Eigen::Isometry3d::Identity();
    turn.linear() = Eigen::AngleAxisd(q[i], axes[i]).toRotationMatrix();
    turn.translation() = p - turn.linear() * p;
    X = X * turn;
  }
  Eigen::Isometry3d M = Eigen::Isometry3d::Identity();
  M.translation() = Eigen::Vector3d(0.0, 0.0, height + 0.045);
  return X * M;
}

TEST(RobotFile, ReadsBothShippedFiles) {
  const RobotFile iiwa = LoadRobotFile(IiwaFile());
  EXPECT_EQ(iiwa.name, "iiwa14_allegro");
  EXPECT_EQ(iiwa.urdf, Models() / "iiwa14_allegro.urdf");
  EXPECT_EQ(iiwa.arm.base_link, "base_link");
  EXPECT_EQ(iiwa.arm.flange_link, "flange_link");
  EXPECT_EQ(iiwa.arm.ik, "srs");
  EXPECT_EQ(iiwa.arm.srs_tolerance_m, 1e-6);
  EXPECT_EQ(iiwa.arm.servo.position_gain, 20.0);
  // the iiwa stands at (0.20, -0.20, 0) m, yaw 0 (docs/robot-file-draft.md).
  EXPECT_EQ(iiwa.X_WB.translation(), Eigen::Vector3d(0.20, -0.20, 0.0));
  EXPECT_EQ(iiwa.X_WB.linear(), Eigen::Matrix3d::Identity());
  const RobotFile pa10 = LoadRobotFile(Pa10File());
  EXPECT_EQ(pa10.name, "pa10_gifu3");
  EXPECT_EQ(pa10.arm.flange_link, "W2_link");
  EXPECT_EQ(pa10.X_WB.matrix(), Eigen::Matrix4d::Identity());
}

TEST(RobotFile, ReadsTheBasePoseAsAYawThenAShift) {
  const std::string text = R"({"format": "graspsynth-robot/1", "name": "x", "urdf": "x.urdf",
      "base": {"position_m": [0.5, -0.25, 0.125], "yaw_deg": 90},
      "arm": {"base_link": "a", "flange_link": "b", "ik": "srs"}})";
  const RobotFile file = ParseRobotFile(text, "x.json", ".");
  const Eigen::Vector3d p_B(1.0, 0.0, 0.0);  // a point 1 m along the base's x
  EXPECT_LE((file.X_WB * p_B - Eigen::Vector3d(0.5, 0.75, 0.125)).norm(), 1e-15);
}

TEST(RobotFile, IiwaArmIsThePa10TableWithA4Turned) {
  const ArmModel arm = LoadArmFromRobotFile(IiwaFile());
  EXPECT_NEAR(arm.lengths().d_bs, 0.36, 1e-12);
  EXPECT_NEAR(arm.lengths().d_se, 0.42, 1e-12);
  EXPECT_NEAR(arm.lengths().d_ew, 0.40, 1e-12);
  EXPECT_NEAR(arm.lengths().d_wt, 0.126, 1e-12);
  const std::array<int, kArmDof> signs = {1, 1, 1, -1, 1, 1, 1};
  EXPECT_EQ(arm.dh_map().sign, signs);
  EXPECT_EQ(arm.dh_map().offset, Vector7d::Zero());
  EXPECT_EQ(arm.dh_map().R_7F, Eigen::Matrix3d::Identity());
  EXPECT_FALSE(arm.dh_map().identity);
  EXPECT_EQ(arm.joint(3).name, "A4");
  EXPECT_EQ(arm.link(7).name, "A7_link");
  EXPECT_NEAR(arm.X_7F().translation().z(), 0.045, 1e-15);
  // A4's +-120 deg is symmetric: the same in DH values.
  EXPECT_EQ(arm.dh_lower()[3], -arm.upper()[3]);
  EXPECT_EQ(arm.dh_upper()[3], -arm.lower()[3]);
}

TEST(RobotFile, IiwaForwardKinematicsMatchesThePublishedChain) {
  const ArmModel arm = LoadArmFromRobotFile(IiwaFile());
  std::mt19937_64 rng(46);
  double worst_dh = 0.0, worst_links = 0.0;
  ArmFrames frames;
  for (int k = 0; k < 5000; ++k) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    const Eigen::Isometry3d expected = PublishedIiwaFlange(q);
    worst_dh = std::max(worst_dh, PoseError(ArmFlangePose(arm, q), expected));
    ArmLinkFrames(arm, q, &frames);
    worst_links = std::max(worst_links, PoseError(frames.X_WL[7] * arm.X_7F(), expected));
  }
  std::cout << "[   info   ] iiwa FK against the published chain: DH " << worst_dh
            << ", URDF link frames " << worst_links << "\n";
  EXPECT_LE(worst_dh, 1e-9);
  EXPECT_LE(worst_links, 1e-9);
}

TEST(RobotFile, IiwaIkRoundTripsOnItsBranchAndArmAngle) {
  const ArmModel arm = LoadArmFromRobotFile(IiwaFile());
  std::mt19937_64 rng(47);
  double worst = 0.0;
  int used = 0, gc4_positive = 0;
  while (used < 100000) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    if (NearSingular(q)) continue;
    ++used;
    const Eigen::Isometry3d X_WF = PublishedIiwaFlange(q);
    const ArmBranch branch = BranchOf(arm, q);
    // the branches are DH signs: A4's DH value is -A4.
    ASSERT_EQ(branch.gc4, q[3] <= 0.0 ? 1 : -1);
    ASSERT_EQ(branch.gc2, q[1] >= 0.0 ? 1 : -1);
    gc4_positive += branch.gc4 > 0;
    const double psi = ArmAngleOf(arm, q);
    const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, branch, &q);
    ASSERT_EQ(s.status, IkStatus::kOk) << q.transpose();
    const double err = (s.q - q).cwiseAbs().maxCoeff();
    worst = std::max(worst, err);
    ASSERT_LE(err, 1e-9) << "q = " << q.transpose() << "\nIK = " << s.q.transpose();
    // without q_near the nearest-to-zero equivalent is the same (no iiwa joint spans 2 pi).
    const ArmIkSolution plain = SolveArmIk(arm, X_WF, psi, branch);
    ASSERT_LE((plain.q - q).cwiseAbs().maxCoeff(), 1e-9);
    if (used % 50 == 0) {
      bool found = false;
      for (const Vector7d& other : SolveArmIkAllBranches(arm, X_WF, psi)) {
        found = found || (other - q).cwiseAbs().maxCoeff() <= 1e-9;
        EXPECT_LE(PoseError(PublishedIiwaFlange(other), X_WF), 1e-9);
        EXPECT_TRUE(arm.WithinLimits(other));
      }
      ASSERT_TRUE(found) << q.transpose();
    }
  }
  std::cout << "[   info   ] iiwa psi round trip worst joint error " << worst << " rad\n";
  EXPECT_GT(gc4_positive, 25000);
  EXPECT_LT(gc4_positive, 75000);
}

TEST(RobotFile, IiwaFeasibleArmAnglesAgreeWithADenseScan) {
  const ArmModel arm = LoadArmFromRobotFile(IiwaFile());
  std::mt19937_64 rng(48);
  constexpr int kSamples = 3600;
  constexpr double kBoundaryBand = 1e-6;
  int64_t samples = 0, mismatches = 0, feasible = 0, partial_sets = 0;
  for (int k = 0; k < 40; ++k) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    const Eigen::Isometry3d X_WF = PublishedIiwaFlange(q);
    for (int index = 0; index < 8; ++index) {
      const ArmBranch b = ArmBranch::FromIndex(index);
      const ArmTargetForm form = PrepareArmTarget(arm, X_WF, b.gc4);
      const std::vector<Interval> set = FeasibleArmAngles(arm, form, b.gc2, b.gc6);
      if (!set.empty() && !(set.size() == 1 && set[0].width() >= 2 * M_PI)) ++partial_sets;
      for (int i = 0; i < kSamples; ++i) {
        const double psi = -M_PI + (i + 0.5) * 2.0 * M_PI / kSamples;
        // the brute-force definition: the IK's own solution is within every joint limit.
        const bool expected = SolveArmIk(arm, X_WF, psi, b).status == IkStatus::kOk;
        bool inside = false;
        double boundary = 1e9;
        for (const Interval& iv : set) {
          inside = inside || iv.Contains(psi);
          boundary = std::min({boundary, std::abs(psi - iv.lo), std::abs(psi - iv.hi)});
        }
        ++samples;
        feasible += expected;
        if (inside != expected && boundary > kBoundaryBand) {
          if (mismatches < 5) ADD_FAILURE() << "branch " << index << " psi " << psi;
          ++mismatches;
        }
      }
    }
    // the generating configuration's arm angle lies in its branch's set.
    if (!NearSingular(q)) {
      const ArmBranch b = BranchOf(arm, q);
      const double psi = ArmAngleOf(arm, q);
      bool found = false;
      for (const Interval& iv :
           FeasibleArmAngles(arm, PrepareArmTarget(arm, X_WF, b.gc4), b.gc2, b.gc6)) {
        found = found || (iv.lo - 1e-9 <= psi && psi <= iv.hi + 1e-9);
      }
      EXPECT_TRUE(found) << q.transpose();
    }
  }
  std::cout << "[   info   ] iiwa feasible psi: " << samples << " samples, " << feasible
            << " feasible, " << partial_sets << " partial sets, " << mismatches << " mismatches\n";
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(partial_sets, 50);
}

TEST(RobotFile, IiwaMidArcSolutionReachesTheTarget) {
  const ArmModel arm = LoadArmFromRobotFile(IiwaFile());
  std::mt19937_64 rng(49);
  for (int k = 0; k < 200; ++k) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    const Eigen::Isometry3d X_WF = PublishedIiwaFlange(q);
    const std::optional<MidArcSolution> s = SolveArmIkMidArc(arm, X_WF);
    ASSERT_TRUE(s.has_value()) << q.transpose();
    EXPECT_TRUE(arm.WithinLimits(s->q));
    EXPECT_LE(PoseError(PublishedIiwaFlange(s->q), X_WF), 1e-9);
    EXPECT_EQ(BranchOf(arm, s->q), s->branch);
    if (!NearSingular(s->q)) {
      EXPECT_NEAR(ArmAngleOf(arm, s->q), s->psi, 1e-9);
    }
  }
}

TEST(RobotFile, Pa10ArmFromItsRobotFileIsTheUrdfLoadersBitForBit) {
  const ArmModel arm = LoadArmFromRobotFile(Pa10File());
  const RobotModel robot = LoadRobotModel(Models() / "pa10_gifu3.urdf");
  EXPECT_TRUE(arm.dh_map().identity);
  EXPECT_TRUE(robot.arm.dh_map().identity);
  EXPECT_EQ(arm.lengths().d_bs, robot.arm.lengths().d_bs);
  EXPECT_EQ(arm.lengths().d_se, robot.arm.lengths().d_se);
  EXPECT_EQ(arm.lengths().d_ew, robot.arm.lengths().d_ew);
  EXPECT_EQ(arm.lengths().d_wt, robot.arm.lengths().d_wt);
  EXPECT_EQ(arm.lower(), robot.arm.lower());
  EXPECT_EQ(arm.upper(), robot.arm.upper());
  EXPECT_EQ(arm.X_7F().matrix(), Eigen::Matrix4d::Identity());
  std::mt19937_64 rng(50);
  for (int k = 0; k < 200; ++k) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    const Eigen::Isometry3d X = ArmFlangePose(arm, q);
    EXPECT_EQ(X.matrix(), DhFlangePose(robot.arm.lengths(), q).matrix());
    const ArmIkSolution a = SolveArmIk(arm, X, 0.3, BranchOf(q));
    const ArmIkSolution b = SolveArmIk(robot.arm, X, 0.3, BranchOf(q));
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.q, b.q);
  }
}

// Writes `text` to `folder`/`name` and returns the path.
fs::path Write(const fs::path& folder, const std::string& name, const std::string& text) {
  std::ofstream(folder / name) << text;
  return folder / name;
}

// A robot file for the shipped iiwa URDF (or `urdf`) with the arm part `arm`.
std::string RobotJson(const std::string& arm, const std::string& urdf = "") {
  const std::string u = urdf.empty() ? (Models() / "iiwa14_allegro.urdf").string() : urdf;
  return R"({"format": "graspsynth-robot/1", "name": "test", "urdf": ")" + u + R"(", "arm": )" +
         arm + "}";
}

std::string ArmJson(const std::string& base, const std::string& flange) {
  return R"({"base_link": ")" + base + R"(", "flange_link": ")" + flange +
         R"(", "ik": "srs", "srs_tolerance_m": 1e-6})";
}

TEST(RobotFile, RefusesALinkThatDoesNotExist) {
  testing::TestFolder dir;
  const fs::path flange = Write(dir.path(), "a.json", RobotJson(ArmJson("base_link", "nope")));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(flange), InputError, flange.string(),
                       "field 'arm.flange_link'", "expected a link of", "found \"nope\"");
  const fs::path base = Write(dir.path(), "b.json", RobotJson(ArmJson("nope", "flange_link")));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(base), InputError, base.string(),
                       "field 'arm.base_link'", "found \"nope\"");
}

TEST(RobotFile, RefusesAChainThatIsNotOne) {
  testing::TestFolder dir;
  const fs::path path = Write(dir.path(), "a.json", RobotJson(ArmJson("flange_link", "base_link")));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(path), InputError, path.string(),
                       "fields 'arm.base_link', 'arm.flange_link'",
                       "'base_link' is not below "
                       "'flange_link'");
  // two branches of the hand: neither is below the other.
  const fs::path hand =
      Write(dir.path(), "b.json", RobotJson(ArmJson("index_tip_link", "thumb_tip_link")));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(hand), InputError, "is not below");
}

TEST(RobotFile, RefusesAnotherNumberOfRevoluteJoints) {
  testing::TestFolder dir;
  const fs::path short_chain =
      Write(dir.path(), "a.json", RobotJson(ArmJson("base_link", "A6_link")));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(short_chain), InputError, short_chain.string(),
                       "fields 'arm.base_link', 'arm.flange_link'", "expected 7 revolute joints",
                       "found 6 ('A1', 'A2', 'A3', 'A4', 'A5', 'A6')");
  const fs::path long_chain =
      Write(dir.path(), "b.json", RobotJson(ArmJson("base_link", "index_tip_link")));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(long_chain), InputError, "found 11");
}

TEST(RobotFile, RefusesAnArmThatIsNotSrsNamingTheAxesAndTheMiss) {
  testing::TestFolder dir;
  std::ifstream in(Models() / "iiwa14_allegro.urdf");
  std::stringstream text;
  text << in.rdbuf();
  std::string urdf = text.str();
  // A2 moved 2 mm along x: A1 and A2 no longer meet.
  const std::string a2 = R"(<origin xyz="0 0 0.2025" rpy="-1.5707963267948966 0 0"/>)";
  ASSERT_NE(urdf.find(a2), std::string::npos);
  urdf.replace(urdf.find(a2), a2.size(),
               R"(<origin xyz="0.002 0 0.2025" rpy="-1.5707963267948966 0 0"/>)");
  const fs::path bad_urdf = Write(dir.path(), "bent.urdf", urdf);
  const fs::path path =
      Write(dir.path(), "a.json", RobotJson(ArmJson("base_link", "flange_link"), "bent.urdf"));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(path), InputError, path.string(), "field 'arm.ik'",
                       "expected an SRS arm", bad_urdf.string(),
                       "'A1' and 'A2' miss each other by 0.002 m (2 mm)");
  // a 5 mm tolerance lets it through: the DH chain then misses the URDF's by about the 2 mm.
  const fs::path loose =
      Write(dir.path(), "b.json",
            RobotJson(R"({"base_link": "base_link", "flange_link": "flange_link", "ik": "srs",
                    "srs_tolerance_m": 0.005})",
                      "bent.urdf"));
  const ArmModel arm = LoadArmFromRobotFile(loose);
  std::mt19937_64 rng(51);
  ArmFrames frames;
  for (int k = 0; k < 20; ++k) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    ArmLinkFrames(arm, q, &frames);
    const double miss =
        ((frames.X_WL[7] * arm.X_7F()).translation() - ArmFlangePose(arm, q).translation()).norm();
    EXPECT_GT(miss, 0.0005);
    EXPECT_LE(miss, 0.005);
  }
}

TEST(RobotFile, RefusesBadFieldsNamingThem) {
  testing::TestFolder dir;
  const auto expect_field = [&](const std::string& text, const std::string& field) {
    const fs::path path = Write(dir.path(), "bad.json", text);
    GS_EXPECT_THROW_WITH(LoadRobotFile(path), InputError, path.string(), field);
  };
  expect_field(R"({"format": "graspsynth-robot/2", "name": "x", "urdf": "x.urdf", "arm": {}})",
               "field 'format'");
  expect_field(RobotJson(R"({"base_link": "base_link", "flange_link": "flange_link",
                             "ik": "numeric"})"),
               "field 'arm.ik': expected \"srs\"");
  expect_field(RobotJson(R"({"base_link": "base_link", "flange_link": "flange_link",
                             "ik": "srs", "srs_tolerance_m": 0.5})"),
               "field 'arm.srs_tolerance_m': expected a tolerance in (0, 0.01] m, found 0.5");
  expect_field(RobotJson(R"({"base_link": "base_link", "flange": "flange_link", "ik": "srs"})"),
               "arm.flange");
  expect_field(RobotJson(R"({"base_link": "", "flange_link": "flange_link", "ik": "srs"})"),
               "field 'arm.base_link': expected a non-empty string");
  expect_field(RobotJson(R"({"base_link": "a", "flange_link": "a", "ik": "srs"})"),
               "field 'arm.flange_link': expected a link other than arm.base_link");
  expect_field(RobotJson(R"({"base_link": "a", "flange_link": "b", "ik": "srs",
                             "servo": {"position_gain": -1}})"),
               "field 'arm.servo.position_gain'");
  expect_field(R"({"format": "graspsynth-robot/1", "name": "x", "urdf": "x.urdf"})", "field 'arm'");
  const std::string arm = R"("arm": {"base_link": "a", "flange_link": "b", "ik": "srs"})";
  const std::string head = R"({"format": "graspsynth-robot/1", "name": "x", "urdf": "x.urdf", )";
  expect_field(head + R"("base": {"position_m": [0, 0]}, )" + arm + "}",
               "field 'base.position_m': expected an array of 3 numbers");
  expect_field(head + R"("base": {"position_m": [0, 0, 11]}, )" + arm + "}",
               "field 'base.position_m[2]'");
  expect_field(head + R"("base": {"position_m": [0, 0, 0], "yaw_deg": 270}, )" + arm + "}",
               "field 'base.yaw_deg': expected a number in [-180, 180], found 270");
  expect_field(head + R"("base": {"position_m": [0, 0, 0], "roll_deg": 1}, )" + arm + "}",
               "base.roll_deg");
  expect_field(head + R"("base": {"yaw_deg": 1}, )" + arm + "}", "field 'base.position_m'");
  // a URDF that is not there: named with the robot file's folder.
  const fs::path path = Write(dir.path(), "c.json", RobotJson(ArmJson("a", "b"), "missing.urdf"));
  GS_EXPECT_THROW_WITH(LoadArmFromRobotFile(path), InputError, "missing.urdf");
}

TEST(ShippedRobots, ListsEachRobotFileOfTheDataFolderByName) {
  const std::vector<ShippedRobot> robots = ShippedRobots();
  ASSERT_EQ(robots.size(), 2u);
  EXPECT_EQ(robots[0].name, "iiwa14_allegro");
  EXPECT_EQ(robots[0].file, IiwaFile());
  EXPECT_THAT(robots[0].comment, ::testing::HasSubstr("KUKA LBR iiwa 14 R820"));
  EXPECT_EQ(robots[1].name, kDefaultRobotName);
  EXPECT_EQ(robots[1].file, Pa10File());
}

TEST(ShippedRobots, RefusesAFileWhoseNameIsNotItsFilesName) {
  testing::TestFolder dir;
  fs::create_directories(dir.path() / "models");
  Write(dir.path() / "models", "mine.robot.json", RobotJson(ArmJson("base_link", "flange_link")));
  const testing::DataDirOverride data(dir.path().c_str());
  GS_EXPECT_THROW_WITH(ShippedRobots(), InputError, "mine.robot.json",
                       "field 'name': expected \"mine\" (the file's name), found \"test\"");
}

TEST(ResolveRobotPath, NamesAShippedRobotOrTakesAPath) {
  EXPECT_EQ(ResolveRobotPath("iiwa14_allegro"), IiwaFile());
  EXPECT_EQ(ResolveRobotPath("pa10_gifu3"), Pa10File());
  EXPECT_EQ(ResolveRobotPath("my.robot.json"), fs::path("my.robot.json"));
  EXPECT_EQ(ResolveRobotPath("arm.urdf"), fs::path("arm.urdf"));
  EXPECT_EQ(ResolveRobotPath("robots/panda"), fs::path("robots/panda"));
  GS_EXPECT_THROW_WITH(ResolveRobotPath("panda"), InputError,
                       "expected a shipped robot (iiwa14_allegro, pa10_gifu3;", "found \"panda\"");
}

}  // namespace
}  // namespace graspsynth
