// Tests of kinematics/robot_file.hpp: the shipped robot files, the KUKA LBR iiwa's arm loaded
// from its robot file (FK against the published joint positions, IK round trips on its DH
// branches, feasible arm angles against a scan), the PA-10's arm unchanged, and bad files.

#include "kinematics/robot_file.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <iterator>
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
  // the iiwa stands at (-0.10, 0.10, 0) m, yaw 0, where its scripted grasp reaches the pan at
  // every orientation 20-100 deg (models/iiwa14_allegro.robot.json).
  EXPECT_EQ(iiwa.X_WB.translation(), Eigen::Vector3d(-0.10, 0.10, 0.0));
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

// --- the whole robot (LoadRobot) ----------------------------------------------------------

void ExpectSameLink(const RigidLink& a, const RigidLink& b) {
  SCOPED_TRACE(a.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.inertia.mass, b.inertia.mass);
  EXPECT_EQ(a.inertia.p_LCm, b.inertia.p_LCm);
  EXPECT_EQ(a.inertia.I_Cm, b.inertia.I_Cm);
  ASSERT_EQ(a.shapes.size(), b.shapes.size());
  for (size_t i = 0; i < a.shapes.size(); ++i) {
    EXPECT_EQ(a.shapes[i].kind, b.shapes[i].kind);
    EXPECT_EQ(a.shapes[i].size, b.shapes[i].size);
    EXPECT_EQ(a.shapes[i].X_LG.matrix(), b.shapes[i].X_LG.matrix());
  }
}

void ExpectSameJoint(const RevoluteJoint& a, const RevoluteJoint& b) {
  SCOPED_TRACE(a.name);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.X_PJ.matrix(), b.X_PJ.matrix());
  EXPECT_EQ(a.axis_J, b.axis_J);
  EXPECT_EQ(a.lower, b.lower);
  EXPECT_EQ(a.upper, b.upper);
  EXPECT_EQ(a.max_velocity, b.max_velocity);
  EXPECT_EQ(a.max_effort, b.max_effort);
}

TEST(LoadRobot, Pa10RobotFileIsTheUrdfLoadersRobotFieldByField) {
  const RobotModel file = LoadRobot(Pa10File());
  const RobotModel urdf = LoadRobotModel(Models() / "pa10_gifu3.urdf");
  EXPECT_EQ(file.source, Pa10File().string());
  EXPECT_EQ(file.name, "pa10_gifu3");
  EXPECT_EQ(urdf.name, "pa10_gifu3");
  EXPECT_EQ(file.X_WB.matrix(), Eigen::Matrix4d::Identity());
  // the arm
  EXPECT_EQ(file.arm.source(), urdf.arm.source());
  ExpectSameLink(file.arm.base(), urdf.arm.base());
  for (int i = 0; i < kArmDof; ++i) {
    ExpectSameJoint(file.arm.joint(i), urdf.arm.joint(i));
    ExpectSameLink(file.arm.link(i + 1), urdf.arm.link(i + 1));
  }
  EXPECT_EQ(file.arm.X_7F().matrix(), urdf.arm.X_7F().matrix());
  EXPECT_EQ(file.arm.lower(), urdf.arm.lower());
  EXPECT_EQ(file.arm.upper(), urdf.arm.upper());
  EXPECT_EQ(file.arm.dh_map().identity, urdf.arm.dh_map().identity);
  // the mount and the hand
  EXPECT_EQ(file.X_FH.matrix(), urdf.X_FH.matrix());
  const HandModel& a = file.hand;
  const HandModel& b = urdf.hand;
  EXPECT_EQ(a.source(), b.source());
  ExpectSameLink(a.mount(), b.mount());
  ExpectSameLink(a.palm(), b.palm());
  EXPECT_EQ(a.X_HP().matrix(), b.X_HP().matrix());
  ASSERT_EQ(a.finger_count(), b.finger_count());
  ASSERT_EQ(a.joint_count(), b.joint_count());
  for (int i = 0; i < a.finger_count(); ++i) {
    const Finger& fa = a.finger(i);
    const Finger& fb = b.finger(i);
    EXPECT_EQ(fa.name, fb.name);
    ASSERT_EQ(fa.joints.size(), fb.joints.size());
    for (size_t k = 0; k < fa.joints.size(); ++k) {
      ExpectSameJoint(fa.joints[k].joint, fb.joints[k].joint);
      EXPECT_EQ(fa.joints[k].actuated, fb.joints[k].actuated);
      ASSERT_EQ(fa.joints[k].coupling.has_value(), fb.joints[k].coupling.has_value());
      if (fa.joints[k].coupling) {
        EXPECT_EQ(fa.joints[k].coupling->source, fb.joints[k].coupling->source);
        EXPECT_EQ(fa.joints[k].coupling->multiplier, fb.joints[k].coupling->multiplier);
        EXPECT_EQ(fa.joints[k].coupling->offset, fb.joints[k].coupling->offset);
      }
      ExpectSameLink(fa.links[k], fb.links[k]);
    }
    EXPECT_EQ(fa.tip_name, fb.tip_name);
    EXPECT_EQ(fa.X_LT.matrix(), fb.X_LT.matrix());
  }
  EXPECT_EQ(a.actuated_names(), b.actuated_names());
  EXPECT_EQ(a.lower(), b.lower());
  EXPECT_EQ(a.upper(), b.upper());
  EXPECT_EQ(a.max_velocity(), b.max_velocity());
  EXPECT_EQ(a.max_effort(), b.max_effort());
  // the Gifu's four coupled DIPs, from the file and the URDF's <mimic>s alike.
  int coupled = 0;
  for (int j = 0; j < a.joint_count(); ++j) coupled += a.joint(j).coupling.has_value();
  EXPECT_EQ(coupled, 4);
}

