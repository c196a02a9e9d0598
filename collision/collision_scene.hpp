#pragma once

/// @file
/// The collision scene of graspsynth: the PA-10-7C's links, the Gifu Hand III's mount, palm and
/// phalanges, the pan (body and handle) and the table, as FCL primitives. STYLE.md's Model/Data
/// split: an immutable CollisionModel built once from the robot and scene models, and a
/// per-thread CollisionData that holds the FCL objects, their poses for one state and a broad
/// phase. FCL itself stays inside collision/ (no FCL type in this header).
///
/// Frames as in kinematics/types.hpp: W world, L a link frame, G a shape's own frame (centred,
/// z along the axis of capsules and cylinders), H the hand mount, O the object. Units: metres.
///
/// Shape names (unique): the link's name when the link has one shape ("S2_link", "palm",
/// "index_link2"), "<link>/<k>" for shape k of a link with several ("S1_link/0", "S1_link/1"),
/// "<object>/body" and "<object>/handle" for the pan, "table" for the table.
///
/// Ignored pairs (computed when the model is built, listed by CollisionModel::ignored_pairs()):
/// 1. kSameBody: shapes of one rigid body. The flange link W2_link, hand_mount_link and palm are
///    one body (fixed joints); the pan's body and handle are one body.
/// 2. kAdjacentBodies: bodies joined by one joint. These overlap or touch at the joint by
///    construction: base_link-S1_link, ..., E2_link-W1_link, W1_link-{W2_link, hand_mount_link,
///    palm} (through W2), and consecutive phalanges of a finger.
/// 3. kHandSelf: every other hand-hand pair. The fingers' capsules meet at the knuckles and
///    the thumb's base lies in the palm face; finger-finger contact is left to the simulation.
/// 4. kOverlapAtZero: any other robot-robot pair (arm-arm, arm-hand) closer than
///    CollisionModelOptions::zero_configuration_margin at q = 0 (arm straight up), f = 0 (hand
///    open). With the shipped description there is none: every touching pair is already
///    covered by 1-3; the rule is a safety net for descriptions whose housings overlap.
/// 5. kObjectOnTable: the pan and the table. The pan rests on the table (its body touches the
///    top face by construction); its support is the simulation's business.
/// Every other pair - arm or hand against the pan or the table, and robot self-collision
/// between links two or more joints apart (e.g. fingers against the forearm) - is checked.
///
/// Signed distance (SignedDistance, ClearanceProfile, ShapeSignedDistance), per pair of
/// shapes, all through FCL 0.7 with the libccd solver (GST_LIBCCD):
/// 1. FCL's unsigned distance (fcl::distance): closed forms for capsule-capsule and sphere
///    pairs, GJK for the others, run to SignedDistanceOptions::gjk_tolerance. When the shapes
///    are apart this is the answer.
/// 2. When they touch or penetrate:
///    - capsule-capsule: FCL's closed form of step 1 is already signed (distance of the axes
///      minus the radii) and exact;
///    - a sphere against anything: FCL's closed-form contact depth (fcl::collide), exact;
///    - the rest (a box or a cylinder on one side): fcl::distance with
///      DistanceRequest::enable_signed_distance (GJK + EPA) to epa_tolerance, which returns
///      minus the penetration depth. Should EPA fail (FCL throws on some degenerate
///      configurations, e.g. two coincident boxes), FCL's contact depth (MPR, which can
///      overestimate the depth of curved shapes) is used instead and the result is marked
///      `approximate`.
///    EPA is not used for capsule-capsule pairs: on that doubly curved pair it crawls (two
///    coaxial phalanges overlapping at their joint: 0.3 ms at 1e-3 m, 1.3 s at 1e-5 m).
/// Accuracy measured against closed forms (tests/collision/collision_scene_test.cpp, FCL 0.7):
/// - separated pairs: within 1e-7 m at the default gjk_tolerance of 1e-10 m (worst seen
///   4e-8 m over 2,000 random capsules, cylinders and boxes above a box face: a cylinder's rim).
///   FCL's default tolerance of 1e-6 m leaves errors up to 9e-4 m on a capsule's cap over a
///   box face.
/// - penetration depths: exact for capsule-capsule and sphere pairs; within epa_tolerance
///   (1e-5 m by default) for the others (worst seen 5e-6 m, shapes sunk into a box face). EPA's
///   time grows as its tolerance shrinks on curved pairs: typically 20-150 us per penetrating pair,
///   but a capsule deep and coaxial inside a cylinder takes 30 ms at 1e-5 m and 0.3 s at 1e-6 m.

#include <cstdint>
#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/robot_description.hpp"
#include "kinematics/types.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

