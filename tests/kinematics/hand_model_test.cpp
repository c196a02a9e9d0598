#include "kinematics/hand_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Deg;
using testing::MatricesNear;

constexpr int kThumb = 0;
constexpr int kIndex = 1;
constexpr int kMiddle = 2;
constexpr int kRing = 3;
constexpr int kLittle = 4;
// the Gifu's layout, written out: five fingers of four joints.
constexpr int kGifuFingers = 5;
constexpr int kGifuFingerJoints = 4;
const std::array<std::string, kGifuFingers> kGifuNames = {"thumb", "index", "middle", "ring",
                                                          "little"};

const HandModel& Hand() {
  static const RobotModel robot = LoadRobotModel(testing::ShippedUrdfPath());
  return robot.hand;
}

// index into HandVector of joint `joint` (0-based) of `finger` (models/README.md's f0..f15).
int F(int finger, int joint) { return finger == kThumb ? joint : 4 + 3 * (finger - 1) + joint; }

// the documented layout of models/README.md, written out independently of the URDF.
struct FingerLayout {
  Eigen::Vector3d p_HM;  // MCP point in H
  double l1, l2, l3;     // phalanx lengths, m
};
const std::array<FingerLayout, kGifuFingers> kLayout = {{
    {Eigen::Vector3d::Zero(), 0.045, 0.032, 0.028},  // thumb: see ThumbBase() / ThumbAxis()
    {Eigen::Vector3d(0, 0.033, 0.098), 0.045, 0.028, 0.023},
    {Eigen::Vector3d(0, 0.011, 0.100), 0.045, 0.028, 0.023},
    {Eigen::Vector3d(0, -0.011, 0.094), 0.045, 0.028, 0.023},
    {Eigen::Vector3d(0, -0.033, 0.088), 0.035, 0.020, 0.020},
}};
Eigen::Vector3d ThumbBase() { return {0.015, 0.060, 0.030}; }
Eigen::Vector3d ThumbAxis() { return Eigen::Vector3d(0.84, -0.50, 0.21).normalized(); }
// the thumb's pad direction at zero: -y of H made perpendicular to the thumb's axis.
Eigen::Vector3d ThumbPadAtZero() {
  const Eigen::Vector3d u = ThumbAxis();
  return (-Eigen::Vector3d::UnitY() + u.y() * u).normalized();
}

HandFrames Fk(const HandVector& f) {
  HandFrames frames;
  HandLinkFrames(Hand(), f, &frames);
  return frames;
}

TEST(HandModel, ActuatedJointsAreNumberedThumbFirst) {
  const std::array<std::string, kHandDof> expected = {
      "thumb_j1", "thumb_j2",  "thumb_j3",  "thumb_j4",  "index_j1", "index_j2",
      "index_j3", "middle_j1", "middle_j2", "middle_j3", "ring_j1",  "ring_j2",
      "ring_j3",  "little_j1", "little_j2", "little_j3"};
  for (int k = 0; k < kHandDof; ++k) {
    EXPECT_EQ(Hand().actuated_names()[k], expected[k]) << "f" << k;
    EXPECT_EQ(Hand().joint(Hand().actuated_joint_index(k)).joint.name, expected[k]);
  }
  ASSERT_EQ(Hand().finger_count(), kGifuFingers);
  ASSERT_EQ(Hand().joint_count(), kGifuFingers * kGifuFingerJoints);
  for (int i = 0; i < kGifuFingers; ++i) EXPECT_EQ(Hand().finger(i).name, kGifuNames[i]);
  EXPECT_EQ(Hand().finger_names(), std::vector<std::string>(kGifuNames.begin(), kGifuNames.end()));
  for (int j = 0; j < Hand().joint_count(); ++j) {
    EXPECT_EQ(Hand().joint_finger(j), j / kGifuFingerJoints);
    EXPECT_EQ(Hand().joint_in_finger(j), j % kGifuFingerJoints);
    EXPECT_EQ(Hand().JointIndex(j / kGifuFingerJoints, j % kGifuFingerJoints), j);
    EXPECT_EQ(Hand().is_distal(j), j % kGifuFingerJoints == kGifuFingerJoints - 1);
    EXPECT_EQ(&Hand().link(j), &Hand().finger(j / 4).links[static_cast<size_t>(j % 4)]);
  }
}

