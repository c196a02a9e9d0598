#pragma once

/// @file
/// Internal to the simulation module (include it from simulation/*.cpp only): the ODE world
/// behind SimulationData (simulation_data.hpp), whose parts are kept by the files that use them:
/// - world_building.cpp: the world, its geometry, bodies and joints (Build), the ODE thread set-up
///   and error handlers;
/// - contacts.cpp: collision detection, the broad phase that mirrors ODE's simple space, and the
///   contacts' joints or rows;
/// - structured_step.cpp: the structured step (ODE 0.16's dWorldStep with SolveConstraints) and
///   its check against dWorldStep from the same state;
/// - simulation_data.cpp: the controller, the two kinds of step, and SimulationData's methods.

#include <ode/ode.h>

#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <vector>

#include "simulation/constraint_solver.hpp"
#include "simulation/simulation_data.hpp"

#ifndef dDOUBLE
#error "graspsynth needs ODE built in double precision (Debian's libode-dev is)"
#endif

namespace graspsynth::sim_internal {

/// Roles of geometry, ordered so that a pair can be classified with role(a) <= role(b).
enum class Role { kTable, kObject, kArm, kPalm, kFinger };

/// Collision categories: only the pairs listed in simulation_data.hpp are ever tested. The
/// object's parts touch the robot and the table (kCatHandle: the pan's handle), the robot only
/// (kCatPan: the pan's cylinder) or the table only (kCatFoot: the pan's foot), as the object
/// description says (PartContact).
constexpr unsigned long kCatTable = 1, kCatHandle = 2, kCatArm = 4, kCatPalm = 8, kCatFinger = 16,
                        kCatPan = 32, kCatFoot = 64;
constexpr unsigned long kCatRobot = kCatArm | kCatPalm | kCatFinger;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// What a geom is (its user data).
struct GeomInfo {
  Role role = Role::kTable;
  std::string link;       ///< name of the link the geometry belongs to
  int hand_index = -1;    ///< HandJointVector index of a finger link; the hand's joint count
                          ///< (HandModel::joint_count(), 20 for the Gifu) for the palm and mount
  double friction = 0.0;  ///< an object part's Coulomb coefficient with the fingers
  int id = 0;             ///< creation order (names a geom's contacts from step to step)
};

/// A rigid body made of one or more links, with its frame at the centre of mass and axes of
/// the first (frame-defining) link.
struct BodyPart {
  dBodyID body = nullptr;
  Eigen::Vector3d p_LC = Eigen::Vector3d::Zero();  ///< centre of mass in the link frame
};

/// An ODE vector (3 values) or matrix (3x4, row-major) as Eigen's.
inline Eigen::Vector3d FromOde(const dReal* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }
Eigen::Matrix3d FromOdeMatrix(const dReal* R);

/// A body's orientation, its quaternion normalized, and its pose.
Eigen::Quaterniond BodyOrientation(dBodyID body);
Eigen::Isometry3d BodyPose(dBodyID body);
/// Places a body (frame at the centre of mass) for link pose X_WL.
void PlaceBody(const BodyPart& part, const Eigen::Isometry3d& X_WL);
/// Sets the velocity that carries the body from link pose `from` to `to` in h seconds.
void SetBodyVelocity(const BodyPart& part, const Eigen::Isometry3d& from,
                     const Eigen::Isometry3d& to, double h);

/// dCollide, one trimesh pair at a time across threads (contacts.cpp says why).
int CollideGeoms(dGeomID a, dGeomID b, int max_contacts, dContactGeom* contacts);

/// Set while a world steps on this thread, so that an ODE error marks that world as broken.
extern thread_local bool* current_world_broken;

/// A hinge's anchor and axis in each of its bodies' frames, as ODE keeps them.
struct HingeFrame {
  dBodyID b0 = nullptr, b1 = nullptr;
  Eigen::Vector3d anchor0 = Eigen::Vector3d::Zero(), anchor1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis0 = Eigen::Vector3d::Zero(), axis1 = Eigen::Vector3d::Zero();
};

/// A contact made by the last collision pass, for the structured step.
struct PendingContact {
  dContactGeom geom{};
  dBodyID b0 = nullptr, b1 = nullptr;  ///< b0 is never null (ODE's order)
  double normal_sign = 1.0;            ///< -1: geom.normal turned, the bodies swapped
  double mu = 0.0, erp = 0.0, cfm = 0.0;
  int hand_object = -1;  ///< index into hand_object of an object-hand contact
  int index = 0;         ///< its place among its geom pair's contacts
};

/// The broad phase (contacts.cpp): dSpaceCollide on a simple space tests every pair of its
/// geoms; only the pairs whose categories may touch (the robot's geoms with the object's and the
/// table, the object's with the table) can give contacts. Run calls `collide` on these in the
/// order ODE's simple space tests them (its list: the geoms moved last come first), with its
/// rules (enabled geoms, not on one body, categories, sizes, overlapping bounding boxes; ODE's
/// AABBTest hooks accept every pair for these shapes), so that the contacts come in the same
/// order.
class BroadPhase {
 public:
  /// Tests the pairs of `space` (geoms whose user data is a GeomInfo; `geoms` of them made so
  /// far) and calls collide(a, b) on those that may touch.
  template <typename Collide>
  void Run(dSpaceID space, size_t geoms, const Collide& collide);

