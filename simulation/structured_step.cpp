/// @file
/// The structured step (WorldOptions::structured_solver): ODE 0.16's dWorldStep for the fast
/// fidelity's world (every arm body kinematic), with the same rows (hinges, their motors and
/// stops, soft contacts with pyramid friction), the same right-hand sides, gyroscopic term and
/// integration, but solved by SolveConstraints: each finger's equality rows are eliminated on
/// their own before the pivoting solve of the bounded rows. And its check against dWorldStep
/// from the same state (SimulationData::StepBothWays).

#include <ode/ode.h>

#include <algorithm>
#include <cstdint>

#include "simulation/detail/simulation_data_internal.hpp"

namespace graspsynth::sim_internal {
namespace {

// Two unit vectors perpendicular to n and to each other, as ODE chooses them for a hinge's
// axis rows and a contact's friction directions (dPlaneSpace).
void PlaneSpace(const Eigen::Vector3d& n, Eigen::Vector3d* p, Eigen::Vector3d* q) {
  const dVector3 nn = {n.x(), n.y(), n.z(), 0.0};
  dVector3 pp, qq;
  dPlaneSpace(nn, pp, qq);
  *p = FromOde(pp);
  *q = FromOde(qq);
}

// a contact row's key for SolveConstraints (its first guess): the two geoms' ids and the
// contact's place among theirs, the low two bits left for the row's kind (normal, first and
// second friction direction); the top bit keeps it apart from the hinges' keys.
std::uint64_t ContactKey(dGeomID ga, dGeomID gb, int index) {
  const std::uint64_t a = static_cast<const GeomInfo*>(dGeomGetData(ga))->id;
  const std::uint64_t b = static_cast<const GeomInfo*>(dGeomGetData(gb))->id;
  return (1ull << 63) | (a << 40) | (b << 18) | (static_cast<std::uint64_t>(index) << 2);
}

using Vector6d = Eigen::Matrix<double, 6, 1>;

Vector6d Stack(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Vector6d v;
  v << a, b;
  return v;
}

Vector6d Stack(const dReal* a, const dReal* b) { return Stack(FromOde(a), FromOde(b)); }

}  // namespace

// Adds a row on b0 (moving) and b1 (moving, kinematic or null); the velocity of a kinematic b1
// goes into c, as ODE's right-hand side has it.
void WorldImpl::AddRow(dBodyID b0, dBodyID b1, const Eigen::Vector3d& lin0,
                       const Eigen::Vector3d& ang0, const Eigen::Vector3d& lin1,
                       const Eigen::Vector3d& ang1, double c, double cfm, double lo, double hi,
                       int findex, std::uint64_t key) {
  ConstraintRow r;
  r.key = key;
  r.body = {SolverIndex(b0), SolverIndex(b1)};
  r.lin = {lin0, lin1};
  r.ang = {ang0, ang1};
  r.c = c;
  for (int k = 0; k < 2; ++k) {
    const dBodyID b = k == 0 ? b0 : b1;
    if (b && r.body[k] < 0) {
      r.c -= r.lin[k].dot(FromOde(dBodyGetLinearVel(b))) +
             r.ang[k].dot(FromOde(dBodyGetAngularVel(b)));
      r.lin[k].setZero();
      r.ang[k].setZero();
    }
  }
  r.cfm = cfm;
  r.lo = lo;
  r.hi = hi;
  r.findex = findex;
  rows.push_back(r);
}

void WorldImpl::AddHingeRows(int j) {
  const SimulationOptions& so = model->options();
  const HingeFrame& f = hinges[j];
  const double k = so.erp / h;
  const Eigen::Vector3d p0 = FromOde(dBodyGetPosition(f.b0)), p1 = FromOde(dBodyGetPosition(f.b1));
  const Eigen::Matrix3d R0 = FromOdeMatrix(dBodyGetRotation(f.b0)),
                        R1 = FromOdeMatrix(dBodyGetRotation(f.b1));
  const Eigen::Vector3d a0 = R0 * f.anchor0, a1 = R1 * f.anchor1;
  const Eigen::Vector3d z = Eigen::Vector3d::Zero();
  // the anchors coincide (three rows).
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(i);
    AddRow(f.b0, f.b1, e, a0.cross(e), -e, -a1.cross(e), k * ((a1[i] + p1[i]) - a0[i] - p0[i]),
           so.cfm, -kInf, kInf, -1, 0);
  }
  // the axes stay aligned (two rows).
  const Eigen::Vector3d ax0 = R0 * f.axis0, ax1 = R1 * f.axis1;
  Eigen::Vector3d p, q;
  PlaneSpace(ax0, &p, &q);
  const Eigen::Vector3d u = ax0.cross(ax1);
  AddRow(f.b0, f.b1, z, p, z, -p, k * u.dot(p), so.cfm, -kInf, kInf, -1, 0);
  AddRow(f.b0, f.b1, z, q, z, -q, k * u.dot(q), so.cfm, -kInf, kInf, -1, 0);
  // the motor, and the stop when the joint is past it (ODE's limit-motor row).
  const double lo_stop = hand_stop_lo[j], hi_stop = hand_stop_hi[j];
  const double vel = hand_vel[j], fmax = hand_fmax[j];  // as Step() set them
  const double theta = dJointGetHingeAngle(finger_joints[j]);
  int limit = 0;
  double err = 0.0;
  if (theta <= lo_stop) {
    limit = 1;
    err = theta - lo_stop;
  } else if (theta >= hi_stop) {
    limit = 2;
    err = theta - hi_stop;
  }
  const bool powered = fmax > 0.0;
  if (!powered && limit == 0) return;
  if (limit == 0) {
    AddRow(f.b0, f.b1, z, ax0, z, -ax0, vel, so.cfm, -fmax, fmax, -1, (j + 1) * 4);
    return;
  }
  if (powered) {
    // a motor at its stop pushes with its full force as an external torque.
    double fm = fmax;
    if (vel > 0.0 || (vel == 0.0 && limit == 2)) fm = -fm;
    const int i0 = SolverIndex(f.b0), i1 = SolverIndex(f.b1);
    if (i1 >= 0) solver_bodies[i1].torque += fm * ax0;
    if (i0 >= 0) solver_bodies[i0].torque -= fm * ax0;
  }
  AddRow(f.b0, f.b1, z, ax0, z, -ax0, -(so.erp / h) * err, so.cfm, limit == 1 ? 0.0 : -kInf,
         limit == 1 ? kInf : 0.0, -1, (j + 1) * 4 + limit);
}

