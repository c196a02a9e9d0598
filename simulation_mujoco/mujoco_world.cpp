/// @file
/// MujocoModel and MujocoData (simulation_mujoco/mujoco_world.hpp) over MuJoCo's C API; without
/// MuJoCo in the build, every constructor throws InputError.

#include "simulation_mujoco/mujoco_world.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"

#ifdef GRASPSYNTH_HAS_MUJOCO
#include <mujoco/mujoco.h>

#include <cstring>
#include <mutex>
#include <stdexcept>

#include "common/stopwatch.hpp"
#endif

namespace graspsynth {

#ifndef GRASPSYNTH_HAS_MUJOCO

bool MujocoAvailable() { return false; }
std::string MujocoVersion() { return "none"; }

struct MujocoModel::Impl {};
struct MujocoData::Impl {};

MujocoModel::MujocoModel(const SimulationModel&, const MjcfModel&) {
  throw InputError(
      "this graspsynth is built without MuJoCo (install libmujoco-dev, or run scripts/setup.sh, "
      "and build again)");
}
MujocoModel::~MujocoModel() = default;
MujocoData::MujocoData(const MujocoModel&, const Vector7d&, const HandVector&) {
  throw InputError("this graspsynth is built without MuJoCo");
}
MujocoData::~MujocoData() = default;
void MujocoData::SetArmCommand(const Vector7d&, const Vector7d&) {}
void MujocoData::SetHandCommand(const HandVector&) {}
void MujocoData::Step() {}
void MujocoData::Kinematics() {}
void MujocoData::SetRobotPositions(const Vector7d&, const HandVector&) {}
double MujocoData::time() const { return 0.0; }
Vector7d MujocoData::arm_positions() const { return Vector7d::Zero(); }
HandVector MujocoData::hand_positions() const { return HandVector::Zero(); }
Eigen::Isometry3d MujocoData::object_pose() const { return Eigen::Isometry3d::Identity(); }
Eigen::Vector3d MujocoData::object_velocity() const { return Eigen::Vector3d::Zero(); }
Eigen::Vector3d MujocoData::object_angular_velocity() const { return Eigen::Vector3d::Zero(); }
Eigen::Isometry3d MujocoData::wrist_pose() const { return Eigen::Isometry3d::Identity(); }
Eigen::Isometry3d MujocoData::arm_link_pose(int) const { return Eigen::Isometry3d::Identity(); }
const ContactReport& MujocoData::contacts() const {
  static const ContactReport none;
  return none;
}
const std::vector<HandObjectContact>& MujocoData::hand_object_contacts() const {
  static const std::vector<HandObjectContact> none;
  return none;
}
int MujocoData::limit_violation() const { return -1; }
double MujocoData::limit_violation_value() const { return 0.0; }
bool MujocoData::IsFinite() const { return true; }
double MujocoData::HandObjectKineticEnergy() const { return 0.0; }
double MujocoData::MaxDynamicSpeed() const { return 0.0; }
double MujocoData::MaxDynamicAngularSpeed() const { return 0.0; }
WorldCounts MujocoData::counts() const { return {}; }
const StepStatistics& MujocoData::statistics() const {
  static const StepStatistics none;
  return none;
}

#else

namespace {

// MuJoCo's default error handler exits the process and its warning handler prints: the library
// never prints, and a failed simulation is a result. Errors throw (MuJoCo is left at a state
// that must be discarded), warnings are read from mjData's counters instead.
[[noreturn]] void ThrowMujocoError(const char* message) {
  throw std::runtime_error(std::string("MuJoCo error: ") + message);
}
void IgnoreMujocoWarning(const char*) {}

void InstallHandlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = &ThrowMujocoError;
    mju_user_warning = &IgnoreMujocoWarning;
  });
}

Eigen::Isometry3d Pose(const mjtNum* p, const mjtNum* R) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) X.linear()(r, c) = R[3 * r + c];
  }
  return X;
}

}  // namespace

bool MujocoAvailable() { return true; }
std::string MujocoVersion() { return mj_versionString(); }

