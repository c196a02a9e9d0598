/// @file
/// Collision detection of the ODE world behind SimulationData: the broad phase (ODE's simple
/// space's pairs, in its order, without the pairs whose categories never touch), the narrow
/// phase (dCollide), and what each contact becomes: a report, an object-hand contact point, a
/// contact joint for dWorldStep or a pending contact for the structured step.

#include <ode/ode.h>

#include <algorithm>
#include <mutex>

#include "simulation/detail/simulation_data_internal.hpp"

namespace graspsynth::sim_internal {
namespace {

int GeomId(dGeomID g) { return static_cast<const GeomInfo*>(dGeomGetData(g))->id; }

// ODE's simple space skips a geom of zero size (its GEOM_ZERO_SIZED flag).
bool ZeroSized(dGeomID g) {
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

}  // namespace

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

// the table of the pairs that may touch, by slot (a geom's place in the space's list when the
// table is built).
void BroadPhase::Build(dSpaceID space, size_t geoms, int n) {
  geoms_.resize(n);
  slot_.assign(geoms + 1, -1);
  words_ = (n + 63) / 64;
  may_touch_.assign(static_cast<size_t>(n) * words_, 0);
  for (int i = 0; i < n; ++i) slot_[GeomId(dSpaceGetGeom(space, i))] = i;
  for (int i = 0; i < n; ++i) {
    const dGeomID a = dSpaceGetGeom(space, i);
    for (int j = 0; j < n; ++j) {
      const dGeomID b = dSpaceGetGeom(space, j);
      const dBodyID body = dGeomGetBody(a);
      if (i == j || (body && body == dGeomGetBody(b)) || ZeroSized(a) || ZeroSized(b)) continue;
      if ((dGeomGetCategoryBits(a) & dGeomGetCollideBits(b)) ||
          (dGeomGetCategoryBits(b) & dGeomGetCollideBits(a))) {
        may_touch_[static_cast<size_t>(i) * words_ + (j >> 6)] |= 1ull << (j & 63);
      }
    }
  }
  count_ = n;
}

void BroadPhase::Prepare(dSpaceID space, size_t geoms) {
  dSpaceClean(space);  // every geom's bounding box is up to date
  const int n = dSpaceGetNumGeoms(space);
  if (n != count_) Build(space, geoms, n);
  order_slot_.resize(n);
  for (int i = 0; i < n; ++i) {
    Geom& g = geoms_[i];
    g.geom = dSpaceGetGeom(space, i);
    g.enabled = dGeomIsEnabled(g.geom) != 0;
    dGeomGetAABB(g.geom, g.box);
    const int id = GeomId(g.geom);
    if (id >= static_cast<int>(slot_.size()) || slot_[id] < 0) {
      Build(space, geoms, n);  // a geom added since the table was built (never in a trial)
      i = -1;
      continue;
    }
    order_slot_[i] = slot_[id];
  }
}

void WorldImpl::Collide(bool only_detect) {
  detect_only = only_detect;
  report = ContactReport{};
  hand_object.clear();
  feedback_contact.clear();
  pending.clear();
  if (options.ode_broad_phase) {
    dSpaceCollide(space, this, &WorldImpl::NearCallback);
  } else {
    broad_phase.Run(space, geom_info.size(), [this](dGeomID a, dGeomID b) { CollidePair(a, b); });
  }
}

void WorldImpl::NearCallback(void* data, dGeomID a, dGeomID b) {
  static_cast<WorldImpl*>(data)->CollidePair(a, b);
}

void WorldImpl::CollidePair(dGeomID a, dGeomID b) {
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
  for (int i = 0; i < n; ++i) {
    // the structured step makes the rows itself (StepStructured); dJointAttach(j, 0, b)
    // would swap the bodies and turn the normal, which is done here alike.
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
    ++report.total;
    if (structured()) {
      pending.push_back(pc);
      continue;
    }
    const dJointID j = MakeContactJoint(pc);
    if (hand_pair) {
      // body 1 is the object: the feedback's f1 is the force on it.
      const size_t slot = feedback_contact.size();
      if (slot == feedback.size()) feedback.emplace_back();
      dJointSetFeedback(j, &feedback[slot]);
      feedback_contact.push_back(static_cast<size_t>(pc.hand_object));
    }
  }
}

dJointID WorldImpl::MakeContactJoint(const PendingContact& pc) {
  dContact c{};
  c.surface.mode = dContactApprox1 | dContactSoftERP | dContactSoftCFM;
  c.surface.mu = pc.mu;
  c.surface.soft_erp = pc.erp;
  c.surface.soft_cfm = pc.cfm;
  c.geom = pc.geom;
  dJointID j = dJointCreateContact(world, contact_group, &c);
  // the geoms' bodies as CollidePair found them (a null first body was swapped).
  if (pc.normal_sign > 0.0) {
    dJointAttach(j, pc.b0, pc.b1);
  } else {
    dJointAttach(j, nullptr, pc.b0);
  }
  return j;
}

}  // namespace graspsynth::sim_internal