TEST(HandModel, LimitsSpeedsAndEffortsAreTheDocumentedOnes) {
  const HandModel& hand = Hand();
  for (int k = 0; k < 4; ++k) EXPECT_DOUBLE_EQ(hand.max_effort()[F(kThumb, k)], 2.0);
  EXPECT_DOUBLE_EQ(hand.lower()[F(kThumb, 0)], 0.0);
  EXPECT_DOUBLE_EQ(hand.upper()[F(kThumb, 0)], Deg(90));
  EXPECT_DOUBLE_EQ(hand.lower()[F(kThumb, 1)], -Deg(40));
  EXPECT_DOUBLE_EQ(hand.upper()[F(kThumb, 1)], Deg(40));
  EXPECT_DOUBLE_EQ(hand.lower()[F(kThumb, 2)], -Deg(10));
  EXPECT_DOUBLE_EQ(hand.upper()[F(kThumb, 2)], Deg(90));
  EXPECT_DOUBLE_EQ(hand.lower()[F(kThumb, 3)], 0.0);
  EXPECT_DOUBLE_EQ(hand.upper()[F(kThumb, 3)], Deg(90));
  for (int i = kIndex; i <= kLittle; ++i) {
    EXPECT_DOUBLE_EQ(hand.lower()[F(i, 0)], -Deg(20));
    EXPECT_DOUBLE_EQ(hand.upper()[F(i, 0)], Deg(20));
    EXPECT_DOUBLE_EQ(hand.lower()[F(i, 1)], -Deg(10));
    EXPECT_DOUBLE_EQ(hand.upper()[F(i, 1)], Deg(90));
    EXPECT_DOUBLE_EQ(hand.lower()[F(i, 2)], 0.0);
    EXPECT_DOUBLE_EQ(hand.upper()[F(i, 2)], Deg(90));
    EXPECT_DOUBLE_EQ(hand.max_effort()[F(i, 0)], 0.2);
    EXPECT_DOUBLE_EQ(hand.max_effort()[F(i, 1)], 0.5);
    EXPECT_DOUBLE_EQ(hand.max_effort()[F(i, 2)], 0.5);
    // the coupled DIP keeps its own limits: 0..90 deg, 0.5 N m.
    const RevoluteJoint& dip = hand.finger(i).joints[3].joint;
    EXPECT_DOUBLE_EQ(dip.lower, 0.0);
    EXPECT_DOUBLE_EQ(dip.upper, Deg(90));
    EXPECT_DOUBLE_EQ(dip.max_effort, 0.5);
  }
  EXPECT_TRUE((hand.max_velocity().array() == 4.0).all());
  EXPECT_TRUE(hand.WithinLimits(HandVector::Zero()));
  HandVector f = HandVector::Zero();
  f[F(kIndex, 2)] = -0.01;
  EXPECT_FALSE(hand.WithinLimits(f));
  EXPECT_TRUE(hand.WithinLimits(f, 0.02));
}

TEST(HandModel, EachDipFollowsItsPipOneToOne) {
  for (int i = 0; i < kGifuFingers; ++i) {
    for (int k = 0; k < kGifuFingerJoints; ++k) {
      const HandJoint& hj = Hand().finger(i).joints[k];
      const bool dip = i != kThumb && k == 3;
      EXPECT_EQ(hj.is_actuated(), !dip) << hj.joint.name;
      if (!dip) continue;
      ASSERT_TRUE(hj.coupling.has_value());
      EXPECT_EQ(hj.coupling->source, Hand().JointIndex(i, 2)) << hj.joint.name;
      EXPECT_DOUBLE_EQ(hj.coupling->multiplier, 1.0);
      EXPECT_DOUBLE_EQ(hj.coupling->offset, 0.0);
    }
  }
}

TEST(HandModel, MassIsThatOfAHumanSizedHand) {
  // palm and fingers 1.40 kg (robot.md 2.3) plus the 0.10 kg adapter.
  EXPECT_NEAR(Hand().total_mass(), 1.50, 1e-9);
  for (const Finger& finger : Hand().fingers()) {
    for (const RigidLink& link : finger.links) EXPECT_GE(link.inertia.mass, 0.015) << link.name;
  }
}

