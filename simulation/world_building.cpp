/// @file
/// The ODE world behind SimulationData: its parameters, geometry, bodies and joints, built in an
/// order that fixes the order of ODE's bodies (and so its results); the ODE thread set-up and
/// error handlers.

#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <sstream>

#include "common/demand.hpp"
#include "common/errors.hpp"
#include "kinematics/pose_math.hpp"
#include "scene/triangle_mesh.hpp"
#include "simulation/detail/simulation_data_internal.hpp"
#include "simulation/library_info.hpp"

namespace graspsynth {
namespace sim_internal {
namespace {

// How far outside a joint's range its ODE stop lies, rad.
constexpr double kStopMargin = Radians(2.0);

// Mass properties of several links expressed in one frame L.
struct MassSum {
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I_L = Eigen::Matrix3d::Zero();  // about the origin of L

  void Add(const LinkInertia& in, const Eigen::Isometry3d& X_LK) {
    const Eigen::Matrix3d R = X_LK.linear();
    const Eigen::Vector3d c = X_LK * in.p_LCm;
    mass += in.mass;
    first_moment += in.mass * c;
    I_L += R * in.I_Cm * R.transpose() +
           in.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  }
  Eigen::Vector3d com() const { return first_moment / mass; }
  Eigen::Matrix3d I_com() const {
    const Eigen::Vector3d c = com();
    return I_L - mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  }
};

void SetMass(dBodyID body, double mass, const Eigen::Matrix3d& I) {
  dMass m;
  dMassSetZero(&m);
  dMassSetParameters(&m, mass, 0, 0, 0, I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
  dBodySetMass(body, &m);
}

void ToOde(const Eigen::Matrix3d& R, dMatrix3 out) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[4 * r + c] = R(r, c);
    out[4 * r + 3] = 0.0;
  }
}

// A rigid body for the links summed in `sum`.
BodyPart MakeBody(dWorldID world, const MassSum& sum) {
  BodyPart part;
  part.body = dBodyCreate(world);
  part.p_LC = sum.com();
  SetMass(part.body, sum.mass, sum.I_com());
  return part;
}

// ODE reports internal errors (failed assertions, e.g. on a NaN state) through handlers that
// abort by default. A simulation that became unstable must be a failed trial, never a crash,
// so they throw instead; ODE's informational messages are dropped (the library never prints).
[[noreturn]] void ThrowOdeError(int errnum, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof(text), msg, ap);
  if (current_world_broken) *current_world_broken = true;
  throw OdeError("ODE error " + std::to_string(errnum) + ": " + text);
}

void IgnoreOdeMessage(int, const char*, va_list) {}

}  // namespace

thread_local bool* current_world_broken = nullptr;

Eigen::Matrix3d FromOdeMatrix(const dReal* R) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = R[4 * r + c];
  }
  return m;
}

Eigen::Quaterniond BodyOrientation(dBodyID body) {
  const dReal* q = dBodyGetQuaternion(body);
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
}

Eigen::Isometry3d BodyPose(dBodyID body) {
  return PoseFrom(FromOde(dBodyGetPosition(body)), BodyOrientation(body));
}

void PlaceBody(const BodyPart& part, const Eigen::Isometry3d& X_WL) {
  const Eigen::Vector3d p = X_WL * part.p_LC;
  dBodySetPosition(part.body, p.x(), p.y(), p.z());
  const Eigen::Quaterniond q(X_WL.linear());
  const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
  dBodySetQuaternion(part.body, dq);
}

void SetBodyVelocity(const BodyPart& part, const Eigen::Isometry3d& from,
                     const Eigen::Isometry3d& to, double h) {
  const Eigen::Vector3d v = ((to * part.p_LC) - (from * part.p_LC)) / h;
  const Eigen::AngleAxisd aa(to.linear() * from.linear().transpose());
  const Eigen::Vector3d w = aa.angle() * aa.axis() / h;
  dBodySetLinearVel(part.body, v.x(), v.y(), v.z());
  dBodySetAngularVel(part.body, w.x(), w.y(), w.z());
}

