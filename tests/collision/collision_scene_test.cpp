#include "collision/collision_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "kinematics/arm_ik.hpp"
#include "scene/triangle_mesh.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Deg;

// separated pairs: FCL (GJK at the default tolerance, or its closed forms) against the closed
// forms below, m.
constexpr double kDistanceTol = 1e-7;
// penetration depth through EPA (boxes and cylinders; the default epa_tolerance), m.
constexpr double kDepthTol = 1e-5;
// penetration depth of capsule-capsule and sphere pairs (closed forms), m.
constexpr double kExactDepthTol = 1e-12;

#ifdef GRASPSYNTH_SANITIZED
constexpr int kRandomStates = 40;
constexpr int kRandomShapes = 300;
#else
constexpr int kRandomStates = 200;
constexpr int kRandomShapes = 2000;
#endif

// ---------------------------------------------------------------------------------------------
// primitives

CollisionShape Sphere(double r) {
  CollisionShape s;
  s.kind = CollisionShape::Kind::kSphere;
  s.size << r, 0, 0;
  return s;
}
CollisionShape Capsule(double r, double length) {
  CollisionShape s;
  s.kind = CollisionShape::Kind::kCapsule;
  s.size << r, length, 0;
  return s;
}
CollisionShape Cylinder(double r, double length) {
  CollisionShape s;
  s.kind = CollisionShape::Kind::kCylinder;
  s.size << r, length, 0;
  return s;
}
CollisionShape Box(double x, double y, double z) {
  CollisionShape s;
  s.kind = CollisionShape::Kind::kBox;
  s.size << x, y, z;
  return s;
}

Eigen::Isometry3d Pose(const Eigen::Vector3d& p,
                       const Eigen::Matrix3d& R = Eigen::Matrix3d::Identity()) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

Eigen::Matrix3d Rot(double angle, const Eigen::Vector3d& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

std::string Scientific(double x) {
  std::ostringstream s;
  s << std::scientific << std::setprecision(2) << x;
  return s.str();
}

// the closest points are apart by the distance.
void ExpectWitnessesConsistent(const ShapeDistance& d) {
  EXPECT_NEAR((d.p_WCb - d.p_WCa).norm(), std::abs(d.distance), 1e-6);
}

TEST(ShapeSignedDistance, SphereSphere) {
  const Eigen::Vector3d c1(0.1, -0.2, 0.3), c2(0.17, -0.15, 0.33);
  const ShapeDistance d = ShapeSignedDistance(Sphere(0.02), Pose(c1), Sphere(0.03), Pose(c2));
  EXPECT_NEAR(d.distance, (c2 - c1).norm() - 0.05, kDistanceTol);
  EXPECT_NEAR((d.p_WCa - c1).norm(), 0.02, 1e-9);
  EXPECT_NEAR((d.p_WCb - c2).norm(), 0.03, 1e-9);
  ExpectWitnessesConsistent(d);
  EXPECT_FALSE(d.approximate);

  // penetrating by 1 cm, either way round.
  const ShapeDistance p =
      ShapeSignedDistance(Sphere(0.05), Pose({0, 0, 0}), Sphere(0.03), Pose({0.07, 0, 0}));
  EXPECT_NEAR(p.distance, -0.01, kExactDepthTol);
  ExpectWitnessesConsistent(p);
  EXPECT_NEAR(p.p_WCa.x(), 0.05, 1e-9);  // a's point deepest inside b
  EXPECT_NEAR(p.p_WCb.x(), 0.04, 1e-9);
  const ShapeDistance q =
      ShapeSignedDistance(Sphere(0.03), Pose({0.07, 0, 0}), Sphere(0.05), Pose({0, 0, 0}));
  EXPECT_NEAR(q.distance, -0.01, kExactDepthTol);
  EXPECT_NEAR(q.p_WCa.x(), 0.04, 1e-9);
  EXPECT_NEAR(q.p_WCb.x(), 0.05, 1e-9);
}

TEST(ShapeSignedDistance, CapsuleCapsuleParallel) {
  // side by side along z, 5 cm between the axes, radii 2 and 1 cm.
  const ShapeDistance d = ShapeSignedDistance(Capsule(0.02, 0.10), Pose({0, 0, 0}),
                                              Capsule(0.01, 0.08), Pose({0.05, 0, 0.03}));
  EXPECT_NEAR(d.distance, 0.02, kDistanceTol);
  ExpectWitnessesConsistent(d);
  // end to end on one axis: caps 0.10 / 2 + 0.08 / 2 + radii from the centres.
  const ShapeDistance e =
      ShapeSignedDistance(Capsule(0.02, 0.10), Pose({0, 0, 0}), Capsule(0.01, 0.08),
                          Pose({0, 0, 0.05 + 0.04 + 0.03 + 0.015}));
  EXPECT_NEAR(e.distance, 0.015, kDistanceTol);
  // overlapping side by side by 1 cm.
  const ShapeDistance p = ShapeSignedDistance(Capsule(0.02, 0.10), Pose({0, 0, 0}),
                                              Capsule(0.01, 0.08), Pose({0.02, 0, 0.03}));
  EXPECT_NEAR(p.distance, -0.01, kExactDepthTol);
  ExpectWitnessesConsistent(p);
  // two phalanges end to end, overlapping at their joint: the axes touch, so the depth is the
  // sum of the radii (EPA would take seconds here).
  const ShapeDistance joint =
      ShapeSignedDistance(Capsule(0.009, 0.045), Pose({0, 0, 0.0225}), Capsule(0.0085, 0.028),
                          Pose({0, 0, 0.045 + 0.014}));
  EXPECT_NEAR(joint.distance, -0.0175, kExactDepthTol);
}

TEST(ShapeSignedDistance, CapsuleCapsuleSkew) {
  // axes crossing in projection, 5 cm apart along the common normal (y), at 90 and 37 deg.
  for (double angle : {M_PI / 2, Deg(37)}) {
    const Eigen::Matrix3d R = Rot(angle, Eigen::Vector3d::UnitY());
    const ShapeDistance d = ShapeSignedDistance(Capsule(0.02, 0.10), Pose({0, 0, 0}),
                                                Capsule(0.01, 0.08), Pose({0, 0.05, 0.01}, R));
    EXPECT_NEAR(d.distance, 0.05 - 0.03, kDistanceTol) << "angle " << angle;
    ExpectWitnessesConsistent(d);
    // the closest point on a lies on its surface toward b: y = radius.
    EXPECT_NEAR(d.p_WCa.y(), 0.02, 1e-6);
  }
  // a generic skew pair: closest points of the two segments by brute force.
  const Eigen::Matrix3d Ra = Rot(0.4, {1, 2, 0.5}), Rb = Rot(1.3, {-0.3, 1, 1});
  const Eigen::Vector3d ca(0.01, 0.02, -0.03), cb(0.03, 0.09, 0.01);
  double best = 1e9;
  for (int i = 0; i <= 2000; ++i) {
    const Eigen::Vector3d pa = ca + Ra.col(2) * (-0.05 + 0.1 * i / 2000.0);
    // the closest point of segment b to pa, exactly.
    const Eigen::Vector3d u = Rb.col(2);
    const double t = std::clamp(u.dot(pa - cb), -0.04, 0.04);
    best = std::min(best, (pa - (cb + t * u)).norm());
  }
  const ShapeDistance g =
      ShapeSignedDistance(Capsule(0.02, 0.10), Pose(ca, Ra), Capsule(0.01, 0.08), Pose(cb, Rb));
  EXPECT_NEAR(g.distance, best - 0.03, 1e-6);  // the sampling's own error is below 1e-7
}

// distance from a point to an axis-aligned box centred at the origin (closed form).
double PointBoxDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& half) {
  const Eigen::Vector3d q = p.cwiseAbs() - half;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside;  // negative inside: minus the distance to the nearest face
}

