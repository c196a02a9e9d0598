#pragma once

/// @file
/// The immutable model of the Gifu Hand III (STYLE.md's Model/Data split) and its forward
/// kinematics. Five fingers (thumb, index, middle, ring, little) of four revolute joints each:
/// 20 joints, 16 actuated. The DIP joint (j4) of each non-thumb finger follows its PIP joint (j3)
/// through a coupling. Built once from the robot description (kinematics/robot_description.hpp);
/// frames and the joint order f0..f15 are documented in models/README.md.
///
/// Frames: H is the hand mount (the paper's "wrist"): z along the hand toward the fingertips,
/// x the palm normal (the side the fingers flex toward), y toward the thumb/index side. P is the
/// palm link, L the link frames of the phalanges, T the fingertip frames.

#include <array>
#include <optional>
#include <string>
#include <string_view>

#include "kinematics/arm_model.hpp"
#include "kinematics/types.hpp"

namespace graspsynth {

/// Number of fingers (thumb first).
inline constexpr int kFingers = 5;
/// Joints per finger, proximal to distal.
inline constexpr int kFingerJoints = 4;
/// All hand joints, actuated and coupled.
inline constexpr int kHandJoints = kFingers * kFingerJoints;

/// The values of all 20 hand joints in radians, finger-major: thumb j1..j4, index j1..j4,
/// middle j1..j4, ring j1..j4, little j1..j4 (index = 4 * finger + joint).
using HandJointVector = Eigen::Matrix<double, kHandJoints, 1>;

/// Finger names in model order (the index used by HandModel::finger()).
inline constexpr std::array<std::string_view, kFingers> kFingerNames = {"thumb", "index", "middle",
                                                                        "ring", "little"};

/// Index of joint `joint` (0..3) of finger `finger` (0..4) in a HandJointVector.
constexpr int HandJointIndex(int finger, int joint) { return finger * kFingerJoints + joint; }

/// A passive joint that follows another one: q = multiplier * q_source + offset.
struct JointCoupling {
  int source = -1;          ///< HandJointVector index (0..19) of the driving, actuated joint
  double multiplier = 1.0;  ///< dimensionless
  double offset = 0.0;      ///< rad
};

/// One hand joint: its geometry and limits, and how it is driven - either actuated (an index
/// into HandVector) or coupled to another joint.
struct HandJoint {
  RevoluteJoint joint;
  int actuated = -1;                      ///< HandVector index 0..15; -1 when coupled
  std::optional<JointCoupling> coupling;  ///< set exactly when `actuated` is -1

  /// True when the joint has its own actuator (an index into HandVector).
  bool is_actuated() const { return actuated >= 0; }
};

/// One finger: four joints and their child links, proximal to distal, and the fingertip frame.
struct Finger {
  std::string name;
  /// joints[0]'s parent is the palm (its X_PJ is in the palm frame P); joints[k]'s parent is
  /// links[k - 1].
  std::array<HandJoint, kFingerJoints> joints;
  /// links[k] is the child of joints[k]; its frame is joints[k]'s frame turned by the joint angle.
  std::array<RigidLink, kFingerJoints> links;
  std::string tip_name;                                    ///< name of the fingertip frame
  Eigen::Isometry3d X_LT = Eigen::Isometry3d::Identity();  ///< fingertip T in the distal link
};

/// The Gifu Hand III. Finger i is kFingerNames[i]. The actuated joints are numbered f0..f15 in
/// the order of models/README.md (thumb j1..j4, then j1..j3 of index, middle, ring, little).
class HandModel {
 public:
  /// Checks the model and collects the limits of the actuated joints. `source` names the
  /// description (a file) in messages; `mount` is the link of frame H (the adapter between the
  /// flange and the palm), `palm` the palm link and X_HP its pose in H. Throws InputError naming
  /// the joint or link when: a finger is not named kFingerNames[i]; a joint range is empty, its
  /// velocity or effort limit is not positive, or its axis is not a unit vector; the actuated
  /// indices are not 0..15 each exactly once; a coupled joint has no coupling, or its source is
  /// not an actuated joint or its multiplier is not finite; a link (mount, palm, phalanx) has no
  /// positive mass.
  HandModel(std::string source, RigidLink mount, RigidLink palm, const Eigen::Isometry3d& X_HP,
            std::array<Finger, kFingers> fingers);

