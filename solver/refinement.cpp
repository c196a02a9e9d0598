#include "solver/refinement.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <nlopt.hpp>
#include <sstream>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"
#include "kinematics/arm_ik.hpp"
#include "motion/joint_space.hpp"

namespace graspsynth {

namespace {

constexpr double kRadToMetre = 0.1;  // weight of a rad of violation against a metre
// a constraint violated by less than this (m) holds: NLopt's constraint tolerance.
constexpr double kFeasibilityTolerance = 1e-5;

using Clock = WallClock;

// Index of the first waypoint where the fingers have started closing (motion size if never).
int FingerStart(const GraspingMotion& m, double threshold) {
  const HandVector& f0 = m.waypoints.front().f;
  for (size_t i = 0; i < m.waypoints.size(); ++i) {
    if ((m.waypoints[i].f - f0).cwiseAbs().maxCoeff() > threshold) return static_cast<int>(i);
  }
  return static_cast<int>(m.waypoints.size());
}

// Up to `count` indices evenly chosen from `from` (sorted).
std::vector<int> Subsample(const std::vector<int>& from, int count) {
  if (static_cast<int>(from.size()) <= count) return from;
  std::vector<int> out;
  for (int k = 0; k < count; ++k) {
    const double u = count == 1 ? 1.0 : static_cast<double>(k) / (count - 1);
    const int i = from[static_cast<size_t>(std::lround(u * (from.size() - 1)))];
    if (out.empty() || out.back() != i) out.push_back(i);
  }
  return out;
}

// The states stage 2 checks: indices of far and near approach states, the grasp (last index,
// with the approach fingers), split by FingerStart.
struct CheckedStates {
  std::vector<int> far, near;
  int approach_end = 0;  // last waypoint before the fingers start closing
};

CheckedStates ChooseStates(const GraspingMotion& m, const RefinementOptions& o) {
  CheckedStates s;
  const int n = static_cast<int>(m.waypoints.size());
  s.approach_end = std::max(0, std::min(n, FingerStart(m, o.finger_start_threshold)) - 1);
  const Eigen::Vector3d p_end = m.waypoints[s.approach_end].p_WH;
  std::vector<int> far, near;
  for (int i = 0; i < s.approach_end; ++i) {
    ((m.waypoints[i].p_WH - p_end).norm() > o.contact_zone ? far : near).push_back(i);
  }
  s.far = Subsample(far, o.approach_states);
  s.near = Subsample(near, o.near_states);
  return s;
}

// Distance of p_W from the handle's axis (clamped to the bar) of object `o` at pose X_WO.
double HandleAxisDistance(const ObjectModel& o, const Eigen::Isometry3d& X_WO,
                          const Eigen::Vector3d& p_W) {
  const HandleAxis& handle = o.Handle("the refinement");
  const Eigen::Vector3d h = o.HandleDirection(X_WO);
  const Eigen::Vector3d a0 =
      X_WO.translation() + (handle.axis_height - o.rest_height) * Eigen::Vector3d::UnitZ();
  const double along = std::clamp((p_W - a0).dot(h), handle.start_radius, handle.end_radius);
  return (a0 + along * h - p_W).norm();
}

// The motion moved by stage 2's variables x = (dx, dy, dz, yaw, closure).
GraspingMotion Transformed(const GraspingMotion& m, const double* x, const HandModel& hand) {
  GraspingMotion out = m;
  const Eigen::Vector3d p_G = m.grasp().p_WH;
  const Eigen::Vector3d d(x[0], x[1], x[2]);
  const Eigen::AngleAxisd turn(x[3], Eigen::Vector3d::UnitZ());
  const HandVector& f0 = m.waypoints.front().f;
  for (MotionWaypoint& w : out.waypoints) {
    w.p_WH = p_G + d + turn * (w.p_WH - p_G);
    w.q_WH = (Eigen::Quaterniond(turn) * w.q_WH).normalized();
    w.f = (f0 + x[4] * (w.f - f0)).cwiseMax(hand.lower()).cwiseMin(hand.upper());
  }
  return out;
}

struct ReachResidual {
  const RobotModel* robot;
  Eigen::Vector3d b;
  Eigen::Isometry3d X;
  ArmBranch branch;
  double min_width, sigma;
  bool operator()(const double* d, double* r) const {
    Eigen::Isometry3d Y = X;
    Y.translation() = b + Eigen::Vector3d(d[0], d[1], d[2]);
    r[0] = std::max(0.0, min_width - WidestArmAngleWidth(*robot, Y, branch)) / sigma;
    return true;
  }
};

struct FidelityResidual {
  double inv_sigma;
  template <typename T>
  bool operator()(const T* d, T* r) const {
    for (int k = 0; k < 3; ++k) r[k] = d[k] * inv_sigma;
    return true;
  }
};

struct SmoothnessResidual {
  double inv_sigma;
  template <typename T>
  bool operator()(const T* a, const T* b, const T* c, T* r) const {
    for (int k = 0; k < 3; ++k) r[k] = (a[k] - 2.0 * b[k] + c[k]) * inv_sigma;
    return true;
  }
};

struct LineResidual {
  Eigen::Vector2d normal;
  double offset;  // normal . (line point + object centre)
  Eigen::Vector2d b;
  double inv_sigma;
  template <typename T>
  bool operator()(const T* d, T* r) const {
    r[0] = (normal.x() * (b.x() + d[0]) + normal.y() * (b.y() + d[1]) - offset) * inv_sigma;
    return true;
  }
};

// What stage 2's callbacks need.
struct NloptContext {
  const RobotModel* robot;
  const SceneModel* scene;
  const CollisionModel* collision;
  const GraspingMotion* base;
  const RefinementInputs* inputs;
  const RefinementOptions* options;
  CollisionData* data;
  int evaluations = 0;
};

// Stage 2's constraints g(x) <= 0 (g[2] in metres: rad times kRadToMetre).
void ConstraintsAt(NloptContext& c, const double* x, double* g) {
  ++c.evaluations;
  const GraspingMotion moved = Transformed(*c.base, x, c.robot->hand);
  const RefinementConstraints v = EvaluateRefinementConstraints(
      *c.robot, *c.scene, *c.collision, moved, *c.inputs, *c.options, c.data);
  g[0] = c.options->clearance_margin - v.approach_clearance;
  g[1] = -c.options->penetration_tolerance - v.grasp_clearance;
  g[2] = kRadToMetre * (c.options->min_psi_width - v.min_psi_width);
  if (c.inputs->handle_in_hand) g[3] = v.contact_error - c.options->contact_tolerance;
}

// The residual blocks of stage 1, by kind.
struct CeresTerms {
  std::vector<ceres::ResidualBlockId> fidelity, smoothness, line, reach;
};

// Adds stage 1's residuals over the corrections `d` (one per waypoint) to `problem`.
CeresTerms AddCeresResiduals(const RobotModel& robot, const GraspingMotion& motion,
                             const RefinementInputs& inputs, const RefinementOptions& options,
                             std::vector<Eigen::Vector3d>* d, ceres::Problem* problem) {
  CeresTerms t;
  const int n = static_cast<int>(motion.waypoints.size());
  for (int i = 0; i < n; ++i) {
    t.fidelity.push_back(
        problem->AddResidualBlock(new ceres::AutoDiffCostFunction<FidelityResidual, 3, 3>(
                                      new FidelityResidual{1.0 / options.fidelity_sigma}),
                                  nullptr, (*d)[i].data()));
  }
  for (int i = 1; i + 1 < n; ++i) {
    t.smoothness.push_back(
        problem->AddResidualBlock(new ceres::AutoDiffCostFunction<SmoothnessResidual, 3, 3, 3, 3>(
                                      new SmoothnessResidual{1.0 / options.smoothness_sigma}),
                                  nullptr, (*d)[i - 1].data(), (*d)[i].data(), (*d)[i + 1].data()));
  }
  if (inputs.wrist_line) {
    const Line2d& l = *inputs.wrist_line;
    const Eigen::Vector2d o = motion.p_WO.head<2>();
    t.line.push_back(problem->AddResidualBlock(
        new ceres::AutoDiffCostFunction<LineResidual, 1, 3>(
            new LineResidual{l.normal(), l.normal().dot(l.point + o), motion.grasp().p_WH.head<2>(),
                             1.0 / options.line_sigma}),
        nullptr, (*d)[n - 1].data()));
  }
  const ArmBranch branch = BranchOf(robot.arm, inputs.q_start);
  for (int i = 0; i < n; i += options.reach_stride) {
    const int k = (i + options.reach_stride >= n) ? n - 1 : i;
    const MotionWaypoint& w = motion.waypoints[k];
    t.reach.push_back(problem->AddResidualBlock(
        new ceres::NumericDiffCostFunction<ReachResidual, ceres::CENTRAL, 1, 3>(new ReachResidual{
            &robot, w.p_WH, WaypointPose(w), branch, options.min_psi_width, options.reach_sigma}),
        nullptr, (*d)[k].data()));
    if (k == n - 1) break;
  }
  return t;
}

// 1/2 the sum of squared residuals of `ids` (0 when there are none).
double TermCost(ceres::Problem& problem, const std::vector<ceres::ResidualBlockId>& ids) {
  if (ids.empty()) return 0.0;
  ceres::Problem::EvaluateOptions eo;
  eo.residual_blocks = ids;
  double cost = 0.0;
  problem.Evaluate(eo, &cost, nullptr, nullptr, nullptr);
  return cost;
}

ceres::Solver::Options CeresSolverOptions(const RefinementOptions& options) {
  ceres::Solver::Options so;
  so.max_num_iterations = options.ceres_max_iterations;
  so.linear_solver_type =
      ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE) ||
              ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)
          ? ceres::SPARSE_NORMAL_CHOLESKY
          : ceres::DENSE_QR;
  if (!ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)) {
    so.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  }
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  so.num_threads = 1;
  return so;
}

