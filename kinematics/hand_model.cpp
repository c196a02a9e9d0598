#include "kinematics/hand_model.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <utility>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

void RequirePositiveMass(const std::string& source, const RigidLink& link) {
  if (!(link.inertia.mass > 0.0) || !std::isfinite(link.inertia.mass)) {
    std::ostringstream msg;
    msg << source << ": hand link '" << link.name << "' needs a positive mass, has "
        << link.inertia.mass << " kg";
    throw InputError(msg.str());
  }
}

void CheckJointLimits(const std::string& source, const RevoluteJoint& j) {
  std::ostringstream where;
  where << source << ": hand joint '" << j.name << "'";
  if (!(j.lower < j.upper)) {
    std::ostringstream msg;
    msg << where.str() << " has an empty position range [" << j.lower << ", " << j.upper << "] rad";
    throw InputError(msg.str());
  }
  if (!(j.max_velocity > 0.0)) {
    std::ostringstream msg;
    msg << where.str() << " needs a positive velocity limit, has " << j.max_velocity;
    throw InputError(msg.str());
  }
  if (!(j.max_effort > 0.0)) {
    std::ostringstream msg;
    msg << where.str() << " needs a positive effort limit, has " << j.max_effort;
    throw InputError(msg.str());
  }
  if (std::abs(j.axis_J.norm() - 1.0) > 1e-9) {
    throw InputError(where.str() + " has an axis that is not a unit vector");
  }
}

Eigen::Isometry3d JointMotion(const RevoluteJoint& joint, double q) {
  Eigen::Isometry3d X = joint.X_PJ;
  X.rotate(Eigen::AngleAxisd(q, joint.axis_J));
  return X;
}

}  // namespace

HandModel::HandModel(std::string source, RigidLink mount, RigidLink palm,
                     const Eigen::Isometry3d& X_HP, std::vector<Finger> fingers)
    : source_(std::move(source)),
      mount_(std::move(mount)),
      palm_(std::move(palm)),
      X_HP_(X_HP),
      fingers_(std::move(fingers)) {
  RequirePositiveMass(source_, mount_);
  RequirePositiveMass(source_, palm_);
  CheckFingers();
  CheckActuation();
}

// the fingers' names, joint and link counts, limits and masses; fills the joint numbering.
void HandModel::CheckFingers() {
  if (fingers_.empty()) throw InputError(source_ + ": the hand has no finger");
  std::set<std::string> names;
  for (size_t i = 0; i < fingers_.size(); ++i) {
    const Finger& finger = fingers_[i];
    const std::string where =
        source_ + ": finger " + std::to_string(i) + " ('" + finger.name + "')";
    if (finger.name.empty()) throw InputError(where + " has no name");
    if (!names.insert(finger.name).second) throw InputError(where + " repeats a finger's name");
    if (finger.joints.empty()) throw InputError(where + " has no joint");
    if (finger.links.size() != finger.joints.size()) {
      throw InputError(where + " has " + std::to_string(finger.joints.size()) + " joints but " +
                       std::to_string(finger.links.size()) + " links; it needs one per joint");
    }
    first_joint_.push_back(static_cast<int>(joint_finger_.size()));
    for (size_t k = 0; k < finger.joints.size(); ++k) {
      CheckJointLimits(source_, finger.joints[k].joint);
      RequirePositiveMass(source_, finger.links[k]);
      joint_finger_.push_back(static_cast<int>(i));
    }
  }
  // contact reports keep one bit per hand link and one for the palm (ContactReport).
  if (joint_count() > 63) {
    throw InputError(source_ + ": the hand has " + std::to_string(joint_count()) +
                     " joints; at most 63 are supported");
  }
}

