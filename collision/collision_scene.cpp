#include "collision/collision_scene.hpp"

#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "common/demand.hpp"
#include "common/valid_options.hpp"
#include "scene/triangle_mesh.hpp"

namespace graspsynth {

namespace internal {

// Where a shape's link frame comes from at a state.
enum class FrameKind : uint8_t { kArmLink, kHandMount, kPalm, kPhalanx, kObject, kTable };

struct ShapeSource {
  FrameKind kind = FrameKind::kArmLink;
  int index = 0;  // arm link 0..7, or finger 0..4
  int link = 0;   // phalanx link 0..3 of the finger
};

struct CollisionModelImpl {
  CollisionModelImpl(const RobotModel& robot_model, const SceneModel& scene_model)
      : robot(robot_model), scene(scene_model) {}

  RobotModel robot;
  SceneModel scene;
  Eigen::Isometry3d X_WTable = Eigen::Isometry3d::Identity();
  std::vector<CollisionShapeInfo> shapes;
  std::vector<ShapeSource> sources;
  std::vector<uint8_t> ignored;  // n x n, row-major
  std::vector<IgnoredPair> ignored_pairs;

  int n() const { return static_cast<int>(shapes.size()); }
  bool Ignored(int a, int b) const { return ignored[static_cast<size_t>(a * n() + b)] != 0; }
};

// Candidate pairs of one (a, b) query, oriented so that .first lies in a.
using PairList = std::vector<std::pair<int, int>>;

// An FCL object whose world box is set from the primitive's exact bounds: FCL's own box of a
// rotated shape bounds its local box's circumsphere, two to three times too large for the
// slender phalanges and the diagonal handle.
class SceneObject : public fcl::CollisionObjectd {
 public:
  using fcl::CollisionObjectd::CollisionObjectd;
  void SetAabb(const fcl::AABBd& box) { aabb = box; }
};

struct CollisionDataImpl {
  std::shared_ptr<const CollisionModelImpl> model;
  std::vector<std::unique_ptr<SceneObject>> objects;
  std::vector<Eigen::Isometry3d> X_WG;
  std::vector<double> bounding_radius;  // of each shape about its centre, m
  std::array<std::unique_ptr<fcl::DynamicAABBTreeCollisionManagerd>, kCollisionGroups> managers;
  std::array<bool, kCollisionGroups> group_used{};
  std::array<bool, kCollisionGroups> tree_stale{};  // moved since the last broad-phase update
  ArmFrames arm_frames;
  HandFrames hand_frames;
  bool has_state = false;
  std::unordered_map<unsigned, PairList> pair_cache;
  std::vector<std::pair<double, int>> bounds;  // scratch: (AABB distance, candidate index)
};

struct CollisionAccess {
  static const std::shared_ptr<const CollisionModelImpl>& Model(const CollisionModel& m) {
    return m.impl_;
  }
  static CollisionDataImpl& Data(CollisionData* d) { return *d->impl_; }
};

}  // namespace internal

namespace {

using internal::CollisionAccess;
using internal::CollisionDataImpl;
using internal::CollisionModelImpl;
using internal::FrameKind;
using internal::ShapeSource;

constexpr double kInf = std::numeric_limits<double>::infinity();

std::shared_ptr<fcl::CollisionGeometryd> MakeGeometry(const CollisionShape& s) {
  switch (s.kind) {
    case CollisionShape::Kind::kBox:
      return std::make_shared<fcl::Boxd>(s.size.x(), s.size.y(), s.size.z());
    case CollisionShape::Kind::kCapsule:
      // FCL's lz is the straight part, as in CollisionShape.
      return std::make_shared<fcl::Capsuled>(s.size[0], s.size[1]);
    case CollisionShape::Kind::kCylinder:
      return std::make_shared<fcl::Cylinderd>(s.size[0], s.size[1]);
    case CollisionShape::Kind::kSphere:
      return std::make_shared<fcl::Sphered>(s.size[0]);
    case CollisionShape::Kind::kMesh: {
      auto bvh = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
      std::vector<fcl::Triangle> triangles;
      triangles.reserve(s.mesh->triangles.size());
      for (const std::array<int, 3>& t : s.mesh->triangles) {
        triangles.emplace_back(static_cast<size_t>(t[0]), static_cast<size_t>(t[1]),
                               static_cast<size_t>(t[2]));
      }
      bvh->beginModel();
      bvh->addSubModel(s.mesh->vertices, triangles);
      bvh->endModel();
      return bvh;
    }
  }
  GS_DEMAND(false, "unknown collision shape kind");
  return nullptr;
}

std::unique_ptr<fcl::CollisionObjectd> MakeObject(const CollisionShape& s,
                                                  const Eigen::Isometry3d& X_WG) {
  auto object = std::make_unique<fcl::CollisionObjectd>(MakeGeometry(s));
  object->setTransform(X_WG);
  object->computeAABB();
  return object;
}

// The exact world box of a primitive at pose X_WG.
fcl::AABBd TightBox(const CollisionShape& s, const Eigen::Isometry3d& X_WG) {
  const Eigen::Vector3d c = X_WG.translation();
  const Eigen::Matrix3d& R = X_WG.linear();
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  switch (s.kind) {
    case CollisionShape::Kind::kSphere:
      e.setConstant(s.size[0]);
      break;
    case CollisionShape::Kind::kCapsule:
      e = (0.5 * s.size[1] * R.col(2)).cwiseAbs() + Eigen::Vector3d::Constant(s.size[0]);
      break;
    case CollisionShape::Kind::kCylinder:
      for (int k = 0; k < 3; ++k) {
        const double a = R(k, 2);
        e[k] = 0.5 * s.size[1] * std::abs(a) + s.size[0] * std::sqrt(std::max(0.0, 1.0 - a * a));
      }
      break;
    case CollisionShape::Kind::kBox:
      e = R.cwiseAbs() * (0.5 * s.size);
      break;
    case CollisionShape::Kind::kMesh: {
      // the mesh's own bounding box, turned: not tight, but it holds the mesh.
      const Eigen::Vector3d lo = s.mesh->BoxMin(), hi = s.mesh->BoxMax();
      const Eigen::Vector3d mid = c + R * (0.5 * (lo + hi));
      e = R.cwiseAbs() * (0.5 * (hi - lo));
      return fcl::AABBd(Eigen::Vector3d(mid - e), Eigen::Vector3d(mid + e));
    }
  }
  return fcl::AABBd(Eigen::Vector3d(c - e), Eigen::Vector3d(c + e));
}

// Radius of the smallest ball about the shape's centre that holds it, m.
double BoundingRadius(const CollisionShape& s) {
  switch (s.kind) {
    case CollisionShape::Kind::kSphere:
      return s.size[0];
    case CollisionShape::Kind::kCapsule:
      return 0.5 * s.size[1] + s.size[0];
    case CollisionShape::Kind::kCylinder:
      return std::hypot(0.5 * s.size[1], s.size[0]);
    case CollisionShape::Kind::kBox:
      return 0.5 * s.size.norm();
    case CollisionShape::Kind::kMesh: {
      double r = 0.0;
      for (const Eigen::Vector3d& v : s.mesh->vertices) r = std::max(r, v.norm());
      return r;
    }
  }
  return 0.0;
}

// Distance from point p_W to a primitive at X_WG; 0 inside. Closed forms.
double PointShapeDistance(const CollisionShape& s, const Eigen::Isometry3d& X_WG,
                          const Eigen::Vector3d& p_W) {
  const Eigen::Vector3d p = X_WG.linear().transpose() * (p_W - X_WG.translation());
  switch (s.kind) {
    case CollisionShape::Kind::kSphere:
      return std::max(p.norm() - s.size[0], 0.0);
    case CollisionShape::Kind::kCapsule: {
      const double h = 0.5 * s.size[1];
      const Eigen::Vector3d q(p.x(), p.y(), p.z() - std::clamp(p.z(), -h, h));
      return std::max(q.norm() - s.size[0], 0.0);
    }
    case CollisionShape::Kind::kCylinder: {
      const double dr = std::max(std::hypot(p.x(), p.y()) - s.size[0], 0.0);
      const double dz = std::max(std::abs(p.z()) - 0.5 * s.size[1], 0.0);
      return std::hypot(dr, dz);
    }
    case CollisionShape::Kind::kBox:
      return (p.cwiseAbs() - 0.5 * s.size).cwiseMax(0.0).norm();
    case CollisionShape::Kind::kMesh:
      // to the mesh's bounding box: a lower bound of the distance to the mesh.
      return (p - s.mesh->BoxMax()).cwiseMax(s.mesh->BoxMin() - p).cwiseMax(0.0).norm();
  }
  return 0.0;
}

int ShapeIndex(const fcl::CollisionObjectd* object) {
  return static_cast<int>(reinterpret_cast<intptr_t>(object->getUserData()));
}

// The penetration of two objects from FCL's contact (one contact, the deepest). The witness
// points lie `depth` apart along the contact normal n (a -> b); when a or b is a sphere, its
// witness is its surface point along n (exact), else they straddle the contact point.
bool ContactPenetration(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                        ShapeDistance* out) {
  fcl::CollisionRequestd request(1, /*enable_contact=*/true);
  request.gjk_solver_type = fcl::GST_LIBCCD;
  fcl::CollisionResultd result;
  try {
    fcl::collide(&a, &b, request, result);
  } catch (const std::exception&) {
    return false;
  }
  if (result.numContacts() == 0) return false;
  const fcl::Contactd& contact = result.getContact(0);
  const double depth = contact.penetration_depth;
  const Eigen::Vector3d n = contact.normal;
  out->distance = -depth;
  if (a.getNodeType() == fcl::GEOM_SPHERE) {
    const auto& sphere = static_cast<const fcl::Sphered&>(*a.collisionGeometry());
    out->p_WCa = a.getTranslation() + sphere.radius * n;
    out->p_WCb = out->p_WCa - depth * n;
  } else if (b.getNodeType() == fcl::GEOM_SPHERE) {
    const auto& sphere = static_cast<const fcl::Sphered&>(*b.collisionGeometry());
    out->p_WCb = b.getTranslation() - sphere.radius * n;
    out->p_WCa = out->p_WCb + depth * n;
  } else {
    out->p_WCa = contact.pos + 0.5 * depth * n;
    out->p_WCb = contact.pos - 0.5 * depth * n;
  }
  return true;
}

// Signed distance of two FCL objects (see the header's file comment).
ShapeDistance PairDistance(const fcl::CollisionObjectd& a, const fcl::CollisionObjectd& b,
                           const SignedDistanceOptions& options) {
  ShapeDistance out;
  fcl::DistanceRequestd request(/*enable_nearest_points=*/true,
                                /*enable_signed_distance=*/false, 0.0, 0.0, options.gjk_tolerance,
                                fcl::GST_LIBCCD);
  fcl::DistanceResultd result;
  const double unsigned_distance = fcl::distance(&a, &b, request, result);
  out.distance = unsigned_distance;
  out.p_WCa = result.nearest_points[0];
  out.p_WCb = result.nearest_points[1];
  if (unsigned_distance > 0.0) return out;

  const fcl::NODE_TYPE type_a = a.getNodeType(), type_b = b.getNodeType();
  // capsule-capsule: FCL's closed form (distance of the axes minus the radii) is signed and
  // exact, while EPA crawls on the doubly curved pair (seconds for two phalanges end to end).
  if (type_a == fcl::GEOM_CAPSULE && type_b == fcl::GEOM_CAPSULE) return out;
  // a sphere against anything: FCL's closed-form contact gives the exact depth.
  if (type_a == fcl::GEOM_SPHERE || type_b == fcl::GEOM_SPHERE) {
    if (!ContactPenetration(a, b, &out)) out.distance = 0.0;  // touching
    return out;
  }
  // the rest (a box or a cylinder and no sphere): EPA.
  request.enable_signed_distance = true;
  request.distance_tolerance = options.epa_tolerance;
  result.clear();
  try {
    out.distance = fcl::distance(&a, &b, request, result);
    out.p_WCa = result.nearest_points[0];
    out.p_WCb = result.nearest_points[1];
    return out;
  } catch (const std::exception&) {
    // FCL throws when EPA meets a degenerate configuration (e.g. two coincident boxes).
  }
  out.approximate = true;
  if (!ContactPenetration(a, b, &out)) out.distance = 0.0;
  return out;
}

// Link frame of a shape at the given kinematic state (frames filled by the caller).
Eigen::Isometry3d LinkPose(const CollisionModelImpl& m, const ShapeSource& src,
                           const ArmFrames& arm, const Eigen::Isometry3d& X_WH,
                           const HandFrames& hand, const Eigen::Isometry3d& X_WO) {
  switch (src.kind) {
    case FrameKind::kArmLink:
      return arm.X_WL[src.index];
    case FrameKind::kHandMount:
      return X_WH;
    case FrameKind::kPalm:
      return X_WH * hand.X_HP;
    case FrameKind::kPhalanx:
      return X_WH * hand.X_HL[src.index][src.link];
    case FrameKind::kObject:
      return X_WO;
    case FrameKind::kTable:
      return m.X_WTable;
  }
  return Eigen::Isometry3d::Identity();
}

// World poses of every shape at (q, f, X_WO).
void ShapePoses(const CollisionModelImpl& m, const Eigen::Ref<const Vector7d>& q,
                const Eigen::Ref<const HandVector>& f, const Eigen::Isometry3d& X_WO,
                ArmFrames* arm, HandFrames* hand, std::vector<Eigen::Isometry3d>* X_WG) {
  ArmLinkFrames(m.robot.arm, q, arm);
  HandLinkFrames(m.robot.hand, f, hand);
  const Eigen::Isometry3d X_WH = arm->X_WL[kArmDof] * m.robot.X_FH;
  X_WG->resize(m.shapes.size());
  for (int i = 0; i < m.n(); ++i) {
    (*X_WG)[i] = LinkPose(m, m.sources[i], *arm, X_WH, *hand, X_WO) * m.shapes[i].shape.X_LG;
  }
}

std::string ShapeName(const std::string& link, size_t k, size_t count) {
  return count == 1 ? link : link + "/" + std::to_string(k);
}

// Adds every shape of `link` with the given group, body and frame source.
void AddLinkShapes(const RigidLink& link, CollisionGroup group, int body, ShapeSource src,
                   CollisionModelImpl* m) {
  for (size_t k = 0; k < link.shapes.size(); ++k) {
    m->shapes.push_back(
        {ShapeName(link.name, k, link.shapes.size()), link.name, group, body, link.shapes[k]});
    m->sources.push_back(src);
  }
}

void Ignore(int a, int b, IgnoreReason reason, CollisionModelImpl* m) {
  if (a > b) std::swap(a, b);
  if (m->Ignored(a, b)) return;
  m->ignored[static_cast<size_t>(a * m->n() + b)] = 1;
  m->ignored[static_cast<size_t>(b * m->n() + a)] = 1;
  m->ignored_pairs.push_back({a, b, reason});
}

bool IsRobot(CollisionGroup g) { return g == CollisionGroup::kArm || g == CollisionGroup::kHand; }

// The candidate pairs of a query: each unordered pair once, oriented (a-side, b-side), ignored
// pairs left out.
const internal::PairList& CandidatePairs(const CollisionModelImpl& m, GroupSet a, GroupSet b,
                                         CollisionDataImpl* d) {
  const unsigned key = (static_cast<unsigned>(a.bits()) << 8) | b.bits();
  auto it = d->pair_cache.find(key);
  if (it != d->pair_cache.end()) return it->second;
  internal::PairList pairs;
  for (int i = 0; i < m.n(); ++i) {
    for (int j = i + 1; j < m.n(); ++j) {
      const CollisionGroup gi = m.shapes[i].group, gj = m.shapes[j].group;
      const bool forward = a.Contains(gi) && b.Contains(gj);
      const bool backward = a.Contains(gj) && b.Contains(gi);
      if ((!forward && !backward) || m.Ignored(i, j)) continue;
      pairs.emplace_back(forward ? std::make_pair(i, j) : std::make_pair(j, i));
    }
  }
  return d->pair_cache.emplace(key, std::move(pairs)).first->second;
}

CollisionDataImpl& CheckedData(const CollisionModel& model, CollisionData* data, bool need_state) {
  GS_DEMAND(data != nullptr, "CollisionData is null");
  CollisionDataImpl& d = CollisionAccess::Data(data);
  GS_DEMAND(d.model == CollisionAccess::Model(model),
            "CollisionData was made from another CollisionModel");
  GS_DEMAND(!need_state || d.has_state, "CollisionData has no state: call SetState first");
  return d;
}

template <typename Options>
void DemandValid(const Options& options) {
  RequireValid(options, "invalid collision options");
}

struct CollideContext {
  const CollisionModelImpl* model = nullptr;
  GroupSet a, b;
  const CollideOptions* options = nullptr;
  fcl::CollisionRequestd request;
  CollisionReport* report = nullptr;
  bool done = false;
};

bool CollideCallback(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* raw) {
  auto* ctx = static_cast<CollideContext*>(raw);
  if (ctx->done) return true;
  int i = ShapeIndex(o1), j = ShapeIndex(o2);
  const CollisionModelImpl& m = *ctx->model;
  if (i == j || m.Ignored(i, j)) return false;
  // orient the pair (a-side first); when both orientations fit, the lower index first.
  const bool forward = ctx->a.Contains(m.shapes[i].group) && ctx->b.Contains(m.shapes[j].group);
  const bool backward = ctx->a.Contains(m.shapes[j].group) && ctx->b.Contains(m.shapes[i].group);
  if (!forward && !backward) return false;
  if (!forward || (backward && j < i)) {
    std::swap(i, j);
    std::swap(o1, o2);
  }
  fcl::CollisionResultd result;
  fcl::collide(o1, o2, ctx->request, result);
  if (!result.isCollision()) return false;
  CollidingPair pair;
  pair.shape_a = i;
  pair.shape_b = j;
  pair.name_a = m.shapes[i].name;
  pair.name_b = m.shapes[j].name;
  pair.group_a = m.shapes[i].group;
  pair.group_b = m.shapes[j].group;
  if (ctx->options->compute_contacts && result.numContacts() > 0) {
    const fcl::Contactd& contact = result.getContact(0);
    pair.depth = contact.penetration_depth;
    pair.p_WC = contact.pos;
  }
  ctx->report->pairs.push_back(std::move(pair));
  if (ctx->options->max_pairs > 0 &&
      static_cast<int>(ctx->report->pairs.size()) >= ctx->options->max_pairs) {
    ctx->done = true;
    ctx->report->truncated = true;
    return true;
  }
  return false;
}

}  // namespace

std::string_view ToString(CollisionGroup group) {
  switch (group) {
    case CollisionGroup::kArm:
      return "arm";
    case CollisionGroup::kHand:
      return "hand";
    case CollisionGroup::kObject:
      return "object";
    case CollisionGroup::kTable:
      return "table";
  }
  return "unknown";
}

std::string_view ToString(IgnoreReason reason) {
  switch (reason) {
    case IgnoreReason::kSameBody:
      return "same body";
    case IgnoreReason::kAdjacentBodies:
      return "adjacent bodies";
    case IgnoreReason::kHandSelf:
      return "hand self";
    case IgnoreReason::kOverlapAtZero:
      return "overlap at zero";
    case IgnoreReason::kObjectOnTable:
      return "object on table";
  }
  return "unknown";
}

bool CollisionModelOptions::IsValid(std::string* why) const {
  if (!(zero_configuration_margin >= 0.0) || !std::isfinite(zero_configuration_margin)) {
    if (why) *why = "zero_configuration_margin must be finite and >= 0";
    return false;
  }
  return true;
}

bool CollideOptions::IsValid(std::string* why) const {
  if (max_pairs < 0) {
    if (why) *why = "max_pairs must be >= 0";
    return false;
  }
  return true;
}

bool SignedDistanceOptions::IsValid(std::string* why) const {
  if (!(gjk_tolerance > 0.0) || !std::isfinite(gjk_tolerance)) {
    if (why) *why = "gjk_tolerance must be finite and > 0";
    return false;
  }
  if (!(epa_tolerance > 0.0) || !std::isfinite(epa_tolerance)) {
    if (why) *why = "epa_tolerance must be finite and > 0";
    return false;
  }
  if (!(max_distance > 0.0)) {
    if (why) *why = "max_distance must be > 0 (infinity allowed)";
    return false;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// CollisionModel

CollisionModel::CollisionModel(const RobotModel& robot, const SceneModel& scene,
                               const CollisionModelOptions& options) {
  DemandValid(options);
  auto m = std::make_shared<CollisionModelImpl>(robot, scene);
  const ArmModel& arm = robot.arm;
  const HandModel& hand = robot.hand;

  // rigid bodies and their parents (the joint tree): base, S1..W1, then W2 + hand mount + palm
  // (fixed joints), then the phalanges, then the object and the table.
  std::vector<int> parent;
  const auto new_body = [&parent](int parent_body) {
    parent.push_back(parent_body);
    return static_cast<int>(parent.size()) - 1;
  };
  int body = new_body(-1);
  AddLinkShapes(arm.base(), CollisionGroup::kArm, body, {FrameKind::kArmLink, 0, 0}, m.get());
  for (int i = 1; i <= kArmDof; ++i) {
    body = new_body(body);
    AddLinkShapes(arm.link(i), CollisionGroup::kArm, body, {FrameKind::kArmLink, i, 0}, m.get());
  }
  const int hand_body = body;  // W2_link, rigidly joined to the hand mount and the palm
  AddLinkShapes(hand.mount(), CollisionGroup::kHand, hand_body, {FrameKind::kHandMount, 0, 0},
                m.get());
  AddLinkShapes(hand.palm(), CollisionGroup::kHand, hand_body, {FrameKind::kPalm, 0, 0}, m.get());
  for (int fi = 0; fi < hand.finger_count(); ++fi) {
    int link_body = hand_body;
    const std::vector<RigidLink>& links = hand.finger(fi).links;
    for (int k = 0; k < static_cast<int>(links.size()); ++k) {
      link_body = new_body(link_body);
      AddLinkShapes(links[static_cast<size_t>(k)], CollisionGroup::kHand, link_body,
                    {FrameKind::kPhalanx, fi, k}, m.get());
    }
  }

  // the object in its frame O: every part the robot can touch (a part that touches only the
  // table supports the object in the simulation and lies inside it, as the pan's foot does).
  const ObjectModel& o = scene.object;
  const int object_body = new_body(-1);
  for (const ObjectPart& part : o.parts) {
    if (!part.touches_robot()) continue;
    m->shapes.push_back(
        {o.name + "/" + part.name, o.name, CollisionGroup::kObject, object_body, part.shape});
    m->sources.push_back({FrameKind::kObject, 0, 0});
  }

  // the table: a box whose top face is z = top_z.
  const TableModel& t = scene.table;
  m->X_WTable.translation() << t.centre_xy, t.top_z - 0.5 * t.size.z();
  CollisionShape table;
  table.kind = CollisionShape::Kind::kBox;
  table.size = t.size;
  m->shapes.push_back({"table", "table", CollisionGroup::kTable, new_body(-1), table});
  m->sources.push_back({FrameKind::kTable, 0, 0});

  // ignored pairs, by rule (the first rule that applies names the reason).
  const int n = m->n();
  m->ignored.assign(static_cast<size_t>(n * n), 0);
  for (int i = 0; i < n; ++i) m->ignored[static_cast<size_t>(i * n + i)] = 1;
  std::vector<std::pair<int, int>> unresolved_robot_pairs;
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const CollisionShapeInfo& a = m->shapes[i];
      const CollisionShapeInfo& b = m->shapes[j];
      if (a.body == b.body) {
        Ignore(i, j, IgnoreReason::kSameBody, m.get());
      } else if (parent[a.body] == b.body || parent[b.body] == a.body) {
        Ignore(i, j, IgnoreReason::kAdjacentBodies, m.get());
      } else if (a.group == CollisionGroup::kHand && b.group == CollisionGroup::kHand) {
        Ignore(i, j, IgnoreReason::kHandSelf, m.get());
      } else if ((a.group == CollisionGroup::kObject && b.group == CollisionGroup::kTable) ||
                 (a.group == CollisionGroup::kTable && b.group == CollisionGroup::kObject)) {
        Ignore(i, j, IgnoreReason::kObjectOnTable, m.get());
      } else if (IsRobot(a.group) && IsRobot(b.group)) {
        unresolved_robot_pairs.emplace_back(i, j);
      }
    }
  }
  // robot pairs that overlap (or nearly touch) at the zero configuration.
  ArmFrames arm_frames;
  HandFrames hand_frames;
  std::vector<Eigen::Isometry3d> X_WG;
  ShapePoses(*m, Vector7d::Zero(), HandVector::Zero(), scene.ObjectPose(0.0), &arm_frames,
             &hand_frames, &X_WG);
  for (const auto& [i, j] : unresolved_robot_pairs) {
    const auto a = MakeObject(m->shapes[i].shape, X_WG[i]);
    const auto b = MakeObject(m->shapes[j].shape, X_WG[j]);
    if (PairDistance(*a, *b, {}).distance < options.zero_configuration_margin) {
      Ignore(i, j, IgnoreReason::kOverlapAtZero, m.get());
    }
  }
  std::sort(m->ignored_pairs.begin(), m->ignored_pairs.end(),
            [](const IgnoredPair& x, const IgnoredPair& y) {
              return std::make_pair(x.a, x.b) < std::make_pair(y.a, y.b);
            });
  impl_ = std::move(m);
}

int CollisionModel::num_shapes() const { return impl_->n(); }

const CollisionShapeInfo& CollisionModel::shape(int i) const {
  GS_DEMAND(i >= 0 && i < impl_->n(), "shape index out of range");
  return impl_->shapes[static_cast<size_t>(i)];
}

int CollisionModel::FindShape(std::string_view name) const {
  for (int i = 0; i < impl_->n(); ++i) {
    if (impl_->shapes[i].name == name) return i;
  }
  return -1;
}

std::vector<int> CollisionModel::ShapesIn(GroupSet groups) const {
  std::vector<int> out;
  for (int i = 0; i < impl_->n(); ++i) {
    if (groups.Contains(impl_->shapes[i].group)) out.push_back(i);
  }
  return out;
}

bool CollisionModel::IsIgnored(int a, int b) const {
  GS_DEMAND(a >= 0 && a < impl_->n() && b >= 0 && b < impl_->n(), "shape index out of range");
  return impl_->Ignored(a, b);
}

const std::vector<IgnoredPair>& CollisionModel::ignored_pairs() const {
  return impl_->ignored_pairs;
}

const Eigen::Isometry3d& CollisionModel::X_WTable() const { return impl_->X_WTable; }

// ---------------------------------------------------------------------------------------------
// CollisionData

CollisionData::CollisionData(const CollisionModel& model)
    : impl_(std::make_unique<CollisionDataImpl>()) {
  CollisionDataImpl& d = *impl_;
  d.model = CollisionAccess::Model(model);
  const CollisionModelImpl& m = *d.model;
  // every Data makes its own FCL geometries: FCL writes a geometry's local AABB when an object
  // is made from it, so sharing them between threads would race.
  d.X_WG.assign(m.shapes.size(), Eigen::Isometry3d::Identity());
  std::array<std::vector<fcl::CollisionObjectd*>, kCollisionGroups> members;
  for (int i = 0; i < m.n(); ++i) {
    const Eigen::Isometry3d X_WG = m.sources[i].kind == FrameKind::kTable
                                       ? m.X_WTable * m.shapes[i].shape.X_LG
                                       : Eigen::Isometry3d::Identity();
    d.X_WG[i] = X_WG;
    d.bounding_radius.push_back(BoundingRadius(m.shapes[i].shape));
    d.objects.push_back(std::make_unique<internal::SceneObject>(MakeGeometry(m.shapes[i].shape)));
    d.objects.back()->setTransform(X_WG);
    d.objects.back()->SetAabb(TightBox(m.shapes[i].shape, X_WG));
    d.objects.back()->setUserData(reinterpret_cast<void*>(static_cast<intptr_t>(i)));
    members[static_cast<int>(m.shapes[i].group)].push_back(d.objects.back().get());
  }
  for (int g = 0; g < kCollisionGroups; ++g) {
    d.managers[g] = std::make_unique<fcl::DynamicAABBTreeCollisionManagerd>();
    d.group_used[g] = !members[g].empty();
    if (d.group_used[g]) d.managers[g]->registerObjects(members[g]);
    d.managers[g]->setup();
  }
}

CollisionData::~CollisionData() = default;
CollisionData::CollisionData(CollisionData&&) noexcept = default;
CollisionData& CollisionData::operator=(CollisionData&&) noexcept = default;

bool CollisionData::has_state() const { return impl_->has_state; }

const Eigen::Isometry3d& CollisionData::X_WG(int i) const {
  GS_DEMAND(i >= 0 && i < static_cast<int>(impl_->X_WG.size()), "shape index out of range");
  return impl_->X_WG[static_cast<size_t>(i)];
}

// ---------------------------------------------------------------------------------------------
// State and queries

void SetState(const CollisionModel& model, const Eigen::Ref<const Vector7d>& q_arm,
              const Eigen::Ref<const HandVector>& f, double theta, CollisionData* data) {
  SetState(model, q_arm, f, CollisionAccess::Model(model)->scene.ObjectPose(theta), data);
}

void SetState(const CollisionModel& model, const Eigen::Ref<const Vector7d>& q_arm,
              const Eigen::Ref<const HandVector>& f, const Eigen::Isometry3d& X_WO,
              CollisionData* data) {
  CollisionDataImpl& d = CheckedData(model, data, /*need_state=*/false);
  const CollisionModelImpl& m = *d.model;
  ShapePoses(m, q_arm, f, X_WO, &d.arm_frames, &d.hand_frames, &d.X_WG);
  for (int i = 0; i < m.n(); ++i) {
    if (m.sources[i].kind == FrameKind::kTable) continue;  // fixed
    d.objects[i]->setTransform(d.X_WG[i]);
    d.objects[i]->SetAabb(TightBox(m.shapes[i].shape, d.X_WG[i]));
  }
  // the broad phase is brought up to date by the next Collide that needs it.
  for (int g = 0; g < kCollisionGroups; ++g) {
    d.tree_stale[g] = d.group_used[g] && g != static_cast<int>(CollisionGroup::kTable);
  }
  d.has_state = true;
}

CollisionReport Collide(const CollisionModel& model, GroupSet a, GroupSet b, CollisionData* data,
                        const CollideOptions& options) {
  DemandValid(options);
  CollisionDataImpl& d = CheckedData(model, data, /*need_state=*/true);
  CollisionReport report;
  CollideContext ctx;
  ctx.model = d.model.get();
  ctx.a = a;
  ctx.b = b;
  ctx.options = &options;
  ctx.request = fcl::CollisionRequestd(1, options.compute_contacts);
  ctx.request.gjk_solver_type = fcl::GST_LIBCCD;
  ctx.report = &report;
  for (int ga = 0; ga < kCollisionGroups && !ctx.done; ++ga) {
    for (int gb = ga; gb < kCollisionGroups && !ctx.done; ++gb) {
      const auto g1 = static_cast<CollisionGroup>(ga), g2 = static_cast<CollisionGroup>(gb);
      const bool wanted = (a.Contains(g1) && b.Contains(g2)) || (a.Contains(g2) && b.Contains(g1));
      if (!wanted || !d.group_used[ga] || !d.group_used[gb]) continue;
      for (const int g : {ga, gb}) {
        if (d.tree_stale[g]) {
          d.managers[g]->update();
          d.tree_stale[g] = false;
        }
      }
      if (ga == gb) {
        d.managers[ga]->collide(&ctx, CollideCallback);
      } else {
        d.managers[ga]->collide(d.managers[gb].get(), &ctx, CollideCallback);
      }
    }
  }
  std::sort(report.pairs.begin(), report.pairs.end(),
            [](const CollidingPair& x, const CollidingPair& y) {
              return std::make_pair(x.shape_a, x.shape_b) < std::make_pair(y.shape_a, y.shape_b);
            });
  return report;
}

ShapeDistance ShapeSignedDistance(const CollisionShape& a, const Eigen::Isometry3d& X_WLa,
                                  const CollisionShape& b, const Eigen::Isometry3d& X_WLb,
                                  const SignedDistanceOptions& options) {
  DemandValid(options);
  const auto object_a = MakeObject(a, X_WLa * a.X_LG);
  const auto object_b = MakeObject(b, X_WLb * b.X_LG);
  return PairDistance(*object_a, *object_b, options);
}

SignedDistanceResult SignedDistance(const CollisionModel& model, GroupSet a, GroupSet b,
                                    CollisionData* data, const SignedDistanceOptions& options) {
  DemandValid(options);
  CollisionDataImpl& d = CheckedData(model, data, /*need_state=*/true);
  const CollisionModelImpl& m = *d.model;
  const internal::PairList& pairs = CandidatePairs(m, a, b, &d);
  SignedDistanceResult out;
  out.pairs_considered = static_cast<int>(pairs.size());
  if (pairs.empty()) return out;

  // visit pairs by increasing lower bound of their distance: the larger of the boxes'
  // distance and each shape's bounding ball against the other shape (closed forms).
  d.bounds.clear();
  for (size_t k = 0; k < pairs.size(); ++k) {
    const auto& [i, j] = pairs[k];
    const CollisionShape& si = m.shapes[i].shape;
    const CollisionShape& sj = m.shapes[j].shape;
    const double bound = std::max(
        {d.objects[i]->getAABB().distance(d.objects[j]->getAABB()),
         PointShapeDistance(sj, d.X_WG[j], d.X_WG[i].translation()) - d.bounding_radius[i],
         PointShapeDistance(si, d.X_WG[i], d.X_WG[j].translation()) - d.bounding_radius[j]});
    d.bounds.emplace_back(bound, static_cast<int>(k));
  }
  std::sort(d.bounds.begin(), d.bounds.end());
  ShapeDistance best;
  int best_pair = -1;
  double unvisited_bound = kInf;  // lower bound of the pairs left out by max_distance
  for (const auto& [bound, k] : d.bounds) {
    // a pair whose boxes are apart cannot penetrate; one farther than the best cannot win.
    if (best_pair >= 0 && bound > std::max(best.distance, 0.0)) break;
    if (bound > options.max_distance) {
      unvisited_bound = bound;
      break;
    }
    const auto& [i, j] = pairs[static_cast<size_t>(k)];
    const ShapeDistance dist = PairDistance(*d.objects[i], *d.objects[j], options);
    ++out.pairs_evaluated;
    if (best_pair < 0 || dist.distance < best.distance) {
      best = dist;
      best_pair = k;
    }
  }
  if (best_pair < 0 || best.distance > unvisited_bound) {
    // the minimum lies beyond max_distance: report only a lower bound.
    out.status = SignedDistanceResult::Status::kBeyondMaxDistance;
    out.distance = std::min(unvisited_bound, best_pair < 0 ? kInf : best.distance);
    return out;
  }
  const auto& [i, j] = pairs[static_cast<size_t>(best_pair)];
  out.status = SignedDistanceResult::Status::kOk;
  out.distance = best.distance;
  out.shape_a = i;
  out.shape_b = j;
  out.name_a = m.shapes[i].name;
  out.name_b = m.shapes[j].name;
  out.p_WCa = best.p_WCa;
  out.p_WCb = best.p_WCb;
  out.approximate = best.approximate;
  return out;
}

ClearanceProfileResult ClearanceProfile(const CollisionModel& model,
                                        const std::vector<RobotState>& states,
                                        const Eigen::Isometry3d& X_WO, GroupSet a, GroupSet b,
                                        CollisionData* data, const SignedDistanceOptions& options) {
  DemandValid(options);
  ClearanceProfileResult out;
  out.states.reserve(states.size());
  for (size_t s = 0; s < states.size(); ++s) {
    SetState(model, states[s].q_arm, states[s].f, X_WO, data);
    out.states.push_back(SignedDistance(model, a, b, data, options));
    if (out.argmin_state < 0 || out.states.back().distance < out.min_clearance) {
      out.min_clearance = out.states.back().distance;
      out.argmin_state = static_cast<int>(s);
    }
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Reports

std::string CollisionReport::BriefReport() const {
  std::ostringstream s;
  if (pairs.empty()) s << "no collision";
  for (size_t k = 0; k < pairs.size(); ++k) {
    const CollidingPair& p = pairs[k];
    if (k > 0) s << "\n";
    s << p.name_a << " (" << ToString(p.group_a) << ") - " << p.name_b << " ("
      << ToString(p.group_b) << ")";
    if (std::isfinite(p.depth)) s << ", depth " << p.depth << " m";
  }
  if (truncated) s << "\n(stopped at max_pairs)";
  return s.str();
}

std::string SignedDistanceResult::BriefReport() const {
  std::ostringstream s;
  switch (status) {
    case Status::kNoPairs:
      return "no pair to check";
    case Status::kBeyondMaxDistance:
      s << "every pair beyond max_distance (at least " << distance << " m)";
      return s.str();
    case Status::kOk:
      break;
  }
  s << distance << " m between " << name_a << " and " << name_b;
  if (approximate) s << " (approximate depth)";
  return s.str();
}

std::vector<double> ClearanceProfileResult::Clearances() const {
  std::vector<double> out;
  out.reserve(states.size());
  for (const SignedDistanceResult& r : states) out.push_back(r.distance);
  return out;
}

int ClearanceProfileResult::FirstStateBelow(double margin) const {
  for (size_t s = 0; s < states.size(); ++s) {
    if (states[s].distance < margin) return static_cast<int>(s);
  }
  return -1;
}

std::string ClearanceProfileResult::BriefReport() const {
  std::ostringstream s;
  s << states.size() << " states";
  if (argmin_state >= 0) {
    const SignedDistanceResult& r = states[static_cast<size_t>(argmin_state)];
    s << ", min clearance " << min_clearance << " m at state " << argmin_state;
    if (r.shape_a >= 0) s << " (" << r.name_a << " - " << r.name_b << ")";
  }
  return s.str();
}

}  // namespace graspsynth