// NLopt's callback for stage 2's constraints, with forward-difference gradients.
void NloptConstraints(unsigned mm, double* g, unsigned nn, const double* x, double* grad,
                      void* data) {
  NloptContext& c = *static_cast<NloptContext*>(data);
  ConstraintsAt(c, x, g);
  if (grad) {
    const double steps[5] = {1e-4, 1e-4, 1e-4, 1e-3, 1e-3};
    std::vector<double> xh(x, x + nn), gh(mm);
    for (unsigned j = 0; j < nn; ++j) {
      xh[j] = x[j] + steps[j];
      ConstraintsAt(c, xh.data(), gh.data());
      for (unsigned k = 0; k < mm; ++k) grad[k * nn + j] = (gh[k] - g[k]) / steps[j];
      xh[j] = x[j];
    }
  }
}

// Stage 2's objective: the scaled distance of x from (0, 0, 0, 0, 1).
double NloptObjective(unsigned, const double* x, double* grad, void* data) {
  const RefinementOptions& o = *static_cast<NloptContext*>(data)->options;
  const double ws = 1.0 / (o.shift_scale * o.shift_scale);
  const double wy = 1.0 / (o.yaw_scale * o.yaw_scale);
  const double wc = 1.0 / (o.closure_scale * o.closure_scale);
  if (grad) {
    for (int k = 0; k < 3; ++k) grad[k] = 2.0 * ws * x[k];
    grad[3] = 2.0 * wy * x[3];
    grad[4] = 2.0 * wc * (x[4] - 1.0);
  }
  return ws * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) + wy * x[3] * x[3] +
         wc * (x[4] - 1.0) * (x[4] - 1.0);
}