HingeFrame HingeFrames(dJointID j, dBodyID b0, dBodyID b1) {
  HingeFrame f;
  f.b0 = b0;
  f.b1 = b1;
  dVector3 a, a2, axis, out;
  dJointGetHingeAnchor(j, a);
  dJointGetHingeAnchor2(j, a2);
  dJointGetHingeAxis(j, axis);
  dBodyGetPosRelPoint(b0, a[0], a[1], a[2], out);
  f.anchor0 = FromOde(out);
  dBodyGetPosRelPoint(b1, a2[0], a2[1], a2[2], out);
  f.anchor1 = FromOde(out);
  dBodyVectorFromWorld(b0, axis[0], axis[1], axis[2], out);
  f.axis0 = FromOde(out);
  dBodyVectorFromWorld(b1, axis[0], axis[1], axis[2], out);
  f.axis1 = FromOde(out);
  return f;
}

WorldImpl::~WorldImpl() {
  if (world) {
    dWorldSetStepThreadingImplementation(world, nullptr, nullptr);
  }
  // a step that ODE aborted leaves jobs in the threading implementation, whose release
  // would fail ODE's checks again: it is left allocated (a small leak on a path that only
  // a broken simulation takes).
  if (threading && !broken) {
    dThreadingImplementationShutdownProcessing(threading);
    dThreadingFreeImplementation(threading);
  }
  if (contact_group) dJointGroupDestroy(contact_group);
  if (space) dSpaceDestroy(space);
  for (MeshBuffers& b : mesh_data) dGeomTriMeshDataDestroy(b.data);
  if (world) dWorldDestroy(world);
}

// A triangle mesh: an ODE trimesh over the shape's vertices, kept in mesh_data.
dGeomID WorldImpl::AddMeshGeom(dSpaceID into, const CollisionShape& shape) {
  const TriangleMesh& m = *shape.mesh;
  MeshBuffers& b = mesh_data.emplace_back();
  for (const Eigen::Vector3d& v : m.vertices)
    b.vertices.insert(b.vertices.end(), {v.x(), v.y(), v.z()});
  for (const std::array<int, 3>& t : m.triangles) {
    for (int k : t) b.indices.push_back(static_cast<dTriIndex>(k));
  }
  b.data = dGeomTriMeshDataCreate();
  dGeomTriMeshDataBuildDouble(b.data, b.vertices.data(), 3 * sizeof(double),
                              static_cast<int>(m.vertices.size()), b.indices.data(),
                              static_cast<int>(b.indices.size()), 3 * sizeof(dTriIndex));
  return dCreateTriMesh(into, b.data, nullptr, nullptr, nullptr);
}

dGeomID WorldImpl::AddGeom(dSpaceID into, const CollisionShape& shape, Role role,
                           const std::string& link, unsigned long category) {
  dGeomID g = nullptr;
  const Eigen::Vector3d& s = shape.size;
  switch (shape.kind) {
    case CollisionShape::Kind::kBox:
      g = dCreateBox(into, s.x(), s.y(), s.z());
      break;
    case CollisionShape::Kind::kCapsule:
      g = dCreateCapsule(into, s.x(), s.y());
      break;
    case CollisionShape::Kind::kCylinder:
      g = dCreateCylinder(into, s.x(), s.y());
      break;
    case CollisionShape::Kind::kSphere:
      g = dCreateSphere(into, s.x());
      break;
    case CollisionShape::Kind::kMesh:
      g = AddMeshGeom(into, shape);
      break;
  }
  geom_info.push_back({role, link});
  geom_info.back().id = static_cast<int>(geom_info.size());
  dGeomSetData(g, &geom_info.back());
  unsigned long cat = 0, collide = 0;
  switch (role) {
    case Role::kTable:
      cat = kCatTable;
      collide = kCatHandle | kCatFoot | kCatRobot;
      break;
    case Role::kObject:
      cat = category;
      collide = category == kCatFoot  ? kCatTable
                : category == kCatPan ? kCatRobot
                                      : kCatTable | kCatRobot;
      break;
    case Role::kArm:
    case Role::kPalm:
    case Role::kFinger:
      cat = role == Role::kArm ? kCatArm : role == Role::kPalm ? kCatPalm : kCatFinger;
      collide = kCatTable | kCatHandle | kCatPan;
      break;
  }
  dGeomSetCategoryBits(g, cat);
  dGeomSetCollideBits(g, collide);
  ++geom_count;
  return g;
}