TEST(ShapeSignedDistance, BoxSphere) {
  const Eigen::Vector3d half(0.1, 0.05, 0.025);
  const Eigen::Matrix3d R = Rot(0.7, {0.2, -1, 0.4});
  const Eigen::Vector3d p_WB(0.3, -0.1, 0.2);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  int checked = 0;
  for (int n = 0; n < 200; ++n) {
    const Eigen::Vector3d p_B(u(rng), u(rng), u(rng));  // sphere centre in the box frame
    const double r = 0.02;
    const double expected = PointBoxDistance(p_B, half) - r;
    if (std::abs(expected) < 1e-4) continue;  // touching: either answer is right
    const ShapeDistance d =
        ShapeSignedDistance(Box(0.2, 0.1, 0.05), Pose(p_WB, R), Sphere(r), Pose(p_WB + R * p_B));
    EXPECT_NEAR(d.distance, expected, expected > 0 ? kDistanceTol : kExactDepthTol)
        << "centre " << p_B.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 150);
}

TEST(ShapeSignedDistance, BoxCapsule) {
  const CollisionShape box = Box(0.2, 0.1, 0.05);
  // lying across the top face (top z = 0.025), 1.5 cm above it.
  const Eigen::Matrix3d lying = Rot(M_PI / 2, Eigen::Vector3d::UnitY());
  EXPECT_NEAR(ShapeSignedDistance(box, Pose({0, 0, 0}), Capsule(0.02, 0.1),
                                  Pose({0, 0, 0.025 + 0.02 + 0.015}, lying))
                  .distance,
              0.015, kDistanceTol);
  // standing on its cap, 1.5 cm above the face.
  EXPECT_NEAR(ShapeSignedDistance(box, Pose({0, 0, 0}), Capsule(0.02, 0.1),
                                  Pose({0.03, 0.01, 0.025 + 0.05 + 0.02 + 0.015}))
                  .distance,
              0.015, kDistanceTol);
  // tilted by 0.3 rad: the lower cap is the closest.
  const double tilt = 0.3;
  EXPECT_NEAR(ShapeSignedDistance(box, Pose({0, 0, 0}), Capsule(0.02, 0.1),
                                  Pose({0, 0, 0.025 + 0.02 + 0.015 + 0.05 * std::sin(tilt)},
                                       Rot(M_PI / 2 - tilt, Eigen::Vector3d::UnitY())))
                  .distance,
              0.015, kDistanceTol);
  // sunk 5 mm into the face.
  const ShapeDistance p = ShapeSignedDistance(box, Pose({0, 0, 0}), Capsule(0.02, 0.1),
                                              Pose({0, 0, 0.025 + 0.02 - 0.005}, lying));
  EXPECT_NEAR(p.distance, -0.005, kDepthTol);
  ExpectWitnessesConsistent(p);
}

TEST(ShapeSignedDistance, CylinderBoxVerticalSeparation) {
  // a disc standing above a slab and a slab above a disc, offset sideways within the face.
  const CollisionShape cyl = Cylinder(0.08, 0.05);
  const CollisionShape slab = Box(0.2, 0.1, 0.05);
  EXPECT_NEAR(
      ShapeSignedDistance(cyl, Pose({0, 0, 0}), slab, Pose({0.05, 0.02, 0.025 + 0.025 + 0.04}))
          .distance,
      0.04, kDistanceTol);
  EXPECT_NEAR(
      ShapeSignedDistance(slab, Pose({0.05, 0.02, 0.0}), cyl, Pose({0, 0, -0.05 - 0.033})).distance,
      0.033, kDistanceTol);
  // sunk 4 mm.
  EXPECT_NEAR(
      ShapeSignedDistance(cyl, Pose({0, 0, 0}), slab, Pose({0.05, 0.02, 0.025 + 0.025 - 0.004}))
          .distance,
      -0.004, kDepthTol);
}