std::string TerminationText(nlopt::result r) {
  switch (r) {
    case nlopt::SUCCESS:
      return "success";
    case nlopt::FTOL_REACHED:
      return "ftol reached";
    case nlopt::XTOL_REACHED:
      return "xtol reached";
    case nlopt::MAXEVAL_REACHED:
      return "maximum evaluations reached";
    default:
      return "nlopt result " + std::to_string(static_cast<int>(r));
  }
}

// One NLopt run of stage 2 from x = (0, 0, 0, 0, 1).
struct NloptAttempt {
  std::vector<double> x;
  double f = 0.0;
  double violation = INFINITY;
  std::string algorithm, termination;
};

NloptAttempt RunNloptAlgorithm(NloptAlgorithm algorithm, unsigned constraints,
                               const RefinementOptions& options, NloptContext* ctx) {
  NloptAttempt a;
  a.algorithm = ToString(algorithm);
  a.x = {0.0, 0.0, 0.0, 0.0, 1.0};
  const nlopt::algorithm which = algorithm == NloptAlgorithm::kSlsqp ? nlopt::LD_SLSQP
                                 : algorithm == NloptAlgorithm::kMma ? nlopt::LD_MMA
                                                                     : nlopt::LN_COBYLA;
  nlopt::opt opt(which, 5);
  opt.set_lower_bounds({-options.max_shift, -options.max_shift, -options.max_shift,
                        -options.max_yaw, options.min_closure});
  opt.set_upper_bounds({options.max_shift, options.max_shift, options.max_shift, options.max_yaw,
                        options.max_closure});
  opt.set_min_objective(NloptObjective, ctx);
  opt.add_inequality_mconstraint(NloptConstraints, ctx,
                                 std::vector<double>(constraints, 0.5 * kFeasibilityTolerance));
  opt.set_xtol_rel(options.xtol);
  opt.set_maxeval(options.max_evaluations);
  if (algorithm == NloptAlgorithm::kCobyla) {
    opt.set_initial_step({0.01, 0.01, 0.01, 2.0 * kDeg, 0.02});
  }
  try {
    a.termination = TerminationText(opt.optimize(a.x, a.f));
  } catch (const std::exception& e) {
    a.termination = std::string("failed: ") + e.what();
    a.f = NloptObjective(5, a.x.data(), nullptr, ctx);
  }
  std::vector<double> g(constraints);
  ConstraintsAt(*ctx, a.x.data(), g.data());
  a.violation = 0.0;
  for (double v : g) a.violation += std::max(0.0, v);
  return a;
}

}  // namespace