// the actuated numbering f0..f15 and the couplings.
void HandModel::CheckActuation() {
  std::array<int, kHandDof> seen;
  seen.fill(-1);
  int actuated = 0;
  for (int j = 0; j < joint_count(); ++j) actuated += joint(j).is_actuated() ? 1 : 0;
  if (actuated != kHandDof) {
    throw InputError(source_ + ": the hand has " + std::to_string(actuated) +
                     " actuated joints (joints without a coupling); graspsynth needs " +
                     std::to_string(kHandDof) + " for now");
  }
  for (int j = 0; j < joint_count(); ++j) {
    const HandJoint& hj = joint(j);
    const std::string where = source_ + ": hand joint '" + hj.joint.name + "'";
    if (hj.is_actuated()) {
      if (hj.actuated >= kHandDof) {
        throw InputError(where + " has actuated index " + std::to_string(hj.actuated) +
                         "; the hand has " + std::to_string(kHandDof) + " actuated joints");
      }
      if (seen[hj.actuated] >= 0) {
        throw InputError(where + " has actuated index " + std::to_string(hj.actuated) +
                         ", already used by '" + joint(seen[hj.actuated]).joint.name + "'");
      }
      if (hj.coupling) {
        throw InputError(where + " is actuated and must not also have a coupling");
      }
      seen[hj.actuated] = j;
    } else if (!hj.coupling) {
      throw InputError(where + " is neither actuated nor coupled to another joint");
    }
  }
  for (int a = 0; a < kHandDof; ++a) {
    if (seen[a] < 0) {
      throw InputError(source_ + ": no hand joint drives actuated index f" + std::to_string(a));
    }
  }
  // couplings are checked after every actuated joint is known.
  for (int j = 0; j < joint_count(); ++j) {
    const HandJoint& hj = joint(j);
    if (hj.is_actuated()) continue;
    const JointCoupling& c = *hj.coupling;
    const std::string where = source_ + ": hand joint '" + hj.joint.name + "'";
    if (c.source < 0 || c.source >= joint_count() || !joint(c.source).is_actuated()) {
      throw InputError(where + " must follow an actuated hand joint");
    }
    if (!std::isfinite(c.multiplier) || !std::isfinite(c.offset) || c.multiplier == 0.0) {
      throw InputError(where + " has a coupling with a zero or non-finite multiplier or offset");
    }
  }

  for (int a = 0; a < kHandDof; ++a) {
    const RevoluteJoint& j = joint(seen[a]).joint;
    actuated_joint_index_[a] = seen[a];
    actuated_names_[a] = j.name;
    lower_[a] = j.lower;
    upper_[a] = j.upper;
    max_velocity_[a] = j.max_velocity;
    max_effort_[a] = j.max_effort;
  }
}

std::vector<std::string> HandModel::finger_names() const {
  std::vector<std::string> names;
  for (const Finger& finger : fingers_) names.push_back(finger.name);
  return names;
}

double HandModel::total_mass() const {
  double m = mount_.inertia.mass + palm_.inertia.mass;
  for (const Finger& finger : fingers_) {
    for (const RigidLink& link : finger.links) m += link.inertia.mass;
  }
  return m;
}

bool HandModel::WithinLimits(const Eigen::Ref<const HandVector>& f, double tol) const {
  return ((f.array() >= lower_.array() - tol) && (f.array() <= upper_.array() + tol)).all();
}

void HandFrames::Resize(const HandModel& hand) {
  X_HL.resize(static_cast<size_t>(hand.finger_count()));
  for (int i = 0; i < hand.finger_count(); ++i) {
    X_HL[static_cast<size_t>(i)].resize(hand.finger(i).joints.size());
  }
  X_HT.resize(static_cast<size_t>(hand.finger_count()));
}

HandJointVector HandJointPositions(const HandModel& hand, const Eigen::Ref<const HandVector>& f) {
  HandJointVector q(hand.joint_count());
  for (int j = 0; j < hand.joint_count(); ++j) {
    const HandJoint& hj = hand.joint(j);
    if (hj.is_actuated()) q[j] = f[hj.actuated];
  }
  // the model guarantees that every coupling source is actuated, so one pass suffices.
  for (int j = 0; j < hand.joint_count(); ++j) {
    const HandJoint& hj = hand.joint(j);
    if (!hj.is_actuated()) {
      q[j] = hj.coupling->multiplier * q[hj.coupling->source] + hj.coupling->offset;
    }
  }
  return q;
}

void HandLinkFrames(const HandModel& hand, const Eigen::Ref<const HandVector>& f,
                    HandFrames* frames) {
  const HandJointVector q = HandJointPositions(hand, f);
  frames->Resize(hand);
  frames->X_HP = hand.X_HP();
  for (int i = 0; i < hand.finger_count(); ++i) {
    const Finger& finger = hand.finger(i);
    Eigen::Isometry3d X_HL = hand.X_HP();
    for (size_t k = 0; k < finger.joints.size(); ++k) {
      X_HL = X_HL * JointMotion(finger.joints[k].joint, q[hand.JointIndex(i, static_cast<int>(k))]);
      frames->X_HL[static_cast<size_t>(i)][k] = X_HL;
    }
    frames->X_HT[static_cast<size_t>(i)] = X_HL * finger.X_LT;
  }
}

}  // namespace graspsynth