namespace internal {
struct CollisionModelImpl;
struct CollisionDataImpl;
struct CollisionAccess;
}  // namespace internal

/// What a shape belongs to.
enum class CollisionGroup : uint8_t {
  kArm = 0,     ///< base_link .. W2_link (W2_link carries the flange disc)
  kHand = 1,    ///< hand mount adapter, palm, phalanges
  kObject = 2,  ///< the pan: body cylinder and handle box
  kTable = 3,   ///< the table box
};
/// Number of CollisionGroup values.
inline constexpr int kCollisionGroups = 4;

/// A short lowercase name of the group: "arm", "hand", "object", "table".
std::string_view ToString(CollisionGroup group);

/// A set of collision groups (a bit mask). Converts implicitly from one group.
class GroupSet {
 public:
  constexpr GroupSet() = default;
  constexpr GroupSet(CollisionGroup group) : bits_(Bit(group)) {}  // NOLINT: implicit on purpose
  constexpr GroupSet(std::initializer_list<CollisionGroup> groups) {
    for (CollisionGroup g : groups) bits_ |= Bit(g);
  }
  /// Arm and hand.
  static constexpr GroupSet Robot() { return {CollisionGroup::kArm, CollisionGroup::kHand}; }
  /// Object and table.
  static constexpr GroupSet World() { return {CollisionGroup::kObject, CollisionGroup::kTable}; }

  constexpr bool Contains(CollisionGroup group) const { return (bits_ & Bit(group)) != 0; }
  constexpr bool empty() const { return bits_ == 0; }
  constexpr uint8_t bits() const { return bits_; }
  constexpr GroupSet operator|(GroupSet other) const { return FromBits(bits_ | other.bits_); }
  constexpr bool operator==(const GroupSet&) const = default;

 private:
  static constexpr uint8_t Bit(CollisionGroup g) {
    return static_cast<uint8_t>(1u << static_cast<unsigned>(g));
  }
  static constexpr GroupSet FromBits(unsigned bits) {
    GroupSet s;
    s.bits_ = static_cast<uint8_t>(bits);
    return s;
  }
  uint8_t bits_ = 0;
};

/// One primitive of the scene.
struct CollisionShapeInfo {
  std::string name;  ///< unique, see the file comment
  std::string link;  ///< the link (or "<object>", "table") it belongs to
  CollisionGroup group = CollisionGroup::kArm;
  int body = -1;         ///< rigid body index (equal for rigidly joined links)
  CollisionShape shape;  ///< geometry; X_LG is its pose in the link frame
};

/// Why a pair of shapes is never checked (see the file comment).
enum class IgnoreReason : uint8_t {
  kSameBody,
  kAdjacentBodies,
  kHandSelf,
  kOverlapAtZero,
  kObjectOnTable,
};

/// A lowercase name of the reason, e.g. "adjacent bodies".
std::string_view ToString(IgnoreReason reason);

/// A pair of shapes that no query checks. a < b (shape indices).
struct IgnoredPair {
  int a = -1;
  int b = -1;
  IgnoreReason reason = IgnoreReason::kSameBody;
};

/// Options of the CollisionModel.
struct CollisionModelOptions {
  /// Robot-robot pairs (not already ignored) whose signed distance at q = 0, f = 0 is below
  /// this are ignored too (kOverlapAtZero). m, >= 0.
  double zero_configuration_margin = 1e-4;

  /// True when the options can be used; otherwise false with the reason in *why (if given).
  bool IsValid(std::string* why) const;
};

/// The immutable collision description: shapes, groups and ignored pairs. Cheap to copy
/// (copies share one description). Thread-safe to read.
class CollisionModel {
 public:
  /// Builds one shape per primitive of the robot (arm links, hand mount, palm, phalanges) and
  /// of the scene (pan body and handle, table) and computes the ignored pairs. Aborts
  /// (GS_DEMAND) on invalid options.
  CollisionModel(const RobotModel& robot, const SceneModel& scene,
                 const CollisionModelOptions& options = {});

  /// Number of shapes.
  int num_shapes() const;
  /// Shape i in 0..num_shapes() - 1.
  const CollisionShapeInfo& shape(int i) const;
  /// Index of the shape named `name`, or -1.
  int FindShape(std::string_view name) const;
  /// Indices of every shape in `groups`, ascending.
  std::vector<int> ShapesIn(GroupSet groups) const;
  /// True when the pair (a, b) (either order) is never checked; true for a == b.
  bool IsIgnored(int a, int b) const;
  /// Every ignored pair with its reason, sorted by (a, b).
  const std::vector<IgnoredPair>& ignored_pairs() const;
  /// Pose of the table box centre in the world (fixed).
  const Eigen::Isometry3d& X_WTable() const;