const char* ToString(NloptAlgorithm algorithm) {
  switch (algorithm) {
    case NloptAlgorithm::kSlsqp:
      return "slsqp";
    case NloptAlgorithm::kMma:
      return "mma";
    case NloptAlgorithm::kCobyla:
      return "cobyla";
  }
  return "?";
}

bool RefinementOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  for (double v :
       {fidelity_sigma, smoothness_sigma, line_sigma, reach_sigma, contact_zone, contact_tolerance,
        max_shift, max_yaw, shift_scale, yaw_scale, closure_scale, xtol}) {
    if (!positive(v)) return fail("every sigma, scale, bound and tolerance must be positive");
  }
  if (!(std::isfinite(min_psi_width) && min_psi_width >= 0.0)) {
    return fail("min_psi_width must be >= 0 (rad)");
  }
  if (!std::isfinite(clearance_margin)) return fail("clearance_margin must be finite (m)");
  if (!(std::isfinite(penetration_tolerance) && penetration_tolerance >= 0.0)) {
    return fail("penetration_tolerance must be >= 0 (m)");
  }
  if (!(std::isfinite(finger_start_threshold) && finger_start_threshold > 0.0)) {
    return fail("finger_start_threshold must be positive (rad)");
  }
  if (!(std::isfinite(min_closure) && std::isfinite(max_closure) && min_closure > 0.0 &&
        min_closure <= 1.0 && max_closure >= 1.0)) {
    return fail("the closure bounds must satisfy 0 < min_closure <= 1 <= max_closure");
  }
  if (reach_stride < 1 || ceres_max_iterations < 1 || approach_states < 1 || near_states < 0 ||
      max_evaluations < 1) {
    return fail(
        "reach_stride, ceres_max_iterations, approach_states and max_evaluations must be "
        ">= 1, near_states >= 0");
  }
  return true;
}