// Attaches geometry given in link frame L to a body whose frame is the link frame moved to
// the centre of mass p_LC.
void WorldImpl::AttachShapes(const BodyPart& part, const RigidLink& link,
                             const Eigen::Isometry3d& X_BL, Role role, int hand_index) {
  for (const CollisionShape& shape : link.shapes) {
    dGeomID g = AddGeom(space, shape, role, link.name);
    geom_info.back().hand_index = hand_index;
    dGeomSetBody(g, part.body);
    const Eigen::Isometry3d X_CG =
        Eigen::Translation3d(-part.p_LC) * X_BL * shape.X_LG;  // body (CoM) frame to geom
    dGeomSetOffsetPosition(g, X_CG.translation().x(), X_CG.translation().y(),
                           X_CG.translation().z());
    dMatrix3 R;
    ToOde(X_CG.linear(), R);
    dGeomSetOffsetRotation(g, R);
  }
}

// the world, its parameters, spaces and contact group; then the geometry, the bodies and the
// joints, in an order that fixes the order of ODE's bodies (and so its results).
void WorldImpl::Build(const Vector7d& arm_q, const HandVector& hand_f) {
  SizeHand();
  CreateWorld();
  AddStaticGeometry();
  AddRobotBodies();
  AddObject();
  AddArmJoints();
  AddFingerJoints();
  // the moving bodies' solver indices, plus one, in their user data (SolverIndex).
  const int n = robot().hand.joint_count();
  for (int i = 0; i <= n; ++i) {
    const dBodyID b = i < n ? fingers[static_cast<size_t>(i)].body : object.body;
    dBodySetData(b, reinterpret_cast<void*>(static_cast<std::intptr_t>(i) + 1));
  }

  // the initial configuration, at rest, with commands that hold it.
  const RobotModel& r = robot();
  q_arm = arm_q;
  q_hand = HandJointPositions(r.hand, hand_f);
  ComputeFrames(q_arm, q_hand, &arm_frames, &hand_frames);
  PlaceAll(arm_frames, hand_frames);
  arm_command = arm_q;
  hand_command = hand_f;
}

void WorldImpl::SizeHand() {
  const HandModel& hand = robot().hand;
  const size_t n = static_cast<size_t>(hand.joint_count());
  fingers.assign(n, BodyPart{});
  finger_joints.assign(n, nullptr);
  mounts.assign(static_cast<size_t>(hand.finger_count()), nullptr);
  hinges.assign(n, HingeFrame{});
  for (HandJointVector* v : {&hand_vmax, &hand_fmax, &hand_stop_lo, &hand_stop_hi, &hand_vel}) {
    v->setZero(hand.joint_count());
  }
  q_hand.setZero(hand.joint_count());
  hand_frames.Resize(hand);
  next_hand_frames.Resize(hand);
  inertias.assign(n + 1, BodyInertia{});
  hinge_row0.assign(n + 1, 0);
}

void WorldImpl::CreateWorld() {
  const SimulationOptions& so = model->options();
  world = dWorldCreate();
  dWorldSetGravity(world, 0, 0, -so.gravity);
  dWorldSetERP(world, so.erp);
  dWorldSetCFM(world, so.cfm);
  dWorldSetAutoDisableFlag(world, 0);
  dWorldSetContactSurfaceLayer(world, so.surface_layer);
  dWorldSetContactMaxCorrectingVel(world, so.max_correcting_vel);
  // each world gets its own threading implementation: the process-wide default one is not
  // safe when two threads step two worlds (reference/ode.md, "Threads").
  threading = dThreadingAllocateSelfThreadedImplementation();
  dWorldSetStepThreadingImplementation(world, dThreadingImplementationGetFunctions(threading),
                                       threading);
  space = dSimpleSpaceCreate(nullptr);
  contact_group = dJointGroupCreate(0);
}

// static geometry: table and arm base.
void WorldImpl::AddStaticGeometry() {
  const RobotModel& r = robot();
  const TableModel& t = model->scene().table;
  CollisionShape table_box;
  table_box.size = t.size;
  dGeomID table = AddGeom(space, table_box, Role::kTable, "table");
  dGeomSetPosition(table, t.centre_xy.x(), t.centre_xy.y(), t.top_z - 0.5 * t.size.z());
  for (const CollisionShape& shape : r.arm.base().shapes) {
    dGeomID g = AddGeom(space, shape, Role::kArm, r.arm.base().name);
    dGeomSetPosition(g, shape.X_LG.translation().x(), shape.X_LG.translation().y(),
                     shape.X_LG.translation().z());
    dMatrix3 R;
    ToOde(shape.X_LG.linear(), R);
    dGeomSetRotation(g, R);
  }
}