void WorldImpl::AddContactRows(const PendingContact& pc) {
  const SimulationOptions& so = model->options();
  const Eigen::Vector3d pos = FromOde(pc.geom.pos);
  const Eigen::Vector3d n = pc.normal_sign * FromOde(pc.geom.normal);
  const Eigen::Vector3d r0 = pos - FromOde(dBodyGetPosition(pc.b0));
  const Eigen::Vector3d r1 =
      pc.b1 ? Eigen::Vector3d(pos - FromOde(dBodyGetPosition(pc.b1))) : Eigen::Vector3d::Zero();
  const double depth = std::max(pc.geom.depth - so.surface_layer, 0.0);
  const double c = std::min(pc.erp / h * depth, so.max_correcting_vel);
  const int normal = static_cast<int>(rows.size());
  // the contact's name from step to step: its geoms and its place among their contacts.
  const std::uint64_t key = ContactKey(pc.geom.g1, pc.geom.g2, pc.index);
  AddRow(pc.b0, pc.b1, n, r0.cross(n), -n, n.cross(r1), c, pc.cfm, 0.0, kInf, -1, key);
  if (pc.mu <= 0.0) return;
  Eigen::Vector3d t1, t2;
  PlaneSpace(n, &t1, &t2);
  AddRow(pc.b0, pc.b1, t1, r0.cross(t1), -t1, t1.cross(r1), 0.0, so.cfm, -pc.mu, pc.mu, normal,
         key + 1);
  AddRow(pc.b0, pc.b1, t2, r0.cross(t2), -t2, t2.cross(r1), 0.0, so.cfm, -pc.mu, pc.mu, normal,
         key + 2);
}

// the moving bodies: mass, world inverse inertia, velocity, gravity and the (implicit)
// gyroscopic torque as ODE computes them.
void WorldImpl::PrepareSolverBodies() {
  const SimulationOptions& so = model->options();
  const int n = static_cast<int>(fingers.size());
  solver_bodies.resize(static_cast<size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) {
    const dBodyID b = i < n ? fingers[static_cast<size_t>(i)].body : object.body;
    dMass m;
    dBodyGetMass(b, &m);
    const Eigen::Matrix3d I_B = FromOdeMatrix(m.I);
    const Eigen::Matrix3d R = FromOdeMatrix(dBodyGetRotation(b));
    BodyInertia& inertia = inertias[i];
    if (inertia.I_B != I_B) inertia = {I_B, I_B.inverse()};  // constant but for a new mass
    SolverBody& sb = solver_bodies[i];
    sb.inv_mass = 1.0 / m.mass;
    sb.inv_inertia_W = R * inertia.inv_I_B * R.transpose();
    sb.v = FromOde(dBodyGetLinearVel(b));
    sb.w = FromOde(dBodyGetAngularVel(b));
    sb.force = FromOde(dBodyGetForce(b)) + Eigen::Vector3d(0.0, 0.0, -so.gravity * m.mass);
    sb.torque = FromOde(dBodyGetTorque(b));
    const Eigen::Matrix3d I_W = R * I_B * R.transpose();
    const Eigen::Vector3d L = I_W * sb.w;
    Eigen::Matrix3d Lx;
    Lx << 0.0, -L.z(), L.y(), L.z(), 0.0, -L.x(), -L.y(), L.x(), 0.0;
    const Eigen::Matrix3d It = I_W - h * Lx;
    if (It.determinant() != 0.0) {
      sb.torque += (I_W * It.inverse() - Eigen::Matrix3d::Identity()) * (L / h);
    }
  }
}