struct MujocoModel::Impl {
  const SimulationModel* model = nullptr;
  mjModel* m = nullptr;
  std::array<int, kArmDof> arm_qpos{}, arm_dof{}, arm_body{};
  // by hand joint (HandJointVector order), sized by Index
  std::vector<int> hand_qpos, hand_dof, hand_body;
  std::array<int, kArmDof> arm_actuator{};
  std::vector<int> hand_actuator;
  int object_body = -1, object_qpos = -1, object_dof = -1, mount_body = -1;
  std::vector<MjcfGeom> geom_roles;  // by MuJoCo geom id
  std::vector<int> geom_has_role;

  ~Impl() {
    if (m) mj_deleteModel(m);
  }
  int Id(int type, const std::string& name) const {
    const int id = mj_name2id(m, type, name.c_str());
    if (id < 0) throw InputError("the MJCF model has no element named '" + name + "'");
    return id;
  }
  void Index(const MjcfModel& mjcf);
};

// addresses of the joints, bodies and geoms the world reads, by name.
void MujocoModel::Impl::Index(const MjcfModel& mjcf) {
  const RobotModel& r = model->robot();
  for (int i = 0; i < kArmDof; ++i) {
    const int j = Id(mjOBJ_JOINT, r.arm.joint(i).name);
    arm_qpos[i] = m->jnt_qposadr[j];
    arm_dof[i] = m->jnt_dofadr[j];
    arm_body[i] = Id(mjOBJ_BODY, r.arm.link(i + 1).name);
    arm_actuator[i] = Id(mjOBJ_ACTUATOR, r.arm.joint(i).name);
  }
  const size_t n = static_cast<size_t>(r.hand.joint_count());
  for (std::vector<int>* v : {&hand_qpos, &hand_dof, &hand_body, &hand_actuator}) v->assign(n, 0);
  for (size_t k = 0; k < n; ++k) {
    const int j = Id(mjOBJ_JOINT, r.hand.joint(static_cast<int>(k)).joint.name);
    hand_qpos[k] = m->jnt_qposadr[j];
    hand_dof[k] = m->jnt_dofadr[j];
    hand_body[k] = m->jnt_bodyid[j];
    hand_actuator[k] = Id(mjOBJ_ACTUATOR, r.hand.joint(static_cast<int>(k)).joint.name);
  }
  object_body = Id(mjOBJ_BODY, "object");
  const int oj = Id(mjOBJ_JOINT, "object");
  object_qpos = m->jnt_qposadr[oj];
  object_dof = m->jnt_dofadr[oj];
  mount_body = Id(mjOBJ_BODY, r.hand.mount().name);
  geom_roles.assign(m->ngeom, MjcfGeom{});
  geom_has_role.assign(m->ngeom, 0);
  for (const MjcfGeom& g : mjcf.geoms) {
    const int id = Id(mjOBJ_GEOM, g.name);
    geom_roles[id] = g;
    geom_has_role[id] = 1;
  }
}

MujocoModel::MujocoModel(const SimulationModel& model, const MjcfModel& mjcf)
    : impl_(std::make_unique<Impl>()) {
  InstallHandlers();
  impl_->model = &model;
  // the text through MuJoCo's virtual file system: nothing is written to disk.
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* name = "graspsynth.xml";
  if (mj_makeEmptyFileVFS(&vfs, name, static_cast<int>(mjcf.xml.size())) != 0) {
    throw InputError("MuJoCo's virtual file system refused the model");
  }
  std::memcpy(vfs.filedata[mj_findFileVFS(&vfs, name)], mjcf.xml.data(), mjcf.xml.size());
  char error[1000] = "";
  {
    // one compile at a time: the sweep compiles its runs' models on several threads, and
    // MuJoCo 2.2 does not promise that its XML parser may run on two at once.
    static std::mutex compile;
    std::lock_guard<std::mutex> lock(compile);
    impl_->m = mj_loadXML(name, &vfs, error, sizeof(error));
  }
  mj_deleteVFS(&vfs);
  if (!impl_->m) throw InputError(std::string("MuJoCo rejected the MJCF model: ") + error);
  impl_->Index(mjcf);
}

