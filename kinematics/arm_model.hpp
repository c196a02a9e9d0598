#pragma once

/// @file
/// The immutable model of a 7-joint spherical-revolute-spherical (SRS) arm, the PA-10-7C or the
/// KUKA LBR iiwa (STYLE.md's Model/Data split): joints, links, the SRS lengths that the analytic
/// IK needs and the map of the description's joint values onto the DH table of
/// reference/robot.md 1.3 (joint signs and offsets, a constant flange turn). It is built once,
/// from the robot description (kinematics/robot_description.hpp, kinematics/robot_file.hpp),
/// and never changes.

#include <array>
#include <memory>
#include <string>
#include <string_view>
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

/// How the description's joint values q map onto the standard DH table of reference/robot.md
/// 1.3, which the analytic IK works in: q_dh_i = sign_i q_i + offset_i, and the flange F is DH
/// frame 7 turned by the constant R_7F (R_WF = R_W7(q_dh) R_7F; the origins coincide). The
/// PA-10's map is the identity; the iiwa's has sign -1 at A4 (its elbow turns the other way).
struct DhJointMap {
  std::array<int, kArmDof> sign = {1, 1, 1, 1, 1, 1, 1};  ///< +1 or -1 per joint
  Vector7d offset = Vector7d::Zero();                     ///< rad, per joint
  Eigen::Matrix3d R_7F = Eigen::Matrix3d::Identity();     ///< flange F in DH frame 7
  /// Every sign +1, every offset exactly 0 and R_7F exactly I: the maps below then return
  /// their argument unchanged (no multiply, no add, so a -0.0 stays -0.0).
  bool identity = true;

  /// q_dh = sign q + offset (rad).
  Vector7d ToDh(const Eigen::Ref<const Vector7d>& q) const;
  /// q = sign (q_dh - offset) (rad); the inverse of ToDh.
  Vector7d ToJoints(const Eigen::Ref<const Vector7d>& q_dh) const;
  /// Pose of DH frame 7 (world) when the flange is at X_WF (world): X_WF with R_WF R_7F^T.
  Eigen::Isometry3d FlangeToDh(const Eigen::Isometry3d& X_WF) const;
  /// Pose of the flange (world) when DH frame 7 is at X_W7 (world): X_W7 with R_W7 R_7F.
  Eigen::Isometry3d DhToFlange(const Eigen::Isometry3d& X_W7) const;
};

/// How ArmModel reads a chain beyond its joints and links (the robot file's arm part sets
/// them, kinematics/robot_file.hpp).
struct ArmChainOptions {
  /// Pose of the flange F in link 7's frame: the fixed joints after the last arm joint
  /// (identity when link 7 is the flange, as on the PA-10; Tz(0.045 m) on the iiwa).
  Eigen::Isometry3d X_7F = Eigen::Isometry3d::Identity();
  /// m: how far the SRS checks let the axes and the flange miss their meeting points and the
  /// description's flange miss the DH table's (the robot file's arm.srs_tolerance_m).
  double srs_tolerance_m = 1e-6;

  /// False (with the reason in `why` when not null) when srs_tolerance_m is not in
  /// (0, 0.01] m or X_7F is not finite.
  bool IsValid(std::string* why) const;
};

/// A 7-joint SRS arm. Link i (1..7) is the child of joint i; link 0 is the base. The flange F
/// is fixed to link 7 (ArmModel::X_7F(); on the PA-10 link 7's frame is the flange, standard DH
/// frame 7). The world frame is the base frame.
class ArmModel {
 public:
  /// Checks that the chain is an SRS arm of the DH pattern of reference/robot.md 1.3 (joint
  /// axes intersecting at the shoulder and the wrist centre, a single elbow joint, the flange
  /// on the last axis, each within options.srs_tolerance_m) and derives its SrsLengths from the
  /// joint origins and its DhJointMap from the axes at q = 0 (each joint's sign from its axis
  /// against the DH table's, each offset from where the next axis or link points; offsets of
  /// S1, S3, E2 in (-pi/2, pi/2], the last joint's 0, the rest of the flange's turn in R_7F).
  /// `source` names the description (a file) in messages. Throws InputError naming the
  /// offending joint (and by how much it misses) otherwise, or when a limit is missing or
  /// empty, or when the options are not valid.
  ArmModel(std::string source, RigidLink base, std::array<RevoluteJoint, kArmDof> joints,
           std::array<RigidLink, kArmDof> links, const ArmChainOptions& options = {});

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
  /// Pose of the flange F in link 7's frame (identity on the PA-10).
  const Eigen::Isometry3d& X_7F() const { return X_7F_; }
  /// The map of joint values onto the DH table (identity on the PA-10).
  const DhJointMap& dh_map() const { return dh_map_; }
  /// The joint limits in DH values (rad): [sign l + o, sign u + o] ordered, so a flipped
  /// joint's [lower, upper] is [-upper + o, -lower + o]. Equal to lower()/upper() on the PA-10.
  const Vector7d& dh_lower() const { return dh_lower_; }
  const Vector7d& dh_upper() const { return dh_upper_; }

  /// True when every q_i lies in [lower_i - tol, upper_i + tol].
  bool WithinLimits(const Eigen::Ref<const Vector7d>& q, double tol = 0.0) const;

 private:
  std::string source_;
  RigidLink base_;
  std::array<RevoluteJoint, kArmDof> joints_;
  std::array<RigidLink, kArmDof> links_;
  SrsLengths lengths_;
  Vector7d lower_, upper_, max_velocity_, max_effort_;
  Eigen::Isometry3d X_7F_ = Eigen::Isometry3d::Identity();
  DhJointMap dh_map_;
  Vector7d dh_lower_, dh_upper_;
};

/// Link frames of the arm for one configuration (a ...Data in STYLE.md's sense).
struct ArmFrames {
  /// X_WL[i]: pose of link i in world; X_WL[0] is the base, X_WL[7] link 7 (the flange on the
  /// PA-10; in general the flange is X_WL[7] * arm.X_7F()).
  std::array<Eigen::Isometry3d, kArmDof + 1> X_WL;
};

/// Computes every link frame of the arm at configuration q (radians) through the description's
/// joint origins and axes.
void ArmLinkFrames(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q, ArmFrames* frames);

/// Flange pose X_WF at configuration q (rad), through the standard DH table of the model's
/// lengths and its DhJointMap (on the PA-10 exactly DhFlangePose(lengths, q)).
Eigen::Isometry3d ArmFlangePose(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q);

/// Pose of DH frame 7 of the standard DH chain (reference/robot.md 1.3) with the given
/// lengths at DH joint values q (rad).
Eigen::Isometry3d DhFlangePose(const SrsLengths& lengths, const Eigen::Ref<const Vector7d>& q);

}  // namespace graspsynth