TEST(HandJointPositions, CopiesTheActuatedJointsAndDrivesEachDipFromItsPip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  HandVector f;
  for (int k = 0; k < kHandDof; ++k) f[k] = u(rng);
  const HandJointVector q = HandJointPositions(Hand(), f);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(q[Hand().JointIndex(kThumb, k)], f[k]);
  for (int i = kIndex; i <= kLittle; ++i) {
    for (int k = 0; k < 3; ++k) EXPECT_EQ(q[Hand().JointIndex(i, k)], f[F(i, k)]);
    EXPECT_EQ(q[Hand().JointIndex(i, 3)], f[F(i, 2)]);
  }
}

TEST(HandFk, AllJointsZeroPutTheFingersStraightAlongZ) {
  const HandFrames frames = Fk(HandVector::Zero());
  EXPECT_TRUE(testing::PosesNear(frames.X_HP, Eigen::Isometry3d::Identity(), 1e-15));
  for (int i = kIndex; i <= kLittle; ++i) {
    const FingerLayout& l = kLayout[i];
    const Eigen::Vector3d tip = l.p_HM + Eigen::Vector3d(0, 0, l.l1 + l.l2 + l.l3);
    EXPECT_TRUE(MatricesNear(frames.X_HT[i].translation(), tip, 1e-12)) << kGifuNames[i];
    EXPECT_TRUE(MatricesNear(frames.X_HT[i].linear(), Eigen::Matrix3d::Identity(), 1e-12));
    // the joints sit at the MCP and at the end of each phalanx.
    EXPECT_TRUE(MatricesNear(frames.X_HL[i][1].translation(), l.p_HM, 1e-12));
    EXPECT_TRUE(
        MatricesNear(frames.X_HL[i][2].translation(), l.p_HM + Eigen::Vector3d(0, 0, l.l1), 1e-12));
    EXPECT_TRUE(MatricesNear(frames.X_HL[i][3].translation(),
                             l.p_HM + Eigen::Vector3d(0, 0, l.l1 + l.l2), 1e-12));
  }
  // middle finger: 0.100 + 0.045 + 0.028 + 0.023.
  EXPECT_NEAR(frames.X_HT[kMiddle].translation().z(), 0.196, 1e-12);
}

TEST(HandFk, IndexMcpFlexionOfNinetyDegreesPointsTheIndexAlongX) {
  HandVector f = HandVector::Zero();
  f[F(kIndex, 1)] = Deg(90);
  const HandFrames frames = Fk(f);
  const FingerLayout& l = kLayout[kIndex];
  const Eigen::Vector3d tip = l.p_HM + Eigen::Vector3d(l.l1 + l.l2 + l.l3, 0, 0);
  EXPECT_TRUE(MatricesNear(frames.X_HT[kIndex].translation(), tip, 1e-12));
  for (int k = 1; k < kGifuFingerJoints; ++k) {
    EXPECT_TRUE(
        MatricesNear(frames.X_HL[kIndex][k].linear().col(2), Eigen::Vector3d::UnitX(), 1e-12));
  }
  // the other fingers did not move.
  EXPECT_NEAR(frames.X_HT[kMiddle].translation().z(), 0.196, 1e-12);
}

TEST(HandFk, PipFlexionBendsTheDipByTheSameAngle) {
  HandVector f = HandVector::Zero();
  f[F(kMiddle, 2)] = Deg(45);  // PIP 45 deg, so the DIP is 45 deg too: the distal is at 90 deg
  const HandFrames frames = Fk(f);
  const FingerLayout& l = kLayout[kMiddle];
  const double s = std::sqrt(0.5);
  const Eigen::Vector3d tip = l.p_HM + Eigen::Vector3d(0, 0, l.l1) +
                              l.l2 * Eigen::Vector3d(s, 0, s) + l.l3 * Eigen::Vector3d(1, 0, 0);
  EXPECT_TRUE(MatricesNear(frames.X_HT[kMiddle].translation(), tip, 1e-12));
  EXPECT_TRUE(
      MatricesNear(frames.X_HL[kMiddle][3].linear().col(2), Eigen::Vector3d::UnitX(), 1e-12));
  // the pad of the distal phalanx (its x axis) now faces back toward the wrist.
  EXPECT_TRUE(MatricesNear(frames.X_HT[kMiddle].linear().col(0), -Eigen::Vector3d::UnitZ(), 1e-12));
}

