#pragma once

/// @file
/// Closed-form inverse kinematics of a 7-joint SRS arm (the PA-10-7C, the KUKA LBR iiwa) with
/// the arm angle psi as the redundancy parameter (reference/robot.md 1.5, after Shimizu et al.
/// 2008).
///
/// DH space: the closed forms are those of the standard DH table of reference/robot.md 1.3. An
/// arm whose joints turn the other way or start elsewhere is mapped onto it by its DhJointMap
/// (kinematics/arm_model.hpp: q_dh = sign q + offset, the flange DH frame 7 turned by R_7F):
/// a flange target becomes a target for DH frame 7, the joint limits are taken in DH values
/// (ArmModel::dh_lower/dh_upper: a flipped joint's [lower, upper] is [-upper, -lower]), and
/// solutions are mapped back to joint values. The branch signs (GC2, GC4, GC6), the arm angle
/// and the feasible-psi intervals are DH quantities: on the iiwa (A4's sign -1) GC4 = +1 is
/// A4 <= 0. On the PA-10 the map is the identity and nothing is mapped (its results stay bit
/// for bit those of the unmapped IK).
///
/// A flange target X_WF fixes the shoulder-wrist vector, hence the elbow angle E1 up to its
/// sign. The remaining freedom is the arm angle psi: the rotation of the arm plane about the
/// shoulder-wrist axis, measured from the reference plane in which S3 = 0. Each joint is then a
/// closed form of psi: S2 and W1 are "cosine type" (acos of a sinusoid), S1, S3, E2 and W2
/// "tangent type" (atan2 of two sinusoids). Eight branches are told apart by the signs
/// (GC2, GC4, GC6) of S2, E1 and W1.
///
/// Conventions: psi and the joint values returned by the closed forms are in (-pi, pi]. Joints
/// whose range is wider than 2*pi minus nothing (E2 and W2 at +-255 deg) can take a value or its
/// 2*pi-equivalent; NearestEquivalent picks the one closest to a current configuration.
/// Failures (unreachable target, singular target, limits) are statuses, never NaN.

#include <array>
#include <optional>
#include <string_view>
#include <vector>

#include "common/field_list.hpp"
#include "kinematics/arm_model.hpp"
#include "kinematics/types.hpp"

namespace graspsynth {

/// Configuration signs of an arm solution: the signs of the DH values of S2 (gc2), E1 (gc4) and
/// W1 (gc6), each +1 or -1.
struct ArmBranch {
  int gc2 = 1;
  int gc4 = 1;
  int gc6 = 1;