TEST(LoadRobot, Pa10RobotFilesFramesAreTheUrdfLoadersBitForBit) {
  const RobotModel file = LoadRobot(Pa10File());
  const RobotModel urdf = LoadRobotModel(Models() / "pa10_gifu3.urdf");
  std::mt19937_64 rng(52);
  ArmFrames arm_a, arm_b;
  HandFrames hand_a, hand_b;
  for (int k = 0; k < 200; ++k) {
    const Vector7d q = RandomConfiguration(file.arm, &rng);
    EXPECT_EQ(ArmFlangePose(file.arm, q).matrix(), ArmFlangePose(urdf.arm, q).matrix());
    ArmLinkFrames(file.arm, q, &arm_a);
    ArmLinkFrames(urdf.arm, q, &arm_b);
    for (int i = 0; i <= kArmDof; ++i) EXPECT_EQ(arm_a.X_WL[i].matrix(), arm_b.X_WL[i].matrix());
    HandVector f;
    for (int j = 0; j < kHandDof; ++j) {
      f[j] =
          std::uniform_real_distribution<double>(file.hand.lower()[j], file.hand.upper()[j])(rng);
    }
    HandLinkFrames(file.hand, f, &hand_a);
    HandLinkFrames(urdf.hand, f, &hand_b);
    for (int i = 0; i < file.hand.finger_count(); ++i) {
      EXPECT_EQ(hand_a.X_HT[i].matrix(), hand_b.X_HT[i].matrix());
      for (size_t l = 0; l < hand_a.X_HL[i].size(); ++l) {
        EXPECT_EQ(hand_a.X_HL[i][l].matrix(), hand_b.X_HL[i][l].matrix());
      }
    }
  }
}

TEST(LoadRobot, IiwaAllegroLoadsWithFourFingersAndSixteenActuatedJoints) {
  const RobotModel robot = LoadRobot(IiwaFile());
  EXPECT_EQ(robot.name, "iiwa14_allegro");
  EXPECT_EQ(robot.source, IiwaFile().string());
  EXPECT_EQ(robot.X_WB.translation(), Eigen::Vector3d(-0.10, 0.10, 0.0));
  EXPECT_EQ(robot.hand.finger_names(),
            (std::vector<std::string>{"thumb", "index", "middle", "ring"}));
  EXPECT_EQ(robot.hand.joint_count(), 16);
  for (int j = 0; j < robot.hand.joint_count(); ++j) {
    EXPECT_TRUE(robot.hand.joint(j).is_actuated()) << j;
    EXPECT_EQ(robot.hand.joint(j).actuated, j);
  }
  EXPECT_EQ(robot.hand.actuated_names()[0], "thumb_j1");
  EXPECT_EQ(robot.hand.actuated_names()[15], "ring_j4");
  EXPECT_EQ(robot.hand.mount().name, "hand_mount_link");
  EXPECT_EQ(robot.hand.palm().name, "palm");
  EXPECT_EQ(robot.hand.finger(2).tip_name, "middle_tip_link");
  // the URDF's hand_mount: 0.02 m beyond the flange, not turned; the palm on the mount.
  EXPECT_EQ(robot.X_FH.matrix(), Eigen::Isometry3d(Eigen::Translation3d(0, 0, 0.02)).matrix());
  EXPECT_EQ(robot.hand.X_HP().matrix(), Eigen::Matrix4d::Identity());
  EXPECT_NEAR(robot.hand.palm().inertia.mass, 0.4154, 1e-15);
}