RefinementConstraints EvaluateRefinementConstraints(
    const RobotModel& robot, const SceneModel& scene, const CollisionModel& collision,
    const GraspingMotion& motion, const RefinementInputs& inputs, const RefinementOptions& options,
    CollisionData* data) {
  RefinementConstraints c;
  const Eigen::Isometry3d& X_WO = inputs.X_WO;
  c.approach_clearance = std::numeric_limits<double>::infinity();
  c.grasp_clearance = std::numeric_limits<double>::infinity();
  c.reachable = true;
  const CheckedStates s = ChooseStates(motion, options);
  const ArmBranch branch = BranchOf(robot.arm, inputs.q_start);
  double psi = ArmAngleOf(robot.arm, inputs.q_start);
  Vector7d q_near = inputs.q_start;
  SignedDistanceOptions sd;
  sd.max_distance = std::max(0.05, 2.0 * options.clearance_margin);
  sd.epa_tolerance = 1e-4;
  double closest = std::numeric_limits<double>::infinity();
  auto check = [&](const MotionWaypoint& w, const HandVector& f, double* into,
                   double* arm_object = nullptr) {
    ++c.states;
    const std::optional<Vector7d> q =
        SolveWristPose(robot, WaypointPose(w), branch, psi, q_near, 5.0 * kDeg);
    if (!q) {
      c.reachable = false;
      *into = std::min(*into, -0.1);  // unreachable: counts as a deep violation
      return;
    }
    q_near = *q;
    psi = ArmAngleOf(robot.arm, *q);
    SetState(collision, *q, f, X_WO, data);
    const SignedDistanceResult r =
        SignedDistance(collision, GroupSet::Robot(), GroupSet::World(), data, sd);
    *into = std::min(*into, r.distance);
    if (arm_object) {
      *arm_object =
          SignedDistance(collision, CollisionGroup::kArm, CollisionGroup::kObject, data, sd)
              .distance;
    }
    if (r.distance < closest && r.shape_a >= 0) {
      closest = r.distance;
      c.closest_pair = r.BriefReport();
    }
  };
  for (int i : s.far) check(motion.waypoints[i], motion.waypoints[i].f, &c.approach_clearance);
  for (int i : s.near) check(motion.waypoints[i], motion.waypoints[i].f, &c.grasp_clearance);
  check(motion.grasp(), motion.waypoints[s.approach_end].f, &c.grasp_clearance,
        &c.arm_object_clearance);
  c.min_psi_width = std::min(WidestArmAngleWidth(robot, WaypointPose(motion.pregrasp()), branch),
                             WidestArmAngleWidth(robot, WaypointPose(motion.grasp()), branch));
  c.contact_error = std::numeric_limits<double>::quiet_NaN();
  double violation = std::max(0.0, options.clearance_margin - c.approach_clearance) +
                     std::max(0.0, -options.penetration_tolerance - c.grasp_clearance) +
                     kRadToMetre * std::max(0.0, options.min_psi_width - c.min_psi_width);
  if (inputs.handle_in_hand) {
    const Eigen::Vector3d p = WaypointPose(motion.grasp()) * *inputs.handle_in_hand;
    c.contact_error = HandleAxisDistance(scene.object, X_WO, p);
    violation += std::max(0.0, c.contact_error - options.contact_tolerance);
  }
  c.violation = violation;
  c.feasible = c.reachable && violation <= kFeasibilityTolerance;
  return c;
}