 private:
  struct Geom {
    dGeomID geom = nullptr;
    bool enabled = false;
    dReal box[6] = {};  // its bounding box this step
  };
  void Prepare(dSpaceID space, size_t geoms);  // fills geoms_ and order_slot_
  void Build(dSpaceID space, size_t geoms, int n);
  bool MayTouch(int slot_a, int slot_b) const {
    return (may_touch_[static_cast<size_t>(slot_a) * words_ + (slot_b >> 6)] >> (slot_b & 63)) & 1u;
  }

  std::vector<Geom> geoms_;               // this step, in the space's list order
  std::vector<int> order_slot_;           // this step, by place in the list: the slot
  std::vector<int> slot_;                 // by GeomInfo::id: the geom's row in may_touch_
  std::vector<std::uint64_t> may_touch_;  // by slot: a bit per slot it may touch
  int words_ = 0;
  int count_ = -1;  // the space's geoms when the table was built
};

template <typename Collide>
void BroadPhase::Run(dSpaceID space, size_t geoms, const Collide& collide) {
  Prepare(space, geoms);
  const int n = static_cast<int>(geoms_.size());
  for (int i = 0; i < n; ++i) {
    const Geom& a = geoms_[i];
    if (!a.enabled) continue;
    for (int j = i + 1; j < n; ++j) {
      const Geom& b = geoms_[j];
      if (!b.enabled || !MayTouch(order_slot_[i], order_slot_[j])) continue;
      if (a.box[0] > b.box[1] || a.box[1] < b.box[0] || a.box[2] > b.box[3] ||
          a.box[3] < b.box[2] || a.box[4] > b.box[5] || a.box[5] < b.box[4]) {
        continue;
      }
      collide(a.geom, b.geom);
    }
  }
}

/// The ODE world and its state. The members are grouped by the file that fills them.
struct WorldImpl {
  ~WorldImpl();

  // ---- the world (world_building.cpp) ----
  const SimulationModel* model = nullptr;
  WorldOptions options;
  double h = 0.0;

  dWorldID world = nullptr;
  dSpaceID space = nullptr;
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
  // finger links, finger-major (HandJointVector order), and their joints (the model's hand
  // joint count of each, sized by Build).
  std::vector<BodyPart> fingers;
  std::vector<dJointID> finger_joints;
  BodyPart object;
  // Each finger's base hinge hangs from a kinematic mount of its own when the wrist body is
  // kinematic (world_building.cpp, SyncMounts); null for none.
  std::vector<dBodyID> mounts;  // by finger

  // arm joint limits and caps
  Vector7d arm_lower, arm_upper, arm_vmax, arm_fmax;
  // per hand joint (HandJointVector order)
  HandJointVector hand_vmax, hand_fmax;
  // the fingers' hinge stops as ODE keeps them, and their motors' velocities this step (the
  // hinges' parameters, for the structured step).
  HandJointVector hand_stop_lo, hand_stop_hi, hand_vel;
  // the finger hinges' frames as ODE keeps them (for the structured step's rows).
  std::vector<HingeFrame> hinges;

  void Build(const Vector7d& arm_q, const HandVector& hand_f);
  /// Sizes every per-finger and per-hand-joint member to the model's hand.
  void SizeHand();
  void CreateWorld();
  void AddStaticGeometry();
  void AddRobotBodies();
  void AddObject();
  void AddArmJoints();
  void AddFingerJoints();
  dGeomID AddMeshGeom(dSpaceID into, const CollisionShape& shape);
  dGeomID AddGeom(dSpaceID into, const CollisionShape& shape, Role role, const std::string& link,
                  unsigned long category = kCatHandle);
  void AttachShapes(const BodyPart& part, const RigidLink& link, const Eigen::Isometry3d& X_BL,
                    Role role, int hand_index = -1);
  dJointID MakeHinge(dBodyID child, dBodyID parent, const Eigen::Isometry3d& X_WJ,
                     const Eigen::Vector3d& axis_J);
  /// Moves every finger mount to the wrist body's pose and velocity.
  void SyncMounts();
  void ComputeFrames(const Vector7d& qa, const HandJointVector& qh, ArmFrames* af,
                     HandFrames* hf) const;
  void HandFramesFromJoints(const HandJointVector& qh, HandFrames* hf) const;
  void PlaceAll(const ArmFrames& af, const HandFrames& hf);