TEST(LoadRobot, IiwaAllegroTipsAtZeroAreThoseOfTheUrdfsJointOrigins) {
  // Each tip in H at q = 0: palm_joint is the identity, so p_HT = p_j1 + R_j1 (sum of the
  // origins of j2, j3, j4 and the tip joint, all without rotation), R_j1 = Rz(yaw) Ry(pitch)
  // Rx(roll) of j1's rpy. From models/iiwa14_allegro.urdf:
  //   thumb_j1 xyz (-0.0182, 0.019333, 0.049013) rpy (0, -1.6580627893946132, -pi/2);
  //     then (-0.027, 0.005, 0.0399), (0, 0, 0.0177), (0, 0, 0.0514), tip (0, 0, 0.0423)
  //   index_j1 xyz (0, 0.0435, 0.093458) rpy (-0.08726646259971647, 0, 0);
  //     then (0, 0, 0.0164), (0, 0, 0.054), (0, 0, 0.0384), tip (0, 0, 0.0267)
  //   middle_j1 xyz (0, 0, 0.0957) rpy 0; the index's others
  //   ring_j1 xyz (0, -0.0435, 0.093458) rpy (0.08726646259971647, 0, 0); the index's others
  // worked out by hand (a Python script, not this code):
  const Eigen::Vector3d expected[4] = {
      {-0.01320000000000001, 0.16770405276709432, 0.0089290792738021818},
      {0.0, 0.055309603142307678, 0.22844238159143154},
      {0.0, 0.0, 0.23120000000000002},
      {0.0, -0.055309603142307678, 0.22844238159143154}};
  const RobotModel robot = LoadRobot(IiwaFile());
  HandFrames frames;
  HandLinkFrames(robot.hand, HandVector::Zero(), &frames);
  ASSERT_EQ(frames.X_HT.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_LE((frames.X_HT[i].translation() - expected[i]).norm(), 1e-15)
        << robot.hand.finger(i).name << ": " << frames.X_HT[i].translation().transpose();
  }
  // and in the base frame, with the arm straight up: the flange at 1.306 m (the joints'
  // offsets 0.1575 + 0.2025 + 0.2045 + 0.2155 + 0.1845 + 0.2155 + 0.081 and 0.045 m), H 0.02 m
  // above it, not turned.
  const Eigen::Isometry3d X_BH = ArmFlangePose(robot.arm, Vector7d::Zero()) * robot.X_FH;
  EXPECT_LE((X_BH * frames.X_HT[2].translation() - Eigen::Vector3d(0, 0, 1.326 + 0.2312)).norm(),
            1e-12);
}

TEST(LoadRobot, AUrdfIsLoadedAsTheUrdfLoaderDoes) {
  const RobotModel a = LoadRobot(Models() / "pa10_gifu3.urdf");
  EXPECT_EQ(a.source, (Models() / "pa10_gifu3.urdf").string());
  EXPECT_EQ(a.name, "pa10_gifu3");
  EXPECT_EQ(a.hand.joint_count(), 20);
}

TEST(LoadRobotOption, EmptyIsTheDefaultUrdfANameIsItsRobotFile) {
  const RobotModel none = LoadRobotOption("");
  EXPECT_EQ(none.source, DefaultRobotDescriptionPath().string());
  const RobotModel iiwa = LoadRobotOption("iiwa14_allegro");
  EXPECT_EQ(iiwa.source, IiwaFile().string());
  EXPECT_EQ(LoadRobotOption(Pa10File().string()).name, "pa10_gifu3");
  GS_EXPECT_THROW_WITH(LoadRobotOption("nosuchrobot"), InputError,
                       "expected a shipped robot (iiwa14_allegro, pa10_gifu3;",
                       "found \"nosuchrobot\"");
}

// The iiwa's robot file with its hand part replaced by `hand` (and its URDF by `urdf`).
std::string IiwaWithHand(const std::string& hand, const std::string& urdf = "") {
  const std::string u = urdf.empty() ? (Models() / "iiwa14_allegro.urdf").string() : urdf;
  return R"({"format": "graspsynth-robot/1", "name": "test", "urdf": ")" + u + R"(", "arm": )" +
         ArmJson("base_link", "flange_link") + R"(, "hand": )" + hand + "}";
}