std::string RefinementReport::BriefReport() const {
  std::ostringstream s;
  auto constraints = [&](const RefinementConstraints& c) {
    s << "clearance " << c.approach_clearance << " m, grasp " << c.grasp_clearance
      << " m, psi width " << c.min_psi_width / kDeg << " deg";
    if (std::isfinite(c.contact_error)) s << ", contact error " << c.contact_error << " m";
    s << (c.feasible ? " (feasible)" : " (infeasible)");
  };
  s << "before: ";
  constraints(before);
  s << "; after: ";
  constraints(after);
  if (ceres.run) {
    s << "; ceres " << ceres.initial_cost << " -> " << ceres.final_cost << " in "
      << ceres.iterations << " iterations (" << ceres.termination << ")";
  }
  s << "; nlopt " << (nlopt.run ? nlopt.algorithm + " " : std::string()) << nlopt.termination;
  if (nlopt.run) s << ", " << nlopt.evaluations << " evaluations";
  s << "; kept " << ToString(kept) << ", " << time_s * 1e3 << " ms";
  return s.str();
}

const char* ToString(RefinementStage stage) {
  switch (stage) {
    case RefinementStage::kInput:
      return "input";
    case RefinementStage::kCeres:
      return "ceres";
    case RefinementStage::kNlopt:
      return "nlopt";
  }
  return "?";
}

RefinementOptions ThresholdsFromSources(const RefinementOptions& options,
                                        const std::vector<RefinementConstraints>& sources) {
  RefinementOptions ro = options;
  for (const RefinementConstraints& c : sources) {
    ro.clearance_margin = std::min(ro.clearance_margin, c.approach_clearance);
    ro.penetration_tolerance = std::max(ro.penetration_tolerance, -c.grasp_clearance);
    if (std::isfinite(c.contact_error)) {
      ro.contact_tolerance = std::max(ro.contact_tolerance, c.contact_error);
    }
  }
  return ro;
}

CeresStageResult RunCeresStage(const RobotModel& robot, const GraspingMotion& motion,
                               const RefinementInputs& inputs, const RefinementOptions& options) {
  const auto t0 = Clock::now();
  CeresStageResult result;
  CeresStageReport& cr = result.report;
  cr.run = true;
  const int n = static_cast<int>(motion.waypoints.size());
  std::vector<Eigen::Vector3d> d(static_cast<size_t>(n), Eigen::Vector3d::Zero());
  ceres::Problem::Options po;
  ceres::Problem problem(po);
  const CeresTerms terms = AddCeresResiduals(robot, motion, inputs, options, &d, &problem);
  cr.initial_reach = TermCost(problem, terms.reach);
  ceres::Solver::Summary summary;
  ceres::Solve(CeresSolverOptions(options), &problem, &summary);
  cr.initial_cost = summary.initial_cost;
  cr.final_cost = summary.final_cost;
  cr.iterations = static_cast<int>(summary.iterations.size()) - 1;
  cr.termination = ceres::TerminationTypeToString(summary.termination_type);
  cr.fidelity = TermCost(problem, terms.fidelity);
  cr.smoothness = TermCost(problem, terms.smoothness);
  cr.line = TermCost(problem, terms.line);
  cr.reach = TermCost(problem, terms.reach);
  result.motion = motion;
  result.usable = summary.IsSolutionUsable();
  if (result.usable) {
    for (int i = 0; i < n; ++i) result.motion.waypoints[i].p_WH += d[i];
  }
  cr.time_s = SecondsSince(t0);
  return result;
}