 private:
  friend struct internal::CollisionAccess;
  std::shared_ptr<const internal::CollisionModelImpl> impl_;
};

/// The mutable collision state for one thread: FCL objects at the poses of the last SetState
/// (with exact world boxes) and a broad phase (one dynamic AABB tree per group, brought up to
/// date by the first Collide after a SetState). Make one per thread from the model.
class CollisionData {
 public:
  explicit CollisionData(const CollisionModel& model);
  ~CollisionData();
  CollisionData(CollisionData&&) noexcept;
  CollisionData& operator=(CollisionData&&) noexcept;
  CollisionData(const CollisionData&) = delete;
  CollisionData& operator=(const CollisionData&) = delete;

  /// True once SetState has been called.
  bool has_state() const;
  /// Pose of shape i's own frame G in the world at the last SetState.
  const Eigen::Isometry3d& X_WG(int i) const;

 private:
  friend struct internal::CollisionAccess;
  std::unique_ptr<internal::CollisionDataImpl> impl_;
};

/// A robot configuration: arm joints and actuated hand joints.
struct RobotState {
  Vector7d q_arm = Vector7d::Zero();  ///< S1..W2, rad
  HandVector f = HandVector::Zero();  ///< f0..f15, rad
};

/// Moves every shape to the state: the arm at q_arm (rad), the hand at f (rad, f0..f15), the
/// object at its rest pose ObjectPose(theta) (theta in rad). Updates the broad phase. Aborts
/// (GS_DEMAND) when `data` was not made from `model` (or a copy of it).
void SetState(const CollisionModel& model, const Eigen::Ref<const Vector7d>& q_arm,
              const Eigen::Ref<const HandVector>& f, double theta, CollisionData* data);

/// As above with the object at the explicit pose X_WO (object frame O in the world).
void SetState(const CollisionModel& model, const Eigen::Ref<const Vector7d>& q_arm,
              const Eigen::Ref<const HandVector>& f, const Eigen::Isometry3d& X_WO,
              CollisionData* data);

/// Options of Collide.
struct CollideOptions {
  /// Stop after this many colliding pairs; 0 reports every pair. 1 answers "is anything in
  /// collision" fastest.
  int max_pairs = 0;
  /// Also compute one contact per pair: FCL's contact point and penetration depth (MPR for
  /// most primitive pairs: approximate; SignedDistance gives an accurate depth).
  bool compute_contacts = false;

  bool IsValid(std::string* why) const;
};

/// One colliding pair. shape_a belongs to the first group set of the query.
struct CollidingPair {
  int shape_a = -1;
  int shape_b = -1;
  std::string name_a;
  std::string name_b;
  CollisionGroup group_a = CollisionGroup::kArm;
  CollisionGroup group_b = CollisionGroup::kArm;
  /// With CollideOptions::compute_contacts: penetration depth (m, >= 0) and the contact point
  /// in the world (m); NaN otherwise.
  double depth = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector3d p_WC = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
};

/// What Collide found.
struct CollisionReport {
  /// Colliding pairs sorted by (shape_a, shape_b); empty when nothing collides.
  std::vector<CollidingPair> pairs;
  /// True when max_pairs stopped the search early (more pairs may collide).
  bool truncated = false;

  bool collision() const { return !pairs.empty(); }
  /// One line per pair, e.g. "index_link4 (hand) - table (table), depth 0.004 m".
  std::string BriefReport() const;
};

/// Every colliding pair (shape in `a`, shape in `b`) at the state of the last SetState, by the
/// broad phase (dynamic AABB trees) and FCL's narrow phase; ignored pairs are skipped. A pair
/// counts once even when both shapes' groups are in both sets (`a` = `b` = Robot() checks the
/// robot's self-collision). Aborts (GS_DEMAND) on invalid options, a data not made from
/// `model`, or a data without a state.
CollisionReport Collide(const CollisionModel& model, GroupSet a, GroupSet b, CollisionData* data,
                        const CollideOptions& options = {});

/// Options of SignedDistance and ClearanceProfile.
struct SignedDistanceOptions {
  /// GJK's stopping tolerance for separated shapes, m (> 0). FCL's default (1e-6) leaves
  /// errors up to 1e-3 m on a capsule or cylinder facing a box; 1e-10 leaves below 1e-7 m (see
  /// the file comment) for about 10% more time.
  double gjk_tolerance = 1e-10;
  /// EPA's tolerance on the penetration depth of overlapping shapes (pairs with a box or a
  /// cylinder), m (> 0). Smaller values cost much more time on curved pairs (file comment).
  double epa_tolerance = 1e-5;
  /// Pairs whose lower bound (see SignedDistance) exceeds this are not evaluated, m (> 0,
  /// infinity to evaluate every pair that can be the closest). When the minimum lies beyond
  /// it, the result is kBeyondMaxDistance with a lower bound (> max_distance) as distance.
  double max_distance = std::numeric_limits<double>::infinity();