// the lowest point of a shape at pose X_WG (its own frame), closed form.
Eigen::Vector3d LowestPoint(const CollisionShape& s, const Eigen::Isometry3d& X_WG) {
  const Eigen::Vector3d c = X_WG.translation();
  const Eigen::Vector3d a = X_WG.linear().col(2);
  const Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
  switch (s.kind) {
    case CollisionShape::Kind::kSphere:
      return c + s.size[0] * down;
    case CollisionShape::Kind::kCapsule: {
      const Eigen::Vector3d end = c + (a.z() > 0 ? -1.0 : 1.0) * 0.5 * s.size[1] * a;
      return end + s.size[0] * down;
    }
    case CollisionShape::Kind::kCylinder: {
      const Eigen::Vector3d end = c + (a.z() > 0 ? -1.0 : 1.0) * 0.5 * s.size[1] * a;
      const Eigen::Vector3d radial = down - down.dot(a) * a;  // the rim point most downward
      return radial.norm() < 1e-12 ? end : Eigen::Vector3d(end + s.size[0] * radial.normalized());
    }
    case CollisionShape::Kind::kBox: {
      Eigen::Vector3d corner = c;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d e = X_WG.linear().col(k) * 0.5 * s.size[k];
        corner += e.z() > 0 ? -e : e;
      }
      return corner;
    }
    case CollisionShape::Kind::kMesh: {
      Eigen::Vector3d low = c;
      low.z() = INFINITY;
      for (const Eigen::Vector3d& v : s.mesh->vertices) {
        if ((X_WG * v).z() < low.z()) low = X_WG * v;
      }
      return low;
    }
  }
  return c;
}

TEST(ShapeSignedDistance, RandomShapesAboveABoxFace) {
  // capsules, cylinders and boxes at random orientations above the table's top face, within
  // the face: the distance is the height of their lowest point.
  const CollisionShape table = Box(0.9, 0.9, 0.05);
  const Eigen::Isometry3d X_WT = Pose({-0.25, 0.85, -0.025});
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int n = 0; n < kRandomShapes; ++n) {
    const double r = 0.009 + 0.05 * std::abs(u(rng)), length = 0.02 + 0.2 * std::abs(u(rng));
    const CollisionShape s = n % 3 == 0   ? Capsule(r, length)
                             : n % 3 == 1 ? Cylinder(r, length)
                                          : Box(r, length, 0.05);
    Eigen::Isometry3d X_WG = Pose({0, 0, 0}, Rot(M_PI * u(rng), {u(rng), u(rng), u(rng)}));
    const double gap = 5e-4 + 0.1 * std::abs(u(rng));
    X_WG.translation() << -0.25 + 0.3 * u(rng), 0.85 + 0.3 * u(rng), gap - LowestPoint(s, X_WG).z();
    const ShapeDistance d = ShapeSignedDistance(s, X_WG, table, X_WT);
    worst = std::max(worst, std::abs(d.distance - gap));
    ASSERT_NEAR(d.distance, gap, kDistanceTol) << "shape " << n;
    // the closest point on the table is on its top face.
    EXPECT_NEAR(d.p_WCb.z(), 0.0, 1e-6);
  }
  RecordProperty("worst_error_m", Scientific(worst));
}

TEST(ShapeSignedDistance, PenetrationDepthOfShapesSunkIntoABoxFace) {
  const CollisionShape table = Box(0.9, 0.9, 0.05);
  const Eigen::Isometry3d X_WT = Pose({-0.25, 0.85, -0.025});
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int n = 0; n < kRandomShapes / 10; ++n) {
    const CollisionShape s = n % 3 == 0   ? Capsule(0.01, 0.04)
                             : n % 3 == 1 ? Cylinder(0.02, 0.03)
                                          : Box(0.03, 0.02, 0.04);
    Eigen::Isometry3d X_WG = Pose({0, 0, 0}, Rot(M_PI * u(rng), {u(rng), u(rng), u(rng)}));
    // sunk by 0.5 - 10 mm: less than the slab's thickness minus the shape, so the top face
    // gives the shortest way out.
    const double depth = 5e-4 + 0.0095 * std::abs(u(rng));
    X_WG.translation() << -0.25 + 0.3 * u(rng), 0.85 + 0.3 * u(rng),
        -depth - LowestPoint(s, X_WG).z();
    const ShapeDistance d = ShapeSignedDistance(s, X_WG, table, X_WT);
    EXPECT_NEAR(d.distance, -depth, kDepthTol) << "shape " << n;
    worst = std::max(worst, std::abs(d.distance + depth));
  }
  RecordProperty("worst_error_m", Scientific(worst));
}

TEST(ShapeSignedDistance, OptionsAreChecked) {
  std::string why;
  SignedDistanceOptions o;
  EXPECT_TRUE(o.IsValid(&why));
  o.gjk_tolerance = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("gjk_tolerance"), std::string::npos);
  o = {};
  o.epa_tolerance = std::nan("");
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.max_distance = -1.0;
  EXPECT_FALSE(o.IsValid(&why));
  CollideOptions c;
  c.max_pairs = -1;
  EXPECT_FALSE(c.IsValid(&why));
  CollisionModelOptions m;
  m.zero_configuration_margin = -1.0;
  EXPECT_FALSE(m.IsValid(&why));
}

// ---------------------------------------------------------------------------------------------
// the scene

const RobotModel& Robot() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot;
}
const SceneModel& Scene() {
  static const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  return scene;
}
const CollisionModel& Model() {
  static const CollisionModel model(Robot(), Scene());
  return model;
}

int Shape(const std::string& name) {
  const int i = Model().FindShape(name);
  EXPECT_GE(i, 0) << "no shape " << name;
  return i;
}

// an in-limit IK solution for the hand-mount pose X_WH: branch (+, +, +) first, then the
// others; the arm angle in the middle of the widest feasible interval.
std::optional<MidArcSolution> SolveWrist(const Eigen::Isometry3d& X_WH) {
  return SolveArmIkMidArc(Robot().arm, X_WH * Robot().X_FH.inverse());
}

// the hand's shapes at hand-mount pose X_WH and fingers f, computed here from the hand model
// (independently of the collision module): the lowest point of the whole hand and its shape.
struct HandLowest {
  Eigen::Vector3d p_W;
  std::string link;
};
HandLowest LowestHandPoint(const Eigen::Isometry3d& X_WH, const HandVector& f) {
  const HandModel& hand = Robot().hand;
  HandFrames frames;
  HandLinkFrames(hand, f, &frames);
  HandLowest best{Eigen::Vector3d::Constant(1e9), ""};
  const auto visit = [&best](const RigidLink& link, const Eigen::Isometry3d& X_WL) {
    for (const CollisionShape& s : link.shapes) {
      const Eigen::Vector3d p = LowestPoint(s, X_WL * s.X_LG);
      if (p.z() < best.p_W.z()) best = {p, link.name};
    }
  };
  visit(hand.mount(), X_WH);
  visit(hand.palm(), X_WH * frames.X_HP);
  for (int j = 0; j < hand.joint_count(); ++j) {
    visit(hand.link(j), X_WH * frames.X_HL[static_cast<size_t>(hand.joint_finger(j))]
                                          [static_cast<size_t>(hand.joint_in_finger(j))]);
  }
  return best;
}

