#include "kinematics/robot_description.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>

#include "common/errors.hpp"
#include "tests/utils/data_dir_override.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::MatricesNear;
using testing::PosesNear;

const std::string& ShippedText() {
  static const std::string text = [] {
    std::ifstream in(testing::ShippedUrdfPath());
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }();
  return text;
}

const RobotModel& Shipped() {
  static const RobotModel robot = LoadRobotModel(testing::ShippedUrdfPath());
  return robot;
}

// Replaces the first `from` inside the element that starts with `start` (e.g. `<joint
// name="S2"`) by `to`. Throws std::logic_error when the test's edit does not apply, so that a
// change to the shipped file cannot silently turn an error test into a no-op.
std::string EditElement(std::string text, const std::string& start, const std::string& from,
                        const std::string& to) {
  const size_t begin = text.find(start);
  if (begin == std::string::npos) throw std::logic_error("no element " + start);
  const std::string tag = start.substr(1, start.find(' ') - 1);
  const size_t end = text.find("</" + tag + ">", begin);
  const size_t at = text.find(from, begin);
  if (at == std::string::npos || at > end) throw std::logic_error("no " + from + " in " + start);
  return text.replace(at, from.size(), to);
}

std::string Joint(const std::string& name) { return "<joint name=\"" + name + "\""; }
std::string Link(const std::string& name) { return "<link name=\"" + name + "\""; }

RobotModel ParseEdited(const std::string& text) { return ParseRobotModel(text, "edited.urdf"); }

// --- the shipped description ---------------------------------------------------------------

TEST(RobotDescription, ShippedFileLoads) {
  const RobotModel& robot = Shipped();
  EXPECT_EQ(robot.source, testing::ShippedUrdfPath());
  EXPECT_EQ(robot.name, "pa10_gifu3");
  EXPECT_EQ(robot.X_WB.matrix(), Eigen::Matrix4d::Identity());
  EXPECT_EQ(robot.arm.source(), testing::ShippedUrdfPath());
  EXPECT_EQ(robot.hand.source(), testing::ShippedUrdfPath());
  const std::array<const char*, kArmDof> joints = {"S1", "S2", "S3", "E1", "E2", "W1", "W2"};
  for (int i = 0; i < kArmDof; ++i) {
    EXPECT_EQ(robot.arm.joint(i).name, joints[i]);
    EXPECT_EQ(robot.arm.link(i + 1).name, std::string(joints[i]) + "_link");
  }
  EXPECT_EQ(robot.arm.base().name, "base_link");
  EXPECT_EQ(robot.hand.mount().name, "hand_mount_link");
  EXPECT_EQ(robot.hand.palm().name, "palm");
  EXPECT_EQ(robot.hand.finger(1).tip_name, "index_tip_link");
  EXPECT_EQ(robot.hand.finger(0).links[3].name, "thumb_link4");
}

TEST(RobotDescription, ArmLengthsAndLimitsAreThoseOfRobotMd) {
  const ArmModel& arm = Shipped().arm;
  EXPECT_NEAR(arm.lengths().d_bs, 0.317, 1e-12);
  EXPECT_NEAR(arm.lengths().d_se, 0.450, 1e-12);
  EXPECT_NEAR(arm.lengths().d_ew, 0.480, 1e-12);
  EXPECT_NEAR(arm.lengths().d_wt, 0.070, 1e-12);
  const ArmModel dh = testing::Pa10FromDh();
  EXPECT_TRUE(MatricesNear(arm.lower(), dh.lower(), 1e-15));
  EXPECT_TRUE(MatricesNear(arm.upper(), dh.upper(), 1e-15));
  EXPECT_TRUE(MatricesNear(arm.max_velocity(), dh.max_velocity(), 1e-15));
  EXPECT_TRUE(MatricesNear(arm.max_effort(), dh.max_effort(), 1e-15));
}

