#include "kinematics/arm_ik.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "kinematics/arm_reach.hpp"

namespace graspsynth {
namespace {

constexpr double kPi = M_PI;
constexpr double kTwoPi = 2.0 * M_PI;

// a target whose wrist centre lies beyond reach by more than this fraction of d_se + d_ew is
// unreachable; closer than that it is treated as just reachable (stretched or folded).
constexpr double kReachTol = 1e-12;
// an elbow within this fraction of d_se + d_ew of fully stretched (or folded) is singular: the
// elbow then lies on the shoulder-wrist axis and the arm angle is undefined (robot.md 1.6).
// With the PA-10 lengths it means |E1| below about 9e-5 rad.
constexpr double kStretchTol = 1e-9;
// sub-arcs of the feasible-psi construction narrower than this (rad) carry no information:
// they come from duplicate roots and are neither tested nor allowed to split an interval.
constexpr double kTinyArc = 1e-12;
// relative size of a_t^2 + b_t^2 - c_t^2 below which a tangent-type joint is taken as singular
// (its numerator and denominator vanish together somewhere). A spurious extra cut is harmless.
constexpr double kTangentSingularTol = 1e-6;
// |cos(psi - phi)| beyond 1 by less than this still counts as a (tangent) root: rounding must
// not drop a limit that is just touched. Again an extra cut is harmless.
constexpr double kRootTol = 1e-9;

// the joints by closed-form type (robot.md 1.5 step 5), as indices into q.
constexpr std::array<int, 4> kTangentJoints = {0, 2, 4, 6};  // S1, S3, E2, W2
constexpr std::array<int, 2> kCosineJoints = {1, 5};         // S2, W1

// maps (-inf, inf) to (-pi, pi].
double WrapToPi(double x) {
  x = std::remainder(x, kTwoPi);
  return x <= -kPi ? x + kTwoPi : x;
}

// atan2 in (-pi, pi]: atan2 returns -pi for a negative zero numerator.
double Atan2Pi(double y, double x) {
  const double t = std::atan2(y, x);
  return t <= -kPi ? kPi : t;
}

// Any number of turns: candidates are angle + 2 pi k for k in [k_lo, k_hi]; the distance to
// the reference is convex in k, so the unconstrained best k clamped to that range is the answer.
bool NearestEquivalentGeneral(double angle, double reference, double lower, double upper,
                              double* value) {
  if (!std::isfinite(angle) || !std::isfinite(reference) || !(lower <= upper)) return false;
  const double k_lo = std::ceil((lower - angle) / kTwoPi);
  const double k_hi = std::floor((upper - angle) / kTwoPi);
  double k = std::round((reference - angle) / kTwoPi);
  if (k < k_lo) k = k_lo;
  if (k > k_hi) k = k_hi;
  double v = angle + k * kTwoPi;
  // the divisions round; step back in when a candidate landed a rounding error outside.
  if (v < lower) v = angle + (k + 1.0) * kTwoPi;
  if (v > upper) v = angle + (k - 1.0) * kTwoPi;
  if (v < lower || v > upper) return false;
  *value = v;
  return true;
}

// NearestEquivalentAngle without the optional, inlined in the hot loops. Common case first: the
// angle is in range and the range is narrower than 4 pi, so at most one neighbour 2 pi away
// can compete.
inline bool NearestEquivalentTo(double angle, double reference, double lower, double upper,
                                double* value) {
  const double width = upper - lower;
  if (angle >= lower && angle <= upper && width < 2.0 * kTwoPi) {
    double best = angle;
    if (width >= kTwoPi) {
      const double down = angle - kTwoPi;
      const double up = angle + kTwoPi;
      if (down >= lower && std::abs(down - reference) < std::abs(best - reference)) best = down;
      if (up <= upper && std::abs(up - reference) < std::abs(best - reference)) best = up;
    }
    *value = best;
    return true;
  }
  return NearestEquivalentGeneral(angle, reference, lower, upper, value);
}

// true when some 2*pi-equivalent of theta lies in [lower, upper].
bool InRangeModulo(double theta, double lower, double upper) {
  if (theta >= lower && theta <= upper) return true;
  if (upper - lower >= kTwoPi) return true;
  double value;
  return NearestEquivalentGeneral(theta, theta, lower, upper, &value);
}

// a * sin(psi) + b * cos(psi) + c.
struct Sinusoid {
  double a = 0.0;
  double b = 0.0;
  double c = 0.0;
  double At(double s, double co) const { return a * s + b * co + c; }
};

Sinusoid Entry(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B, const Eigen::Matrix3d& C,
               int row, int col, double sign) {
  return {sign * A(row, col), sign * B(row, col), sign * C(row, col)};
}

// The six psi-dependent joints of one branch (robot.md 1.5 step 5): tangent-type joints are
// atan2(num, den), cosine-type joints gc * acos(f).
struct BranchForms {
  std::array<Sinusoid, 4> num, den;  // in kTangentJoints order
  std::array<Sinusoid, 2> f;         // in kCosineJoints order
  std::array<double, 2> gc;
};

BranchForms MakeBranchForms(const ArmTargetForm& form, int gc2, int gc6) {
  assert(gc2 == 1 || gc2 == -1);
  assert(gc6 == 1 || gc6 == -1);
  const double g2 = gc2;
  const double g6 = gc6;
  const Eigen::Matrix3d& As = form.As;
  const Eigen::Matrix3d& Bs = form.Bs;
  const Eigen::Matrix3d& Cs = form.Cs;
  const Eigen::Matrix3d& Aw = form.Aw;
  const Eigen::Matrix3d& Bw = form.Bw;
  const Eigen::Matrix3d& Cw = form.Cw;
  BranchForms b;
  // S1 = atan2(-gc2 s22, -gc2 s12), S3 = atan2(gc2 s33, -gc2 s31) (1-based entries).
  b.num[0] = Entry(As, Bs, Cs, 1, 1, -g2);
  b.den[0] = Entry(As, Bs, Cs, 0, 1, -g2);
  b.num[1] = Entry(As, Bs, Cs, 2, 2, g2);
  b.den[1] = Entry(As, Bs, Cs, 2, 0, -g2);
  // E2 = atan2(gc6 w23, gc6 w13), W2 = atan2(gc6 w32, -gc6 w31).
  b.num[2] = Entry(Aw, Bw, Cw, 1, 2, g6);
  b.den[2] = Entry(Aw, Bw, Cw, 0, 2, g6);
  b.num[3] = Entry(Aw, Bw, Cw, 2, 1, g6);
  b.den[3] = Entry(Aw, Bw, Cw, 2, 0, -g6);
  // S2 = gc2 acos(-s32), W1 = gc6 acos(w33).
  b.f[0] = Entry(As, Bs, Cs, 2, 1, -1.0);
  b.f[1] = Entry(Aw, Bw, Cw, 2, 2, 1.0);
  b.gc = {g2, g6};
  return b;
}

double TangentValue(const BranchForms& b, int k, double s, double c) {
  return Atan2Pi(b.num[k].At(s, c), b.den[k].At(s, c));
}

double CosineValue(const BranchForms& b, int k, double s, double c) {
  // rounding can push the cosine just outside [-1, 1].
  const double f = std::clamp(b.f[k].At(s, c), -1.0, 1.0);
  const double theta = b.gc[k] * std::acos(f);
  return theta <= -kPi ? kPi : theta;
}

// The psi-dependent joints of branch gc2 = gc6 = +1 at (sin psi, cos psi) = (s, c). The other
// branches follow from it: flipping gc2 negates S2 and turns S1 and S3 by pi (their atan2
// arguments change sign), and the same holds for gc6 with W1, E2 and W2.
struct PositiveBranchJoints {
  double s1, s2, s3, e2, w1, w2;
};

PositiveBranchJoints EvaluatePositiveBranch(const ArmTargetForm& form, double s, double c) {
  const auto at = [s, c](const Eigen::Matrix3d& A, const Eigen::Matrix3d& B,
                         const Eigen::Matrix3d& C, int row,
                         int col) { return A(row, col) * s + B(row, col) * c + C(row, col); };
  const auto shoulder = [&](int row, int col) { return at(form.As, form.Bs, form.Cs, row, col); };
  const auto wrist = [&](int row, int col) { return at(form.Aw, form.Bw, form.Cw, row, col); };
  PositiveBranchJoints j;
  // robot.md 1.5 step 5 with 0-based entries of R03 = [s] and R47 = [w].
  j.s1 = Atan2Pi(-shoulder(1, 1), -shoulder(0, 1));
  j.s2 = std::acos(std::clamp(-shoulder(2, 1), -1.0, 1.0));
  j.s3 = Atan2Pi(shoulder(2, 2), -shoulder(2, 0));
  j.e2 = Atan2Pi(wrist(1, 2), wrist(0, 2));
  j.w1 = std::acos(std::clamp(wrist(2, 2), -1.0, 1.0));
  j.w2 = Atan2Pi(wrist(2, 1), -wrist(2, 0));
  return j;
}

// theta + pi in (-pi, pi] for theta in (-pi, pi]; a tiny positive theta rounds to -pi.
double TurnByPi(double theta) {
  const double turned = theta > 0.0 ? theta - kPi : theta + kPi;
  return turned <= -kPi ? kPi : turned;
}

// -theta in (-pi, pi] for theta in [0, pi].
double Negate(double theta) { return theta >= kPi ? kPi : -theta; }

Vector7d AssembleBranch(const PositiveBranchJoints& j, double theta4, int gc2, int gc6) {
  assert(gc2 == 1 || gc2 == -1);
  assert(gc6 == 1 || gc6 == -1);
  Vector7d q;
  if (gc2 > 0) {
    q[0] = j.s1;
    q[1] = j.s2;
    q[2] = j.s3;
  } else {
    q[0] = TurnByPi(j.s1);
    q[1] = Negate(j.s2);
    q[2] = TurnByPi(j.s3);
  }
  q[3] = theta4;
  if (gc6 > 0) {
    q[4] = j.e2;
    q[5] = j.w1;
    q[6] = j.w2;
  } else {
    q[4] = TurnByPi(j.e2);
    q[5] = Negate(j.w1);
    q[6] = TurnByPi(j.w2);
  }
  return q;
}

// Elbow frame of the reference arm plane (S3 = 0, robot.md 1.5 step 3) as the sines and
// cosines of S1 and S2, for shoulder-to-wrist vector x_sw of length L and elbow (s4, c4).
struct ReferenceShoulder {
  double c1, s1, c2, s2;
};

ReferenceShoulder MakeReferenceShoulder(const SrsLengths& len, const Eigen::Vector3d& x_sw,
                                        double L, double s4, double c4) {
  ReferenceShoulder ref;
  const double r = std::sqrt(x_sw.x() * x_sw.x() + x_sw.y() * x_sw.y());
  // wrist centre on the base z axis: every S1 spans a valid reference plane; use S1 = 0.
  if (r > 0.0) {
    ref.c1 = x_sw.x() / r;
    ref.s1 = x_sw.y() / r;
  } else {
    ref.c1 = 1.0;
    ref.s1 = 0.0;
  }
  // S2 = beta - gamma with beta = atan2(r, z) and gamma = atan2(d_ew s4, d_se + d_ew c4);
  // built from sines and cosines directly, no trigonometric call.
  const double cb = x_sw.z() / L;
  const double sb = r / L;
  const double vx = len.d_ew * s4;
  const double vz = len.d_se + len.d_ew * c4;
  const double v = std::sqrt(vx * vx + vz * vz);
  const double cg = vz / v;
  const double sg = vx / v;
  ref.c2 = cb * cg + sb * sg;
  ref.s2 = sb * cg - cb * sg;
  return ref;
}

// Direction of the upper arm (z axis of DH frame 2) for S1, S2 given by sine and cosine.
Eigen::Vector3d UpperArmDirection(double c1, double s1, double c2, double s2) {
  return {c1 * s2, s1 * s2, c2};
}

// Rotation of the standard DH step Rz(theta) Rx(alpha) for alpha = +-pi/2 (sa = sin alpha).
Eigen::Matrix3d DhRotation(double c, double s, double sa) {
  Eigen::Matrix3d R;
  R << c, 0.0, s * sa, s, 0.0, -c * sa, 0.0, sa, 0.0;
  return R;
}

// |x_sw| within kStretchTol of the fully stretched or folded elbow.
bool ElbowOnShoulderWristAxis(const SrsLengths& len, double L) {
  const double reach = len.d_se + len.d_ew;
  return reach - L <= kStretchTol * reach ||
         L - std::abs(len.d_se - len.d_ew) <= kStretchTol * reach;
}

// Adds the psi in (-pi, pi] with alpha sin(psi) + beta cos(psi) + gamma = 0.
template <size_t N>
void AddSinusoidRoots(double alpha, double beta, double gamma, std::array<double, N>* cuts,
                      int* count) {
  const double R = std::sqrt(alpha * alpha + beta * beta);
  if (!(R > 1e-14)) return;  // constant in psi: no crossing
  const double x = -gamma / R;
  if (std::abs(x) > 1.0 + kRootTol) return;
  const double phi = std::atan2(alpha, beta);
  const double delta = std::acos(std::clamp(x, -1.0, 1.0));
  assert(*count + 2 <= static_cast<int>(N));
  (*cuts)[(*count)++] = WrapToPi(phi + delta);
  (*cuts)[(*count)++] = WrapToPi(phi - delta);
}

// True when every psi-dependent joint of the branch is within its limits (modulo 2*pi).
bool BranchFeasibleAt(const BranchForms& b, const ArmModel& arm, double psi,
                      const std::array<bool, kArmDof>& binds) {
  const double s = std::sin(psi);
  const double c = std::cos(psi);
  for (int k = 0; k < 2; ++k) {
    const int j = kCosineJoints[k];
    if (binds[j] && !InRangeModulo(CosineValue(b, k, s, c), arm.dh_lower()[j], arm.dh_upper()[j])) {
      return false;
    }
  }
  for (int k = 0; k < 4; ++k) {
    const int j = kTangentJoints[k];
    if (binds[j] &&
        !InRangeModulo(TangentValue(b, k, s, c), arm.dh_lower()[j], arm.dh_upper()[j])) {
      return false;
    }
  }
  return true;
}

}  // namespace

ArmBranch BranchOf(const Eigen::Ref<const Vector7d>& q_dh) {
  return {q_dh[1] >= 0.0 ? 1 : -1, q_dh[3] >= 0.0 ? 1 : -1, q_dh[5] >= 0.0 ? 1 : -1};
}

ArmBranch BranchOf(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q) {
  if (arm.dh_map().identity) return BranchOf(q);
  return BranchOf(arm.dh_map().ToDh(q));
}

std::string_view ToString(IkStatus status) {
  switch (status) {
    case IkStatus::kOk:
      return "ok";
    case IkStatus::kUnreachable:
      return "unreachable";
    case IkStatus::kSingular:
      return "singular";
    case IkStatus::kElbowLimit:
      return "elbow limit";
    case IkStatus::kOutOfLimits:
      return "out of limits";
  }
  return "unknown";
}

ArmTargetForm PrepareArmTarget(const ArmModel& arm, const Eigen::Isometry3d& X_WF, int gc4) {
  assert(gc4 == 1 || gc4 == -1);
  const SrsLengths& len = arm.lengths();
  ArmTargetForm form;
  form.gc4 = gc4;
  form.dh_map = arm.dh_map();
  form.As.setZero();
  form.Bs.setZero();
  form.Cs.setZero();
  form.Aw.setZero();
  form.Bw.setZero();
  form.Cw.setZero();

  // step 1: wrist centre and shoulder-to-wrist vector, from DH frame 7 (the flange itself
  // when the arm's DH map is the identity).
  const Eigen::Isometry3d X_W7 = arm.dh_map().FlangeToDh(X_WF);
  const Eigen::Matrix3d& R_WF = X_W7.linear();
  const Eigen::Vector3d x_sw = ShoulderToWrist(len, X_W7);
  const double L = x_sw.norm();
  if (!std::isfinite(L)) return form;

  // step 2: 1 - cos(E1) and 1 + cos(E1) as products of sums, accurate near the stretched and
  // folded elbow where the law of cosines itself loses digits.
  const double reach = len.d_se + len.d_ew;
  const double inner = std::abs(len.d_se - len.d_ew);
  const double two_se_ew = 2.0 * len.d_se * len.d_ew;
  if (reach - L < -kReachTol * reach || L - inner < -kReachTol * reach) return form;
  if (reach - L <= kStretchTol * reach) {
    form.status = IkStatus::kSingular;
    return form;
  }
  const double one_minus = std::max(0.0, (reach - L) * (reach + L) / two_se_ew);
  const double one_plus = std::max(0.0, (L - inner) * (L + inner) / two_se_ew);
  const double half = std::atan2(std::sqrt(one_minus), std::sqrt(one_plus));
  const double theta4 = gc4 * 2.0 * half;
  form.theta4 = theta4 <= -kPi ? kPi : theta4;
  if (!InRangeModulo(form.theta4, arm.dh_lower()[3], arm.dh_upper()[3])) {
    form.status = IkStatus::kElbowLimit;
    return form;
  }
  if (L - inner <= kStretchTol * reach) {
    form.status = IkStatus::kSingular;  // folded: the elbow sits on the shoulder-wrist axis
    return form;
  }
  // sin and cos of E1 consistent with theta4 to rounding (one_minus + one_plus = 2).
  const double sum = one_minus + one_plus;
  const double s4 = gc4 * 2.0 * std::sqrt(one_minus * one_plus) / sum;
  const double c4 = (one_plus - one_minus) / sum;

  // step 3: reference plane, R03 at S3 = 0 (R01 R12 R23(0) written out).
  const ReferenceShoulder ref = MakeReferenceShoulder(len, x_sw, L, s4, c4);
  Eigen::Matrix3d R03;
  R03 << ref.c1 * ref.c2, -ref.c1 * ref.s2, -ref.s1,  //
      ref.s1 * ref.c2, -ref.s1 * ref.s2, ref.c1,      //
      -ref.s2, -ref.c2, 0.0;

  // step 4: Rodrigues about u; [u x]^2 R = u u^T R - R, so Bs = R - u u^T R and Cs = u u^T R.
  const Eigen::Vector3d u = x_sw / L;
  form.u_sw = u;
  for (int j = 0; j < 3; ++j) {
    form.As.col(j) = u.cross(R03.col(j));
  }
  form.Cs.noalias() = u * (u.transpose() * R03);
  form.Bs = R03 - form.Cs;
  // R47 = R34^T R03^T R07; R34^T (alpha = +pi/2) maps rows (x, y, z) to
  // (c4 x + s4 y, z, s4 x - c4 y).
  const auto wrist_form = [&](const Eigen::Matrix3d& S, Eigen::Matrix3d* W) {
    Eigen::Matrix3d X;
    X.noalias() = S.transpose() * R_WF;
    W->row(0) = c4 * X.row(0) + s4 * X.row(1);
    W->row(1) = X.row(2);
    W->row(2) = s4 * X.row(0) - c4 * X.row(1);
  };
  wrist_form(form.As, &form.Aw);
  wrist_form(form.Bs, &form.Bw);
  wrist_form(form.Cs, &form.Cw);
  form.status = IkStatus::kOk;
  return form;
}

Vector7d JointsAtArmAngle(const ArmTargetForm& form, double psi, int gc2, int gc6) {
  assert(form.status == IkStatus::kOk);
  const PositiveBranchJoints j = EvaluatePositiveBranch(form, std::sin(psi), std::cos(psi));
  if (form.dh_map.identity) return AssembleBranch(j, form.theta4, gc2, gc6);
  return form.dh_map.ToJoints(AssembleBranch(j, form.theta4, gc2, gc6));
}

ArmIkSolution SolveArmIk(const ArmModel& arm, const Eigen::Isometry3d& X_WF, double psi,
                         ArmBranch branch, const Vector7d* q_near) {
  ArmIkSolution solution;
  const ArmTargetForm form = PrepareArmTarget(arm, X_WF, branch.gc4);
  solution.status = form.status;
  if (form.status != IkStatus::kOk) return solution;
  solution.q = JointsAtArmAngle(form, psi, branch.gc2, branch.gc6);
  for (int i = 0; i < kArmDof; ++i) {
    const double reference = q_near != nullptr ? (*q_near)[i] : 0.0;
    double equivalent;
    if (NearestEquivalentTo(solution.q[i], reference, arm.lower()[i], arm.upper()[i],
                            &equivalent)) {
      solution.q[i] = equivalent;
    } else {
      solution.status = IkStatus::kOutOfLimits;  // keep the closed-form value
    }
  }
  return solution;
}

std::vector<Vector7d> SolveArmIkAllBranches(const ArmModel& arm, const Eigen::Isometry3d& X_WF,
                                            double psi) {
  std::vector<Vector7d> solutions;
  const std::array<ArmTargetForm, 2> forms = {PrepareArmTarget(arm, X_WF, 1),
                                              PrepareArmTarget(arm, X_WF, -1)};
  if (forms[0].status != IkStatus::kOk && forms[1].status != IkStatus::kOk) return solutions;
  // the trigonometry is done once per elbow sign; the other branches only flip signs.
  const double s = std::sin(psi);
  const double c = std::cos(psi);
  std::array<PositiveBranchJoints, 2> joints;
  for (int e = 0; e < 2; ++e) {
    if (forms[e].status == IkStatus::kOk) joints[e] = EvaluatePositiveBranch(forms[e], s, c);
  }
  const Vector7d zero = Vector7d::Zero();
  for (int index = 0; index < 8; ++index) {
    const ArmBranch branch = ArmBranch::FromIndex(index);
    const int e = branch.gc4 > 0 ? 0 : 1;
    if (forms[e].status != IkStatus::kOk) continue;
    Vector7d q = AssembleBranch(joints[e], forms[e].theta4, branch.gc2, branch.gc6);
    if (!arm.dh_map().identity) q = arm.dh_map().ToJoints(q);
    if (std::optional<Vector7d> in_limits = NearestEquivalent(arm, q, zero)) {
      if (solutions.empty()) solutions.reserve(8);
      solutions.push_back(*in_limits);
    }
  }
  return solutions;
}

namespace {

// ArmAngleOf on DH values q.
double ArmAngleOfDh(const SrsLengths& len, const Eigen::Ref<const Vector7d>& q) {
  // elbow and wrist centre from the shoulder: x_se along z of DH frame 2, x_ew along z of 4.
  const double c1 = std::cos(q[0]), s1 = std::sin(q[0]);
  const double c2 = std::cos(q[1]), s2 = std::sin(q[1]);
  const double c3 = std::cos(q[2]), s3 = std::sin(q[2]);
  const double c4 = std::cos(q[3]), s4 = std::sin(q[3]);
  const Eigen::Vector3d e = UpperArmDirection(c1, s1, c2, s2);
  Eigen::Matrix3d R04;
  R04.noalias() = DhRotation(c1, s1, -1.0) * DhRotation(c2, s2, 1.0);
  R04 = (R04 * DhRotation(c3, s3, -1.0)).eval();
  const Eigen::Vector3d z4 = R04 * DhRotation(c4, s4, 1.0).col(2);
  const Eigen::Vector3d x_sw = len.d_se * e + len.d_ew * z4;
  const double L = x_sw.norm();
  if (ElbowOnShoulderWristAxis(len, L)) return 0.0;

  // the reference elbow has the same E1 and S3 = 0 (same construction as PrepareArmTarget).
  const ReferenceShoulder ref = MakeReferenceShoulder(len, x_sw, L, s4, c4);
  const Eigen::Vector3d e_ref = UpperArmDirection(ref.c1, ref.s1, ref.c2, ref.s2);
  const Eigen::Vector3d u = x_sw / L;
  // signed angle about u between the projections of e_ref and e on the plane normal to u.
  // Projecting first keeps the digits when the arm is nearly stretched and both are short.
  const Eigen::Vector3d a = e_ref - u.dot(e_ref) * u;
  const Eigen::Vector3d b = e - u.dot(e) * u;
  return Atan2Pi(u.dot(a.cross(b)), a.dot(b));
}

}  // namespace

double ArmAngleOf(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q) {
  // the construction works on DH values (the joint values themselves on the PA-10).
  if (arm.dh_map().identity) return ArmAngleOfDh(arm.lengths(), q);
  return ArmAngleOfDh(arm.lengths(), arm.dh_map().ToDh(q));
}

std::vector<Interval> FeasibleArmAngles(const ArmModel& arm, const ArmTargetForm& form, int gc2,
                                        int gc6) {
  std::vector<Interval> intervals;
  if (form.status != IkStatus::kOk) return intervals;
  if (!InRangeModulo(form.theta4, arm.dh_lower()[3], arm.dh_upper()[3])) return intervals;
  const BranchForms b = MakeBranchForms(form, gc2, gc6);

  // a joint whose range spans 2*pi always has an in-limit equivalent: it never binds.
  std::array<bool, kArmDof> binds;
  for (int j = 0; j < kArmDof; ++j) binds[j] = arm.dh_upper()[j] - arm.dh_lower()[j] < kTwoPi;

  // cut points: every psi where some joint can enter or leave its range.
  std::array<double, 48> cuts;
  int count = 0;
  cuts[count++] = -kPi;
  cuts[count++] = kPi;
  for (int k = 0; k < 2; ++k) {
    const int j = kCosineJoints[k];
    if (!binds[j]) continue;
    for (const double limit : {arm.dh_lower()[j], arm.dh_upper()[j]}) {
      // theta = gc * acos(f) has the branch's sign, so only limits on that side are crossed;
      // limits at 0 or +-pi are only touched at an extreme of f.
      const double t = WrapToPi(limit);
      if (t == 0.0 || std::abs(t) >= kPi || (t > 0.0) != (b.gc[k] > 0.0)) continue;
      AddSinusoidRoots(b.f[k].a, b.f[k].b, b.f[k].c - std::cos(t), &cuts, &count);
    }
  }
  for (int k = 0; k < 4; ++k) {
    const int j = kTangentJoints[k];
    if (!binds[j]) continue;
    const Sinusoid& n = b.num[k];
    const Sinusoid& d = b.den[k];
    for (const double limit : {arm.dh_lower()[j], arm.dh_upper()[j]}) {
      // n cos(t) - d sin(t) = 0 where theta = t or t +- pi; the spurious roots only add cuts.
      const double t = WrapToPi(limit);
      const double ct = std::cos(t);
      const double st = std::sin(t);
      AddSinusoidRoots(n.a * ct - d.a * st, n.b * ct - d.b * st, n.c * ct - d.c * st, &cuts,
                       &count);
    }
    // where numerator and denominator vanish together the joint jumps by pi without crossing
    // a limit; that psi is the double root of d(theta)/d(psi)'s numerator. (It also solves
    // every limit equation above, so this cut only guards against their rounding.)
    const double at = d.b * n.c - n.b * d.c;
    const double bt = n.a * d.c - d.a * n.c;
    const double ctan = n.a * d.b - d.a * n.b;
    const double scale = at * at + bt * bt + ctan * ctan;
    const double disc = at * at + bt * bt - ctan * ctan;
    if (scale > 1e-28 && std::abs(disc) <= kTangentSingularTol * scale && ctan != 0.0) {
      assert(count < static_cast<int>(cuts.size()));
      cuts[count++] = std::atan2(-at * ctan, -bt * ctan);
    }
  }
  std::sort(cuts.begin(), cuts.begin() + count);

  // the joints are continuous between neighbouring cuts, so a midpoint decides each sub-arc.
  bool previous_feasible = false;
  for (int i = 0; i + 1 < count; ++i) {
    const double lo = cuts[i];
    const double hi = cuts[i + 1];
    if (hi - lo <= kTinyArc) continue;
    const bool feasible = BranchFeasibleAt(b, arm, 0.5 * (lo + hi), binds);
    if (feasible) {
      if (previous_feasible) {
        intervals.back().hi = hi;
      } else {
        intervals.push_back({lo, hi});
      }
    }
    previous_feasible = feasible;
  }
  return intervals;
}

std::optional<double> NearestEquivalentAngle(double angle, double reference, double lower,
                                             double upper) {
  double value;
  if (!NearestEquivalentTo(angle, reference, lower, upper, &value)) return std::nullopt;
  return value;
}

std::optional<Vector7d> NearestEquivalent(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q,
                                          const Eigen::Ref<const Vector7d>& q_ref) {
  Vector7d out;
  for (int i = 0; i < kArmDof; ++i) {
    if (!NearestEquivalentTo(q[i], q_ref[i], arm.lower()[i], arm.upper()[i], &out[i])) {
      return std::nullopt;
    }
  }
  return out;
}

std::optional<Interval> WidestInterval(const std::vector<Interval>& intervals) {
  std::optional<Interval> widest;
  for (const Interval& iv : intervals) {
    if (!widest || iv.width() > widest->width()) widest = iv;
  }
  return widest;
}

std::optional<MidArcSolution> SolveArmIkMidArc(const ArmModel& arm, const Eigen::Isometry3d& X_WF,
                                               std::optional<ArmBranch> branch) {
  for (int index = 0; index < 8; ++index) {
    const ArmBranch b = branch ? *branch : ArmBranch::FromIndex(index);
    if (branch && index > 0) break;
    const ArmTargetForm form = PrepareArmTarget(arm, X_WF, b.gc4);
    if (form.status != IkStatus::kOk) continue;
    const std::optional<Interval> widest =
        WidestInterval(FeasibleArmAngles(arm, form, b.gc2, b.gc6));
    if (!widest) continue;
    const double psi = 0.5 * (widest->lo + widest->hi);
    const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, b);
    if (s.status == IkStatus::kOk) return MidArcSolution{s.q, psi, b};
  }
  return std::nullopt;
}

}  // namespace graspsynth