// the handle box: its pose in the world and half sides.
struct HandleBox {
  Eigen::Isometry3d X_WG;
  Eigen::Vector3d half;
  double top_z() const { return X_WG.translation().z() + half.z(); }
};
HandleBox Handle(double theta) {
  const ObjectPart& handle = Scene().object.parts[1];
  EXPECT_EQ(handle.name, "handle");
  return {Scene().ObjectPose(theta) * handle.shape.X_LG, 0.5 * handle.shape.size};
}

// hand orientation over the handle at theta: palm down (x_H = -z_W), the hand's long axis z_H
// horizontal and across the handle, the thumb side (+y_H) toward the pan's centre.
Eigen::Matrix3d PalmDownAcrossHandle(double theta) {
  const double phi = theta + Scene().object_yaw_offset;  // handle direction in the world
  const Eigen::Vector3d x(0, 0, -1);
  const Eigen::Vector3d z(std::cos(phi + M_PI / 2), std::sin(phi + M_PI / 2), 0);
  Eigen::Matrix3d R;
  R << x, z.cross(x), z;
  return R;
}

// the hand-mount pose that puts the hand's lowest point (fingers f, orientation R_WH) at
// p_W_target.
Eigen::Isometry3d WristPoseWithLowestPointAt(const Eigen::Matrix3d& R_WH, const HandVector& f,
                                             const Eigen::Vector3d& p_W_target) {
  const HandLowest at_origin = LowestHandPoint(Pose({0, 0, 0}, R_WH), f);
  return Pose(p_W_target - at_origin.p_W, R_WH);
}

TEST(CollisionModel, HasOneShapePerPrimitiveWithUniqueNames) {
  const CollisionModel& m = Model();
  const ArmModel& arm = Robot().arm;
  const HandModel& hand = Robot().hand;
  size_t arm_shapes = arm.base().shapes.size(), hand_shapes = 0;
  for (int i = 1; i <= kArmDof; ++i) arm_shapes += arm.link(i).shapes.size();
  hand_shapes += hand.mount().shapes.size() + hand.palm().shapes.size();
  for (const Finger& finger : hand.fingers()) {
    for (const RigidLink& link : finger.links) hand_shapes += link.shapes.size();
  }
  EXPECT_EQ(m.ShapesIn(CollisionGroup::kArm).size(), arm_shapes);
  EXPECT_EQ(m.ShapesIn(CollisionGroup::kHand).size(), hand_shapes);
  EXPECT_EQ(arm_shapes, 11u);   // models/README.md: 8 links, S1 S3 E2 with two shapes
  EXPECT_EQ(hand_shapes, 17u);  // mount, palm, 15 phalanges
  EXPECT_EQ(m.ShapesIn(CollisionGroup::kObject).size(), 2u);
  EXPECT_EQ(m.ShapesIn(CollisionGroup::kTable).size(), 1u);
  std::set<std::string> names;
  for (int i = 0; i < m.num_shapes(); ++i) names.insert(m.shape(i).name);
  EXPECT_EQ(static_cast<int>(names.size()), m.num_shapes());
  EXPECT_EQ(m.shape(Shape("thumb_link4")).shape.kind, CollisionShape::Kind::kCapsule);
  EXPECT_EQ(m.shape(Shape("pan/body")).shape.kind, CollisionShape::Kind::kCylinder);
  EXPECT_EQ(m.shape(Shape("pan/handle")).shape.kind, CollisionShape::Kind::kBox);
  EXPECT_EQ(m.FindShape("no such shape"), -1);
  // the table's top face is the scene's top_z.
  EXPECT_NEAR(m.X_WTable().translation().z() + 0.5 * m.shape(Shape("table")).shape.size.z(),
              Scene().table.top_z, 1e-12);
}

TEST(CollisionModel, IgnoresJointNeighboursTheHandItselfAndThePanOnTheTable) {
  const CollisionModel& m = Model();
  const auto reason_of = [&m](const std::string& a, const std::string& b) {
    const int i = Shape(a), j = Shape(b);
    for (const IgnoredPair& p : m.ignored_pairs()) {
      if (p.a == std::min(i, j) && p.b == std::max(i, j)) return std::optional(p.reason);
    }
    return std::optional<IgnoreReason>();
  };
  EXPECT_EQ(reason_of("base_link", "S1_link/0"), IgnoreReason::kAdjacentBodies);
  EXPECT_EQ(reason_of("S2_link", "S3_link/0"), IgnoreReason::kAdjacentBodies);
  EXPECT_EQ(reason_of("E2_link/1", "W1_link"), IgnoreReason::kAdjacentBodies);
  EXPECT_EQ(reason_of("W1_link", "hand_mount_link"), IgnoreReason::kAdjacentBodies);
  EXPECT_EQ(reason_of("W2_link", "hand_mount_link"), IgnoreReason::kSameBody);
  EXPECT_EQ(reason_of("W2_link", "palm"), IgnoreReason::kSameBody);
  EXPECT_EQ(reason_of("S1_link/0", "S1_link/1"), IgnoreReason::kSameBody);
  EXPECT_EQ(reason_of("index_link2", "index_link3"), IgnoreReason::kAdjacentBodies);
  EXPECT_EQ(reason_of("thumb_link2", "palm"), IgnoreReason::kHandSelf);
  EXPECT_EQ(reason_of("index_link4", "middle_link4"), IgnoreReason::kHandSelf);
  EXPECT_EQ(reason_of("pan/body", "table"), IgnoreReason::kObjectOnTable);
  // checked: links two or more joints apart, and the robot against the world.
  EXPECT_FALSE(reason_of("E2_link/0", "W2_link"));
  EXPECT_FALSE(reason_of("E2_link/0", "index_link4"));
  EXPECT_FALSE(reason_of("S1_link/1", "S3_link/0"));
  EXPECT_FALSE(reason_of("palm", "table"));
  EXPECT_FALSE(reason_of("base_link", "pan/handle"));
  for (int i = 0; i < m.num_shapes(); ++i) {
    for (int j = 0; j < m.num_shapes(); ++j) {
      const bool world_pair = (GroupSet::Robot().Contains(m.shape(i).group) &&
                               GroupSet::World().Contains(m.shape(j).group));
      if (world_pair) {
        EXPECT_FALSE(m.IsIgnored(i, j)) << m.shape(i).name << " " << m.shape(j).name;
      }
      EXPECT_EQ(m.IsIgnored(i, j), m.IsIgnored(j, i));
    }
  }
  // the shipped description touches only across joints: no pair needs the zero-pose rule.
  for (const IgnoredPair& p : m.ignored_pairs()) {
    EXPECT_NE(p.reason, IgnoreReason::kOverlapAtZero)
        << m.shape(p.a).name << " - " << m.shape(p.b).name;
  }
}