// A finger of the iiwa's hand as a robot file lists it.
std::string FingerJson(const std::string& name, const std::string& joints_or_empty = "",
                       const std::string& tip = "", const std::string& extra = "") {
  const std::string joints =
      joints_or_empty.empty()
          ? "\"" + name + "_j1\", \"" + name + "_j2\", \"" + name + "_j3\", \"" + name + "_j4\""
          : joints_or_empty;
  return R"({"name": ")" + name + R"(", "joints": [)" + joints + R"(], "tip_link": ")" +
         (tip.empty() ? name + "_tip_link" : tip) + "\"" + extra + "}";
}

std::string HandJson(const std::vector<std::string>& fingers,
                     const std::string& mount = "hand_mount_link",
                     const std::string& palm = "palm") {
  std::string list;
  for (const std::string& f : fingers) list += (list.empty() ? "" : ", ") + f;
  return R"({"mount_link": ")" + mount + R"(", "palm_link": ")" + palm +
         R"(", "palm_frame": "gifu", "fingers": [)" + list + "]}";
}

std::vector<std::string> IiwaFingers() {
  return {FingerJson("thumb"), FingerJson("index"), FingerJson("middle"), FingerJson("ring")};
}

TEST(LoadRobot, AHandWrittenAsTheShippedOneLoads) {
  testing::TestFolder dir;
  const fs::path path = Write(dir.path(), "ok.json", IiwaWithHand(HandJson(IiwaFingers())));
  const RobotModel robot = LoadRobot(path);
  EXPECT_EQ(robot.name, "test");
  EXPECT_EQ(robot.X_WB.matrix(), Eigen::Matrix4d::Identity());  // no base: the world's origin
  EXPECT_EQ(robot.hand.joint_count(), 16);
}

TEST(LoadRobot, RefusesBadHandsNamingTheFieldAndTheValue) {
  testing::TestFolder dir;
  int n = 0;
  const auto expect = [&](const std::string& text, const std::vector<std::string>& parts) {
    const fs::path path = Write(dir.path(), "bad" + std::to_string(n++) + ".json", text);
    try {
      LoadRobot(path);
      ADD_FAILURE() << "no error for " << text;
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr(path.string())) << e.what();
      for (const std::string& part : parts) {
        EXPECT_THAT(e.what(), ::testing::HasSubstr(part)) << e.what();
      }
    }
  };
  std::vector<std::string> f = IiwaFingers();
  // no hand at all
  expect(RobotJson(ArmJson("base_link", "flange_link")), {"field 'hand': expected an object"});
  // a joint that does not exist
  f[1] = FingerJson("index", R"("index_j1", "index_j2", "index_j9", "index_j4")");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[1].joints[2]': expected a joint of", "found \"index_j9\""});
  // a chain that is not one: j3 before j2
  f[1] = FingerJson("index", R"("index_j1", "index_j3", "index_j2", "index_j4")");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[1].joints[1]': expected a joint on link 'index_link1' (the child "
          "of joint 'index_j1')",
          "found \"index_j3\" on link 'index_link2'"});
  // a first joint that is not on the palm
  f[1] = FingerJson("index", R"("index_j2", "index_j3", "index_j4")");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[1].joints[0]': expected a joint on link 'palm'"});
  // a joint of the arm
  f[1] = FingerJson("index", R"("A7")");
  expect(IiwaWithHand(HandJson(f)), {"field 'hand.fingers[1].joints[0]'", "found \"A7\""});
  // a joint two fingers name
  f[1] = FingerJson("index", R"("middle_j1", "middle_j2", "middle_j3", "middle_j4")",
                    "middle_tip_link");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[2].joints[0]': expected a joint that no finger names before",
          "found \"middle_j1\" again"});
  f = IiwaFingers();
  // a tip that is not a fixed child of the last joint's link
  f[1] = FingerJson("index", "", "middle_tip_link");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[1].tip_link': expected a link fixed to link 'index_link4'",
          "found \"middle_tip_link\""});
  f[1] = FingerJson("index", R"("index_j1", "index_j2", "index_j3")", "index_link4");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[1].tip_link'", "found \"index_link4\"", "revolute"});
  // a tip with mass: the last phalanx is named as the tip of a finger one joint short
  f[1] = FingerJson("index", R"("index_j1", "index_j2", "index_j3", "index_j4")", "nope");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[1].tip_link': expected a link of", "found \"nope\""});
  f = IiwaFingers();
  // the palm (or the mount) on the arm
  expect(IiwaWithHand(HandJson(f, "hand_mount_link", "A6_link")),
         {"field 'hand.palm_link': expected a link of the hand, below arm.flange_link "
          "'flange_link', found \"A6_link\", a link of the arm"});
  expect(IiwaWithHand(HandJson(f, "flange_link", "palm")),
         {"field 'hand.mount_link'", "found \"flange_link\", a link of the arm"});
  // the palm above the mount: the mount's path from the flange passes the massive mount link
  expect(IiwaWithHand(HandJson(f, "palm", "hand_mount_link")),
         {"field 'hand.mount_link': expected massless frames without collision geometry from "
          "link 'flange_link' down to link 'palm'",
          "found link 'hand_mount_link' with mass or collision geometry"});
  // a palm below the real palm and a revolute joint
  expect(IiwaWithHand(HandJson(f, "hand_mount_link", "index_link1")),
         {"field 'hand.palm_link'", "found link 'palm' with mass"});
  // a coupling loop, and a coupling that follows a joint outside the hand
  f[1] = FingerJson("index", "", "",
                    R"(, "coupled": [{"joint": "index_j3", "follows": "index_j4"},
                                    {"joint": "index_j4", "follows": "index_j3"}])");
  expect(IiwaWithHand(HandJson(f)), {"field 'hand.fingers[1].coupled[", "which is coupled itself",
                                     "the couplings make a loop: index_j"});
  f[1] = FingerJson("index", "", "", R"(, "coupled": [{"joint": "index_j4", "follows": "A7"}])");
  expect(IiwaWithHand(HandJson(f)),
         {"field 'hand.fingers[1].coupled[0]': expected 'index_j4' to follow a joint of the "
          "hand, found \"A7\""});
  // a coupling leaves 15 actuated joints: HandModel refuses the hand
  f[1] =
      FingerJson("index", "", "", R"(, "coupled": [{"joint": "index_j4", "follows": "index_j3"}])");
  expect(IiwaWithHand(HandJson(f)), {"field 'hand.fingers': expected a hand", "16"});
  // three fingers: the ring finger's links are in neither the arm nor the hand
  expect(IiwaWithHand(HandJson({FingerJson("thumb"), FingerJson("index"), FingerJson("middle")})),
         {"field 'hand': expected every link of", "found link 'ring_link1' in neither"});
}