// arm links 1..6 and the wrist body in link-7 (flange) axes, then the finger links.
void WorldImpl::AddRobotBodies() {
  const RobotModel& r = robot();
  for (int i = 1; i <= kArmDof; ++i) {
    MassSum sum;
    sum.Add(r.arm.link(i).inertia, Eigen::Isometry3d::Identity());
    if (i == kArmDof) {
      sum.Add(r.hand.mount().inertia, r.X_FH);
      sum.Add(r.hand.palm().inertia, r.X_FH * r.hand.X_HP());
    }
    arm[i - 1] = MakeBody(world, sum);
    if (!joint_dynamic(i - 1)) dBodySetKinematic(arm[i - 1].body);
    AttachShapes(arm[i - 1], r.arm.link(i), Eigen::Isometry3d::Identity(), Role::kArm);
    if (i == kArmDof) {
      // the palm and the mount carry the hand's joint count as their hand index.
      const int palm = r.hand.joint_count();
      AttachShapes(arm[i - 1], r.hand.mount(), r.X_FH, Role::kPalm, palm);
      AttachShapes(arm[i - 1], r.hand.palm(), r.X_FH * r.hand.X_HP(), Role::kPalm, palm);
    }
  }
  for (int j = 0; j < r.hand.joint_count(); ++j) {
    const RigidLink& link = r.hand.link(j);
    MassSum sum;
    sum.Add(link.inertia, Eigen::Isometry3d::Identity());
    fingers[j] = MakeBody(world, sum);
    AttachShapes(fingers[j], link, Eigen::Isometry3d::Identity(), Role::kFinger, j);
  }
}

// the object: its parts on one body whose frame is at the centre of mass. Each part gets
// the collision category of what it touches (PartContact).
void WorldImpl::AddObject() {
  const ObjectModel& o = model->scene().object;
  const ObjectInertia& oi = model->object_inertia();
  object.body = dBodyCreate(world);
  const PhysicsVariation& pv = options.physics;
  object.p_LC = oi.p_OC + pv.object_com_offset;
  SetMass(object.body, oi.mass * pv.object_mass, oi.I_C * pv.object_mass);
  for (const ObjectPart& part : o.parts) {
    const unsigned long category = part.touches == PartContact::kTable   ? kCatFoot
                                   : part.touches == PartContact::kRobot ? kCatPan
                                                                         : kCatHandle;
    const CollisionShape& shape = part.shape;
    dGeomID g = AddGeom(space, shape, Role::kObject, o.name, category);
    geom_info.back().friction = part.friction;
    dGeomSetBody(g, object.body);
    const Eigen::Vector3d off = Eigen::Vector3d(shape.X_LG.translation()) - object.p_LC;
    dGeomSetOffsetPosition(g, off.x(), off.y(), off.z());
    dMatrix3 R;
    ToOde(shape.X_LG.linear(), R);
    dGeomSetOffsetRotation(g, R);
  }
  PlaceBody(object, model->scene().ObjectPose(Placement{options.theta, options.object_xy}));
}

// the arm's hinges (none when the arm is kinematic) and its limits. Joints are made with
// every joint at zero: ODE measures hinge angles from the relative orientation at the time
// the axis is set.
void WorldImpl::AddArmJoints() {
  const RobotModel& r = robot();
  q_arm.setZero();
  q_hand.setZero();
  ComputeFrames(q_arm, q_hand, &arm_frames, &hand_frames);
  PlaceAll(arm_frames, hand_frames);
  const ArmModel& am = r.arm;
  for (int i = 0; i < kArmDof; ++i) {
    arm_lower[i] = am.lower()[i];
    arm_upper[i] = am.upper()[i];
    arm_vmax[i] = am.max_velocity()[i];
    arm_fmax[i] = am.max_effort()[i];
    if (!joint_dynamic(i)) continue;
    const Eigen::Isometry3d X_WJ = arm_frames.X_WL[i] * am.joint(i).X_PJ;
    arm_joints[i] =
        MakeHinge(arm[i].body, i == 0 ? nullptr : arm[i - 1].body, X_WJ, am.joint(i).axis_J);
    // stops only where the range lies inside (-pi, pi); E2 and W2 are the controller's.
    if (am.upper()[i] < M_PI - 1e-6 && am.lower()[i] > -M_PI + 1e-6) {
      dJointSetHingeParam(arm_joints[i], dParamLoStop, am.lower()[i] - kStopMargin);
      dJointSetHingeParam(arm_joints[i], dParamHiStop, am.upper()[i] + kStopMargin);
    }
  }
}