TEST(CollisionModel, ZeroConfigurationRuleIgnoresPairsCloserThanTheMargin) {
  // at q = 0 the W1 housing (radius 0.05 about the W1 axis) is 0.005 m from the flange disc,
  // which starts 0.070 - 0.015 = 0.055 m from the wrist centre. A 1 cm margin ignores it.
  CollisionModelOptions options;
  options.zero_configuration_margin = 0.01;
  const CollisionModel wide(Robot(), Scene(), options);
  const int i = wide.FindShape("E2_link/1"), j = wide.FindShape("W2_link");
  ASSERT_TRUE(wide.IsIgnored(i, j));
  bool found = false;
  for (const IgnoredPair& p : wide.ignored_pairs()) {
    if (p.a == std::min(i, j) && p.b == std::max(i, j)) {
      EXPECT_EQ(p.reason, IgnoreReason::kOverlapAtZero);
      found = true;
    } else if (p.reason == IgnoreReason::kOverlapAtZero) {
      ADD_FAILURE() << "unexpected " << wide.shape(p.a).name << " - " << wide.shape(p.b).name;
    }
  }
  EXPECT_TRUE(found);
  EXPECT_FALSE(Model().IsIgnored(i, j));
}

TEST(CollisionScene, RobotAtZeroIsClearOfTheWorld) {
  const CollisionModel& m = Model();
  CollisionData data(m);
  EXPECT_FALSE(data.has_state());
  SetState(m, Vector7d::Zero(), HandVector::Zero(), Deg(60), &data);
  ASSERT_TRUE(data.has_state());
  const CollisionReport report = Collide(m, GroupSet::Robot(), GroupSet::World(), &data);
  EXPECT_FALSE(report.collision()) << report.BriefReport();
  EXPECT_FALSE(Collide(m, GroupSet::Robot(), GroupSet::Robot(), &data).collision());

  // the table's near edge is y = 0.85 - 0.45 = 0.40; the base cylinder's radius is 0.09.
  const SignedDistanceResult table =
      SignedDistance(m, GroupSet::Robot(), CollisionGroup::kTable, &data);
  ASSERT_EQ(table.status, SignedDistanceResult::Status::kOk);
  EXPECT_NEAR(table.distance, 0.40 - 0.09, kDistanceTol);
  EXPECT_EQ(table.name_a, "base_link");
  EXPECT_EQ(table.name_b, "table");
  EXPECT_NEAR(table.p_WCb.y(), 0.40, 1e-6);
  EXPECT_LT(table.pairs_evaluated, table.pairs_considered);  // pruned by the bounding boxes

  const SignedDistanceResult object =
      SignedDistance(m, GroupSet::Robot(), CollisionGroup::kObject, &data);
  ASSERT_EQ(object.status, SignedDistanceResult::Status::kOk);
  EXPECT_GT(object.distance, 0.3);
  EXPECT_TRUE(object.name_b == "pan/body" || object.name_b == "pan/handle");

  // robot self-clearance: the W1 housing and the flange disc, 0.005 m (see above).
  const SignedDistanceResult self = SignedDistance(m, GroupSet::Robot(), GroupSet::Robot(), &data);
  EXPECT_NEAR(self.distance, 0.005, kDistanceTol);
  EXPECT_EQ(std::set<std::string>({self.name_a, self.name_b}),
            std::set<std::string>({"E2_link/1", "W2_link"}));
}

TEST(CollisionScene, HandPushedIntoTheTableCollidesWithIt) {
  const CollisionModel& m = Model();
  const double theta = 0.0;  // the handle points away from the spot used below
  const HandVector f = HandVector::Zero();
  const Eigen::Matrix3d R_WH = PalmDownAcrossHandle(Deg(60));
  // the hand's lowest point 1 cm below the table top, well inside the table's outline.
  const Eigen::Isometry3d X_WH =
      WristPoseWithLowestPointAt(R_WH, f, {0.05, 0.75, Scene().table.top_z - 0.01});
  const std::optional<MidArcSolution> ik = SolveWrist(X_WH);
  ASSERT_TRUE(ik.has_value());
  CollisionData data(m);
  SetState(m, ik->q, f, theta, &data);
  EXPECT_TRUE(testing::PosesNear(
      data.X_WG(Shape("hand_mount_link")) * m.shape(Shape("hand_mount_link")).shape.X_LG.inverse(),
      X_WH, 1e-9));

  const CollisionReport report = Collide(m, GroupSet::Robot(), GroupSet::World(), &data);
  ASSERT_TRUE(report.collision());
  bool hand_table = false;
  for (const CollidingPair& p : report.pairs) {
    EXPECT_TRUE(GroupSet::Robot().Contains(p.group_a));
    EXPECT_EQ(p.name_b, "table") << report.BriefReport();
    hand_table |= p.group_a == CollisionGroup::kHand;
  }
  EXPECT_TRUE(hand_table);
  // the arm itself stays above the table, and nothing touches the pan.
  EXPECT_FALSE(Collide(m, CollisionGroup::kArm, CollisionGroup::kTable, &data).collision());
  EXPECT_FALSE(Collide(m, GroupSet::Robot(), CollisionGroup::kObject, &data).collision());

  // the deepest shape is 1 cm into the top face (far from the table's sides).
  const SignedDistanceResult d =
      SignedDistance(m, CollisionGroup::kHand, CollisionGroup::kTable, &data);
  EXPECT_NEAR(d.distance, -0.01, kDepthTol);
  EXPECT_EQ(d.name_a, LowestHandPoint(X_WH, f).link);
  EXPECT_FALSE(d.approximate);

  // contacts on request; at most one pair when asked for one.
  CollideOptions options;
  options.compute_contacts = true;
  const CollisionReport with_contacts =
      Collide(m, CollisionGroup::kHand, CollisionGroup::kTable, &data, options);
  ASSERT_TRUE(with_contacts.collision());
  for (const CollidingPair& p : with_contacts.pairs) {
    EXPECT_TRUE(std::isfinite(p.depth));
    EXPECT_GT(p.depth, 0.0);
    EXPECT_LE(p.depth, 0.01 + 1e-4);
  }
  options.max_pairs = 1;
  const CollisionReport first = Collide(m, GroupSet::Robot(), GroupSet::World(), &data, options);
  EXPECT_EQ(first.pairs.size(), 1u);
  EXPECT_TRUE(first.truncated);
}