MujocoModel::~MujocoModel() = default;

// One servo as the exported model describes it: force = gain kv (ctrl - q) - kv qdot, capped.
struct Servo {
  int actuator = -1, qpos = -1, dof = -1;
  double kv = 0.0, cap = 0.0, gain = 0.0;
  bool finger = false;  // a hand joint's servo (Drive's second bound)
};

struct MujocoData::Impl {
  const MujocoModel::Impl* mm = nullptr;
  mjModel* m_own = nullptr;  // the model's copy whose servo parameters Drive() switches
  mjData* d = nullptr;
  std::vector<Servo> servos;  // the arm's, then the hand's joints (MakeServos)
  Vector7d arm_target = Vector7d::Zero(), arm_ff = Vector7d::Zero();
  HandVector hand_target = HandVector::Zero();
  int violation = -1;
  double violation_value = 0.0;
  ContactReport report;
  std::vector<HandObjectContact> hand_object;
  StepStatistics stats;

  ~Impl() {
    if (d) mj_deleteData(d);
    if (m_own) mj_deleteModel(m_own);
  }
  const mjModel* m() const { return m_own; }
  void MakeServos();
  void Drive(Servo& s, double v);
  const RobotModel& robot() const { return mm->model->robot(); }
  double q(int adr) const { return d->qpos[adr]; }
  void Control();
  void Report();
  void AddContact(const mjContact& c, int object_geom_side, const MjcfGeom& other);
};

void MujocoData::Impl::MakeServos() {
  const SimulationOptions& so = mm->model->options();
  servos.assign(static_cast<size_t>(kArmDof + robot().hand.joint_count()), Servo{});
  for (int k = 0; k < static_cast<int>(servos.size()); ++k) {
    Servo& s = servos[static_cast<size_t>(k)];
    const bool arm = k < kArmDof;
    s.actuator = arm ? mm->arm_actuator[k] : mm->hand_actuator[k - kArmDof];
    s.qpos = arm ? mm->arm_qpos[k] : mm->hand_qpos[k - kArmDof];
    s.dof = arm ? mm->arm_dof[k] : mm->hand_dof[k - kArmDof];
    s.kv = -m_own->actuator_biasprm[mjNBIAS * s.actuator + 2];
    s.cap = m_own->actuator_forcerange[2 * s.actuator + 1];
    s.gain = arm ? so.arm_servo_gain : so.finger_servo_gain;
    s.finger = !arm;
  }
}

// Drives servo `s` at joint velocity v (rad/s): force = kv (v - qdot), its damping integrated
// implicitly (which keeps a stiff servo on a light link stable), with kv lowered where its force
// would exceed the cap. MuJoCo 2.2's implicit integrator linearises a servo's force without its
// cap: a capped servo of gain kv acts in the step as a damper of gain kv, as if its link were
// h kv heavier, and hits what it touches as a hammer. The gain is lowered to cap / |v - qdot|,
// so that the force at the step's start is the cap; a finger's also to cap / |v|, so that the
// linearised force stays within the cap for any end-of-step velocity between the current one
// and rest: the step in which a closing finger meets the object stops it, and with the gain of
// free motion (v - qdot near 0) its servo would push with kv |v|, |v| / v_sat times its cap (400
// for a stiff finger at its 4 rad/s), where ODE's motor, solved with the contact, pushes with at
// most the cap (docs/mujoco.md, "Servos").
// The arm keeps the first bound only: its servos carry gravity, and ODE's fast trial moves it
// kinematically.
void MujocoData::Impl::Drive(Servo& s, double v) {
  const double error = std::abs(v - d->qvel[s.dof]);
  const double reach = s.finger ? std::max(error, std::abs(v)) : error;
  const double kv = reach * s.kv > s.cap ? s.cap / reach : s.kv;
  m_own->actuator_gainprm[mjNGAIN * s.actuator] = s.gain * kv;
  mjtNum* bias = m_own->actuator_biasprm + mjNBIAS * s.actuator;
  bias[1] = -s.gain * kv;
  bias[2] = -kv;
  d->ctrl[s.actuator] = d->qpos[s.qpos] + v / s.gain;
}

