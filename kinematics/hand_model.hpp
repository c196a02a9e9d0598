#pragma once

/// @file
/// The immutable model of the Gifu Hand III (STYLE.md's Model/Data split) and its forward
/// kinematics: its fingers (any number, each of any number of revolute joints) and their order,
/// couplings and actuated numbering as the description says; for the Gifu five fingers (thumb,
/// index, middle, ring, little) of four joints each: 20 joints, 16 actuated, the DIP joint (j4) of
/// each non-thumb finger following its PIP joint (j3) through a coupling. Built once from the
/// robot description (kinematics/robot_description.hpp); frames and the joint order f0..f15 are
/// documented in models/README.md.
///
/// Frames: H is the hand mount (the paper's "wrist"): z along the hand toward the fingertips,
/// x the palm normal (the side the fingers flex toward), y toward the thumb/index side. P is the
/// palm link, L the link frames of the phalanges, T the fingertip frames.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/arm_model.hpp"
#include "kinematics/types.hpp"

namespace graspsynth {

/// The values of every hand joint in radians, actuated and coupled, finger-major: the model's
/// fingers in order, each finger's joints proximal to distal (index HandModel::JointIndex(finger,
/// joint)); sized HandModel::joint_count() (20 for the Gifu Hand III: thumb j1..j4, index
/// j1..j4, middle j1..j4, ring j1..j4, little j1..j4).
using HandJointVector = Eigen::VectorXd;

/// A passive joint that follows another one: q = multiplier * q_source + offset.
struct JointCoupling {
  int source = -1;          ///< HandJointVector index of the driving, actuated joint
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

/// One finger: its joints and their child links (one or more, as many links as joints),
/// proximal to distal, and the fingertip frame.
struct Finger {
  std::string name;  ///< unique in the hand (result files name fingers by it)
  /// joints[0]'s parent is the palm (its X_PJ is in the palm frame P); joints[k]'s parent is
  /// links[k - 1].
  std::vector<HandJoint> joints;
  /// links[k] is the child of joints[k]; its frame is joints[k]'s frame turned by the joint angle.
  std::vector<RigidLink> links;
  std::string tip_name;                                    ///< name of the fingertip frame
  Eigen::Isometry3d X_LT = Eigen::Isometry3d::Identity();  ///< fingertip T in the distal link
};

/// A hand of any number of fingers, each of any number of joints (the Gifu Hand III: thumb,
/// index, middle, ring, little, four joints each). The actuated joints are numbered f0..f15 as
/// the description says (for the Gifu the order of models/README.md: thumb j1..j4, then j1..j3 of
/// index, middle, ring, little); the hand must have kHandDof actuated joints for now.
class HandModel {
 public:
  /// Checks the model and collects the limits of the actuated joints. `source` names the
  /// description (a file) in messages; `mount` is the link of frame H (the adapter between the
  /// flange and the palm), `palm` the palm link and X_HP its pose in H; `fingers` in the order of
  /// every HandJointVector. Throws InputError naming the joint, link or finger when: there is no
  /// finger, a finger has no joint, not one link per joint, or an empty or repeated name; the
  /// hand has more than 63 joints; a joint range is empty, its velocity or effort limit is not
  /// positive, or its axis is not a unit vector; the hand has other than kHandDof actuated
  /// joints, or their indices are not 0..kHandDof-1 each exactly once; a coupled joint has no
  /// coupling, or its source is not an actuated joint or its multiplier is not finite; a link
  /// (mount, palm, phalanx) has no positive mass.
  HandModel(std::string source, RigidLink mount, RigidLink palm, const Eigen::Isometry3d& X_HP,
            std::vector<Finger> fingers);