  /// The description the model was built from (a file name), for messages.
  const std::string& source() const { return source_; }
  /// The link of frame H: the adapter between the flange and the palm.
  const RigidLink& mount() const { return mount_; }
  /// The palm link (frame P): a box from the wrist plane.
  const RigidLink& palm() const { return palm_; }
  /// Pose of the palm frame P in the hand-mount frame H.
  const Eigen::Isometry3d& X_HP() const { return X_HP_; }
  /// Finger i in 0..4 (thumb, index, middle, ring, little).
  const Finger& finger(int i) const { return fingers_[i]; }
  /// All five fingers, thumb first.
  const std::array<Finger, kFingers>& fingers() const { return fingers_; }
  /// The joint with HandJointVector index i (0..19).
  const HandJoint& joint(int i) const {
    return fingers_[i / kFingerJoints].joints[i % kFingerJoints];
  }

  /// Limits of the actuated joints f0..f15: rad, rad, rad/s, N m.
  const HandVector& lower() const { return lower_; }
  const HandVector& upper() const { return upper_; }
  const HandVector& max_velocity() const { return max_velocity_; }
  const HandVector& max_effort() const { return max_effort_; }
  /// Joint names of f0..f15 (e.g. "thumb_j1", ..., "little_j3").
  const std::array<std::string, kHandDof>& actuated_names() const { return actuated_names_; }
  /// HandJointVector index (0..19) of actuated joint f_k.
  int actuated_joint_index(int k) const { return actuated_joint_index_[k]; }

  /// Sum of the masses of the mount, the palm and every phalanx link, kg.
  double total_mass() const;
  /// True when every f_k lies in [lower_k - tol, upper_k + tol].
  bool WithinLimits(const Eigen::Ref<const HandVector>& f, double tol = 0.0) const;

 private:
  std::string source_;
  RigidLink mount_;
  RigidLink palm_;
  Eigen::Isometry3d X_HP_;
  std::array<Finger, kFingers> fingers_;
  HandVector lower_, upper_, max_velocity_, max_effort_;
  std::array<std::string, kHandDof> actuated_names_;
  std::array<int, kHandDof> actuated_joint_index_{};
};

/// Frames of the hand for one configuration, all in the hand-mount frame H (a ...Data in
/// STYLE.md's sense; make one per thread).
struct HandFrames {
  /// Pose of the palm P in H.
  Eigen::Isometry3d X_HP = Eigen::Isometry3d::Identity();
  /// X_HL[i][k]: pose of finger i's link k (the child of its joint k) in H.
  std::array<std::array<Eigen::Isometry3d, kFingerJoints>, kFingers> X_HL;
  /// X_HT[i]: pose of finger i's fingertip frame in H.
  std::array<Eigen::Isometry3d, kFingers> X_HT;
};

/// Values of all 20 hand joints (radians, HandJointVector order) for the actuated joints f
/// (radians, f0..f15): actuated joints copy f, coupled joints follow their source
/// (multiplier * source + offset). Neither f nor the coupled values are clamped to the limits.
HandJointVector HandJointPositions(const HandModel& hand, const Eigen::Ref<const HandVector>& f);

/// Computes the palm, every phalanx link frame and every fingertip frame in H at the actuated
/// joint values f (radians, f0..f15); coupled joints follow their source joints.
void HandLinkFrames(const HandModel& hand, const Eigen::Ref<const HandVector>& f,
                    HandFrames* frames);

}  // namespace graspsynth