void WorldImpl::StepStructured() {
  PrepareSolverBodies();
  rows.clear();
  const int n = static_cast<int>(fingers.size());
  for (int j = 0; j < n; ++j) {
    hinge_row0[static_cast<size_t>(j)] = static_cast<int>(rows.size());
    AddHingeRows(j);
  }
  hinge_row0[static_cast<size_t>(n)] = static_cast<int>(rows.size());
  contact_row0.clear();
  for (const PendingContact& pc : pending) {
    contact_row0.push_back(static_cast<int>(rows.size()));
    AddContactRows(pc);
  }
  SolveConstraints(h, rows, &solver_bodies, &solver);

  // the object's contact forces with the hand (ODE's feedback f1: the force on body 0).
  const std::vector<double>& lambda = solver.lambda();
  for (size_t k = 0; k < pending.size(); ++k) {
    if (pending[k].hand_object < 0) continue;
    const size_t end = k + 1 < pending.size() ? contact_row0[k + 1] : rows.size();
    Eigen::Vector3d f = Eigen::Vector3d::Zero();
    for (size_t row = contact_row0[k]; row < end; ++row) f += rows[row].lin[0] * lambda[row];
    hand_object[static_cast<size_t>(pending[k].hand_object)].f_W = f;
  }

  // velocities of the moving bodies, then every body moves (kinematic ones by their own
  // velocities, as in dWorldStep).
  for (int i = 0; i <= n; ++i) {
    const dBodyID b = i < n ? fingers[static_cast<size_t>(i)].body : object.body;
    const SolverBody& sb = solver_bodies[i];
    dBodySetLinearVel(b, sb.v.x(), sb.v.y(), sb.v.z());
    dBodySetAngularVel(b, sb.w.x(), sb.w.y(), sb.w.z());
    dBodySetForce(b, 0.0, 0.0, 0.0);
    dBodySetTorque(b, 0.0, 0.0, 0.0);
  }
  for (const BodyPart& a : arm) Integrate(a.body);
  for (dBodyID m : mounts) {
    if (m) Integrate(m);
  }
  for (const BodyPart& f : fingers) Integrate(f.body);
  Integrate(object.body);
}

// ODE's dxStepBody with finite rotation off: p += h v, q += h/2 (0, w) q, normalised.
void WorldImpl::Integrate(dBodyID b) const {
  const dReal* p = dBodyGetPosition(b);
  const dReal* v = dBodyGetLinearVel(b);
  dBodySetPosition(b, p[0] + h * v[0], p[1] + h * v[1], p[2] + h * v[2]);
  const dReal* q = dBodyGetQuaternion(b);
  const dReal* w = dBodyGetAngularVel(b);
  dQuaternion dq;
  dq[0] = 0.5 * (-w[0] * q[1] - w[1] * q[2] - w[2] * q[3]);
  dq[1] = 0.5 * (w[0] * q[0] + w[1] * q[3] - w[2] * q[2]);
  dq[2] = 0.5 * (-w[0] * q[3] + w[1] * q[0] + w[2] * q[1]);
  dq[3] = 0.5 * (w[0] * q[2] - w[1] * q[1] + w[2] * q[0]);
  dQuaternion qn = {q[0] + h * dq[0], q[1] + h * dq[1], q[2] + h * dq[2], q[3] + h * dq[3]};
  dBodySetQuaternion(b, qn);  // normalises
}

// ---- the check against dWorldStep ----

// Every body's state, to take a second step from the same state.
struct WorldImpl::Snapshot {
  struct Body {
    dBodyID body = nullptr;
    dVector3 p, v, w, f, t;
    dQuaternion q;
  };
  std::vector<Body> bodies;
};