TEST(HandFk, AbductionTurnsTheFingerAboutX) {
  HandVector f = HandVector::Zero();
  f[F(kLittle, 0)] = Deg(20);
  f[F(kIndex, 0)] = -Deg(20);
  const HandFrames frames = Fk(f);
  for (const auto& [finger, angle] : {std::pair{kLittle, Deg(20)}, std::pair{kIndex, -Deg(20)}}) {
    const FingerLayout& l = kLayout[finger];
    const double length = l.l1 + l.l2 + l.l3;
    // positive ab/adduction turns the finger toward -y.
    const Eigen::Vector3d tip =
        l.p_HM + length * Eigen::Vector3d(0, -std::sin(angle), std::cos(angle));
    EXPECT_TRUE(MatricesNear(frames.X_HT[finger].translation(), tip, 1e-12)) << kGifuNames[finger];
  }
  // flexion turns about the abducted finger's own y axis: at 90 deg the finger points along +x
  // whatever its abduction.
  f[F(kLittle, 1)] = Deg(90);
  const HandFrames bent = Fk(f);
  const FingerLayout& l = kLayout[kLittle];
  EXPECT_TRUE(MatricesNear(bent.X_HT[kLittle].translation(),
                           l.p_HM + Eigen::Vector3d(l.l1 + l.l2 + l.l3, 0, 0), 1e-12));
}

TEST(HandFk, StraightThumbLiesAlongItsRestAxisWhateverItsRotation) {
  const Eigen::Vector3d tip = ThumbBase() + (0.045 + 0.032 + 0.028) * ThumbAxis();
  HandVector f = HandVector::Zero();
  EXPECT_TRUE(MatricesNear(Fk(f).X_HT[kThumb].translation(), tip, 1e-12));
  EXPECT_TRUE(MatricesNear(Fk(f).X_HT[kThumb].linear().col(0), ThumbPadAtZero(), 1e-12));
  // j1 turns the thumb about its own axis: the tip stays, the pad turns to face the fingers.
  f[F(kThumb, 0)] = Deg(90);
  const HandFrames opposed = Fk(f);
  EXPECT_TRUE(MatricesNear(opposed.X_HT[kThumb].translation(), tip, 1e-12));
  // the pad has turned by 90 deg about -u: from -y (made perpendicular to u) to u x y, which
  // lies in the x-z plane and faces the fingertips.
  const Eigen::Vector3d pad = ThumbAxis().cross(Eigen::Vector3d::UnitY()).normalized();
  EXPECT_TRUE(MatricesNear(opposed.X_HT[kThumb].linear().col(0), pad, 1e-12));
  EXPECT_GT(pad.z(), 0.95);
}

TEST(HandFk, ThumbAtKnownConfigurations) {
  const Eigen::Vector3d B = ThumbBase();
  const Eigen::Vector3d u = ThumbAxis();
  const Eigen::Vector3d x0 = ThumbPadAtZero();
  // MCP flexed 90 deg: the proximal and distal phalanges point along the pad direction.
  HandVector f = HandVector::Zero();
  f[F(kThumb, 2)] = Deg(90);
  EXPECT_TRUE(MatricesNear(Fk(f).X_HT[kThumb].translation(), B + 0.045 * u + 0.060 * x0, 1e-12));
  // opposed (j1 = 90 deg) and MCP flexed 90 deg: the pad direction has turned by -90 deg about
  // u, to x0 x u.
  f[F(kThumb, 0)] = Deg(90);
  const Eigen::Vector3d pad90 = x0.cross(u);
  EXPECT_GT(pad90.z(), 0.9);
  EXPECT_TRUE(MatricesNear(Fk(f).X_HT[kThumb].translation(), B + 0.045 * u + 0.060 * pad90, 1e-12));
  // IP flexed 90 deg only: the distal phalanx alone points along the pad.
  f = HandVector::Zero();
  f[F(kThumb, 3)] = Deg(90);
  EXPECT_TRUE(MatricesNear(Fk(f).X_HT[kThumb].translation(), B + 0.077 * u + 0.028 * x0, 1e-12));
}