// the hover pose over the handle at theta = 60 deg: lowest hand point `height` above the
// handle's top face, over the handle's axis at 0.20 m from the pan's centre.
Eigen::Isometry3d HoverPose(double theta, const HandVector& f, double height) {
  const HandleBox h = Handle(theta);
  const double phi = theta + Scene().object_yaw_offset;
  const Eigen::Vector3d p_WO = Scene().ObjectPose(theta).translation();
  Eigen::Vector3d target = p_WO + 0.20 * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0.0);
  target.z() = h.top_z() + height;
  return WristPoseWithLowestPointAt(PalmDownAcrossHandle(theta), f, target);
}

// A closed prism of `n` sides around z (radius r, height h, centred at the origin), or a box
// (n = 4, turned 45 deg, radius half its diagonal), as a mesh.
std::shared_ptr<const TriangleMesh> PrismMesh(int n, double r, double h, double turn = 0.0) {
  auto m = std::make_shared<TriangleMesh>();
  m->source = "prism";
  for (int k = 0; k < n; ++k) {
    const double a = turn + 2.0 * M_PI * k / n;
    m->vertices.emplace_back(r * std::cos(a), r * std::sin(a), -0.5 * h);
    m->vertices.emplace_back(r * std::cos(a), r * std::sin(a), 0.5 * h);
  }
  const int bottom = 2 * n, top = 2 * n + 1;
  m->vertices.emplace_back(0, 0, -0.5 * h);
  m->vertices.emplace_back(0, 0, 0.5 * h);
  for (int k = 0; k < n; ++k) {
    const int b0 = 2 * k, t0 = 2 * k + 1, b1 = 2 * ((k + 1) % n), t1 = b1 + 1;
    m->triangles.push_back({b0, b1, t1});
    m->triangles.push_back({b0, t1, t0});
    m->triangles.push_back({bottom, b1, b0});
    m->triangles.push_back({top, t0, t1});
  }
  return m;
}

// The shipped pan with its body a 128-sided prism and its handle a box, both meshes: the mesh
// object's clearance is the primitive object's within the prism's sag, r (1 - cos(pi / 128))
// = 0.024 mm, and FCL's tolerance.
TEST(CollisionScene, MeshObjectGivesItsPrimitiveApproximationsClearance) {
  SceneModel mesh_scene = Scene();
  ObjectPart& body = mesh_scene.object.parts[0];
  ObjectPart& handle = mesh_scene.object.parts[1];
  ASSERT_EQ(body.name, "body");
  ASSERT_EQ(handle.name, "handle");
  body.shape.mesh = PrismMesh(128, body.shape.size[0], body.shape.size[1]);
  body.shape.kind = CollisionShape::Kind::kMesh;
  CheckSolidMesh(*body.shape.mesh);
  // the box as a 4-sided prism turned 45 deg, then stretched to the bar's sides.
  auto bar = std::make_shared<TriangleMesh>(*PrismMesh(4, std::sqrt(0.5), 1.0, M_PI / 4));
  for (Eigen::Vector3d& v : bar->vertices) v = v.cwiseProduct(handle.shape.size);
  CheckSolidMesh(*bar);
  handle.shape.mesh = bar;
  handle.shape.kind = CollisionShape::Kind::kMesh;
  const CollisionModel mesh_model(Robot(), mesh_scene);
  const CollisionModel& primitive_model = Model();

  const double theta = Deg(60);
  const HandVector f = HandVector::Zero();
  int compared = 0;
  for (double height : {0.005, 0.02, 0.05, 0.10}) {
    const std::optional<MidArcSolution> ik = SolveWrist(HoverPose(theta, f, height));
    ASSERT_TRUE(ik.has_value());
    CollisionData a(primitive_model), b(mesh_model);
    SetState(primitive_model, ik->q, f, theta, &a);
    SetState(mesh_model, ik->q, f, theta, &b);
    const SignedDistanceResult da =
        SignedDistance(primitive_model, CollisionGroup::kHand, CollisionGroup::kObject, &a);
    const SignedDistanceResult db =
        SignedDistance(mesh_model, CollisionGroup::kHand, CollisionGroup::kObject, &b);
    ASSERT_EQ(db.status, SignedDistanceResult::Status::kOk) << height;
    EXPECT_NEAR(db.distance, da.distance, 1e-4) << height;
    EXPECT_NEAR(da.distance, height, 1e-6);
    EXPECT_EQ(db.name_b, da.name_b);
    ++compared;
  }
  EXPECT_EQ(compared, 4);
}