// the fingers' hinges and stops, with every joint at zero (AddArmJoints placed the bodies).
void WorldImpl::AddFingerJoints() {
  const SimulationOptions& so = model->options();
  const RobotModel& r = robot();
  for (int j = 0; j < r.hand.joint_count(); ++j) {
    const int finger = r.hand.joint_finger(j), k = r.hand.joint_in_finger(j);
    const HandJoint& hj = r.hand.joint(j);
    const Eigen::Isometry3d X_WParent =
        arm_frames.X_WL[kArmDof] * r.X_FH *
        (k == 0 ? hand_frames.X_HP : hand_frames.X_HL[finger][k - 1]);
    dBodyID parent = k == 0 ? arm[kArmDof - 1].body : fingers[j - 1].body;
    if (k == 0 && options.finger_mounts && !joint_dynamic(kArmDof - 1)) {
      // a kinematic wrist: the finger hangs from a mount of its own that moves with it.
      mounts[finger] = dBodyCreate(world);
      dBodySetKinematic(mounts[finger]);
      parent = mounts[finger];
      SyncMounts();
    }
    finger_joints[j] =
        MakeHinge(fingers[j].body, parent, X_WParent * hj.joint.X_PJ, hj.joint.axis_J);
    hinges[j] = HingeFrames(finger_joints[j], fingers[j].body, parent);
    // stops a little outside the range: the servo targets lie inside it, and a motor
    // holding a joint right at its stop fights the stop's correction.
    dJointSetHingeParam(finger_joints[j], dParamLoStop, hj.joint.lower - kStopMargin);
    dJointSetHingeParam(finger_joints[j], dParamHiStop, hj.joint.upper + kStopMargin);
    hand_stop_lo[j] = dJointGetHingeParam(finger_joints[j], dParamLoStop);
    hand_stop_hi[j] = dJointGetHingeParam(finger_joints[j], dParamHiStop);
    hand_vmax[j] = hj.joint.max_velocity;
    hand_fmax[j] = hj.joint.max_effort * so.hand_effort_scale * options.physics.hand_effort;
  }
}

// Each finger's base hinge hangs from a kinematic mount of its own when the wrist body is
// kinematic. ODE puts every body that a joint reaches into one island, kinematic bodies
// included, and factors each island's constraint matrix whole; a kinematic wrist has zero
// inverse mass, so the fingers do not act on each other through it, but on one shared body
// they would be solved as one system of about 120 rows. On mounts of their own, fingers
// that do not touch the same object are islands of their own (five 4-link chains on a
// kinematic palm in stand-alone ODE 0.16: 110 us a step on the shared palm, 17 us on mounts).
void WorldImpl::SyncMounts() {
  const dBodyID w = arm[kArmDof - 1].body;
  const dReal* p = dBodyGetPosition(w);
  const dReal* q = dBodyGetQuaternion(w);
  const dReal* v = dBodyGetLinearVel(w);
  const dReal* a = dBodyGetAngularVel(w);
  for (dBodyID m : mounts) {
    if (!m) continue;  // not built yet (AddFingerJoints), or none: a dynamic wrist
    dBodySetPosition(m, p[0], p[1], p[2]);
    dBodySetQuaternion(m, q);
    dBodySetLinearVel(m, v[0], v[1], v[2]);
    dBodySetAngularVel(m, a[0], a[1], a[2]);
  }
}