TEST(HandFk, ThumbFlexesAcrossThePalmAtZeroAndTowardTheFingersWhenOpposed) {
  const auto tip_velocity_of_mcp_flexion = [](double j1) {
    HandVector f = HandVector::Zero();
    f[F(kThumb, 0)] = j1;
    const Eigen::Vector3d p0 = Fk(f).X_HT[kThumb].translation();
    f[F(kThumb, 2)] += 1e-6;
    return ((Fk(f).X_HT[kThumb].translation() - p0) / 1e-6).normalized().eval();
  };
  EXPECT_LT(tip_velocity_of_mcp_flexion(0.0).y(), -0.8);     // toward the little finger
  EXPECT_GT(tip_velocity_of_mcp_flexion(Deg(90)).z(), 0.9);  // toward the fingertips
  EXPECT_GT(tip_velocity_of_mcp_flexion(Deg(80)).z(), 0.8);
}

TEST(HandFk, ThumbAndFingertipsPinchABar) {
  // models/README.md's pinch: index and middle at MCP 55 deg, PIP = DIP 25 deg; the thumb
  // opposed at (90, 0, 30, 10) deg. A 24 mm bar across the palm (along y) fits between the
  // 8 mm pads.
  HandVector f = HandVector::Zero();
  f.head<4>() << Deg(90), 0.0, Deg(30), Deg(10);
  for (int i : {kIndex, kMiddle}) {
    f[F(i, 1)] = Deg(55);
    f[F(i, 2)] = Deg(25);
  }
  ASSERT_TRUE(Hand().WithinLimits(f));
  const HandFrames frames = Fk(f);
  const Eigen::Vector3d thumb = frames.X_HT[kThumb].translation();
  const double gap = 0.024 + 2 * 0.008;
  for (int i : {kIndex, kMiddle}) {
    const Eigen::Vector3d d = frames.X_HT[i].translation() - thumb;
    EXPECT_NEAR(d.x(), 0.0, 0.003) << kGifuNames[i];
    EXPECT_NEAR(d.z(), gap, 0.003) << kGifuNames[i];
    // the finger pads face the thumb (-z), the thumb pad faces the fingers (+z).
    EXPECT_LT(frames.X_HT[i].linear().col(0).z(), -0.9);
  }
  EXPECT_GT(frames.X_HT[kThumb].linear().col(0).z(), 0.5);
  // the thumb tip lies between the two fingers along the bar.
  EXPECT_GT(thumb.y(), kLayout[kMiddle].p_HM.y());
  EXPECT_LT(thumb.y(), kLayout[kIndex].p_HM.y());
  // the bar (centred at the thumb tip's depth) clears the palm face x = 0.015.
  EXPECT_GT(thumb.x() - 0.012, 0.015);
}

TEST(HandFk, FingertipsMoveContinuously) {
  // a joint turning by dq moves a point at distance r from its axis by at most r * dq; no
  // point of the hand is farther than 0.12 m from any of its finger's joints.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> step(-1e-3, 1e-3);
  const HandModel& hand = Hand();
  HandVector f;
  for (int k = 0; k < kHandDof; ++k) {
    f[k] = hand.lower()[k] + unit(rng) * (hand.upper()[k] - hand.lower()[k]);
  }
  HandFrames previous = Fk(f);
  double largest = 0.0;
  for (int n = 0; n < 2000; ++n) {
    HandVector df;
    for (int k = 0; k < kHandDof; ++k) df[k] = step(rng);
    const HandVector g = (f + df).cwiseMax(hand.lower()).cwiseMin(hand.upper());
    const HandJointVector dq = HandJointPositions(hand, g) - HandJointPositions(hand, f);
    const HandFrames next = Fk(g);
    for (int i = 0; i < kGifuFingers; ++i) {
      const double moved = (next.X_HT[i].translation() - previous.X_HT[i].translation()).norm();
      const double bound =
          0.12 * dq.segment(hand.JointIndex(i, 0), kGifuFingerJoints).cwiseAbs().sum();
      EXPECT_LE(moved, bound + 1e-12) << kGifuNames[i] << " at step " << n;
      largest = std::max(largest, moved);
    }
    f = g;
    previous = next;
  }
  EXPECT_LT(largest, 1e-3);
}