TEST(LoadRobot, RefusesAMassiveLinkOutsideTheArmAndTheHand) {
  testing::TestFolder dir;
  std::ifstream in(Models() / "iiwa14_allegro.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string camera = R"(
  <joint name="camera_mount" type="fixed"><parent link="A3_link"/><child link="camera"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/></joint>
  <link name="camera"><inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="0.2"/>
    <inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  <joint name="marker_mount" type="fixed"><parent link="A3_link"/><child link="marker"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/></joint>
  <link name="marker"/>
</robot>)";
  const std::string massless = R"(
  <joint name="marker_mount" type="fixed"><parent link="A3_link"/><child link="marker"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/></joint>
  <link name="marker"/>
</robot>)";
  const size_t end = urdf.rfind("</robot>");
  ASSERT_NE(end, std::string::npos);
  const fs::path with_camera = Write(dir.path(), "camera.urdf", urdf.substr(0, end) + camera);
  const fs::path with_marker = Write(dir.path(), "marker.urdf", urdf.substr(0, end) + massless);
  const fs::path a =
      Write(dir.path(), "a.json", IiwaWithHand(HandJson(IiwaFingers()), with_camera.string()));
  GS_EXPECT_THROW_WITH(LoadRobot(a), InputError, a.string(), "field 'hand'",
                       "with mass or collision geometry in the arm or the hand, found link "
                       "'camera' in neither");
  // a massless frame elsewhere changes nothing and is let be.
  const fs::path b =
      Write(dir.path(), "b.json", IiwaWithHand(HandJson(IiwaFingers()), with_marker.string()));
  EXPECT_EQ(LoadRobot(b).hand.joint_count(), 16);
}