TEST(RobotDescription, FlangePoseEqualsTheDhChainAtRandomConfigurations) {
  const ArmModel& arm = Shipped().arm;
  const ArmModel dh = testing::Pa10FromDh();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ArmFrames frames;
  for (int n = 0; n < 2000; ++n) {
    Vector7d q;
    for (int i = 0; i < kArmDof; ++i) {
      q[i] = arm.lower()[i] + unit(rng) * (arm.upper()[i] - arm.lower()[i]);
    }
    const Eigen::Isometry3d expected = ArmFlangePose(dh, q);
    EXPECT_TRUE(PosesNear(ArmFlangePose(arm, q), expected, 1e-12)) << q.transpose();
    ArmLinkFrames(arm, q, &frames);
    EXPECT_TRUE(PosesNear(frames.X_WL[kArmDof], expected, 1e-12)) << q.transpose();
  }
}

TEST(RobotDescription, ArmLinkFramesAreTheModifiedDhFrames) {
  ArmFrames frames;
  ArmLinkFrames(Shipped().arm, Vector7d::Zero(), &frames);
  // arm straight up: shoulder (S1, S2) at 0.317, elbow (S3, E1) at 0.767, wrist (E2, W1) at
  // 1.247, flange at 1.317; the roll joints' z axes point up, the pitch joints' along +y.
  const std::array<double, kArmDof> z = {0.317, 0.317, 0.767, 0.767, 1.247, 1.247, 1.317};
  for (int i = 1; i <= kArmDof; ++i) {
    EXPECT_TRUE(MatricesNear(frames.X_WL[i].translation(), Eigen::Vector3d(0, 0, z[i - 1]), 1e-12))
        << "link " << i;
    const Eigen::Vector3d axis = i % 2 == 1 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    EXPECT_TRUE(MatricesNear(frames.X_WL[i].linear().col(2), axis, 1e-12)) << "link " << i;
  }
  EXPECT_TRUE(MatricesNear(frames.X_WL[7].linear(), Eigen::Matrix3d::Identity(), 1e-12));
}