// A hinge with the child first: dJointGetHingeAngle is then the child's rotation about the
// axis relative to the parent (tests/simulation/simulation_data_test.cpp checks the sign).
dJointID WorldImpl::MakeHinge(dBodyID child, dBodyID parent, const Eigen::Isometry3d& X_WJ,
                              const Eigen::Vector3d& axis_J) {
  dJointID j = dJointCreateHinge(world, nullptr);
  dJointAttach(j, child, parent);
  const Eigen::Vector3d a = X_WJ.translation();
  const Eigen::Vector3d axis = X_WJ.linear() * axis_J;
  dJointSetHingeAnchor(j, a.x(), a.y(), a.z());
  dJointSetHingeAxis(j, axis.x(), axis.y(), axis.z());
  return j;
}

void WorldImpl::ComputeFrames(const Vector7d& qa, const HandJointVector& qh, ArmFrames* af,
                              HandFrames* hf) const {
  ArmLinkFrames(robot().arm, qa, af);
  // the coupled joints take their own (lagging) values, not their couplings'.
  HandFramesFromJoints(qh, hf);
}

// Hand FK from every joint's value (HandLinkFrames takes the actuated ones and derives the
// coupled ones; here the coupled joints are states of their own).
void WorldImpl::HandFramesFromJoints(const HandJointVector& qh, HandFrames* hf) const {
  const HandModel& hand = robot().hand;
  hf->Resize(hand);
  hf->X_HP = hand.X_HP();
  for (int i = 0; i < hand.finger_count(); ++i) {
    const Finger& finger = hand.finger(i);
    std::vector<Eigen::Isometry3d>& X_HL = hf->X_HL[static_cast<size_t>(i)];
    Eigen::Isometry3d X = hand.X_HP();
    for (size_t k = 0; k < finger.joints.size(); ++k) {
      const RevoluteJoint& j = finger.joints[k].joint;
      X = X * j.X_PJ * Eigen::AngleAxisd(qh[hand.JointIndex(i, static_cast<int>(k))], j.axis_J);
      X_HL[k] = X;
    }
    hf->X_HT[static_cast<size_t>(i)] = X * finger.X_LT;
  }
}

void WorldImpl::PlaceAll(const ArmFrames& af, const HandFrames& hf) {
  for (int i = 0; i < kArmDof; ++i) PlaceBody(arm[i], af.X_WL[i + 1]);
  const Eigen::Isometry3d X_WH = af.X_WL[kArmDof] * robot().X_FH;
  const HandModel& hand = robot().hand;
  for (int j = 0; j < hand.joint_count(); ++j) {
    PlaceBody(fingers[static_cast<size_t>(j)],
              X_WH * hf.X_HL[static_cast<size_t>(hand.joint_finger(j))]
                            [static_cast<size_t>(hand.joint_in_finger(j))]);
  }
  for (int i = 0; i < kArmDof; ++i) {
    dBodySetLinearVel(arm[i].body, 0, 0, 0);
    dBodySetAngularVel(arm[i].body, 0, 0, 0);
  }
  for (const BodyPart& f : fingers) {
    dBodySetLinearVel(f.body, 0, 0, 0);
    dBodySetAngularVel(f.body, 0, 0, 0);
  }
}

}  // namespace sim_internal

void EnsureOdeThread() {
  static std::once_flag init;
  std::call_once(init, [] {
    RequireSupportedOde();  // throws, and the next call checks again
    dInitODE2(0);
    dSetErrorHandler(&sim_internal::ThrowOdeError);
    dSetDebugHandler(&sim_internal::ThrowOdeError);
    dSetMessageHandler(&sim_internal::IgnoreOdeMessage);
  });
  // per-thread collision caches; released when the thread ends.
  struct ThreadData {
    ThreadData() { GS_DEMAND(dAllocateODEDataForThread(dAllocateMaskAll), "ODE thread data"); }
    ~ThreadData() { dCleanupODEAllDataForThread(); }
  };
  thread_local ThreadData data;
  (void)data;
}

bool WorldOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& what, double v) {
    if (why) {
      std::ostringstream s;
      s << what << " = " << v;
      *why = s.str();
    }
    return false;
  };
  if (!(std::isfinite(time_step) && time_step > 0.0 && time_step <= 0.02)) {
    return fail("time_step (s, in (0, 0.02])", time_step);
  }
  if (!std::isfinite(theta)) return fail("theta", theta);
  return physics.IsValid(why);
}

}  // namespace graspsynth