TEST(LoadRobot, CouplingsOfTheFileAndTheUrdfMustAgree) {
  testing::TestFolder dir;
  std::ifstream in(Pa10File());
  const std::string pa10((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string urdf = (Models() / "pa10_gifu3.urdf").string();
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string text = pa10;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
    const size_t u = text.find("\"pa10_gifu3.urdf\"");
    text.replace(u, 17, "\"" + urdf + "\"");
    return text;
  };
  const std::string coupling =
      R"({"joint": "index_j4", "follows": "index_j3", "ratio": 1.0, "offset": 0.0})";
  const fs::path ratio =
      Write(dir.path(), "ratio.json",
            with(coupling, R"({"joint": "index_j4", "follows": "index_j3", "ratio": 0.5})"));
  GS_EXPECT_THROW_WITH(LoadRobot(ratio), InputError, ratio.string(),
                       "field 'hand.fingers[1].coupled[0]': expected the coupling of the URDF's "
                       "<mimic> of 'index_j4' (follows 'index_j3', ratio 1, offset 0 rad), found "
                       "follows 'index_j3', ratio 0.5, offset 0 rad");
  const fs::path follows = Write(dir.path(), "follows.json",
                                 with(coupling, R"({"joint": "index_j4", "follows": "index_j2"})"));
  GS_EXPECT_THROW_WITH(LoadRobot(follows), InputError, "found follows 'index_j2'");
  // the URDF's <mimic> alone couples the joint: the same model without the file's coupling.
  const fs::path mimic_only =
      Write(dir.path(), "mimic.json", with(R"("coupled": [)" + coupling + "]", R"("coupled": [])"));
  const RobotModel robot = LoadRobot(mimic_only);
  ASSERT_TRUE(robot.hand.finger(1).joints[3].coupling.has_value());
  EXPECT_EQ(robot.hand.finger(1).joints[3].coupling->source, robot.hand.JointIndex(1, 2));
  // a coupled joint may follow a joint of another finger, but not a coupled one.
  const fs::path chain = Write(dir.path(), "chain.json",
                               with(coupling, R"({"joint": "index_j4", "follows": "middle_j4"})"));
  GS_EXPECT_THROW_WITH(LoadRobot(chain), InputError, "found follows 'middle_j4'");
}

TEST(RobotFile, RefusesBadHandFieldsNamingThem) {
  const auto expect_field = [&](const std::string& hand, const std::string& field) {
    GS_EXPECT_THROW_WITH(ParseRobotFile(IiwaWithHand(hand), "h.json", "."), InputError, "h.json",
                         field);
  };
  std::vector<std::string> f = IiwaFingers();
  expect_field(HandJson(f, "palm", "palm"),
               "field 'hand.palm_link': expected a link other than hand.mount_link");
  expect_field(HandJson({}), "field 'hand.fingers': expected a non-empty array of fingers");
  expect_field(HandJson({FingerJson("thumb"), FingerJson("thumb", "", "index_tip_link")}),
               "field 'hand.fingers[1].name': expected a name no finger has before");
  expect_field(HandJson({FingerJson("thumb", "", "", R"(, "role": "pinky")")}),
               "field 'hand.fingers[0].role': expected \"thumb\"");
  expect_field(HandJson({FingerJson("thumb", "", "", R"(, "role": "thumb")"),
                         FingerJson("index", "", "", R"(, "role": "thumb")")}),
               "field 'hand.fingers[1].role': expected one thumb");
  expect_field(HandJson({FingerJson("thumb", R"("a", "a")")}),
               "field 'hand.fingers[0].joints[1]': expected a name not listed before");
  expect_field(HandJson({FingerJson("thumb", R"("a", "")")}),
               "field 'hand.fingers[0].joints[1]': expected a non-empty string");
  expect_field(
      HandJson({FingerJson("thumb", "", "", R"(, "coupled": [{"joint": "x", "follows": "y"}])")}),
      "field 'hand.fingers[0].coupled[0].joint': expected one of the finger's joints");
  expect_field(
      HandJson({FingerJson("thumb", "", "",
                           R"(, "coupled": [{"joint": "thumb_j4", "follows": "thumb_j4"}])")}),
      "field 'hand.fingers[0].coupled[0].follows': expected a joint other than");
  expect_field(
      HandJson({FingerJson(
          "thumb", "", "",
          R"(, "coupled": [{"joint": "thumb_j4", "follows": "thumb_j3", "ratio": "1"}])")}),
      "field 'hand.fingers[0].coupled[0].ratio': expected a finite number");
  expect_field(HandJson({FingerJson("thumb", "", "", R"(, "nail": 1)")}), "hand.fingers[0].nail");
  expect_field(R"({"mount_link": "a", "palm_link": "b", "palm_frame": "shadow", "fingers": []})",
               "field 'hand.palm_frame': expected \"gifu\"");
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