  bool IsValid(std::string* why) const;
};

/// Signed distance between two shapes.
struct ShapeDistance {
  /// m; > 0 apart, < 0 minus the penetration depth.
  double distance = std::numeric_limits<double>::infinity();
  /// Closest points on a and on b in the world, m. When the shapes penetrate: the witness
  /// points of the depth (p_WCa on a inside b, p_WCb on b inside a, |p_WCb - p_WCa| = depth).
  Eigen::Vector3d p_WCa = Eigen::Vector3d::Zero();
  Eigen::Vector3d p_WCb = Eigen::Vector3d::Zero();
  /// True when EPA failed and FCL's contact depth (MPR) was used instead (file comment).
  bool approximate = false;
};

/// The signed distance between shape `a` attached to frame La at pose X_WLa and shape `b` at
/// X_WLb (each shape's own X_LG is applied). Aborts (GS_DEMAND) on invalid options.
ShapeDistance ShapeSignedDistance(const CollisionShape& a, const Eigen::Isometry3d& X_WLa,
                                  const CollisionShape& b, const Eigen::Isometry3d& X_WLb,
                                  const SignedDistanceOptions& options = {});

/// The minimum signed distance between two group sets.
struct SignedDistanceResult {
  enum class Status {
    kOk,                 ///< distance is the minimum over every pair
    kNoPairs,            ///< the sets have no pair to check (distance is +infinity)
    kBeyondMaxDistance,  ///< every pair is beyond max_distance; distance is a lower bound
  };
  Status status = Status::kNoPairs;
  /// m; > 0 clearance, < 0 minus the deepest penetration among the pairs.
  double distance = std::numeric_limits<double>::infinity();
  int shape_a = -1;  ///< the argmin pair; shape_a in the first set. -1 without one
  int shape_b = -1;
  std::string name_a;
  std::string name_b;
  Eigen::Vector3d p_WCa = Eigen::Vector3d::Zero();  ///< closest point on shape_a, world, m
  Eigen::Vector3d p_WCb = Eigen::Vector3d::Zero();  ///< closest point on shape_b, world, m
  bool approximate = false;  ///< the argmin pair's depth came from FCL's contact (see file)
  int pairs_considered = 0;  ///< pairs between the sets, ignored ones left out
  int pairs_evaluated = 0;   ///< pairs whose narrow phase ran (the rest were pruned)

  /// e.g. "0.0312 m between thumb_link4 and pan/handle".
  std::string BriefReport() const;
};

/// The minimum signed distance over every pair (shape in `a`, shape in `b`) at the state of the
/// last SetState; ignored pairs are skipped. Pairs are visited by increasing lower bound of
/// their distance - the largest of the distance between their exact world boxes and of each
/// shape's bounding ball against the other shape (closed forms) - and the search stops once the
/// bound exceeds the best distance found, so the result is the minimum over every pair (to the
/// tolerances) without evaluating every pair. Aborts (GS_DEMAND) on invalid options, a data
/// not made from `model`, or a data without a state.
SignedDistanceResult SignedDistance(const CollisionModel& model, GroupSet a, GroupSet b,
                                    CollisionData* data, const SignedDistanceOptions& options = {});

/// The clearance along a motion.
struct ClearanceProfileResult {
  /// Per state: the minimum signed distance between the sets and its pair.
  std::vector<SignedDistanceResult> states;
  /// Minimum over the states, m (+infinity without states).
  double min_clearance = std::numeric_limits<double>::infinity();
  /// The state of min_clearance; -1 without states.
  int argmin_state = -1;

  /// Per-state distances, m.
  std::vector<double> Clearances() const;
  /// Index of the first state whose clearance is below `margin` (m), or -1.
  int FirstStateBelow(double margin) const;
  /// e.g. "12 states, min clearance 0.021 m at state 11 (index_link4 - pan/handle)".
  std::string BriefReport() const;
};

/// SignedDistance(a, b) at every state of a motion, the object at X_WO. Leaves `data` at the
/// last state. Aborts (GS_DEMAND) on invalid options or a data not made from `model`.
ClearanceProfileResult ClearanceProfile(const CollisionModel& model,
                                        const std::vector<RobotState>& states,
                                        const Eigen::Isometry3d& X_WO, GroupSet a, GroupSet b,
                                        CollisionData* data,
                                        const SignedDistanceOptions& options = {});

}  // namespace graspsynth