TEST(RobotDescription, HandMountIsCoaxialFiveCentimetresBeyondTheFlangeTurnedHalfATurn) {
  Eigen::Isometry3d expected = Eigen::Isometry3d::Identity();
  expected.translate(Eigen::Vector3d(0, 0, 0.05));
  expected.rotate(Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(PosesNear(Shipped().X_FH, expected, 1e-12));
  // at the zero configuration H is 1.367 m up, its x and y opposite to the world's.
  const Eigen::Isometry3d X_WH = ArmFlangePose(Shipped().arm, Vector7d::Zero()) * Shipped().X_FH;
  EXPECT_TRUE(MatricesNear(X_WH.translation(), Eigen::Vector3d(0, 0, 1.367), 1e-12));
  EXPECT_TRUE(MatricesNear(X_WH.linear().col(0), -Eigen::Vector3d::UnitX(), 1e-12));
  EXPECT_TRUE(MatricesNear(X_WH.linear().col(2), Eigen::Vector3d::UnitZ(), 1e-12));
  EXPECT_TRUE(PosesNear(Shipped().hand.X_HP(), Eigen::Isometry3d::Identity(), 1e-15));
}

TEST(RobotDescription, MassesAreThoseOfRobotMd) {
  const ArmModel& arm = Shipped().arm;
  const std::array<double, kArmDof> masses = {9.78, 8.41, 3.51, 4.31, 3.45, 1.46, 0.24};
  double total = arm.base().inertia.mass;
  EXPECT_DOUBLE_EQ(arm.base().inertia.mass, 3.04);
  for (int i = 1; i <= kArmDof; ++i) {
    EXPECT_DOUBLE_EQ(arm.link(i).inertia.mass, masses[i - 1]) << arm.link(i).name;
    total += arm.link(i).inertia.mass;
  }
  EXPECT_NEAR(total, 34.2, 1e-9);                      // "about 34 kg" (robot.md 1.4)
  EXPECT_NEAR(Shipped().hand.total_mass(), 1.5, 0.1);  // 1.4 kg hand + adapter
}

// --- inertias recomputed from the shapes ---------------------------------------------------

double Volume(const CollisionShape& s) {
  const double r = s.size[0];
  const double l = s.size[1];
  switch (s.kind) {
    case CollisionShape::Kind::kBox:
      return s.size.prod();
    case CollisionShape::Kind::kCylinder:
      return M_PI * r * r * l;
    case CollisionShape::Kind::kCapsule:
      return M_PI * r * r * l + 4.0 / 3.0 * M_PI * r * r * r;
    case CollisionShape::Kind::kSphere:
      return 4.0 / 3.0 * M_PI * r * r * r;
    case CollisionShape::Kind::kMesh:  // the robot description has primitives only
      break;
  }
  return 0.0;
}

// inertia of a solid shape of mass m about its centre, in the shape's axes.
Eigen::Matrix3d ShapeInertia(const CollisionShape& s, double m) {
  const double r = s.size[0];
  const double l = s.size[1];
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  switch (s.kind) {
    case CollisionShape::Kind::kBox: {
      const Eigen::Vector3d q = s.size.cwiseAbs2();
      d << q.y() + q.z(), q.x() + q.z(), q.x() + q.y();
      d *= m / 12.0;
      break;
    }
    case CollisionShape::Kind::kCylinder:
      d << m * (3 * r * r + l * l) / 12, m * (3 * r * r + l * l) / 12, m * r * r / 2;
      break;
    case CollisionShape::Kind::kCapsule: {
      // cylinder plus two hemispheres, each hemisphere's centre of mass 3r/8 from its face.
      const double vc = M_PI * r * r * l;
      const double vh = 4.0 / 3.0 * M_PI * r * r * r;
      const double mc = m * vc / (vc + vh);
      const double mh = m * vh / (vc + vh);
      const double axial = mc * r * r / 2 + mh * 2 * r * r / 5;
      const double across =
          mc * (l * l / 12 + r * r / 4) + mh * (2 * r * r / 5 + l * l / 4 + 3 * l * r / 8);
      d << across, across, axial;
      break;
    }
    case CollisionShape::Kind::kSphere:
      d.setConstant(2 * m * r * r / 5);
      break;
    case CollisionShape::Kind::kMesh:  // the robot description has primitives only
      break;
  }
  return d.asDiagonal();
}

void ExpectInertiaFromShapes(const RigidLink& link) {
  SCOPED_TRACE(link.name);
  double volume = 0.0;
  for (const CollisionShape& s : link.shapes) volume += Volume(s);
  const double mass = link.inertia.mass;
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (const CollisionShape& s : link.shapes) {
    com += mass * Volume(s) / volume * s.X_LG.translation();
  }
  com /= mass;
  Eigen::Matrix3d I = Eigen::Matrix3d::Zero();
  for (const CollisionShape& s : link.shapes) {
    const double m = mass * Volume(s) / volume;
    const Eigen::Matrix3d R = s.X_LG.linear();
    const Eigen::Vector3d d = s.X_LG.translation() - com;
    I += R * ShapeInertia(s, m) * R.transpose() +
         m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  EXPECT_TRUE(MatricesNear(link.inertia.p_LCm, com, 1e-8));
  EXPECT_TRUE(MatricesNear(link.inertia.I_Cm, I, 1e-9 * I.norm()));
}

TEST(RobotDescription, InertiasFollowFromThePrimitiveShapes) {
  const RobotModel& robot = Shipped();
  ExpectInertiaFromShapes(robot.arm.base());
  for (int i = 1; i <= kArmDof; ++i) ExpectInertiaFromShapes(robot.arm.link(i));
  ExpectInertiaFromShapes(robot.hand.mount());
  ExpectInertiaFromShapes(robot.hand.palm());
  int without_geometry = 0;
  for (const Finger& finger : robot.hand.fingers()) {
    for (const RigidLink& link : finger.links) {
      if (!link.shapes.empty()) {
        ExpectInertiaFromShapes(link);
        continue;
      }
      // knuckles and the thumb rotator: a small sphere (9-10 mm) at the joint.
      ++without_geometry;
      const double r = finger.name == "thumb" ? 0.010 : 0.009;
      EXPECT_TRUE(MatricesNear(
          link.inertia.I_Cm,
          (2 * link.inertia.mass * r * r / 5 * Eigen::Matrix3d::Identity()).eval(), 1e-15))
          << link.name;
      EXPECT_TRUE(MatricesNear(link.inertia.p_LCm, Eigen::Vector3d::Zero(), 1e-15));
    }
  }
  EXPECT_EQ(without_geometry, robot.hand.finger_count());
}

TEST(RobotDescription, CapsuleConventionIsApplied) {
  const RobotModel& robot = Shipped();
  const RigidLink& proximal = robot.hand.finger(1).links[1];
  ASSERT_EQ(proximal.shapes.size(), 1u);
  EXPECT_EQ(proximal.shapes[0].kind, CollisionShape::Kind::kCapsule);
  EXPECT_TRUE(MatricesNear(proximal.shapes[0].size, Eigen::Vector3d(0.009, 0.045, 0), 1e-15));
  EXPECT_TRUE(
      MatricesNear(proximal.shapes[0].X_LG.translation(), Eigen::Vector3d(0, 0, 0.0225), 1e-15));
  // every phalanx is a capsule, the flange disc a plain cylinder, the palm a box.
  for (const Finger& finger : robot.hand.fingers()) {
    for (size_t k = 1; k < finger.links.size(); ++k) {
      ASSERT_EQ(finger.links[k].shapes.size(), 1u) << finger.links[k].name;
      const CollisionShape& s = finger.links[k].shapes[0];
      EXPECT_EQ(s.kind, CollisionShape::Kind::kCapsule) << finger.links[k].name;
      EXPECT_GE(s.size[0], 0.008);
      EXPECT_LE(s.size[0], 0.009);
    }
  }
  ASSERT_EQ(robot.arm.link(7).shapes.size(), 1u);
  EXPECT_EQ(robot.arm.link(7).shapes[0].kind, CollisionShape::Kind::kCylinder);
  EXPECT_EQ(robot.hand.palm().shapes.at(0).kind, CollisionShape::Kind::kBox);
  EXPECT_TRUE(
      MatricesNear(robot.hand.palm().shapes[0].size, Eigen::Vector3d(0.03, 0.09, 0.10), 1e-15));
  // naming the flange disc "capsule..." turns it into a capsule.
  const RobotModel renamed = ParseEdited(EditElement(ShippedText(), Link("W2_link"), "<collision>",
                                                     "<collision name=\"capsule_disc\">"));
  EXPECT_EQ(renamed.arm.link(7).shapes[0].kind, CollisionShape::Kind::kCapsule);
  EXPECT_TRUE(
      MatricesNear(renamed.arm.link(7).shapes[0].size, Eigen::Vector3d(0.05, 0.015, 0), 1e-15));
}

TEST(RobotDescription, DefaultPathFollowsGraspsynthDataDir) {
  {
    const testing::DataDirOverride data("/opt/graspsynth-data");
    EXPECT_EQ(DefaultRobotDescriptionPath(),
              std::filesystem::path("/opt/graspsynth-data/models/pa10_gifu3.urdf"));
  }
  {
    const testing::DataDirOverride data("");
    EXPECT_EQ(DefaultRobotDescriptionPath(), std::filesystem::path(testing::ShippedUrdfPath()));
  }
  const testing::DataDirOverride data(nullptr);
  EXPECT_EQ(DefaultRobotDescriptionPath(), std::filesystem::path(testing::ShippedUrdfPath()));
}

TEST(RobotDescription, ParsingNeverPrints) {
  ::testing::internal::CaptureStderr();
  ::testing::internal::CaptureStdout();
  EXPECT_THROW(ParseEdited(EditElement(ShippedText(), Joint("S2"), "<limit", "<nolimit")),
               InputError);
  EXPECT_THROW(ParseRobotModel("not xml at all <<<", "junk.urdf"), InputError);
  (void)Shipped();
  EXPECT_EQ(::testing::internal::GetCapturedStdout(), "");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
}

// --- bad descriptions: each names the file and the element ----------------------------------

TEST(RobotDescriptionErrors, MissingArmJoint) {
  GS_EXPECT_THROW_WITH(ParseEdited(EditElement(ShippedText(), Joint("E2"), "\"E2\"", "\"E2b\"")),
                       InputError, "edited.urdf", "arm joint 'E2' is missing");
}

TEST(RobotDescriptionErrors, ArmJointWithoutLimits) {
  // urdfdom itself refuses a revolute joint without <limit>; its reason is passed on.
  GS_EXPECT_THROW_WITH(ParseEdited(EditElement(ShippedText(), Joint("S2"), "<limit", "<nolimit")),
                       InputError, "edited.urdf", "not a valid URDF", "[S2]",
                       "does not specify limits");
}

TEST(RobotDescriptionErrors, ContinuousWristRoll) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("W2"), "\"revolute\"", "\"continuous\"")),
      InputError, "edited.urdf", "arm joint 'W2' is continuous", "must be revolute");
}