  const RobotModel& robot() const { return model->robot(); }
  bool arm_kinematic() const { return options.arm_mode == ArmMode::kKinematic; }
  bool structured() const { return options.structured_solver && arm_kinematic(); }
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
  template <typename Fn>
  void ForEachDynamic(const Fn& fn) const {
    for (const BodyPart& f : fingers) fn(f.body);
    fn(object.body);
  }

  // ---- the controller and the steps (simulation_data.cpp) ----
  ServoMode arm_mode = ServoMode::kPosition;
  Vector7d arm_command = Vector7d::Zero();
  Vector7d arm_ff = Vector7d::Zero();
  ServoMode hand_mode = ServoMode::kPosition;
  HandVector hand_command = HandVector::Zero();
  int violation = -1;
  double violation_value = 0.0;
  // measured (dynamic) or modelled (kinematic) joint state
  Vector7d q_arm = Vector7d::Zero();
  HandJointVector q_hand;     // sized by Build
  bool hand_dynamic = false;  // set by the first Step()
  // link poses of the current state, for kinematic placement
  ArmFrames arm_frames;
  HandFrames hand_frames;
  HandFrames next_hand_frames;  // StepKinematically's scratch
  double time = 0.0;
  StepStatistics stats;
  bool broken = false;  // ODE raised an error inside a step of this world

  Vector7d ArmVelocity();
  HandJointVector HandVelocity(const HandJointVector& q) const;
  void ReadJoints();
  /// The controller's part of Step(): the arm's bodies or motors and the fingers' motors.
  void ControlStep();
  /// One step of the full physics; with `compare`, also dWorldStep from the same state (the
  /// structured step only).
  void Step(StepComparison* compare = nullptr);
  void StepKinematically();
  bool StateIsFinite() const;

  // ---- contacts (contacts.cpp) ----
  bool detect_only = false;
  ContactReport report;
  std::vector<HandObjectContact> hand_object;  // points of the last pass, object-hand pairs
  // force feedback of the object-hand contact joints: slots reused from pass to pass (a deque
  // keeps their addresses when it grows), and which hand_object entry each slot belongs to.
  std::deque<dJointFeedback> feedback;
  std::vector<size_t> feedback_contact;
  std::vector<PendingContact> pending;  // the contacts of the structured step
  BroadPhase broad_phase;

  void Collide(bool only_detect);
  static void NearCallback(void* data, dGeomID a, dGeomID b);
  void CollidePair(dGeomID a, dGeomID b);
  /// The contact joint of one pending contact, as CollidePair makes it for dWorldStep.
  dJointID MakeContactJoint(const PendingContact& pc);

  // ---- the structured step (structured_step.cpp) ----
  std::vector<SolverBody> solver_bodies;
  // each moving body's inertia in its own frame and its inverse, kept from step to step.
  struct BodyInertia {
    Eigen::Matrix3d I_B = Eigen::Matrix3d::Zero(), inv_I_B = Eigen::Matrix3d::Zero();
  };
  std::vector<BodyInertia> inertias;  // the hand's joint count + 1
  std::vector<ConstraintRow> rows;
  // the first row of each finger hinge (the last entry: the first contact row), and of each
  // pending contact.
  std::vector<int> hinge_row0;  // the hand's joint count + 1
  std::vector<int> contact_row0;
  ConstraintSolverData solver;

  void AddRow(dBodyID b0, dBodyID b1, const Eigen::Vector3d& lin0, const Eigen::Vector3d& ang0,
              const Eigen::Vector3d& lin1, const Eigen::Vector3d& ang1, double c, double cfm,
              double lo, double hi, int findex, std::uint64_t key);
  void AddHingeRows(int j);
  void AddContactRows(const PendingContact& pc);
  void PrepareSolverBodies();
  void StepStructured();
  void Integrate(dBodyID b) const;
  // the check against dWorldStep from the same state (SimulationData::StepBothWays).
  struct Snapshot;
  Snapshot Save() const;
  void Restore(const Snapshot& s);
  void ReadVelocities(StepForces* out) const;
  void StepOde(StepForces* out);
  void ReadStructuredForces(StepForces* out) const;
  void StepStructuredAndOde(StepComparison* compare);
};

/// A hinge's frames as ODE keeps them (world_building.cpp).
HingeFrame HingeFrames(dJointID j, dBodyID b0, dBodyID b1);

/// The solver index of a moving body (the finger links, then the object), -1 for others: Build
/// keeps it, plus one, in the moving bodies' user data (no other body has any).
inline int SolverIndex(dBodyID b) {
  return b ? static_cast<int>(reinterpret_cast<std::intptr_t>(dBodyGetData(b))) - 1 : -1;
}

}  // namespace graspsynth::sim_internal

namespace graspsynth {
/// SimulationData's state is the internal world.
struct SimulationData::Impl : sim_internal::WorldImpl {};
}  // namespace graspsynth