// the ODE world's controller (simulation/simulation_data.cpp, ArmVelocity and HandVelocity),
// its velocity commands turned into the servos' controls ctrl = q + v / gain.
void MujocoData::Impl::Control() {
  const SimulationOptions& so = mm->model->options();
  const ArmModel& arm = robot().arm;
  violation = -1;
  for (int i = 0; i < kArmDof; ++i) {
    double target = arm_target[i];
    if (target < arm.lower()[i] || target > arm.upper()[i]) {
      if (violation < 0) {
        violation = i;
        violation_value = target;
      }
      target = std::clamp(target, arm.lower()[i], arm.upper()[i]);
    }
    const double qi = q(mm->arm_qpos[i]);
    double v = std::clamp(arm_ff[i] + so.arm_servo_gain * (target - qi), -arm.max_velocity()[i],
                          arm.max_velocity()[i]);
    if ((qi >= arm.upper()[i] && v > 0.0) || (qi <= arm.lower()[i] && v < 0.0)) v = 0.0;
    Drive(servos[i], v);
  }
  const HandModel& hand = robot().hand;
  for (int j = 0; j < hand.joint_count(); ++j) {
    const HandJoint& hj = hand.joint(j);
    const double qj = q(mm->hand_qpos[static_cast<size_t>(j)]);
    double target = 0.0;
    if (hj.is_actuated()) {
      target = hand_target[hj.actuated];
    } else {
      // a coupled joint (the Gifu's DIP): its target follows its source's measured angle.
      const JointCoupling& c = *hj.coupling;
      target = c.multiplier * q(mm->hand_qpos[static_cast<size_t>(c.source)]) + c.offset;
    }
    const double v = std::clamp(so.finger_servo_gain * (target - qj), -hj.joint.max_velocity,
                                hj.joint.max_velocity);
    Drive(servos[static_cast<size_t>(kArmDof + j)], v);
  }
}

void MujocoData::Impl::AddContact(const mjContact& c, int object_side, const MjcfGeom& other) {
  // MuJoCo's normal points from geom1 to geom2; its contact force (mj_contactForce, in the
  // contact frame) acts on geom2 along it.
  const Eigen::Vector3d n(c.frame[0], c.frame[1], c.frame[2]);
  const double sign = object_side == 2 ? 1.0 : -1.0;
  HandObjectContact h;
  h.p_WC = Eigen::Vector3d(c.pos[0], c.pos[1], c.pos[2]);
  h.n_W = sign * n;
  h.depth = std::max(0.0, -c.dist);
  h.hand_link = other.hand_index;
  if (c.efc_address >= 0) {
    mjtNum f[6];
    mj_contactForce(m(), d, static_cast<int>(&c - d->contact), f);
    Eigen::Vector3d f_W = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k)
      f_W += f[k] * Eigen::Vector3d(c.frame[3 * k], c.frame[3 * k + 1], c.frame[3 * k + 2]);
    h.f_W = sign * f_W;
  }
  h.friction = c.friction[0];
  hand_object.push_back(h);
}

// what touched what, as the ODE world's ContactReport counts it (simulation/contacts.cpp).
void MujocoData::Impl::Report() {
  report = ContactReport{};
  hand_object.clear();
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if (!mm->geom_has_role[c.geom1] || !mm->geom_has_role[c.geom2]) continue;
    const MjcfGeom* a = &mm->geom_roles[c.geom1];
    const MjcfGeom* b = &mm->geom_roles[c.geom2];
    int object_side = 1;
    if (a->role > b->role) {
      std::swap(a, b);
      object_side = 2;
    }
    ++report.total;
    const MjcfRole ra = a->role, rb = b->role;
    if (ra == MjcfRole::kObject || rb == MjcfRole::kObject) {
      report.max_object_penetration = std::max(report.max_object_penetration, -c.dist);
    }
    if (ra == MjcfRole::kTable && (rb == MjcfRole::kArm || rb == MjcfRole::kPalm)) {
      if (report.arm_table == 0) report.arm_table_link = b->link;
      ++report.arm_table;
    } else if (ra == MjcfRole::kTable && rb == MjcfRole::kObject) {
      ++report.object_table;
    } else if (ra == MjcfRole::kTable && rb == MjcfRole::kFinger) {
      ++report.finger_table;
    } else if (ra == MjcfRole::kObject && rb == MjcfRole::kArm) {
      ++report.object_arm;
    } else if (ra == MjcfRole::kObject) {
      ++report.object_hand;
      report.hand_links_on_object |= 1ul << b->hand_index;
      AddContact(c, object_side, *b);
    }
  }
}