TEST(RobotDescriptionErrors, ArmJointOnTheWrongParent) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("E1"), "\"S3_link\"", "\"S2_link\"")),
      InputError, "edited.urdf", "arm joint 'E1' connects 'S2_link' -> 'E1_link'",
      "'S3_link' -> 'E1_link'");
}

// checked before urdfdom reads the file: urdfdom leaks the link tree of a graph with a cycle
// (found by fuzz/urdf_fuzz.cpp).
TEST(RobotDescriptionErrors, JointGraphThatIsNotATree) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("W2"), "\"W1_link\"", "\"W2_link\"")),
      InputError, "edited.urdf: joint 'W2'", "parent and its child are the same link 'W2_link'");
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("W2"), "\"W2_link\"", "\"E2_link\"")),
      InputError, "edited.urdf: joint 'W2'", "link 'E2_link' is already the child of joint 'E2'");
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("S1"), "\"base_link\"", "\"W2_link\"")),
      InputError, "edited.urdf", "the joints make a loop through link", "a tree");
}

TEST(RobotDescriptionErrors, ArmThatIsNotSrs) {
  // the elbow axis moved 2 cm off the upper arm's axis.
  GS_EXPECT_THROW_WITH(ParseEdited(EditElement(ShippedText(), Joint("E1"), "<origin xyz=\"0 0 0\"",
                                               "<origin xyz=\"0.02 0 0\"")),
                       InputError, "edited.urdf", "'S3' and 'E1'", "miss each other");
}