TEST(CollisionScene, HandHoveringAboveTheHandleHasTheAnalyticClearance) {
  const CollisionModel& m = Model();
  const double theta = Deg(60);
  const HandVector f = HandVector::Zero();
  const Eigen::Isometry3d X_WH = HoverPose(theta, f, 0.03);
  // the closed form holds when the lowest point lies over the handle's top face: then every
  // hand point is at least that high above the handle (and the body is lower than the handle).
  const HandleBox h = Handle(theta);
  const HandLowest lowest = LowestHandPoint(X_WH, f);
  const Eigen::Vector3d p_G = h.X_WG.inverse() * lowest.p_W;
  ASSERT_LT(std::abs(p_G.x()), h.half.x() - 0.01);
  ASSERT_LT(std::abs(p_G.y()), h.half.y() - 1e-3);
  ASSERT_LT(2.0 * Scene().object.rest_height, h.top_z());
  const std::optional<MidArcSolution> ik = SolveWrist(X_WH);
  ASSERT_TRUE(ik.has_value());

  CollisionData data(m);
  SetState(m, ik->q, f, theta, &data);
  const CollisionReport report = Collide(m, GroupSet::Robot(), GroupSet::World(), &data);
  EXPECT_FALSE(report.collision()) << report.BriefReport();
  const SignedDistanceResult d =
      SignedDistance(m, CollisionGroup::kHand, CollisionGroup::kObject, &data);
  ASSERT_EQ(d.status, SignedDistanceResult::Status::kOk);
  EXPECT_NEAR(d.distance, 0.03, 1e-6);
  EXPECT_EQ(d.name_a, lowest.link);
  EXPECT_EQ(d.name_b, "pan/handle");
  EXPECT_TRUE(testing::MatricesNear(d.p_WCa, lowest.p_W, 1e-4));
  EXPECT_NEAR(d.p_WCb.z(), h.top_z(), 1e-6);
  // and to the table: the lowest point's height above the top face.
  EXPECT_NEAR(SignedDistance(m, CollisionGroup::kHand, CollisionGroup::kTable, &data).distance,
              lowest.p_W.z() - Scene().table.top_z, 1e-6);

  // 10 cm lower the hand passes through the handle.
  Eigen::Isometry3d X_WH_low = X_WH;
  X_WH_low.translation().z() -= 0.10;
  const std::optional<MidArcSolution> ik_low = SolveWrist(X_WH_low);
  ASSERT_TRUE(ik_low.has_value());
  SetState(m, ik_low->q, f, theta, &data);
  const CollisionReport low = Collide(m, CollisionGroup::kHand, CollisionGroup::kObject, &data);
  ASSERT_TRUE(low.collision());
  bool handle = false;
  for (const CollidingPair& p : low.pairs) handle |= p.name_b == "pan/handle";
  EXPECT_TRUE(handle) << low.BriefReport();
  EXPECT_LT(SignedDistance(m, CollisionGroup::kHand, CollisionGroup::kObject, &data).distance,
            -1e-3);
}

TEST(CollisionScene, ClearanceOfAStraightDescentIsMonotone) {
  const CollisionModel& m = Model();
  const double theta = Deg(60);
  const HandVector f = HandVector::Zero();
  // from 10 cm to 5 mm above the handle, straight down, one IK branch and arm angle.
  constexpr int kSteps = 12;
  std::vector<RobotState> states;
  std::vector<double> heights;
  std::optional<MidArcSolution> first;
  for (int s = 0; s < kSteps; ++s) {
    const double height = 0.10 + (0.005 - 0.10) * s / (kSteps - 1);
    const Eigen::Isometry3d X_WH = HoverPose(theta, f, height);
    if (!first) {
      first = SolveWrist(X_WH);
      ASSERT_TRUE(first.has_value());
    }
    const Vector7d q_near = states.empty() ? first->q : states.back().q_arm;
    const ArmIkSolution ik =
        SolveArmIk(Robot().arm, X_WH * Robot().X_FH.inverse(), first->psi, first->branch, &q_near);
    ASSERT_EQ(ik.status, IkStatus::kOk) << "step " << s;
    states.push_back({ik.q, f});
    heights.push_back(height);
  }
  CollisionData data(m);
  const ClearanceProfileResult profile = ClearanceProfile(
      m, states, Scene().ObjectPose(theta), CollisionGroup::kHand, GroupSet::World(), &data);
  ASSERT_EQ(profile.states.size(), states.size());
  const std::vector<double> clearance = profile.Clearances();
  for (size_t s = 0; s < clearance.size(); ++s) {
    // the lowest point stays over the handle: the clearance is its height.
    EXPECT_NEAR(clearance[s], heights[s], 1e-6) << "state " << s;
    if (s > 0) {
      EXPECT_LE(clearance[s], clearance[s - 1] + 1e-9) << "state " << s;
    }
  }
  EXPECT_EQ(profile.argmin_state, kSteps - 1);
  EXPECT_NEAR(profile.min_clearance, 0.005, 1e-6);
  EXPECT_EQ(profile.states.back().name_b, "pan/handle");
  // the first state closer than a 2 cm margin.
  const int below = profile.FirstStateBelow(0.02);
  ASSERT_GE(below, 1);
  EXPECT_LT(heights[below], 0.02);
  EXPECT_GE(heights[below - 1], 0.02);
  EXPECT_EQ(profile.FirstStateBelow(0.001), -1);
  EXPECT_FALSE(profile.BriefReport().empty());

  const ClearanceProfileResult none = ClearanceProfile(
      m, {}, Scene().ObjectPose(theta), CollisionGroup::kHand, GroupSet::World(), &data);
  EXPECT_EQ(none.argmin_state, -1);
  EXPECT_TRUE(std::isinf(none.min_clearance));
}

Vector7d RandomArm(std::mt19937_64* rng) {
  Vector7d q;
  for (int i = 0; i < kArmDof; ++i) {
    q[i] = std::uniform_real_distribution<double>(Robot().arm.lower()[i],
                                                  Robot().arm.upper()[i])(*rng);
  }
  return q;
}
HandVector RandomHand(std::mt19937_64* rng) {
  HandVector f;
  for (int i = 0; i < kHandDof; ++i) {
    f[i] = std::uniform_real_distribution<double>(Robot().hand.lower()[i],
                                                  Robot().hand.upper()[i])(*rng);
  }
  return f;
}