MujocoData::MujocoData(const MujocoModel& model, const Vector7d& arm_q, const HandVector& hand_f)
    : impl_(std::make_unique<Impl>()) {
  impl_->mm = &model.impl();
  impl_->m_own = mj_copyModel(nullptr, model.impl().m);
  if (!impl_->m_own) throw InputError("MuJoCo could not copy the model");
  impl_->MakeServos();
  impl_->d = mj_makeData(impl_->m());
  if (!impl_->d) throw InputError("MuJoCo could not allocate the world's data");
  SetRobotPositions(arm_q, hand_f);
}

MujocoData::~MujocoData() = default;

void MujocoData::SetRobotPositions(const Vector7d& arm_q, const HandVector& hand_f) {
  const MujocoModel::Impl& mm = *impl_->mm;
  mjData* d = impl_->d;
  const HandJointVector h = HandJointPositions(impl_->robot().hand, hand_f);
  for (int i = 0; i < kArmDof; ++i) d->qpos[mm.arm_qpos[i]] = arm_q[i];
  for (size_t j = 0; j < mm.hand_qpos.size(); ++j) {
    d->qpos[mm.hand_qpos[j]] = h[static_cast<Eigen::Index>(j)];
  }
  for (int k = 0; k < impl_->m()->nv; ++k) d->qvel[k] = 0.0;
  impl_->arm_target = arm_q;
  impl_->arm_ff.setZero();
  impl_->hand_target = hand_f;
  mj_forward(impl_->m(), d);
  impl_->Report();
}

void MujocoData::SetArmCommand(const Vector7d& target, const Vector7d& velocity_ff) {
  impl_->arm_target = target;
  impl_->arm_ff = velocity_ff;
}

void MujocoData::SetHandCommand(const HandVector& target) { impl_->hand_target = target; }

void MujocoData::Step() {
  const auto t0 = WallClock::now();
  impl_->Control();
  const auto t1 = WallClock::now();
  mj_step(impl_->m(), impl_->d);
  const auto t2 = WallClock::now();
  impl_->Report();
  impl_->stats.dynamic_steps++;
  impl_->stats.control_s += SecondsBetween(t0, t1) + SecondsBetween(t2, WallClock::now());
  impl_->stats.solver_s += SecondsBetween(t1, t2);
  impl_->stats.max_contacts = std::max(impl_->stats.max_contacts, impl_->d->ncon);
}

void MujocoData::Kinematics() { mj_kinematics(impl_->m(), impl_->d); }

double MujocoData::time() const { return impl_->d->time; }

Vector7d MujocoData::arm_positions() const {
  Vector7d q;
  for (int i = 0; i < kArmDof; ++i) q[i] = impl_->q(impl_->mm->arm_qpos[i]);
  return q;
}

HandVector MujocoData::hand_positions() const {
  HandVector f;
  const HandModel& hand = impl_->robot().hand;
  for (int k = 0; k < kHandDof; ++k)
    f[k] = impl_->q(impl_->mm->hand_qpos[hand.actuated_joint_index(k)]);
  return f;
}

Eigen::Isometry3d MujocoData::object_pose() const {
  const int b = impl_->mm->object_body;
  return Pose(impl_->d->xpos + 3 * b, impl_->d->xmat + 9 * b);
}

Eigen::Vector3d MujocoData::object_velocity() const {
  mjtNum v[6];
  mj_objectVelocity(impl_->m(), impl_->d, mjOBJ_BODY, impl_->mm->object_body, v, 0);
  return {v[3], v[4], v[5]};
}