TEST(RobotDescriptionErrors, HandMountThatIsNotFixed) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("hand_mount"), "\"fixed\"", "\"floating\"")),
      InputError, "edited.urdf", "'hand_mount' is floating", "must be fixed");
}

TEST(RobotDescriptionErrors, MissingHandJoint) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("ring_j2"), "\"ring_j2\"", "\"ring_j2b\"")),
      InputError, "edited.urdf", "fingertip joint 'ring_tip' has parent link 'ring_link4'",
      "'ring_link1'", "is joint 'ring_j2' missing?");
}

// a DIP without its <mimic> is actuated: 17 actuated joints.
TEST(RobotDescriptionErrors, DipWithoutMimic) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("middle_j4"), "<mimic", "<nomimic")), InputError,
      "edited.urdf", "the hand has 17 actuated joints", "needs 16");
}

// a coupling is what the URDF says: index_j4 may follow index_j2.
TEST(RobotDescription, ADipFollowsTheJointItsMimicNames) {
  const RobotModel robot = ParseEdited(
      EditElement(ShippedText(), Joint("index_j4"), "joint=\"index_j3\"", "joint=\"index_j2\""));
  const HandJoint& dip = robot.hand.finger(1).joints[3];
  ASSERT_TRUE(dip.coupling.has_value());
  EXPECT_EQ(dip.coupling->source, robot.hand.JointIndex(1, 1));
}

TEST(RobotDescriptionErrors, MimicOfACoupledJoint) {
  GS_EXPECT_THROW_WITH(ParseEdited(EditElement(ShippedText(), Joint("index_j4"),
                                               "joint=\"index_j3\"", "joint=\"middle_j4\"")),
                       InputError, "'index_j4' mimics 'middle_j4'",
                       "must mimic an actuated hand joint");
}

// a thumb joint with a <mimic> is coupled: 15 actuated joints.
TEST(RobotDescriptionErrors, ThumbJointWithMimic) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("thumb_j4"), "<limit",
                              "<mimic joint=\"thumb_j3\" multiplier=\"1\" offset=\"0\"/>\n<limit")),
      InputError, "edited.urdf", "the hand has 15 actuated joints");
}