TEST(HandFk, LinkFramesChainThroughTheJoints) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  HandVector f;
  for (int k = 0; k < kHandDof; ++k) f[k] = u(rng);
  const HandFrames frames = Fk(f);
  const HandJointVector q = HandJointPositions(Hand(), f);
  for (int i = 0; i < kGifuFingers; ++i) {
    const Finger& finger = Hand().finger(i);
    Eigen::Isometry3d X = frames.X_HP;
    for (int k = 0; k < kGifuFingerJoints; ++k) {
      const RevoluteJoint& j = finger.joints[k].joint;
      X = X * j.X_PJ * Eigen::AngleAxisd(q[Hand().JointIndex(i, k)], j.axis_J);
      EXPECT_TRUE(testing::PosesNear(frames.X_HL[i][k], X, 1e-12)) << j.name;
      EXPECT_TRUE(
          MatricesNear((frames.X_HL[i][k].linear().transpose() * frames.X_HL[i][k].linear()).eval(),
                       Eigen::Matrix3d::Identity(), 1e-12));
    }
    EXPECT_TRUE(testing::PosesNear(frames.X_HT[i], X * finger.X_LT, 1e-12));
  }
}

// a copy of the shipped hand's parts, to build broken hands from.
struct HandParts {
  RigidLink mount = Hand().mount();
  RigidLink palm = Hand().palm();
  std::vector<Finger> fingers = Hand().fingers();
  HandModel Build() const {
    return HandModel("hand.urdf", mount, palm, Eigen::Isometry3d::Identity(), fingers);
  }
};

TEST(HandModel, RejectsTwoJointsDrivingTheSameActuatedIndex) {
  HandParts parts;
  parts.fingers[kIndex].joints[2].actuated = F(kIndex, 1);
  GS_EXPECT_THROW_WITH(parts.Build(), InputError, "hand.urdf", "'index_j3'", "already used",
                       "'index_j2'");
}

TEST(HandModel, RejectsACouplingToACoupledJoint) {
  HandParts parts;
  parts.fingers[kRing].joints[3].coupling->source = Hand().JointIndex(kMiddle, 3);
  GS_EXPECT_THROW_WITH(parts.Build(), InputError, "'ring_j4'", "must follow an actuated");
}

TEST(HandModel, RejectsAJointThatIsNeitherActuatedNorCoupled) {
  HandParts parts;
  parts.fingers[kMiddle].joints[3].coupling.reset();
  GS_EXPECT_THROW_WITH(parts.Build(), InputError, "'middle_j4'", "neither actuated nor coupled");
}

TEST(HandModel, RejectsAnEmptyRangeAndAMasslessPhalanx) {
  HandParts parts;
  parts.fingers[kThumb].joints[1].joint.lower = 1.0;
  parts.fingers[kThumb].joints[1].joint.upper = 0.5;
  GS_EXPECT_THROW_WITH(parts.Build(), InputError, "'thumb_j2'", "empty position range");
  HandParts massless;
  massless.fingers[kLittle].links[2].inertia.mass = 0.0;
  GS_EXPECT_THROW_WITH(massless.Build(), InputError, "'little_link3'", "positive mass");
}

TEST(HandModel, TakesTheFingersInTheGivenOrder) {
  HandParts parts;
  std::swap(parts.fingers[kIndex], parts.fingers[kMiddle]);
  const HandModel hand = parts.Build();
  EXPECT_EQ(hand.finger(kIndex).name, "middle");
  EXPECT_EQ(hand.finger(kMiddle).name, "index");
  // f4 is still index_j1, now the first joint of finger 2.
  EXPECT_EQ(hand.actuated_joint_index(F(kIndex, 0)), hand.JointIndex(kMiddle, 0));
  EXPECT_EQ(hand.joint(hand.actuated_joint_index(F(kIndex, 0))).joint.name, "index_j1");
}