Eigen::Vector3d MujocoData::object_angular_velocity() const {
  mjtNum v[6];
  mj_objectVelocity(impl_->m(), impl_->d, mjOBJ_BODY, impl_->mm->object_body, v, 0);
  return {v[0], v[1], v[2]};
}

Eigen::Isometry3d MujocoData::wrist_pose() const {
  const int b = impl_->mm->mount_body;
  return Pose(impl_->d->xpos + 3 * b, impl_->d->xmat + 9 * b);
}

Eigen::Isometry3d MujocoData::arm_link_pose(int i) const {
  if (i < 1 || i > kArmDof) throw std::out_of_range("arm link index out of range");
  const int b = impl_->mm->arm_body[i - 1];
  return Pose(impl_->d->xpos + 3 * b, impl_->d->xmat + 9 * b);
}

const ContactReport& MujocoData::contacts() const { return impl_->report; }
const std::vector<HandObjectContact>& MujocoData::hand_object_contacts() const {
  return impl_->hand_object;
}
int MujocoData::limit_violation() const { return impl_->violation; }
double MujocoData::limit_violation_value() const { return impl_->violation_value; }

bool MujocoData::IsFinite() const {
  const mjData* d = impl_->d;
  const mjModel* m = impl_->m();
  // MuJoCo resets a world whose accelerations went bad (mjWARN_BADQACC): that is instability.
  if (d->warning[mjWARN_BADQACC].number > 0 || d->warning[mjWARN_BADQPOS].number > 0 ||
      d->warning[mjWARN_BADQVEL].number > 0) {
    return false;
  }
  for (int k = 0; k < m->nq; ++k) {
    if (!std::isfinite(d->qpos[k])) return false;
  }
  for (int k = 0; k < m->nv; ++k) {
    if (!std::isfinite(d->qvel[k])) return false;
  }
  return true;
}

namespace {

// the fingers' links and the object: the bodies the solver can destabilise; f(v, w, body) with
// each one's centre-of-mass velocity and angular velocity in its inertial frame.
template <class F>
void ForEachMoving(const MujocoModel::Impl& mm, const mjData* d, F f) {
  auto visit = [&](int body) {
    mjtNum v[6];
    mj_objectVelocity(mm.m, d, mjOBJ_BODY, body, v, 1);
    f(Eigen::Vector3d(v[3], v[4], v[5]), Eigen::Vector3d(v[0], v[1], v[2]), body);
  };
  for (int body : mm.hand_body) visit(body);
  visit(mm.object_body);
}

}  // namespace

double MujocoData::HandObjectKineticEnergy() const {
  const mjModel* m = impl_->m();
  double e = 0.0;
  ForEachMoving(*impl_->mm, impl_->d,
                [&](const Eigen::Vector3d& v, const Eigen::Vector3d& w, int b) {
                  const Eigen::Vector3d I(m->body_inertia[3 * b], m->body_inertia[3 * b + 1],
                                          m->body_inertia[3 * b + 2]);
                  e += 0.5 * m->body_mass[b] * v.squaredNorm() + 0.5 * w.cwiseProduct(w).dot(I);
                });
  return e;
}

double MujocoData::MaxDynamicSpeed() const {
  double s = 0.0;
  ForEachMoving(*impl_->mm, impl_->d, [&](const Eigen::Vector3d& v, const Eigen::Vector3d&, int) {
    s = std::max(s, v.norm());
  });
  return s;
}

double MujocoData::MaxDynamicAngularSpeed() const {
  double s = 0.0;
  ForEachMoving(*impl_->mm, impl_->d, [&](const Eigen::Vector3d&, const Eigen::Vector3d& w, int) {
    s = std::max(s, w.norm());
  });
  return s;
}

WorldCounts MujocoData::counts() const {
  const mjModel* m = impl_->m();
  WorldCounts c;
  c.bodies = m->nbody - 1;
  c.joints = m->njnt;
  c.geoms = m->ngeom;
  c.dynamic_bodies = m->nbody - 1;
  return c;
}

const StepStatistics& MujocoData::statistics() const { return impl_->stats; }

#endif

}  // namespace graspsynth