  /// The description the model was built from (a file name), for messages.
  const std::string& source() const { return source_; }
  /// The link of frame H: the adapter between the flange and the palm.
  const RigidLink& mount() const { return mount_; }
  /// The palm link (frame P): a box from the wrist plane.
  const RigidLink& palm() const { return palm_; }
  /// Pose of the palm frame P in the hand-mount frame H.
  const Eigen::Isometry3d& X_HP() const { return X_HP_; }
  /// Number of fingers (5 for the Gifu).
  int finger_count() const { return static_cast<int>(fingers_.size()); }
  /// Number of hand joints, actuated and coupled: the size of a HandJointVector (20 for the
  /// Gifu). It is also the index that stands for the palm and mount where a hand link is named
  /// by its joint's index (contact reports).
  int joint_count() const { return static_cast<int>(joint_finger_.size()); }
  /// Finger i in 0..finger_count()-1 (the Gifu: thumb, index, middle, ring, little).
  const Finger& finger(int i) const { return fingers_[static_cast<size_t>(i)]; }
  /// Every finger, in order.
  const std::vector<Finger>& fingers() const { return fingers_; }
  /// The fingers' names in order (the Gifu: thumb, index, middle, ring, little).
  std::vector<std::string> finger_names() const;
  /// HandJointVector index of joint `joint` (0-based, proximal first) of finger `finger`.
  int JointIndex(int finger, int joint) const {
    return first_joint_[static_cast<size_t>(finger)] + joint;
  }
  /// The finger of hand joint j (HandJointVector index), and j's place in that finger.
  int joint_finger(int j) const { return joint_finger_[static_cast<size_t>(j)]; }
  int joint_in_finger(int j) const {
    return j - first_joint_[static_cast<size_t>(joint_finger(j))];
  }
  /// The joint with HandJointVector index j.
  const HandJoint& joint(int j) const {
    return fingers_[static_cast<size_t>(joint_finger(j))]
        .joints[static_cast<size_t>(joint_in_finger(j))];
  }
  /// The child link of hand joint j (HandJointVector index).
  const RigidLink& link(int j) const {
    return fingers_[static_cast<size_t>(joint_finger(j))]
        .links[static_cast<size_t>(joint_in_finger(j))];
  }
  /// True when hand joint j's child link is its finger's last (distal) link.
  bool is_distal(int j) const {
    return joint_in_finger(j) + 1 == static_cast<int>(finger(joint_finger(j)).joints.size());
  }

  /// Limits of the actuated joints f0..f15: rad, rad, rad/s, N m.
  const HandVector& lower() const { return lower_; }
  const HandVector& upper() const { return upper_; }
  const HandVector& max_velocity() const { return max_velocity_; }
  const HandVector& max_effort() const { return max_effort_; }
  /// Joint names of f0..f15 (e.g. "thumb_j1", ..., "little_j3").
  const std::array<std::string, kHandDof>& actuated_names() const { return actuated_names_; }
  /// HandJointVector index of actuated joint f_k.
  int actuated_joint_index(int k) const { return actuated_joint_index_[k]; }

  /// Sum of the masses of the mount, the palm and every phalanx link, kg.
  double total_mass() const;
  /// True when every f_k lies in [lower_k - tol, upper_k + tol].
  bool WithinLimits(const Eigen::Ref<const HandVector>& f, double tol = 0.0) const;

 private:
  void CheckFingers();
  void CheckActuation();

  std::string source_;
  RigidLink mount_;
  RigidLink palm_;
  Eigen::Isometry3d X_HP_;
  std::vector<Finger> fingers_;
  std::vector<int> first_joint_;   // by finger: the HandJointVector index of its first joint
  std::vector<int> joint_finger_;  // by HandJointVector index: the joint's finger
  HandVector lower_, upper_, max_velocity_, max_effort_;
  std::array<std::string, kHandDof> actuated_names_;
  std::array<int, kHandDof> actuated_joint_index_{};
};

/// Frames of the hand for one configuration, all in the hand-mount frame H (a ...Data in
/// STYLE.md's sense; make one per thread). HandLinkFrames sizes it to its model.
struct HandFrames {
  /// Pose of the palm P in H.
  Eigen::Isometry3d X_HP = Eigen::Isometry3d::Identity();
  /// X_HL[i][k]: pose of finger i's link k (the child of its joint k) in H.
  std::vector<std::vector<Eigen::Isometry3d>> X_HL;
  /// X_HT[i]: pose of finger i's fingertip frame in H.
  std::vector<Eigen::Isometry3d> X_HT;

  /// Sizes X_HL and X_HT to `hand`'s fingers and joints (no allocation when they fit already).
  void Resize(const HandModel& hand);
};

/// Values of every hand joint (radians, HandJointVector order) for the actuated joints f
/// (radians, f0..f15): actuated joints copy f, coupled joints follow their source
/// (multiplier * source + offset). Neither f nor the coupled values are clamped to the limits.
HandJointVector HandJointPositions(const HandModel& hand, const Eigen::Ref<const HandVector>& f);

/// Computes the palm, every phalanx link frame and every fingertip frame in H at the actuated
/// joint values f (radians, f0..f15); coupled joints follow their source joints.
void HandLinkFrames(const HandModel& hand, const Eigen::Ref<const HandVector>& f,
                    HandFrames* frames);

}  // namespace graspsynth