TEST(CollisionScene, IgnoredPairsAreNeverReported) {
  const CollisionModel& m = Model();
  CollisionData data(m);
  // at q = 0 ignored pairs do overlap (neighbours at their joints), yet nothing is reported.
  SetState(m, Vector7d::Zero(), HandVector::Zero(), 0.0, &data);
  int overlapping_ignored = 0;
  for (const IgnoredPair& p : m.ignored_pairs()) {
    const ShapeDistance d =
        ShapeSignedDistance(m.shape(p.a).shape, data.X_WG(p.a) * m.shape(p.a).shape.X_LG.inverse(),
                            m.shape(p.b).shape, data.X_WG(p.b) * m.shape(p.b).shape.X_LG.inverse());
    overlapping_ignored += d.distance < 0.0;
  }
  EXPECT_GT(overlapping_ignored, 10);
  const GroupSet all = GroupSet::Robot() | GroupSet::World();
  EXPECT_FALSE(Collide(m, all, all, &data).collision());

  // random states (many put the arm through the table): Collide reports exactly the pairs
  // that penetrate, never an ignored one, and SignedDistance equals the minimum over pairs.
  std::mt19937_64 rng(20261125);
  int collisions = 0;
  for (int n = 0; n < kRandomStates; ++n) {
    const double theta = std::uniform_real_distribution<double>(0.0, M_PI)(rng);
    SetState(m, RandomArm(&rng), RandomHand(&rng), theta, &data);
    const CollisionReport report = Collide(m, GroupSet::Robot(), all, &data);
    std::set<std::pair<int, int>> reported;
    for (const CollidingPair& p : report.pairs) {
      ASSERT_FALSE(m.IsIgnored(p.shape_a, p.shape_b)) << p.name_a << " - " << p.name_b;
      EXPECT_TRUE(GroupSet::Robot().Contains(p.group_a));
      reported.insert({std::min(p.shape_a, p.shape_b), std::max(p.shape_a, p.shape_b)});
    }
    collisions += report.collision();
    double brute_world = std::numeric_limits<double>::infinity();
    for (int i = 0; i < m.num_shapes(); ++i) {
      for (int j = i + 1; j < m.num_shapes(); ++j) {
        if (m.IsIgnored(i, j) || !GroupSet::Robot().Contains(m.shape(i).group)) continue;
        const ShapeDistance d =
            ShapeSignedDistance(m.shape(i).shape, data.X_WG(i) * m.shape(i).shape.X_LG.inverse(),
                                m.shape(j).shape, data.X_WG(j) * m.shape(j).shape.X_LG.inverse());
        const bool is_reported = reported.count({i, j}) > 0;
        if (d.distance < -1e-6) {
          EXPECT_TRUE(is_reported) << m.shape(i).name << " - " << m.shape(j).name << " at "
                                   << d.distance << " m, state " << n;
        }
        if (is_reported) {
          EXPECT_LT(d.distance, 1e-6) << m.shape(i).name << " - " << m.shape(j).name;
        }
        if (GroupSet::World().Contains(m.shape(j).group)) {
          brute_world = std::min(brute_world, d.distance);
        }
      }
    }
    const SignedDistanceResult sd = SignedDistance(m, GroupSet::Robot(), GroupSet::World(), &data);
    EXPECT_NEAR(sd.distance, brute_world, 1e-9) << "state " << n;
  }
  EXPECT_GT(collisions, kRandomStates / 10);  // the sample does exercise collisions
}

TEST(CollisionScene, MaxDistanceReportsALowerBound) {
  const CollisionModel& m = Model();
  CollisionData data(m);
  SetState(m, Vector7d::Zero(), HandVector::Zero(), 0.0, &data);
  SignedDistanceOptions options;
  options.max_distance = 0.1;
  const SignedDistanceResult far =
      SignedDistance(m, GroupSet::Robot(), CollisionGroup::kTable, &data, options);
  EXPECT_EQ(far.status, SignedDistanceResult::Status::kBeyondMaxDistance);
  EXPECT_GT(far.distance, 0.1);
  EXPECT_LE(far.distance, 0.31 + 1e-9);
  options.max_distance = 0.5;
  const SignedDistanceResult near =
      SignedDistance(m, GroupSet::Robot(), CollisionGroup::kTable, &data, options);
  EXPECT_EQ(near.status, SignedDistanceResult::Status::kOk);
  EXPECT_NEAR(near.distance, 0.31, kDistanceTol);
  // no pair between a group and itself when its shapes are all ignored together.
  EXPECT_EQ(SignedDistance(m, CollisionGroup::kHand, CollisionGroup::kHand, &data).status,
            SignedDistanceResult::Status::kNoPairs);
}

TEST(CollisionScene, ThreadsWithTheirOwnDataAgreeWithOneThread) {
  const CollisionModel& m = Model();
  std::mt19937_64 rng(5);
  std::vector<RobotState> states;
  for (int n = 0; n < 16; ++n) states.push_back({RandomArm(&rng), RandomHand(&rng)});
  const Eigen::Isometry3d X_WO = Scene().ObjectPose(Deg(60));
  CollisionData data(m);
  const std::vector<double> expected =
      ClearanceProfile(m, states, X_WO, GroupSet::Robot(), GroupSet::Robot() | GroupSet::World(),
                       &data)
          .Clearances();
  std::vector<std::vector<double>> results(2);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < results.size(); ++t) {
    threads.emplace_back([&m, &states, &X_WO, &results, t] {
      CollisionData own(m);
      results[t] = ClearanceProfile(m, states, X_WO, GroupSet::Robot(),
                                    GroupSet::Robot() | GroupSet::World(), &own)
                       .Clearances();
    });
  }
  for (std::thread& t : threads) t.join();
  for (const std::vector<double>& r : results) EXPECT_EQ(r, expected);
}

TEST(CollisionScene, DataIsTiedToItsModel) {
  const CollisionModel copy = Model();  // copies share the description
  CollisionData data(copy);
  SetState(Model(), Vector7d::Zero(), HandVector::Zero(), 0.0, &data);
  CollisionData moved = std::move(data);
  EXPECT_TRUE(moved.has_state());
  EXPECT_FALSE(Collide(Model(), GroupSet::Robot(), GroupSet::World(), &moved).collision());
  const CollisionModel other(Robot(), Scene());
  EXPECT_DEATH(SetState(other, Vector7d::Zero(), HandVector::Zero(), 0.0, &moved),
               "another CollisionModel");
  CollisionData fresh(Model());
  EXPECT_DEATH(Collide(Model(), GroupSet::Robot(), GroupSet::World(), &fresh), "SetState");
}

}  // namespace
}  // namespace graspsynth