NloptStageResult RunNloptStage(const RobotModel& robot, const SceneModel& scene,
                               const CollisionModel& collision, const GraspingMotion& motion,
                               const RefinementInputs& inputs, const RefinementOptions& options,
                               CollisionData* data) {
  const auto t0 = Clock::now();
  NloptStageResult result;
  NloptStageReport& nr = result.report;
  nr.run = true;
  const unsigned m = inputs.handle_in_hand.has_value() ? 4 : 3;
  NloptContext ctx{&robot, &scene, &collision, &motion, &inputs, &options, data};
  nr.initial_objective = 0.0;
  NloptAttempt best = RunNloptAlgorithm(options.algorithm, m, options, &ctx);
  if (best.violation > kFeasibilityTolerance && options.cobyla_fallback &&
      options.algorithm != NloptAlgorithm::kCobyla) {
    NloptAttempt second = RunNloptAlgorithm(NloptAlgorithm::kCobyla, m, options, &ctx);
    nr.fallback_used = true;
    second.termination += " (fallback after " + best.algorithm + ": " + best.termination + ")";
    if (second.violation < best.violation - 1e-9 ||
        (second.violation <= kFeasibilityTolerance && second.f < best.f)) {
      best = second;
    } else {
      best.termination += " (the cobyla fallback did no better)";
    }
  }
  nr.algorithm = best.algorithm;
  nr.termination = best.termination;
  nr.evaluations = ctx.evaluations;
  nr.final_objective = best.f;
  nr.shift = Eigen::Vector3d(best.x[0], best.x[1], best.x[2]);
  nr.yaw = best.x[3];
  nr.closure = best.x[4];
  result.motion = Transformed(motion, best.x.data(), robot.hand);
  result.constraints =
      EvaluateRefinementConstraints(robot, scene, collision, result.motion, inputs, options, data);
  nr.time_s = SecondsSince(t0);
  return result;
}

bool IsValidRefinementStages(const RefinementStages& stages, std::string* why) {
  RefinementStage last = RefinementStage::kInput;
  for (RefinementStage stage : stages) {
    if (stage == RefinementStage::kInput || stage <= last) {
      if (why) *why = "the refinement stages must be ceres, then nlopt, each at most once";
      return false;
    }
    last = stage;
  }
  return true;
}

RefinementResult RefineGraspingMotion(const RobotModel& robot, const SceneModel& scene,
                                      const CollisionModel& collision, const GraspingMotion& motion,
                                      const RefinementInputs& inputs,
                                      const RefinementOptions& options, CollisionData* data,
                                      const RefinementStages& stages) {
  RequireValid(options, "invalid refinement option");
  std::string why;
  if (!IsValidRefinementStages(stages, &why)) throw InputError("invalid refinement: " + why);
  const auto t_start = Clock::now();
  RefinementResult result;
  RefinementReport& rep = result.report;
  rep.before =
      EvaluateRefinementConstraints(robot, scene, collision, motion, inputs, options, data);
  GraspingMotion current = motion;
  RefinementConstraints current_c = rep.before;
  rep.kept = RefinementStage::kInput;
  rep.after_ceres = rep.before;
  rep.nlopt.termination = "not run (disabled)";
  for (RefinementStage stage : stages) {
    if (stage == RefinementStage::kCeres) {
      // stage 1: ceres over the waypoint positions; kept unless it adds violation.
      CeresStageResult stage1 = RunCeresStage(robot, motion, inputs, options);
      rep.ceres = stage1.report;
      rep.after_ceres = EvaluateRefinementConstraints(robot, scene, collision, stage1.motion,
                                                      inputs, options, data);
      if (stage1.usable && rep.after_ceres.violation <= current_c.violation + 1e-9) {
        current = std::move(stage1.motion);
        current_c = rep.after_ceres;
        rep.kept = RefinementStage::kCeres;
      }
    } else if (current_c.feasible) {
      // stage 2: nlopt on the grasp pose and the closure, only when infeasible.
      rep.nlopt.termination = "not run (the start satisfies every constraint)";
    } else {
      NloptStageResult stage2 =
          RunNloptStage(robot, scene, collision, current, inputs, options, data);
      rep.nlopt = stage2.report;
      if (stage2.constraints.violation <= current_c.violation + 1e-9) {
        current = std::move(stage2.motion);
        current_c = stage2.constraints;
        rep.kept = RefinementStage::kNlopt;
      }
    }
  }
  rep.after = current_c;
  rep.time_s = SecondsSince(t_start);
  result.motion = std::move(current);
  return result;
}

}  // namespace graspsynth