WorldImpl::Snapshot WorldImpl::Save() const {
  Snapshot s;
  auto save = [&](dBodyID b) {
    Snapshot::Body sb;
    sb.body = b;
    std::copy_n(dBodyGetPosition(b), 3, sb.p);
    std::copy_n(dBodyGetQuaternion(b), 4, sb.q);
    std::copy_n(dBodyGetLinearVel(b), 3, sb.v);
    std::copy_n(dBodyGetAngularVel(b), 3, sb.w);
    std::copy_n(dBodyGetForce(b), 3, sb.f);
    std::copy_n(dBodyGetTorque(b), 3, sb.t);
    s.bodies.push_back(sb);
  };
  for (const BodyPart& a : arm) save(a.body);
  for (dBodyID m : mounts) {
    if (m) save(m);
  }
  ForEachDynamic(save);
  return s;
}

void WorldImpl::Restore(const Snapshot& s) {
  for (const Snapshot::Body& b : s.bodies) {
    dBodySetPosition(b.body, b.p[0], b.p[1], b.p[2]);
    dBodySetQuaternion(b.body, b.q);  // normalises again: the same state to roundoff
    dBodySetLinearVel(b.body, b.v[0], b.v[1], b.v[2]);
    dBodySetAngularVel(b.body, b.w[0], b.w[1], b.w[2]);
    dBodySetForce(b.body, b.f[0], b.f[1], b.f[2]);
    dBodySetTorque(b.body, b.t[0], b.t[1], b.t[2]);
  }
}

// The moving bodies' velocities after a step.
void WorldImpl::ReadVelocities(StepForces* out) const {
  out->velocities.clear();
  ForEachDynamic([&](dBodyID b) {
    out->velocities.push_back(Stack(dBodyGetLinearVel(b), dBodyGetAngularVel(b)));
  });
}

// dWorldStep from the current state, with feedback on every finger hinge and contact joint;
// the state is restored afterwards.
void WorldImpl::StepOde(StepForces* out) {
  const Snapshot before = Save();
  const size_t n = finger_joints.size();
  std::vector<dJointFeedback> hinge_fb(n), contact_fb(pending.size());
  for (size_t j = 0; j < n; ++j) dJointSetFeedback(finger_joints[j], &hinge_fb[j]);
  for (size_t k = 0; k < pending.size(); ++k) {
    dJointSetFeedback(MakeContactJoint(pending[k]), &contact_fb[k]);
  }
  dWorldStep(world, h);
  for (size_t j = 0; j < n; ++j) {
    const dJointFeedback& fb = hinge_fb[j];
    Eigen::Matrix<double, 12, 1> v;
    v << Stack(fb.f1, fb.t1), Stack(fb.f2, fb.t2);
    if (SolverIndex(hinges[j].b1) < 0) v.tail<6>().setZero();  // a kinematic parent
    out->hinges.push_back(v);
    dJointSetFeedback(finger_joints[j], nullptr);
  }
  for (const dJointFeedback& fb : contact_fb) out->contacts.push_back(Stack(fb.f1, fb.t1));
  ReadVelocities(out);
  dJointGroupEmpty(contact_group);
  Restore(before);
}

// The structured step's forces of the rows of each finger hinge and each contact.
void WorldImpl::ReadStructuredForces(StepForces* out) const {
  const std::vector<double>& lambda = solver.lambda();
  auto sum = [&](size_t begin, size_t end, int k) {
    Vector6d v = Vector6d::Zero();
    for (size_t r = begin; r < end; ++r) v += Stack(rows[r].lin[k], rows[r].ang[k]) * lambda[r];
    return v;
  };
  for (size_t j = 0; j < finger_joints.size(); ++j) {
    Eigen::Matrix<double, 12, 1> v;
    v << sum(hinge_row0[j], hinge_row0[j + 1], 0), sum(hinge_row0[j], hinge_row0[j + 1], 1);
    out->hinges.push_back(v);
  }
  for (size_t k = 0; k < contact_row0.size(); ++k) {
    const size_t end = k + 1 < contact_row0.size() ? contact_row0[k + 1] : rows.size();
    out->contacts.push_back(sum(contact_row0[k], end, 0));
  }
  ReadVelocities(out);
}

void WorldImpl::StepStructuredAndOde(StepComparison* compare) {
  StepOde(&compare->ode);
  const ConstraintSolverStatistics before = solver.statistics();
  StepStructured();
  const ConstraintSolverStatistics& after = solver.statistics();
  compare->guessed = after.guessed - before.guessed;
  compare->amended = after.amended - before.amended;
  compare->pivoted = after.pivoted - before.pivoted;
  ReadStructuredForces(&compare->structured);
}

}  // namespace graspsynth::sim_internal
