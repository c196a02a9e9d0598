#include "simulation/simulation_data.hpp"

#include <ode/ode.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <functional>
#include <limits>
#include <mutex>
#include <sstream>
#include <vector>

#include "common/demand.hpp"
#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "kinematics/pose_math.hpp"
#include "scene/triangle_mesh.hpp"
#include "simulation/constraint_solver.hpp"
#include "simulation/library_info.hpp"

#ifndef dDOUBLE
#error "graspsynth needs ODE built in double precision (Debian's libode-dev is)"
#endif

namespace graspsynth {
namespace {

using Clock = WallClock;

// Roles of geometry, ordered so that a pair can be classified with role(a) <= role(b).
enum class Role { kTable, kObject, kArm, kPalm, kFinger, kProxy };

// Collision categories: only the pairs listed in simulation_data.hpp are ever tested. The
// object's parts touch the robot and the table (kCatHandle: the pan's handle), the robot only
// (kCatPan: the pan's cylinder) or the table only (kCatFoot: the pan's foot), as the object
// description says (PartContact).
constexpr unsigned long kCatTable = 1, kCatHandle = 2, kCatArm = 4, kCatPalm = 8, kCatFinger = 16,
                        kCatPan = 32, kCatFoot = 64;
constexpr unsigned long kCatRobot = kCatArm | kCatPalm | kCatFinger;

constexpr double kInf = std::numeric_limits<double>::infinity();

// How far outside a joint's range its ODE stop lies, rad.
constexpr double kStopMargin = 2.0 * M_PI / 180.0;

struct GeomInfo {
  Role role = Role::kTable;
  std::string link;       // name of the link the geometry belongs to
  int hand_index = -1;    // HandJointVector index of a finger link, 20 for the palm and mount
  double friction = 0.0;  // an object part's Coulomb coefficient with the fingers
  int id = 0;             // creation order (names a geom's contacts from step to step)
};

// A rigid body made of one or more links, with its frame at the centre of mass and axes of
// the first (frame-defining) link.
struct BodyPart {
  dBodyID body = nullptr;
  Eigen::Vector3d p_LC = Eigen::Vector3d::Zero();  // centre of mass in the link frame
};

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

// An ODE vector (3 values) or matrix (3x4, row-major) as Eigen's.
Eigen::Vector3d FromOde(const dReal* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

Eigen::Matrix3d FromOdeMatrix(const dReal* R) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = R[4 * r + c];
  }
  return m;
}

// Two unit vectors perpendicular to n and to each other, as ODE chooses them for a hinge's
// axis rows and a contact's friction directions (dPlaneSpace).
void PlaneSpace(const Eigen::Vector3d& n, Eigen::Vector3d* p, Eigen::Vector3d* q) {
  const dVector3 nn = {n.x(), n.y(), n.z(), 0.0};
  dVector3 pp, qq;
  dPlaneSpace(nn, pp, qq);
  *p = FromOde(pp);
  *q = FromOde(qq);
}

// A body's orientation, its quaternion normalized.
Eigen::Quaterniond BodyOrientation(dBodyID body) {
  const dReal* q = dBodyGetQuaternion(body);
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
}

Eigen::Isometry3d BodyPose(dBodyID body) {
  return PoseFrom(FromOde(dBodyGetPosition(body)), BodyOrientation(body));
}

// Places a body (frame at the centre of mass) for link pose X_WL.
void PlaceBody(const BodyPart& part, const Eigen::Isometry3d& X_WL) {
  const Eigen::Vector3d p = X_WL * part.p_LC;
  dBodySetPosition(part.body, p.x(), p.y(), p.z());
  const Eigen::Quaterniond q(X_WL.linear());
  const dQuaternion dq = {q.w(), q.x(), q.y(), q.z()};
  dBodySetQuaternion(part.body, dq);
}

// Velocity that carries the body from link pose `from` to `to` in h.
void SetBodyVelocity(const BodyPart& part, const Eigen::Isometry3d& from,
                     const Eigen::Isometry3d& to, double h) {
  const Eigen::Vector3d v = ((to * part.p_LC) - (from * part.p_LC)) / h;
  const Eigen::AngleAxisd aa(to.linear() * from.linear().transpose());
  const Eigen::Vector3d w = aa.angle() * aa.axis() / h;
  dBodySetLinearVel(part.body, v.x(), v.y(), v.z());
  dBodySetAngularVel(part.body, w.x(), w.y(), w.z());
}

double Wrap(double a) { return std::remainder(a, 2.0 * M_PI); }

double Clamp(double x, double limit) { return std::clamp(x, -limit, limit); }

bool Finite3(const dReal* v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

}  // namespace

namespace {

// ODE reports internal errors (failed assertions, e.g. on a NaN state) through handlers that
// abort by default. A simulation that became unstable must be a failed trial, never a crash,
// so they throw instead; ODE's informational messages are dropped (the library never prints).
// Set while a world steps on this thread, so that an error marks that world as broken.
thread_local bool* current_world_broken = nullptr;

[[noreturn]] void ThrowOdeError(int errnum, const char* msg, va_list ap) {
  char text[512];
  std::vsnprintf(text, sizeof(text), msg, ap);
  if (current_world_broken) *current_world_broken = true;
  throw OdeError("ODE error " + std::to_string(errnum) + ": " + text);
}

void IgnoreOdeMessage(int, const char*, va_list) {}

// dCollide, one trimesh pair at a time across threads: Debian's ODE is built without its
// thread-local storage (dGetConfiguration has no ODE_EXT_ou), so OPCODE's trimesh colliders share
// one cache, and two threads colliding trimeshes at once crash. Primitive pairs run freely.
int CollideGeoms(dGeomID a, dGeomID b, int max_contacts, dContactGeom* contacts) {
  if (dGeomGetClass(a) != dTriMeshClass && dGeomGetClass(b) != dTriMeshClass) {
    return dCollide(a, b, max_contacts, contacts, sizeof(dContactGeom));
  }
  static std::mutex trimesh_mutex;
  const std::lock_guard<std::mutex> lock(trimesh_mutex);
  return dCollide(a, b, max_contacts, contacts, sizeof(dContactGeom));
}

}  // namespace

void EnsureOdeThread() {
  static std::once_flag init;
  std::call_once(init, [] {
    RequireDoublePrecisionOde();  // throws, and the next call checks again
    dInitODE2(0);
    dSetErrorHandler(&ThrowOdeError);
    dSetDebugHandler(&ThrowOdeError);
    dSetMessageHandler(&IgnoreOdeMessage);
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
  if (!(std::isfinite(proximity_margin) && proximity_margin >= 0.0 && proximity_margin < 0.5)) {
    return fail("proximity_margin (m)", proximity_margin);
  }
  return physics.IsValid(why);
}

struct SimulationData::Impl {
  const SimulationModel* model = nullptr;
  WorldOptions options;
  double h = 0.0;

  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dSpaceID proxy_space = nullptr;
  dJointGroupID contact_group = nullptr;
  dThreadingImplementationID threading = nullptr;
  std::deque<GeomInfo> geom_info;  // stable addresses for dGeomSetData
  // ODE trimesh data of mesh geoms, with the arrays it points into (stable addresses).
  struct MeshBuffers {
    std::vector<double> vertices;
    std::vector<dTriIndex> indices;
    dTriMeshDataID data = nullptr;
  };
  std::deque<MeshBuffers> mesh_data;
  int geom_count = 0;

  // arm bodies: arm[0..5] = links 1..6 (S1..W1), arm[6] = the wrist (W2 + mount + palm).
  std::array<BodyPart, kArmDof> arm;
  std::array<dJointID, kArmDof> arm_joints{};
  // finger links, finger-major (HandJointVector order), and their joints.
  std::array<BodyPart, kHandJoints> fingers;
  std::array<dJointID, kHandJoints> finger_joints{};
  BodyPart object;

  // controller state
  ServoMode arm_mode = ServoMode::kPosition;
  Vector7d arm_command = Vector7d::Zero();
  Vector7d arm_ff = Vector7d::Zero();
  ServoMode hand_mode = ServoMode::kPosition;
  HandVector hand_command = HandVector::Zero();
  int violation = -1;
  double violation_value = 0.0;

  // measured (dynamic) or modelled (kinematic) joint state
  Vector7d q_arm = Vector7d::Zero();
  HandJointVector q_hand = HandJointVector::Zero();
  bool hand_dynamic = false;  // set by the first Step()

  // link poses of the current state, for kinematic placement
  ArmFrames arm_frames;
  HandFrames hand_frames;

  double time = 0.0;
  bool detect_only = false;
  ContactReport report;
  std::vector<HandObjectContact> hand_object;  // points of the last pass, object-hand pairs
  // force feedback of the object-hand contact joints: slots reused from pass to pass (a deque
  // keeps their addresses when it grows), and which hand_object entry each slot belongs to.
  std::deque<dJointFeedback> feedback;
  std::vector<size_t> feedback_contact;
  StepStatistics stats;
  bool near_object = false;
  bool broken = false;  // ODE raised an error inside a step of this world

  // arm joint limits and caps
  Vector7d arm_lower, arm_upper, arm_vmax, arm_fmax;
  // per hand joint (HandJointVector order)
  HandJointVector hand_vmax, hand_fmax;
  // the fingers' hinge stops as ODE keeps them, and their motors' velocities this step (the
  // hinges' parameters, for the structured step).
  HandJointVector hand_stop_lo, hand_stop_hi, hand_vel;

  ~Impl() {
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
    if (proxy_space) dSpaceDestroy(proxy_space);
    if (space) dSpaceDestroy(space);
    for (MeshBuffers& b : mesh_data) dGeomTriMeshDataDestroy(b.data);
    if (world) dWorldDestroy(world);
  }

  const RobotModel& robot() const { return model->robot(); }
  bool arm_kinematic() const { return options.arm_mode == ArmMode::kKinematic; }
  // whether arm joint i (0-based) is a motor-driven hinge of a dynamic link.
  bool joint_dynamic(int i) const {
    return options.arm_mode == ArmMode::kDynamic ||
           (options.arm_mode == ArmMode::kWristDynamic && i >= kFirstWristJoint);
  }
  int dynamic_arm_joints() const {
    int n = 0;
    for (int i = 0; i < kArmDof; ++i) n += joint_dynamic(i);
    return n;
  }

  // A triangle mesh (an ODE trimesh over the shape's vertices, kept in mesh_data); with
  // `inflate` > 0 (a proximity proxy), the mesh's bounding box grown by `inflate` instead,
  // which the caller places at the box's centre.
  dGeomID AddMeshGeom(dSpaceID into, const CollisionShape& shape, double inflate) {
    const TriangleMesh& m = *shape.mesh;
    if (inflate > 0.0) {
      const Eigen::Vector3d size = m.BoxMax() - m.BoxMin() + Eigen::Vector3d::Constant(2 * inflate);
      return dCreateBox(into, size.x(), size.y(), size.z());
    }
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

  dGeomID AddGeom(dSpaceID into, const CollisionShape& shape, Role role, const std::string& link,
                  double inflate = 0.0, unsigned long category = kCatHandle) {
    dGeomID g = nullptr;
    const Eigen::Vector3d& s = shape.size;
    switch (shape.kind) {
      case CollisionShape::Kind::kBox:
        g = dCreateBox(into, s.x() + 2 * inflate, s.y() + 2 * inflate, s.z() + 2 * inflate);
        break;
      case CollisionShape::Kind::kCapsule:
        g = dCreateCapsule(into, s.x() + inflate, s.y());
        break;
      case CollisionShape::Kind::kCylinder:
        g = dCreateCylinder(into, s.x() + inflate, s.y() + 2 * inflate);
        break;
      case CollisionShape::Kind::kSphere:
        g = dCreateSphere(into, s.x() + inflate);
        break;
      case CollisionShape::Kind::kMesh:
        g = AddMeshGeom(into, shape, inflate);
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
      case Role::kProxy:
        break;
    }
    dGeomSetCategoryBits(g, cat);
    dGeomSetCollideBits(g, collide);
    if (role != Role::kProxy) ++geom_count;
    return g;
  }

  // Attaches geometry given in link frame L to a body whose frame is the link frame moved to
  // the centre of mass p_LC.
  void AttachShapes(const BodyPart& part, const RigidLink& link, const Eigen::Isometry3d& X_BL,
                    Role role, int hand_index = -1) {
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

  BodyPart MakeBody(const MassSum& sum) {
    BodyPart part;
    part.body = dBodyCreate(world);
    part.p_LC = sum.com();
    SetMass(part.body, sum.mass, sum.I_com());
    return part;
  }

  // the world, its parameters, spaces and contact group; then the geometry, the bodies and the
  // joints, in an order that fixes the order of ODE's bodies (and so its results).
  void Build(const Vector7d& arm_q, const HandVector& hand_f) {
    CreateWorld();
    AddStaticGeometry();
    AddRobotBodies();
    AddObject();
    AddArmJoints();
    AddFingerJoints();
    // the moving bodies' solver indices, plus one, in their user data (SolverIndex).
    for (int i = 0; i <= kHandJoints; ++i) {
      const dBodyID b = i < kHandJoints ? fingers[i].body : object.body;
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

  void CreateWorld() {
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
    proxy_space = dSimpleSpaceCreate(nullptr);
    contact_group = dJointGroupCreate(0);
  }

  // static geometry: table and arm base.
  void AddStaticGeometry() {
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
  void AddRobotBodies() {
    const RobotModel& r = robot();
    for (int i = 1; i <= kArmDof; ++i) {
      MassSum sum;
      sum.Add(r.arm.link(i).inertia, Eigen::Isometry3d::Identity());
      if (i == kArmDof) {
        sum.Add(r.hand.mount().inertia, r.X_FH);
        sum.Add(r.hand.palm().inertia, r.X_FH * r.hand.X_HP());
      }
      arm[i - 1] = MakeBody(sum);
      if (!joint_dynamic(i - 1)) dBodySetKinematic(arm[i - 1].body);
      AttachShapes(arm[i - 1], r.arm.link(i), Eigen::Isometry3d::Identity(), Role::kArm);
      if (i == kArmDof) {
        AttachShapes(arm[i - 1], r.hand.mount(), r.X_FH, Role::kPalm, kHandJoints);
        AttachShapes(arm[i - 1], r.hand.palm(), r.X_FH * r.hand.X_HP(), Role::kPalm, kHandJoints);
      }
    }
    for (int j = 0; j < kHandJoints; ++j) {
      const RigidLink& link = r.hand.finger(j / kFingerJoints).links[j % kFingerJoints];
      MassSum sum;
      sum.Add(link.inertia, Eigen::Isometry3d::Identity());
      fingers[j] = MakeBody(sum);
      AttachShapes(fingers[j], link, Eigen::Isometry3d::Identity(), Role::kFinger, j);
    }
  }

  // the object: its parts on one body whose frame is at the centre of mass. Each part gets
  // the collision category of what it touches (PartContact), and a proximity proxy unless it
  // touches only the table.
  void AddObject() {
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
      for (bool proxy : {false, true}) {
        if (proxy && category == kCatFoot) continue;
        dGeomID g =
            proxy ? AddGeom(proxy_space, shape, Role::kProxy, o.name, options.proximity_margin)
                  : AddGeom(space, shape, Role::kObject, o.name, 0.0, category);
        geom_info.back().friction = part.friction;
        dGeomSetBody(g, object.body);
        // a mesh's proxy box stands at the centre of the mesh's bounding box.
        const Eigen::Vector3d centre =
            proxy && shape.kind == CollisionShape::Kind::kMesh
                ? Eigen::Vector3d(shape.X_LG *
                                  (0.5 * (shape.mesh->BoxMin() + shape.mesh->BoxMax())))
                : Eigen::Vector3d(shape.X_LG.translation());
        const Eigen::Vector3d off = centre - object.p_LC;
        dGeomSetOffsetPosition(g, off.x(), off.y(), off.z());
        dMatrix3 R;
        ToOde(shape.X_LG.linear(), R);
        dGeomSetOffsetRotation(g, R);
      }
    }
    PlaceBody(object, model->scene().ObjectPose(Placement{options.theta, options.object_xy}));
  }

  // the arm's hinges (none when the arm is kinematic) and its limits. Joints are made with
  // every joint at zero: ODE measures hinge angles from the relative orientation at the time
  // the axis is set.
  void AddArmJoints() {
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
  void AddFingerJoints() {
    const SimulationOptions& so = model->options();
    const RobotModel& r = robot();
    for (int j = 0; j < kHandJoints; ++j) {
      const int finger = j / kFingerJoints, k = j % kFingerJoints;
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
  std::array<dBodyID, kFingers> mounts{};
  // Moves every mount to the wrist body's pose and velocity.
  void SyncMounts() {
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
  dJointID MakeHinge(dBodyID child, dBodyID parent, const Eigen::Isometry3d& X_WJ,
                     const Eigen::Vector3d& axis_J) {
    dJointID j = dJointCreateHinge(world, nullptr);
    dJointAttach(j, child, parent);
    const Eigen::Vector3d a = X_WJ.translation();
    const Eigen::Vector3d axis = X_WJ.linear() * axis_J;
    dJointSetHingeAnchor(j, a.x(), a.y(), a.z());
    dJointSetHingeAxis(j, axis.x(), axis.y(), axis.z());
    return j;
  }

  void ComputeFrames(const Vector7d& qa, const HandJointVector& qh, ArmFrames* af,
                     HandFrames* hf) const {
    ArmLinkFrames(robot().arm, qa, af);
    // the coupled joints take their own (lagging) values, not their couplings'.
    HandFramesFromJoints(qh, hf);
  }

  // Hand FK from all 20 joint values (HandLinkFrames takes the 16 actuated ones and derives
  // the DIPs; here the DIPs are states of their own).
  void HandFramesFromJoints(const HandJointVector& qh, HandFrames* hf) const {
    const HandModel& hand = robot().hand;
    hf->X_HP = hand.X_HP();
    for (int i = 0; i < kFingers; ++i) {
      const Finger& finger = hand.finger(i);
      Eigen::Isometry3d X = hand.X_HP();
      for (int k = 0; k < kFingerJoints; ++k) {
        const RevoluteJoint& j = finger.joints[k].joint;
        X = X * j.X_PJ * Eigen::AngleAxisd(qh[HandJointIndex(i, k)], j.axis_J);
        hf->X_HL[i][k] = X;
      }
      hf->X_HT[i] = X * finger.X_LT;
    }
  }

  Eigen::Isometry3d WristLinkPose(const ArmFrames& af) const { return af.X_WL[kArmDof]; }

  void PlaceAll(const ArmFrames& af, const HandFrames& hf) {
    for (int i = 0; i < kArmDof; ++i) PlaceBody(arm[i], af.X_WL[i + 1]);
    const Eigen::Isometry3d X_WH = af.X_WL[kArmDof] * robot().X_FH;
    for (int j = 0; j < kHandJoints; ++j) {
      PlaceBody(fingers[j], X_WH * hf.X_HL[j / kFingerJoints][j % kFingerJoints]);
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

  // arm joint velocity commanded by the controller at the current state.
  Vector7d ArmVelocity() {
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
        v[i] =
            Clamp(arm_ff[i] + model->options().arm_servo_gain * (target - q_arm[i]), arm_vmax[i]);
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
  HandJointVector HandVelocity(const HandJointVector& q) const {
    const HandModel& hand = robot().hand;
    const double gain = model->options().finger_servo_gain;
    HandJointVector v;
    for (int j = 0; j < kHandJoints; ++j) {
      const HandJoint& hj = hand.joint(j);
      double target_v = 0.0;
      if (hj.is_actuated()) {
        target_v = hand_mode == ServoMode::kPosition ? gain * (hand_command[hj.actuated] - q[j])
                                                     : hand_command[hj.actuated];
      } else {
        // the DIP coupling: its target is the PIP's measured angle.
        const JointCoupling& c = *hj.coupling;
        target_v = gain * (c.multiplier * q[c.source] + c.offset - q[j]);
      }
      v[j] = Clamp(target_v, hand_vmax[j]);
    }
    return v;
  }

  void ReadJoints() {
    for (int i = 0; i < kArmDof; ++i) {
      if (!joint_dynamic(i)) continue;
      const double raw = dJointGetHingeAngle(arm_joints[i]);
      q_arm[i] += Wrap(raw - q_arm[i]);
    }
    if (hand_dynamic) {
      for (int j = 0; j < kHandJoints; ++j) q_hand[j] = dJointGetHingeAngle(finger_joints[j]);
    }
  }

  void Collide(bool only_detect) {
    detect_only = only_detect;
    report = ContactReport{};
    hand_object.clear();
    feedback_contact.clear();
    pending.clear();
    if (options.ode_broad_phase) {
      dSpaceCollide(space, this, &Impl::NearCallback);
    } else {
      BroadPhase();
    }
  }

  static void NearCallback(void* data, dGeomID a, dGeomID b) {
    static_cast<Impl*>(data)->CollidePair(a, b);
  }

  // ---- the broad phase ----
  // dSpaceCollide on a simple space tests every pair of its geoms; only the pairs whose
  // categories may touch (the robot's geoms with the object's and the table, the object's with
  // the table) can give contacts. These are tested here in the order ODE's simple space tests
  // them (its list: the geoms moved last come first), with its rules (enabled geoms, not on one
  // body, categories, sizes, overlapping bounding boxes; ODE's AABBTest hooks accept every pair
  // for these shapes), so that the contacts come in the same order.
  struct BroadGeom {
    dGeomID geom = nullptr;
    bool enabled = false;
    dReal box[6] = {};  // its bounding box this step
  };
  std::vector<BroadGeom> broad;                // this step, in the space's list order
  std::vector<int> broad_order_slot;           // this step, by place in the list: the slot
  std::vector<int> broad_slot;                 // by GeomInfo::id: the geom's row in broad_may_touch
  std::vector<std::uint64_t> broad_may_touch;  // by slot: a bit per slot it may touch
  int broad_words = 0;
  int broad_count = -1;  // the space's geoms when the table was built

  static int GeomId(dGeomID g) { return static_cast<const GeomInfo*>(dGeomGetData(g))->id; }

  bool MayTouch(int slot_a, int slot_b) const {
    return (broad_may_touch[static_cast<size_t>(slot_a) * broad_words + (slot_b >> 6)] >>
            (slot_b & 63)) &
           1u;
  }

  // ODE's simple space skips a geom of zero size (its GEOM_ZERO_SIZED flag).
  static bool ZeroSized(dGeomID g) {
    dVector3 box;
    dReal radius = 0.0, length = 0.0;
    switch (dGeomGetClass(g)) {
      case dBoxClass:
        dGeomBoxGetLengths(g, box);
        return box[0] == 0.0 || box[1] == 0.0 || box[2] == 0.0;
      case dSphereClass:
        return dGeomSphereGetRadius(g) == 0.0;
      case dCapsuleClass:
        dGeomCapsuleGetParams(g, &radius, &length);
        return radius == 0.0;
      case dCylinderClass:
        dGeomCylinderGetParams(g, &radius, &length);
        return radius == 0.0 || length == 0.0;
      default:
        return false;
    }
  }

  void BuildBroadPhase(int n) {
    broad.resize(n);
    broad_slot.assign(geom_info.size() + 1, -1);
    broad_words = (n + 63) / 64;
    broad_may_touch.assign(static_cast<size_t>(n) * broad_words, 0);
    for (int i = 0; i < n; ++i) broad_slot[GeomId(dSpaceGetGeom(space, i))] = i;
    for (int i = 0; i < n; ++i) {
      const dGeomID a = dSpaceGetGeom(space, i);
      for (int j = 0; j < n; ++j) {
        const dGeomID b = dSpaceGetGeom(space, j);
        const dBodyID body = dGeomGetBody(a);
        if (i == j || (body && body == dGeomGetBody(b)) || ZeroSized(a) || ZeroSized(b)) continue;
        if ((dGeomGetCategoryBits(a) & dGeomGetCollideBits(b)) ||
            (dGeomGetCategoryBits(b) & dGeomGetCollideBits(a))) {
          broad_may_touch[static_cast<size_t>(i) * broad_words + (j >> 6)] |= 1ull << (j & 63);
        }
      }
    }
    broad_count = n;
  }

  void BroadPhase() {
    dSpaceClean(space);  // every geom's bounding box is up to date
    const int n = dSpaceGetNumGeoms(space);
    if (n != broad_count) BuildBroadPhase(n);
    broad_order_slot.resize(n);
    for (int i = 0; i < n; ++i) {
      BroadGeom& g = broad[i];
      g.geom = dSpaceGetGeom(space, i);
      g.enabled = dGeomIsEnabled(g.geom) != 0;
      dGeomGetAABB(g.geom, g.box);
      const int id = GeomId(g.geom);
      if (id >= static_cast<int>(broad_slot.size()) || broad_slot[id] < 0) {
        BuildBroadPhase(n);  // a geom added since the table was built (never in a trial)
        i = -1;
        continue;
      }
      broad_order_slot[i] = broad_slot[id];
    }
    for (int i = 0; i < n; ++i) {
      const BroadGeom& a = broad[i];
      if (!a.enabled) continue;
      for (int j = i + 1; j < n; ++j) {
        const BroadGeom& b = broad[j];
        if (!b.enabled || !MayTouch(broad_order_slot[i], broad_order_slot[j])) continue;
        if (a.box[0] > b.box[1] || a.box[1] < b.box[0] || a.box[2] > b.box[3] ||
            a.box[3] < b.box[2] || a.box[4] > b.box[5] || a.box[5] < b.box[4]) {
          continue;
        }
        CollidePair(a.geom, b.geom);
      }
    }
  }

  void CollidePair(dGeomID a, dGeomID b) {
    const GeomInfo* ia = static_cast<const GeomInfo*>(dGeomGetData(a));
    const GeomInfo* ib = static_cast<const GeomInfo*>(dGeomGetData(b));
    if (ia->role > ib->role) {
      std::swap(a, b);
      std::swap(ia, ib);
    }
    const SimulationOptions& so = model->options();
    dContactGeom cg[16];
    const int n = CollideGeoms(a, b, so.max_contacts_per_pair, cg);
    if (n <= 0) return;
    double mu = 0.0;
    const Role ra = ia->role, rb = ib->role;
    if (ra == Role::kTable && (rb == Role::kArm || rb == Role::kPalm)) {
      if (report.arm_table == 0) report.arm_table_link = ib->link;
      report.arm_table += n;
      return;  // reported only: the trial ends there
    }
    if (ra == Role::kTable && rb == Role::kObject) {
      report.object_table += n;
      mu = model->scene().table.friction * options.physics.object_table_friction;
    } else if (ra == Role::kTable && rb == Role::kFinger) {
      report.finger_table += n;
      mu = so.hand_table_friction;
    } else if (ra == Role::kObject && rb == Role::kArm) {
      report.object_arm += n;
      mu = so.arm_object_friction;
    } else if (ra == Role::kObject && (rb == Role::kPalm || rb == Role::kFinger)) {
      report.object_hand += n;
      report.hand_links_on_object |= 1ul << ib->hand_index;
      mu = ia->friction * options.physics.object_hand_friction;
      // geom a is the object: ODE's normal points into body 1, the object.
      for (int i = 0; i < n; ++i) {
        hand_object.push_back({Eigen::Vector3d(cg[i].pos[0], cg[i].pos[1], cg[i].pos[2]),
                               Eigen::Vector3d(cg[i].normal[0], cg[i].normal[1], cg[i].normal[2]),
                               cg[i].depth, ib->hand_index, Eigen::Vector3d::Zero(), ia->friction});
      }
    } else {
      return;
    }
    if (ra == Role::kObject || rb == Role::kObject) {
      for (int i = 0; i < n; ++i) {
        report.max_object_penetration = std::max(report.max_object_penetration, cg[i].depth);
      }
    }
    if (detect_only) return;
    const double kp = so.contact_kp * options.physics.contact_stiffness;
    const double kd = so.contact_kd * options.physics.contact_damping;
    const double erp = h * kp / (h * kp + kd);
    const double cfm = 1.0 / (h * kp + kd);
    dBodyID ba = dGeomGetBody(a), bb = dGeomGetBody(b);
    const bool hand_pair = ra == Role::kObject && (rb == Role::kPalm || rb == Role::kFinger);
    if (options.structured_solver && arm_kinematic()) {
      // the structured step makes the rows itself (StepStructured); dJointAttach(j, 0, b)
      // would swap the bodies and turn the normal, which is done here alike.
      for (int i = 0; i < n; ++i) {
        PendingContact pc;
        pc.geom = cg[i];
        pc.b0 = ba ? ba : bb;
        pc.b1 = ba ? bb : nullptr;
        pc.normal_sign = ba ? 1.0 : -1.0;
        pc.mu = mu;
        pc.erp = erp;
        pc.cfm = cfm;
        pc.hand_object = hand_pair ? static_cast<int>(hand_object.size()) - n + i : -1;
        pc.index = i;
        pending.push_back(pc);
        ++report.total;
      }
      return;
    }
    for (int i = 0; i < n; ++i) {
      dContact c{};
      c.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
      c.surface.mu = mu;
      c.surface.soft_erp = erp;
      c.surface.soft_cfm = cfm;
      c.geom = cg[i];
      dJointID j = dJointCreateContact(world, contact_group, &c);
      dJointAttach(j, ba, bb);
      if (hand_pair) {
        // body 1 is the object: the feedback's f1 is the force on it.
        const size_t slot = feedback_contact.size();
        if (slot == feedback.size()) feedback.emplace_back();
        dJointSetFeedback(j, &feedback[slot]);
        feedback_contact.push_back(hand_object.size() - static_cast<size_t>(n) +
                                   static_cast<size_t>(i));
      }
      ++report.total;
    }
  }

  // ---- the structured step (WorldOptions::structured_solver) ----
  // ODE's dWorldStep for the fast fidelity's world (every arm body kinematic), with the same
  // rows (hinges, their motors and stops, soft contacts with pyramid friction), the same
  // right-hand sides and integration, but solved by SolveConstraints: each finger's equality
  // rows are eliminated on their own before the pivoting solve of the bounded rows.

  // a hinge's anchor and axis in each of its bodies' frames, as ODE keeps them.
  struct HingeFrame {
    dBodyID b0 = nullptr, b1 = nullptr;
    Eigen::Vector3d anchor0 = Eigen::Vector3d::Zero(), anchor1 = Eigen::Vector3d::Zero();
    Eigen::Vector3d axis0 = Eigen::Vector3d::Zero(), axis1 = Eigen::Vector3d::Zero();
  };
  std::array<HingeFrame, kHandJoints> hinges;
  static HingeFrame HingeFrames(dJointID j, dBodyID b0, dBodyID b1) {
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

  // a contact made by the last collision pass, for the structured step.
  struct PendingContact {
    dContactGeom geom{};
    dBodyID b0 = nullptr, b1 = nullptr;  // b0 is never null (ODE's order)
    double normal_sign = 1.0;            // -1: geom.normal turned, the bodies swapped
    double mu = 0.0, erp = 0.0, cfm = 0.0;
    int hand_object = -1;  // index into hand_object of an object-hand contact
    int index = 0;         // its place among its geom pair's contacts
  };
  std::vector<PendingContact> pending;
  std::vector<SolverBody> solver_bodies;
  // each moving body's inertia in its own frame and its inverse, kept from step to step.
  struct BodyInertia {
    Eigen::Matrix3d I_B = Eigen::Matrix3d::Zero(), inv_I_B = Eigen::Matrix3d::Zero();
  };
  std::array<BodyInertia, kHandJoints + 1> inertias;
  std::vector<ConstraintRow> rows;
  ConstraintSolverData solver;

  // a contact row's key for SolveConstraints (its first guess): the two geoms' ids and the
  // contact's place among theirs, the low two bits left for the row's kind (normal, first and
  // second friction direction); the top bit keeps it apart from the hinges' keys.
  static std::uint64_t ContactKey(dGeomID ga, dGeomID gb, int index) {
    const std::uint64_t a = static_cast<const GeomInfo*>(dGeomGetData(ga))->id;
    const std::uint64_t b = static_cast<const GeomInfo*>(dGeomGetData(gb))->id;
    return (1ull << 63) | (a << 40) | (b << 18) | (static_cast<std::uint64_t>(index) << 2);
  }

  // the solver index of a moving body (the finger links, then the object), -1 for others:
  // Build keeps it, plus one, in the moving bodies' user data (no other body has any).
  static int SolverIndex(dBodyID b) {
    return b ? static_cast<int>(reinterpret_cast<std::intptr_t>(dBodyGetData(b))) - 1 : -1;
  }

  // Adds a row on b0 (moving) and b1 (moving, kinematic or null); the velocity of a
  // kinematic b1 goes into c, as ODE's right-hand side has it.
  void AddRow(dBodyID b0, dBodyID b1, const Eigen::Vector3d& lin0, const Eigen::Vector3d& ang0,
              const Eigen::Vector3d& lin1, const Eigen::Vector3d& ang1, double c, double cfm,
              double lo, double hi, int findex, std::uint64_t key) {
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

  void AddHingeRows(int j) {
    const SimulationOptions& so = model->options();
    const HingeFrame& f = hinges[j];
    const double k = so.erp / h;
    const Eigen::Vector3d p0 = FromOde(dBodyGetPosition(f.b0)),
                          p1 = FromOde(dBodyGetPosition(f.b1));
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

  void AddContactRows(const PendingContact& pc) {
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

  void StepStructured() {
    const SimulationOptions& so = model->options();
    // the moving bodies: mass, world inverse inertia, velocity, gravity and the (implicit)
    // gyroscopic torque as ODE computes them.
    solver_bodies.resize(kHandJoints + 1);
    for (int i = 0; i <= kHandJoints; ++i) {
      const dBodyID b = i < kHandJoints ? fingers[i].body : object.body;
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
    rows.clear();
    for (int j = 0; j < kHandJoints; ++j) AddHingeRows(j);
    for (const PendingContact& pc : pending) AddContactRows(pc);
    SolveConstraints(h, rows, &solver_bodies, &solver);

    // the object's contact forces with the hand (ODE's feedback f1: the force on body 0);
    // the contacts' rows are the last ones, one or three per contact.
    size_t row = rows.size();
    for (auto it = pending.rbegin(); it != pending.rend(); ++it) {
      const int nrows = it->mu <= 0.0 ? 1 : 3;  // AddContactRows' rule
      row -= static_cast<size_t>(nrows);
      if (it->hand_object < 0) continue;
      Eigen::Vector3d f = Eigen::Vector3d::Zero();
      for (int k = 0; k < nrows; ++k) f += rows[row + k].lin[0] * solver.lambda[row + k];
      hand_object[static_cast<size_t>(it->hand_object)].f_W = f;
    }

    // velocities of the moving bodies, then every body moves (kinematic ones by their own
    // velocities, as in dWorldStep).
    for (int i = 0; i <= kHandJoints; ++i) {
      const dBodyID b = i < kHandJoints ? fingers[i].body : object.body;
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
  void Integrate(dBodyID b) const {
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

  void Step() {
    const auto t0 = Clock::now();
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
    for (int j = 0; j < kHandJoints; ++j) {
      dJointSetHingeParam(finger_joints[j], dParamVel, vh[j]);
      dJointSetHingeParam(finger_joints[j], dParamFMax, hand_fmax[j]);
      hand_vel[j] = vh[j];
    }
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
    if (options.structured_solver && arm_kinematic()) {
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

  void StepKinematically() {
    GS_DEMAND(!hand_dynamic, "StepKinematically after Step: the fingers are dynamic already");
    const auto t0 = Clock::now();
    const Vector7d va = ArmVelocity();
    const HandJointVector vh = HandVelocity(q_hand);
    const Vector7d qa_next = q_arm + h * va;
    const HandJointVector qh_next = q_hand + h * vh;
    ArmFrames af;
    HandFrames hf;
    ComputeFrames(qa_next, qh_next, &af, &hf);
    const Eigen::Isometry3d X_WH0 = arm_frames.X_WL[kArmDof] * robot().X_FH;
    const Eigen::Isometry3d X_WH1 = af.X_WL[kArmDof] * robot().X_FH;
    for (int i = 0; i < kArmDof; ++i) {
      PlaceBody(arm[i], af.X_WL[i + 1]);
      SetBodyVelocity(arm[i], arm_frames.X_WL[i + 1], af.X_WL[i + 1], h);
    }
    for (int j = 0; j < kHandJoints; ++j) {
      const int i = j / kFingerJoints, k = j % kFingerJoints;
      const Eigen::Isometry3d from = X_WH0 * hand_frames.X_HL[i][k];
      const Eigen::Isometry3d to = X_WH1 * hf.X_HL[i][k];
      PlaceBody(fingers[j], to);
      SetBodyVelocity(fingers[j], from, to, h);
    }
    arm_frames = af;
    hand_frames = hf;
    q_arm = qa_next;
    q_hand = qh_next;
    const auto t1 = Clock::now();
    Collide(true);
    time += h;
    stats.kinematic_steps++;
    stats.control_s += SecondsBetween(t0, t1);
    stats.collision_s += SecondsBetween(t1, Clock::now());
  }

  static void ProxyCallback(void* data, dGeomID a, dGeomID b) {
    auto* self = static_cast<Impl*>(data);
    if (self->near_object) return;
    const GeomInfo* ia = static_cast<const GeomInfo*>(dGeomGetData(a));
    const GeomInfo* ib = static_cast<const GeomInfo*>(dGeomGetData(b));
    const Role other = ia->role == Role::kProxy ? ib->role : ia->role;
    if (other != Role::kArm && other != Role::kPalm && other != Role::kFinger) return;
    dContactGeom cg;
    if (CollideGeoms(a, b, 1, &cg) > 0) self->near_object = true;
  }

  bool HandNearObject() {
    const auto t0 = Clock::now();
    near_object = false;
    dSpaceCollide2(reinterpret_cast<dGeomID>(proxy_space), reinterpret_cast<dGeomID>(space), this,
                   &Impl::ProxyCallback);
    stats.collision_s += SecondsBetween(t0, Clock::now());
    return near_object;
  }

  template <typename Fn>
  void ForEachDynamic(const Fn& fn) const {
    for (const BodyPart& f : fingers) fn(f.body);
    fn(object.body);
  }

  bool StateIsFinite() const {
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
};

SimulationData::SimulationData(const SimulationModel& model, const WorldOptions& options,
                               const Vector7d& arm_q, const HandVector& hand_f)
    : impl_(std::make_unique<Impl>()) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid world option: " + why);
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
void SimulationData::StepKinematically() { impl_->StepKinematically(); }
bool SimulationData::HandNearObject() { return impl_->HandNearObject(); }
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
  GS_DEMAND(j >= 0 && j < kHandJoints, "hand link index out of range");
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
  c.bodies = kArmDof + kHandJoints + 1;
  c.dynamic_bodies = kHandJoints + 1 + impl_->dynamic_arm_joints();
  c.joints = kHandJoints + impl_->dynamic_arm_joints();
  c.geoms = impl_->geom_count;
  return c;
}

const StepStatistics& SimulationData::statistics() const { return impl_->stats; }

void SimulationData::SetObjectVelocity(const Eigen::Vector3d& v, const Eigen::Vector3d& w) {
  dBodySetLinearVel(impl_->object.body, v.x(), v.y(), v.z());
  dBodySetAngularVel(impl_->object.body, w.x(), w.y(), w.z());
}

}  // namespace graspsynth