  /// 0..7, bit 0 for gc2 = -1, bit 1 for gc4 = -1, bit 2 for gc6 = -1.
  int index() const { return (gc2 < 0 ? 1 : 0) | (gc4 < 0 ? 2 : 0) | (gc6 < 0 ? 4 : 0); }
  static ArmBranch FromIndex(int index) {
    return {index & 1 ? -1 : 1, index & 2 ? -1 : 1, index & 4 ? -1 : 1};
  }
  bool operator==(const ArmBranch&) const = default;
};

/// The order in which a replay or a reach tries the branches (ArmBranch::index()): every sign
/// +1 first, then GC2, GC4 and both negated, each followed by its wrist flip (GC6 negated).
inline constexpr std::array<int, 8> kBranchPreference = {0, 4, 1, 5, 2, 6, 3, 7};

/// The branch of DH values q_dh (a zero value counts as +1): the branch of joint values on an
/// arm whose DhJointMap is the identity (the PA-10). For any arm use BranchOf(arm, q).
ArmBranch BranchOf(const Eigen::Ref<const Vector7d>& q_dh);

/// The branch of configuration q (joint values, rad) of `arm`: BranchOf(arm.dh_map().ToDh(q)).
ArmBranch BranchOf(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q);

/// Outcome of an IK query.
enum class IkStatus {
  kOk,           ///< a solution within every joint limit
  kUnreachable,  ///< the wrist centre is farther than d_se + d_ew or closer than |d_se - d_ew|
  kSingular,     ///< the elbow is stretched (E1 = 0): the arm angle is undefined
  kElbowLimit,   ///< E1 needed by the target lies outside its limit, for every psi
  kOutOfLimits,  ///< a solution exists at this psi and branch, but some joint is off limits
};

/// A short lowercase name of the status, e.g. "unreachable".
std::string_view ToString(IkStatus status);

template <>
struct EnumRange<IkStatus> {
  static constexpr IkStatus kLast = IkStatus::kOutOfLimits;
};

/// The closed forms of one flange target for one elbow sign gc4 (robot.md 1.5 steps 1-4):
/// R03(psi) = As sin(psi) + Bs cos(psi) + Cs and R47(psi) = Aw sin(psi) + Bw cos(psi) + Cw.
/// Built once per target by PrepareArmTarget, then evaluated at any psi and (gc2, gc6).
struct ArmTargetForm {
  IkStatus status = IkStatus::kUnreachable;  ///< kOk when the forms below are valid
  int gc4 = 1;
  double theta4 = 0.0;                              ///< E1's DH value, rad, constant in psi
  Eigen::Vector3d u_sw = Eigen::Vector3d::UnitZ();  ///< unit shoulder-to-wrist vector, world
  Eigen::Matrix3d As, Bs, Cs;                       ///< shoulder rotation forms
  Eigen::Matrix3d Aw, Bw, Cw;                       ///< wrist rotation forms
  DhJointMap dh_map;  ///< the arm's map: JointsAtArmAngle returns joint values through it
};

/// Builds the closed forms of flange target X_WF (world) for DH elbow sign gc4, in DH space
/// (the target's DH frame 7, the DH limit of E1). The status is
/// kUnreachable, kSingular or kElbowLimit when no psi can work; kOk otherwise.
ArmTargetForm PrepareArmTarget(const ArmModel& arm, const Eigen::Isometry3d& X_WF, int gc4);

/// Joint values at arm angle psi for DH shoulder and wrist signs gc2, gc6 (E1 from the form).
/// Every DH value is in (-pi, pi] (so is every joint value on the PA-10; a flipped joint's in
/// [-pi, pi), an offset one's shifted); limits are not checked. Requires form.status == kOk.
Vector7d JointsAtArmAngle(const ArmTargetForm& form, double psi, int gc2, int gc6);

/// One IK solution.
struct ArmIkSolution {
  IkStatus status = IkStatus::kUnreachable;
  Vector7d q = Vector7d::Zero();  ///< valid when status is kOk or kOutOfLimits
};

/// Solves X_WF at arm angle psi on one branch. Joints with a range beyond +-pi take the
/// in-limit 2*pi-equivalent closest to `q_near` (or to zero without it). kOutOfLimits when a
/// joint cannot be brought within its limit.
ArmIkSolution SolveArmIk(const ArmModel& arm, const Eigen::Isometry3d& X_WF, double psi,
                         ArmBranch branch, const Vector7d* q_near = nullptr);

/// Every in-limit solution of X_WF at arm angle psi, over the eight branches, in branch index
/// order, each joint its in-limit 2*pi-equivalent closest to 0. Empty when there is none.
std::vector<Vector7d> SolveArmIkAllBranches(const ArmModel& arm, const Eigen::Isometry3d& X_WF,
                                            double psi);

/// The arm angle of configuration q: the signed angle about the shoulder-wrist axis from the
/// reference elbow position (S3 = 0) to the actual elbow, in (-pi, pi]. With it,
/// SolveArmIk(FK(q), ArmAngleOf(q), BranchOf(arm, q)) returns q. Computed on the DH values of
/// q. Returns 0 when the elbow lies on the shoulder-wrist axis (stretched arm), where the
/// angle is undefined.
double ArmAngleOf(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q);

/// The exact set of arm angles at which DH branch (gc2, form.gc4, gc6) of the target is within
/// every joint limit, taken in DH values (robot.md 1.5 step 6: limit-crossing roots of every joint
/// plus the singular psi of tangent-type joints, then a midpoint test of each sub-arc). Disjoint
/// sorted intervals in [-pi, pi]; an arc through +-pi comes back as two intervals, one ending at pi
/// and one starting at -pi. Empty when form.status is not kOk.
std::vector<Interval> FeasibleArmAngles(const ArmModel& arm, const ArmTargetForm& form, int gc2,
                                        int gc6);

/// The widest of `intervals` (the first of equal widths); std::nullopt when there is none.
std::optional<Interval> WidestInterval(const std::vector<Interval>& intervals);

/// A solution chosen for its joint-limit margin: see SolveArmIkMidArc.
struct MidArcSolution {
  Vector7d q = Vector7d::Zero();  ///< in-limit configuration
  double psi = 0.0;               ///< its arm angle: the middle of the widest feasible arc, rad
  ArmBranch branch;               ///< its branch
};

/// The in-limit solution of X_WF whose arm angle is the middle of the widest feasible arc of
/// its branch, trying the branches in index order (elbow-up (+1, +1, +1) first), or only
/// `branch` when given. A good start configuration when nothing else fixes the arm angle.
/// std::nullopt when no branch tried has a feasible arm angle.
std::optional<MidArcSolution> SolveArmIkMidArc(const ArmModel& arm, const Eigen::Isometry3d& X_WF,
                                               std::optional<ArmBranch> branch = std::nullopt);

/// The value equivalent to `angle` modulo 2*pi that lies in [lower, upper] and is closest to
/// `reference`; std::nullopt when no equivalent lies in the range.
std::optional<double> NearestEquivalentAngle(double angle, double reference, double lower,
                                             double upper);

/// q (joint values) with every joint replaced by its in-limit 2*pi-equivalent closest to q_ref
/// (joint values); std::nullopt when some joint has no equivalent within its limits. A joint
/// sign or offset maps 2*pi-equivalents onto 2*pi-equivalents, so this needs no DH map.
std::optional<Vector7d> NearestEquivalent(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q,
                                          const Eigen::Ref<const Vector7d>& q_ref);

}  // namespace graspsynth
