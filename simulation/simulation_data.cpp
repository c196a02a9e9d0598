/// @file
/// SimulationData's methods: the controller, the two kinds of step, and what a trial reads of
/// the world. The world itself is built in world_building.cpp; its contacts are found in
/// contacts.cpp and the structured step is in structured_step.cpp.

#include "simulation/simulation_data.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <utility>

#include "common/demand.hpp"
#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"
#include "simulation/detail/simulation_data_internal.hpp"

namespace graspsynth {
namespace sim_internal {
namespace {

using Clock = WallClock;

double Wrap(double a) { return std::remainder(a, 2.0 * M_PI); }

double Clamp(double x, double limit) { return std::clamp(x, -limit, limit); }

bool Finite3(const dReal* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

}  // namespace

// arm joint velocity commanded by the controller at the current state.
Vector7d WorldImpl::ArmVelocity() {
  violation = -1;
  Vector7d v;
  for (int i = 0; i < kArmDof; ++i) {
    if (arm_mode == ServoMode::kPosition) {
      double target = arm_command[i];
      if (target < arm_lower[i] || target > arm_upper[i]) {
        if (violation < 0) {
          violation = i;
          violation_value = target;
        }
        target = std::clamp(target, arm_lower[i], arm_upper[i]);
      }
      v[i] = Clamp(arm_ff[i] + model->options().arm_servo_gain * (target - q_arm[i]), arm_vmax[i]);
    } else {
      v[i] = Clamp(arm_command[i], arm_vmax[i]);
    }
    // the controller stops a joint at its limit.
    if ((q_arm[i] >= arm_upper[i] && v[i] > 0.0) || (q_arm[i] <= arm_lower[i] && v[i] < 0.0)) {
      v[i] = 0.0;
    }
  }
  return v;
}

// hand joint velocities (HandJointVector order) commanded at state q.
HandJointVector WorldImpl::HandVelocity(const HandJointVector& q) const {
  const HandModel& hand = robot().hand;
  const double gain = model->options().finger_servo_gain;
  HandJointVector v(hand.joint_count());
  for (int j = 0; j < hand.joint_count(); ++j) {
    const HandJoint& hj = hand.joint(j);
    double target_v = 0.0;
    if (hj.is_actuated()) {
      target_v = hand_mode == ServoMode::kPosition ? gain * (hand_command[hj.actuated] - q[j])
                                                   : hand_command[hj.actuated];
    } else {
      // a coupled joint (the Gifu's DIP): its target follows its source's measured angle.
      const JointCoupling& c = *hj.coupling;
      target_v = gain * (c.multiplier * q[c.source] + c.offset - q[j]);
    }
    v[j] = Clamp(target_v, hand_vmax[j]);
  }
  return v;
}

void WorldImpl::ReadJoints() {
  for (int i = 0; i < kArmDof; ++i) {
    if (!joint_dynamic(i)) continue;
    const double raw = dJointGetHingeAngle(arm_joints[i]);
    q_arm[i] += Wrap(raw - q_arm[i]);
  }
  if (hand_dynamic) {
    for (size_t j = 0; j < finger_joints.size(); ++j) {
      q_hand[static_cast<Eigen::Index>(j)] = dJointGetHingeAngle(finger_joints[j]);
    }
  }
}

void WorldImpl::ControlStep() {
  hand_dynamic = true;
  // arm: kinematic bodies get the velocity that carries them to the next state.
  const Vector7d va = ArmVelocity();
  if (arm_kinematic()) {
    const Vector7d q_next = q_arm + h * va;
    ArmFrames next;
    ArmLinkFrames(robot().arm, q_next, &next);
    for (int i = 0; i < kArmDof; ++i) {
      PlaceBody(arm[i], arm_frames.X_WL[i + 1]);
      SetBodyVelocity(arm[i], arm_frames.X_WL[i + 1], next.X_WL[i + 1], h);
    }
    arm_frames = next;
    q_arm = q_next;
  } else {
    // the kinematic joints (none in kDynamic) move their links to the next state; the
    // motors of the dynamic ones get their velocity.
    Vector7d q_next = q_arm;
    for (int i = 0; i < kArmDof; ++i) {
      if (!joint_dynamic(i)) q_next[i] = q_arm[i] + h * va[i];
    }
    ArmFrames next;
    if (options.arm_mode == ArmMode::kWristDynamic) ArmLinkFrames(robot().arm, q_next, &next);
    for (int i = 0; i < kArmDof; ++i) {
      if (joint_dynamic(i)) {
        dJointSetHingeParam(arm_joints[i], dParamVel, va[i]);
        dJointSetHingeParam(arm_joints[i], dParamFMax, arm_fmax[i]);
      } else {
        PlaceBody(arm[i], arm_frames.X_WL[i + 1]);
        SetBodyVelocity(arm[i], arm_frames.X_WL[i + 1], next.X_WL[i + 1], h);
        q_arm[i] = q_next[i];
      }
    }
  }
  const HandJointVector vh = HandVelocity(q_hand);
  for (int j = 0; j < static_cast<int>(finger_joints.size()); ++j) {
    dJointSetHingeParam(finger_joints[j], dParamVel, vh[j]);
    dJointSetHingeParam(finger_joints[j], dParamFMax, hand_fmax[j]);
    hand_vel[j] = vh[j];
  }
}

void WorldImpl::Step(StepComparison* compare) {
  GS_DEMAND(!compare || structured(), "StepBothWays needs the structured step");
  const auto t0 = Clock::now();
  ControlStep();
  const auto t1 = Clock::now();
  Collide(false);
  const auto t2 = Clock::now();
  // a non-finite state must not reach ODE, whose checks would fail deep inside the step.
  if (!StateIsFinite()) {
    dJointGroupEmpty(contact_group);
    throw OdeError("non-finite body state before step " + std::to_string(stats.dynamic_steps));
  }
  current_world_broken = &broken;
  SyncMounts();
  if (compare) {
    StepStructuredAndOde(compare);
  } else if (structured()) {
    StepStructured();
  } else {
    dWorldStep(world, h);
  }
  current_world_broken = nullptr;
  for (size_t k = 0; k < feedback_contact.size(); ++k) {
    const dReal* f = feedback[k].f1;
    hand_object[feedback_contact[k]].f_W = Eigen::Vector3d(f[0], f[1], f[2]);
  }
  dJointGroupEmpty(contact_group);
  const auto t3 = Clock::now();
  ReadJoints();
  if (!arm_kinematic()) ArmLinkFrames(robot().arm, q_arm, &arm_frames);
  time += h;
  stats.dynamic_steps++;
  stats.control_s += SecondsBetween(t0, t1) + SecondsBetween(t3, Clock::now());
  stats.collision_s += SecondsBetween(t1, t2);
  stats.solver_s += SecondsBetween(t2, t3);
  stats.max_contacts = std::max(stats.max_contacts, report.total);
}

void WorldImpl::StepKinematically() {
  GS_DEMAND(!hand_dynamic, "StepKinematically after Step: the fingers are dynamic already");
  const auto t0 = Clock::now();
  const Vector7d va = ArmVelocity();
  const HandJointVector vh = HandVelocity(q_hand);
  const Vector7d qa_next = q_arm + h * va;
  const HandJointVector qh_next = q_hand + h * vh;
  ArmFrames af;
  HandFrames& hf = next_hand_frames;
  ComputeFrames(qa_next, qh_next, &af, &hf);
  const Eigen::Isometry3d X_WH0 = arm_frames.X_WL[kArmDof] * robot().X_FH;
  const Eigen::Isometry3d X_WH1 = af.X_WL[kArmDof] * robot().X_FH;
  for (int i = 0; i < kArmDof; ++i) {
    PlaceBody(arm[i], af.X_WL[i + 1]);
    SetBodyVelocity(arm[i], arm_frames.X_WL[i + 1], af.X_WL[i + 1], h);
  }
  const HandModel& hand = robot().hand;
  for (int j = 0; j < hand.joint_count(); ++j) {
    const size_t i = static_cast<size_t>(hand.joint_finger(j));
    const size_t k = static_cast<size_t>(hand.joint_in_finger(j));
    const Eigen::Isometry3d from = X_WH0 * hand_frames.X_HL[i][k];
    const Eigen::Isometry3d to = X_WH1 * hf.X_HL[i][k];
    PlaceBody(fingers[static_cast<size_t>(j)], to);
    SetBodyVelocity(fingers[static_cast<size_t>(j)], from, to, h);
  }
  arm_frames = af;
  std::swap(hand_frames, next_hand_frames);
  q_arm = qa_next;
  q_hand = qh_next;
  const auto t1 = Clock::now();
  Collide(true);
  time += h;
  stats.kinematic_steps++;
  stats.control_s += SecondsBetween(t0, t1);
  stats.collision_s += SecondsBetween(t1, Clock::now());
}

bool WorldImpl::StateIsFinite() const {
  bool ok = true;
  auto check = [&](dBodyID b) {
    const dReal* q = dBodyGetQuaternion(b);
    ok = ok && Finite3(dBodyGetPosition(b)) && Finite3(dBodyGetLinearVel(b)) &&
         Finite3(dBodyGetAngularVel(b)) && std::isfinite(q[0]) && Finite3(q + 1);
  };
  ForEachDynamic(check);
  for (const BodyPart& a : arm) check(a.body);
  return ok && q_arm.allFinite() && q_hand.allFinite();
}

}  // namespace sim_internal

using sim_internal::BodyOrientation;
using sim_internal::BodyPart;
using sim_internal::BodyPose;
using sim_internal::FromOdeMatrix;

SimulationData::SimulationData(const SimulationModel& model, const WorldOptions& options,
                               const Vector7d& arm_q, const HandVector& hand_f)
    : impl_(std::make_unique<Impl>()) {
  RequireValid(options, "invalid world option");
  EnsureOdeThread();
  impl_->model = &model;
  impl_->options = options;
  impl_->h = options.time_step;
  impl_->Build(arm_q, hand_f);
}

SimulationData::~SimulationData() = default;
SimulationData::SimulationData(SimulationData&&) noexcept = default;
SimulationData& SimulationData::operator=(SimulationData&&) noexcept = default;

void SimulationData::SetArmCommand(ServoMode mode, const Vector7d& value,
                                   const Vector7d& velocity_ff) {
  impl_->arm_mode = mode;
  impl_->arm_command = value;
  impl_->arm_ff = velocity_ff;
}

void SimulationData::SetHandCommand(ServoMode mode, const HandVector& value) {
  impl_->hand_mode = mode;
  impl_->hand_command = value;
}

void SimulationData::Step() { impl_->Step(); }

StepComparison SimulationData::StepBothWays() {
  StepComparison c;
  impl_->Step(&c);
  return c;
}

void SimulationData::StepKinematically() { impl_->StepKinematically(); }
double SimulationData::time() const { return impl_->time; }
Vector7d SimulationData::arm_positions() const { return impl_->q_arm; }

HandVector SimulationData::hand_positions() const {
  HandVector f;
  for (int k = 0; k < kHandDof; ++k) {
    f[k] = impl_->q_hand[impl_->robot().hand.actuated_joint_index(k)];
  }
  return f;
}

HandJointVector SimulationData::hand_joint_positions() const { return impl_->q_hand; }

Eigen::Isometry3d SimulationData::object_pose() const {
  return BodyPose(impl_->object.body) * Eigen::Translation3d(-impl_->object.p_LC);
}

Eigen::Vector3d SimulationData::object_velocity() const {
  const dReal* v = dBodyGetLinearVel(impl_->object.body);
  return {v[0], v[1], v[2]};
}

Eigen::Vector3d SimulationData::object_angular_velocity() const {
  const dReal* v = dBodyGetAngularVel(impl_->object.body);
  return {v[0], v[1], v[2]};
}

Eigen::Isometry3d SimulationData::wrist_pose() const {
  const BodyPart& wrist = impl_->arm[kArmDof - 1];
  return BodyPose(wrist.body) * Eigen::Translation3d(-wrist.p_LC) * impl_->robot().X_FH;
}

Eigen::Isometry3d SimulationData::arm_link_pose(int i) const {
  GS_DEMAND(i >= 1 && i <= kArmDof, "arm link index out of range");
  const BodyPart& b = impl_->arm[i - 1];
  return BodyPose(b.body) * Eigen::Translation3d(-b.p_LC);
}

Eigen::Isometry3d SimulationData::hand_link_pose(int j) const {
  GS_DEMAND(j >= 0 && j < impl_->robot().hand.joint_count(), "hand link index out of range");
  const BodyPart& b = impl_->fingers[j];
  return BodyPose(b.body) * Eigen::Translation3d(-b.p_LC);
}

const ContactReport& SimulationData::contacts() const { return impl_->report; }
const std::vector<HandObjectContact>& SimulationData::hand_object_contacts() const {
  return impl_->hand_object;
}
int SimulationData::limit_violation() const { return impl_->violation; }
double SimulationData::limit_violation_value() const { return impl_->violation_value; }

bool SimulationData::IsFinite() const { return impl_->StateIsFinite(); }

double SimulationData::HandObjectKineticEnergy() const {
  double e = 0.0;
  impl_->ForEachDynamic([&](dBodyID b) {
    dMass m;
    dBodyGetMass(b, &m);
    const dReal* v = dBodyGetLinearVel(b);
    const dReal* w = dBodyGetAngularVel(b);
    const Eigen::Vector3d vw(v[0], v[1], v[2]), ww(w[0], w[1], w[2]);
    const Eigen::Matrix3d R = BodyOrientation(b).toRotationMatrix();
    const Eigen::Matrix3d I = FromOdeMatrix(m.I);
    const Eigen::Vector3d wb = R.transpose() * ww;
    e += 0.5 * m.mass * vw.squaredNorm() + 0.5 * wb.dot(I * wb);
  });
  return e;
}

double SimulationData::MaxDynamicSpeed() const {
  double s = 0.0;
  impl_->ForEachDynamic([&](dBodyID b) {
    const dReal* v = dBodyGetLinearVel(b);
    s = std::max(s, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  });
  return s;
}

double SimulationData::MaxDynamicAngularSpeed() const {
  double s = 0.0;
  impl_->ForEachDynamic([&](dBodyID b) {
    const dReal* v = dBodyGetAngularVel(b);
    s = std::max(s, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
  });
  return s;
}

WorldCounts SimulationData::counts() const {
  WorldCounts c;
  const int hand_joints = impl_->robot().hand.joint_count();
  c.bodies = kArmDof + hand_joints + 1;
  c.dynamic_bodies = hand_joints + 1 + impl_->dynamic_arm_joints();
  c.joints = hand_joints + impl_->dynamic_arm_joints();
  c.geoms = impl_->geom_count;
  return c;
}

const StepStatistics& SimulationData::statistics() const { return impl_->stats; }

void SimulationData::SetObjectVelocity(const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  dBodySetLinearVel(impl_->object.body, v.x(), v.y(), v.z());
  dBodySetAngularVel(impl_->object.body, w.x(), w.y(), w.z());
}

}  // namespace graspsynth