// Renumbers the actuated joints of `parts` f0, f1, ... in finger order and points each coupling
// at its source's new index (by the source joint's name in `before`).
void Renumber(const HandModel& before, HandParts* parts) {
  std::vector<std::string> names;
  for (const Finger& finger : parts->fingers) {
    for (const HandJoint& hj : finger.joints) names.push_back(hj.joint.name);
  }
  int actuated = 0;
  for (Finger& finger : parts->fingers) {
    for (HandJoint& hj : finger.joints) {
      if (hj.is_actuated()) hj.actuated = actuated++;
      if (!hj.coupling) continue;
      const std::string& source = before.joint(hj.coupling->source).joint.name;
      hj.coupling->source =
          static_cast<int>(std::find(names.begin(), names.end(), source) - names.begin());
    }
  }
}

TEST(HandModel, HoldsAnyNumberOfFingersOfAnyNumberOfJoints) {
  // thumb 4, index 4 and middle 4 joints all actuated, ring as shipped (DIP coupled), little
  // cut to its first joint: 16 actuated of 17 joints.
  HandParts parts;
  for (int i : {kIndex, kMiddle}) {
    HandJoint& dip = parts.fingers[static_cast<size_t>(i)].joints[3];
    dip.coupling.reset();
    dip.actuated = 0;  // renumbered below
  }
  Finger& little = parts.fingers[kLittle];
  little.joints.resize(1);
  little.links.resize(1);
  Renumber(Hand(), &parts);
  const HandModel hand = parts.Build();
  EXPECT_EQ(hand.finger_count(), 5);
  EXPECT_EQ(hand.joint_count(), 17);
  EXPECT_EQ(hand.JointIndex(kLittle, 0), 16);
  EXPECT_EQ(hand.joint_finger(16), kLittle);
  EXPECT_TRUE(hand.is_distal(16));
  EXPECT_FALSE(hand.is_distal(hand.JointIndex(kRing, 2)));
  EXPECT_EQ(hand.joint(hand.JointIndex(kRing, 3)).coupling->source, hand.JointIndex(kRing, 2));
  EXPECT_EQ(hand.actuated_names()[15], "little_j1");

  HandVector f;
  for (int k = 0; k < kHandDof; ++k) f[k] = 0.01 * (k + 1);
  const HandJointVector q = HandJointPositions(hand, f);
  ASSERT_EQ(q.size(), 17);
  EXPECT_EQ(q[hand.JointIndex(kRing, 3)], q[hand.JointIndex(kRing, 2)]);
  EXPECT_EQ(q[16], f[15]);
  HandFrames frames;
  HandLinkFrames(hand, f, &frames);
  ASSERT_EQ(frames.X_HL.size(), 5u);
  EXPECT_EQ(frames.X_HL[kLittle].size(), 1u);
  EXPECT_EQ(frames.X_HL[kIndex].size(), 4u);
  EXPECT_TRUE(
      testing::PosesNear(frames.X_HT[kLittle], frames.X_HL[kLittle][0] * little.X_LT, 1e-15));
}

TEST(HandModel, RejectsOtherThanSixteenActuatedJoints) {
  HandParts parts;
  parts.fingers[kThumb].joints[3].actuated = -1;
  parts.fingers[kThumb].joints[3].coupling = JointCoupling{Hand().JointIndex(kThumb, 2), 1.0, 0.0};
  GS_EXPECT_THROW_WITH(parts.Build(), InputError, "hand.urdf", "15 actuated joints", "16");
  HandParts fewer;
  fewer.fingers.pop_back();
  GS_EXPECT_THROW_WITH(fewer.Build(), InputError, "13 actuated joints");
}

TEST(HandModel, RejectsNoFingerAnEmptyFingerAndARepeatedName) {
  HandParts none;
  none.fingers.clear();
  GS_EXPECT_THROW_WITH(none.Build(), InputError, "hand.urdf", "no finger");
  HandParts empty;
  empty.fingers[kLittle].joints.clear();
  empty.fingers[kLittle].links.clear();
  GS_EXPECT_THROW_WITH(empty.Build(), InputError, "finger 4 ('little')", "no joint");
  HandParts links;
  links.fingers[kRing].links.pop_back();
  GS_EXPECT_THROW_WITH(links.Build(), InputError, "finger 3 ('ring')", "4 joints but 3 links");
  HandParts twice;
  twice.fingers[kRing].name = "middle";
  GS_EXPECT_THROW_WITH(twice.Build(), InputError, "finger 3 ('middle')", "repeats");
}

}  // namespace
}  // namespace graspsynth
