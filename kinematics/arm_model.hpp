#pragma once

/// @file
/// The immutable model of the PA-10-7C arm (STYLE.md's Model/Data split): joints, links and the
/// spherical-revolute-spherical (SRS) lengths that the analytic IK needs. It is built once,
/// from the robot description (kinematics/robot_description.hpp), and never changes.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "kinematics/types.hpp"

namespace graspsynth {

struct TriangleMesh;

/// Collision (and visual) geometry attached to a link: a primitive or a triangle mesh.
struct CollisionShape {
  enum class Kind { kBox, kCapsule, kCylinder, kSphere, kMesh };
  Kind kind = Kind::kBox;
  /// Box: full side lengths (x, y, z). Capsule and cylinder: (radius, length of the straight
  /// part along the shape's z axis, 0). Sphere: (radius, 0, 0). Mesh: unused. Metres.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  /// Pose of the shape (centred at its origin; a mesh's own frame) in its link frame.
  Eigen::Isometry3d X_LG = Eigen::Isometry3d::Identity();
  /// Mesh: its closed triangle mesh (scene/triangle_mesh.hpp), shared between copies.
  std::shared_ptr<const TriangleMesh> mesh;
};

/// Mass properties of a link, in its link frame.
struct LinkInertia {
  double mass = 0.0;                                          ///< kg
  Eigen::Vector3d p_LCm = Eigen::Vector3d::Zero();            ///< centre of mass, m
  Eigen::Matrix3d I_Cm = Eigen::Matrix3d::Identity() * 1e-6;  ///< about the centre of mass, kg m^2
};

/// A rigid link with its mass properties and collision geometry.
struct RigidLink {
  std::string name;
  LinkInertia inertia;
  std::vector<CollisionShape> shapes;
};

/// A revolute joint as the robot description states it.
struct RevoluteJoint {
  std::string name;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();  ///< joint frame in parent link, q = 0
  Eigen::Vector3d axis_J = Eigen::Vector3d::UnitZ();       ///< unit axis in the joint frame
  double lower = 0.0;                                      ///< rad
  double upper = 0.0;                                      ///< rad
  double max_velocity = 0.0;                               ///< rad/s
  double max_effort = 0.0;                                 ///< N m
};

/// The four lengths of an SRS arm with the standard DH table of reference/robot.md 1.3.
struct SrsLengths {
  double d_bs = 0.0;  ///< base plate to shoulder centre, m
  double d_se = 0.0;  ///< shoulder centre to elbow, m
  double d_ew = 0.0;  ///< elbow to wrist centre, m
  double d_wt = 0.0;  ///< wrist centre to flange, m
};

/// The PA-10-7C arm. Link i (1..7) is the child of joint i; link 0 is the base. The frame of
/// link i is the modified-DH frame i, so the frame of link 7 is the flange F (standard DH frame
/// 7). The world frame is the base frame.
class ArmModel {
 public:
  /// Checks that the chain is an SRS arm of the DH pattern of reference/robot.md 1.3 (joint
  /// axes intersecting at the shoulder and the wrist centre, a single elbow joint, the flange
  /// on the last axis) and derives its SrsLengths from the joint origins. `source` names the
  /// description (a file) in messages. Throws InputError naming the offending joint otherwise,
  /// or when a limit is missing or empty.
  ArmModel(std::string source, RigidLink base, std::array<RevoluteJoint, kArmDof> joints,
           std::array<RigidLink, kArmDof> links);

  /// An arm with the standard DH table for the given lengths, the given joint limits, zero
  /// masses and no geometry. For tests and tools that need only the kinematics.
  static ArmModel FromDh(const SrsLengths& lengths, const Vector7d& lower, const Vector7d& upper,
                         const Vector7d& max_velocity, const Vector7d& max_effort);

  const std::string& source() const { return source_; }
  const SrsLengths& lengths() const { return lengths_; }
  const RevoluteJoint& joint(int i) const { return joints_[i]; }
  const RigidLink& base() const { return base_; }
  /// Link i in 1..7 (link 7 carries the flange).
  const RigidLink& link(int i) const { return links_[i - 1]; }
  const Vector7d& lower() const { return lower_; }
  const Vector7d& upper() const { return upper_; }
  const Vector7d& max_velocity() const { return max_velocity_; }
  const Vector7d& max_effort() const { return max_effort_; }

  /// True when every q_i lies in [lower_i - tol, upper_i + tol].
  bool WithinLimits(const Eigen::Ref<const Vector7d>& q, double tol = 0.0) const;

 private:
  std::string source_;
  RigidLink base_;
  std::array<RevoluteJoint, kArmDof> joints_;
  std::array<RigidLink, kArmDof> links_;
  SrsLengths lengths_;
  Vector7d lower_, upper_, max_velocity_, max_effort_;
};

/// Link frames of the arm for one configuration (a ...Data in STYLE.md's sense).
struct ArmFrames {
  /// X_WL[i]: pose of link i in world; X_WL[0] is the base, X_WL[7] the flange.
  std::array<Eigen::Isometry3d, kArmDof + 1> X_WL;
};

/// Computes every link frame of the arm at configuration q (radians) through the description's
/// joint origins and axes.
void ArmLinkFrames(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q, ArmFrames* frames);

/// Flange pose X_WF at configuration q, through the standard DH table of the model's lengths.
Eigen::Isometry3d ArmFlangePose(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q);

/// Flange pose of the standard DH chain (reference/robot.md 1.3) with the given lengths.
Eigen::Isometry3d DhFlangePose(const SrsLengths& lengths, const Eigen::Ref<const Vector7d>& q);

}  // namespace graspsynth