TEST(RobotDescriptionErrors, PalmJointNotNamedAsAFingersFirst) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Joint("ring_j1"), "\"ring_j1\"", "\"ring_base\"")),
      InputError, "edited.urdf", "'ring_base' on the palm", "<finger>_j1");
}

TEST(RobotDescriptionErrors, MeshGeometry) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Link("W1_link"),
                              "<geometry><cylinder radius=\"0.05\" length=\"0.05\"/></geometry>",
                              "<geometry><mesh filename=\"package://pa10/w1.stl\"/></geometry>")),
      InputError, "edited.urdf", "link 'W1_link' has a mesh collision geometry");
}

TEST(RobotDescriptionErrors, LinkWithoutMass) {
  GS_EXPECT_THROW_WITH(ParseEdited(EditElement(ShippedText(), Link("E1_link"),
                                               "<mass value=\"4.31\"/>", "<mass value=\"0\"/>")),
                       InputError, "edited.urdf", "link 'E1_link' needs a positive mass");
}

TEST(RobotDescriptionErrors, NonPhysicalInertia) {
  GS_EXPECT_THROW_WITH(
      ParseEdited(EditElement(ShippedText(), Link("index_link3"), "ixx=\"", "ixx=\"1")), InputError,
      "link 'index_link3' has a non-physical inertia");
}

TEST(RobotDescriptionErrors, LinkOutsideTheModel) {
  const std::string camera =
      "  <link name=\"camera\"/>\n  <joint name=\"camera_mount\" type=\"fixed\">\n"
      "    <parent link=\"palm\"/>\n    <child link=\"camera\"/>\n  </joint>\n</robot>";
  std::string text = ShippedText();
  text.replace(text.rfind("</robot>"), 8, camera);
  GS_EXPECT_THROW_WITH(ParseEdited(text), InputError, "edited.urdf",
                       "link 'camera' is not part of the PA-10-7C + Gifu Hand III model");
}

TEST(RobotDescriptionErrors, FingertipFrameWithGeometry) {
  std::string text = ShippedText();
  const std::string tip = "<link name=\"little_tip_link\"/>";
  text.replace(text.find(tip), tip.size(),
               "<link name=\"little_tip_link\"><collision><geometry><sphere radius=\"0.01\"/>"
               "</geometry></collision></link>");
  GS_EXPECT_THROW_WITH(ParseEdited(text), InputError, "fingertip frame 'little_tip_link'");
}

TEST(RobotDescriptionErrors, MissingFile) {
  GS_EXPECT_THROW_WITH(LoadRobotModel("/nonexistent/dir/robot.urdf"), InputError,
                       "cannot read robot description '/nonexistent/dir/robot.urdf': no such file");
}

TEST(RobotDescriptionErrors, NotXml) {
  GS_EXPECT_THROW_WITH(ParseRobotModel("this is not XML <<< >", "junk.urdf"), InputError,
                       "junk.urdf", "not a valid URDF");
  GS_EXPECT_THROW_WITH(ParseRobotModel("", "empty.urdf"), InputError, "empty.urdf",
                       "not a valid URDF");
}

TEST(RobotDescriptionErrors, XmlThatIsNotUrdf) {
  GS_EXPECT_THROW_WITH(
      ParseRobotModel("<?xml version=\"1.0\"?>\n<scene><table/></scene>\n", "scene.xml"),
      InputError, "scene.xml", "not a valid URDF", "'robot' element");
}

TEST(RobotDescriptionErrors, RootOtherThanTheBase) {
  std::string text = ShippedText();
  const std::string robot = "<robot name=\"pa10_gifu3\">";
  const std::string world =
      robot +
      "\n  <link name=\"world\"/>\n  <joint name=\"world_fixed\" type=\"fixed\">"
      "<parent link=\"world\"/><child link=\"base_link\"/></joint>\n";
  text.replace(text.find(robot), robot.size(), world);
  GS_EXPECT_THROW_WITH(ParseEdited(text), InputError, "the root link is 'world'", "'base_link'");
}

}  // namespace
}  // namespace graspsynth
