#include "kinematics/hand_model.hpp"

#include <cmath>
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
                     const Eigen::Isometry3d& X_HP, std::array<Finger, kFingers> fingers)
    : source_(std::move(source)),
      mount_(std::move(mount)),
      palm_(std::move(palm)),
      X_HP_(X_HP),
      fingers_(std::move(fingers)) {
  RequirePositiveMass(source_, mount_);
  RequirePositiveMass(source_, palm_);

  std::array<int, kHandDof> seen;
  seen.fill(-1);
  for (int i = 0; i < kFingers; ++i) {
    const Finger& finger = fingers_[i];
    if (finger.name != kFingerNames[i]) {
      throw InputError(source_ + ": finger " + std::to_string(i) + " must be '" +
                       std::string(kFingerNames[i]) + "', is '" + finger.name + "'");
    }
    for (int k = 0; k < kFingerJoints; ++k) {
      const HandJoint& hj = finger.joints[k];
      CheckJointLimits(source_, hj.joint);
      RequirePositiveMass(source_, finger.links[k]);
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
        seen[hj.actuated] = HandJointIndex(i, k);
      } else if (!hj.coupling) {
        throw InputError(where + " is neither actuated nor coupled to another joint");
      }
    }
  }
  for (int a = 0; a < kHandDof; ++a) {
    if (seen[a] < 0) {
      throw InputError(source_ + ": no hand joint drives actuated index f" + std::to_string(a));
    }
  }
  // couplings are checked after every actuated joint is known.
  for (int j = 0; j < kHandJoints; ++j) {
    const HandJoint& hj = joint(j);
    if (hj.is_actuated()) continue;
    const JointCoupling& c = *hj.coupling;
    const std::string where = source_ + ": hand joint '" + hj.joint.name + "'";
    if (c.source < 0 || c.source >= kHandJoints || !joint(c.source).is_actuated()) {
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

HandJointVector HandJointPositions(const HandModel& hand, const Eigen::Ref<const HandVector>& f) {
  HandJointVector q;
  for (int j = 0; j < kHandJoints; ++j) {
    const HandJoint& hj = hand.joint(j);
    if (hj.is_actuated()) q[j] = f[hj.actuated];
  }
  // the model guarantees that every coupling source is actuated, so one pass suffices.
  for (int j = 0; j < kHandJoints; ++j) {
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
  frames->X_HP = hand.X_HP();
  for (int i = 0; i < kFingers; ++i) {
    const Finger& finger = hand.finger(i);
    Eigen::Isometry3d X_HL = hand.X_HP();
    for (int k = 0; k < kFingerJoints; ++k) {
      X_HL = X_HL * JointMotion(finger.joints[k].joint, q[HandJointIndex(i, k)]);
      frames->X_HL[i][k] = X_HL;
    }
    frames->X_HT[i] = X_HL * finger.X_LT;
  }
}

}  // namespace graspsynth
