#include "analysis/wrist_line.hpp"

#include <CGAL/Dimension.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/linear_least_squares_fitting_2.h>
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <sstream>
#include <tuple>

#include "common/demand.hpp"
#include "common/format.hpp"
#include "common/valid_options.hpp"
#include "kinematics/types.hpp"

namespace graspsynth {
namespace {

// Orthogonal distance of one point from the line {p : (cos a, sin a) . p = c}.
struct LineDistanceResidual {
  explicit LineDistanceResidual(const Eigen::Vector2d& p) : x(p.x()), y(p.y()) {}
  template <typename T>
  bool operator()(const T* const a, const T* const c, T* residual) const {
    using std::cos;
    using std::sin;
    residual[0] = cos(a[0]) * x + sin(a[0]) * y - c[0];
    return true;
  }
  double x, y;
};

// A line as normal angle a and offset c.
struct NormalForm {
  double a = 0.0;
  double c = 0.0;
};

NormalForm ThroughPoints(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const Eigen::Vector2d d = q - p;
  NormalForm line;
  line.a = std::atan2(d.y(), d.x()) + 0.5 * M_PI;
  line.c = std::cos(line.a) * p.x() + std::sin(line.a) * p.y();
  return line;
}

std::unique_ptr<ceres::LossFunction> MakeLoss(LineLoss loss, double scale) {
  switch (loss) {
    case LineLoss::kHuber:
      return std::make_unique<ceres::HuberLoss>(scale);
    case LineLoss::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(scale);
    case LineLoss::kNone:
      break;
  }
  return nullptr;
}

// 1/2 sum rho(r_i^2) of the line (the Ceres cost), with rho(s) = s when `loss` is null.
double Cost(const NormalForm& line, const std::vector<Eigen::Vector2d>& points,
            const ceres::LossFunction* loss) {
  double cost = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const double r = std::cos(line.a) * p.x() + std::sin(line.a) * p.y() - line.c;
    double rho[3] = {r * r, 1.0, 0.0};
    if (loss) loss->Evaluate(r * r, rho);
    cost += 0.5 * rho[0];
  }
  return cost;
}

struct SolveOutcome {
  NormalForm line;
  double cost = 0.0;
  ceres::TerminationType termination = ceres::FAILURE;
  int iterations = 0;
};

SolveOutcome SolveLine(const std::vector<Eigen::Vector2d>& points, NormalForm start, LineLoss loss,
                       const WristLineOptions& options) {
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  const std::unique_ptr<ceres::LossFunction> rho = MakeLoss(loss, options.loss_scale);
  SolveOutcome out;
  out.line = start;
  for (const Eigen::Vector2d& p : points) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<LineDistanceResidual, 1, 1, 1>(new LineDistanceResidual(p)),
        rho.get(), &out.line.a, &out.line.c);
  }
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.function_tolerance = 1e-15;
  solver_options.gradient_tolerance = 1e-15;
  solver_options.parameter_tolerance = 1e-15;
  solver_options.logging_type = ceres::SILENT;
  solver_options.minimizer_progress_to_stdout = false;
  solver_options.num_threads = 1;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  out.termination = summary.termination_type;
  out.cost = summary.final_cost;
  out.iterations = static_cast<int>(summary.iterations.size());
  return out;
}

// The line in point-direction form: `point` the projection of the centroid, `direction`
// oriented from the first point toward the last.
Line2d ToLine2d(const NormalForm& f, const std::vector<Eigen::Vector2d>& points) {
  Line2d line;
  const Eigen::Vector2d n(std::cos(f.a), std::sin(f.a));
  line.direction = Eigen::Vector2d(n.y(), -n.x());
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  line.point = centroid - (n.dot(centroid) - f.c) * n;
  const Eigen::Vector2d span = points.back() - points.front();
  const double along = span.dot(line.direction);
  if (along < 0.0 || (along == 0.0 && line.direction.x() < 0.0)) line.direction = -line.direction;
  return line;
}

Line2d FitWithCgal(const std::vector<Eigen::Vector2d>& points) {
  using Kernel = CGAL::Simple_cartesian<double>;
  std::vector<Kernel::Point_2> cgal_points;
  cgal_points.reserve(points.size());
  for (const Eigen::Vector2d& p : points) cgal_points.emplace_back(p.x(), p.y());
  Kernel::Line_2 cgal_line;
  Kernel::Point_2 centroid;
  CGAL::linear_least_squares_fitting_2(cgal_points.begin(), cgal_points.end(), cgal_line, centroid,
                                       CGAL::Dimension_tag<0>());
  const Kernel::Vector_2 v = cgal_line.to_vector();
  const Eigen::Vector2d direction = Eigen::Vector2d(v.x(), v.y()).normalized();
  const Eigen::Vector2d point(centroid.x(), centroid.y());
  // re-express in normal form so that the point and orientation rules match the Ceres lines.
  NormalForm f;
  f.a = std::atan2(direction.y(), direction.x()) + 0.5 * M_PI;
  f.c = std::cos(f.a) * point.x() + std::sin(f.a) * point.y();
  return ToLine2d(f, points);
}

WristLineTermination FromCeres(ceres::TerminationType t) {
  switch (t) {
    case ceres::CONVERGENCE:
      return WristLineTermination::kConverged;
    case ceres::NO_CONVERGENCE:
      return WristLineTermination::kNoConvergence;
    default:
      return WristLineTermination::kFailed;
  }
}

}  // namespace

double Line2d::angle() const { return std::atan2(direction.y(), direction.x()); }

FitResiduals LineResiduals(const Line2d& line, const std::vector<Eigen::Vector2d>& points) {
  FitResiduals r;
  double sum = 0.0;
  for (const Eigen::Vector2d& p : points) {
    const double e = line.Distance(p);
    r.per_point.push_back(e);
    sum += e * e;
    r.max = std::max(r.max, e);
  }
  if (!points.empty()) r.rms = std::sqrt(sum / static_cast<double>(points.size()));
  return r;
}

LineDifference CompareLines(const Line2d& a, const Line2d& b) {
  LineDifference diff;
  const double dot = a.direction.dot(b.direction);
  const double cross = a.direction.x() * b.direction.y() - a.direction.y() * b.direction.x();
  diff.angle = std::atan2(std::abs(cross), std::abs(dot));
  const double sign = a.normal().dot(b.normal()) < 0.0 ? -1.0 : 1.0;
  diff.offset = std::abs(a.offset() - sign * b.offset());
  return diff;
}

const char* ToString(LineLoss loss) {
  switch (loss) {
    case LineLoss::kNone:
      return "none";
    case LineLoss::kHuber:
      return "huber";
    case LineLoss::kCauchy:
      return "cauchy";
  }
  return "unknown";
}

const char* ToString(WristLineTermination termination) {
  switch (termination) {
    case WristLineTermination::kConverged:
      return "converged";
    case WristLineTermination::kNoConvergence:
      return "no convergence";
    case WristLineTermination::kFailed:
      return "failed";
    case WristLineTermination::kInsufficientData:
      return "insufficient data";
  }
  return "unknown";
}

bool WristLineOptions::IsValid(std::string* why) const {
  const auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (!(std::isfinite(loss_scale) && loss_scale > 0.0)) {
    return fail("loss_scale must be finite and > 0 m, got " + StreamNumber(loss_scale));
  }
  if (max_iterations <= 0) return fail("max_iterations must be > 0");
  if (!(std::isfinite(cgal_angle_tolerance) && cgal_angle_tolerance > 0.0) ||
      !(std::isfinite(cgal_offset_tolerance) && cgal_offset_tolerance > 0.0)) {
    return fail("the CGAL agreement tolerances must be finite and > 0");
  }
  return true;
}

std::string WristLineResult::BriefReport() const {
  std::ostringstream text;
  text.precision(6);
  text << "wrist line: " << ToString(termination);
  if (!usable()) {
    text << " (" << message << ")";
    return text.str();
  }
  text << ", loss " << ToString(loss) << ", angle " << Degrees(line.angle()) << " deg, offset "
       << line.offset() << " m, rms " << residuals.rms << " m, max " << residuals.max << " m; CGAL "
       << (cgal_agrees ? "agrees" : "DISAGREES") << " (angle " << cgal_difference.angle
       << " rad, offset " << cgal_difference.offset << " m)";
  return text.str();
}

namespace {

// The two points farthest apart (indices) and their squared distance (0 when fewer than two
// distinct points).
std::tuple<size_t, size_t, double> FarthestPair(const std::vector<Eigen::Vector2d>& points) {
  size_t far_i = 0, far_j = 0;
  double far_d = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    for (size_t j = i + 1; j < points.size(); ++j) {
      const double d = (points[j] - points[i]).squaredNorm();
      if (d > far_d) {
        far_d = d;
        far_i = i;
        far_j = j;
      }
    }
  }
  return {far_i, far_j, far_d};
}

// The start of the robust fit: of the plain fit and the lines through pairs of (at most 300
// evenly spaced) points, the one of least robust cost.
NormalForm RobustStart(const std::vector<Eigen::Vector2d>& points, const NormalForm& plain,
                       const WristLineOptions& options) {
  const std::unique_ptr<ceres::LossFunction> rho = MakeLoss(options.loss, options.loss_scale);
  const size_t paired = std::min<size_t>(points.size(), 300);
  const size_t step = (points.size() + paired - 1) / paired;
  NormalForm best = plain;
  double best_cost = Cost(plain, points, rho.get());
  for (size_t i = 0; i < points.size(); i += step) {
    for (size_t j = i + step; j < points.size(); j += step) {
      if ((points[j] - points[i]).squaredNorm() == 0.0) continue;
      const NormalForm candidate = ThroughPoints(points[i], points[j]);
      const double cost = Cost(candidate, points, rho.get());
      if (cost < best_cost) {
        best_cost = cost;
        best = candidate;
      }
    }
  }
  return best;
}

}  // namespace

WristLineResult FitWristLine(const std::vector<Eigen::Vector2d>& points,
                             const WristLineOptions& options) {
  RequireValid(options, "invalid wrist-line options");
  for (const Eigen::Vector2d& p : points) {
    GS_DEMAND(p.allFinite(), "FitWristLine: a point is not finite");
  }
  WristLineResult result;
  result.loss = options.loss;
  result.loss_scale = options.loss_scale;

  // the two points farthest apart: the plain fit's start, and a check for coincident points.
  const auto [far_i, far_j, far_d] = FarthestPair(points);
  if (points.size() < 2 || far_d == 0.0) {
    result.termination = WristLineTermination::kInsufficientData;
    result.message = "a line needs at least two distinct points, got " +
                     std::to_string(points.size()) + " point(s)" +
                     (points.size() >= 2 ? ", all at the same place" : "");
    return result;
  }

  const SolveOutcome plain =
      SolveLine(points, ThroughPoints(points[far_i], points[far_j]), LineLoss::kNone, options);
  result.iterations = plain.iterations;
  SolveOutcome main = plain;
  if (options.loss != LineLoss::kNone) {
    // the robust cost has local minima; start from the best of many candidate lines.
    main = SolveLine(points, RobustStart(points, plain.line, options), options.loss, options);
    const SolveOutcome from_plain = SolveLine(points, plain.line, options.loss, options);
    result.iterations += main.iterations + from_plain.iterations;
    const bool main_failed = main.termination == ceres::FAILURE;
    if (from_plain.termination != ceres::FAILURE && (main_failed || from_plain.cost < main.cost)) {
      main = from_plain;
    }
  }

  result.termination = FromCeres(main.termination);
  if (plain.termination == ceres::FAILURE) result.termination = WristLineTermination::kFailed;
  if (!result.usable()) {
    result.message = "the Ceres solve failed";
    return result;
  }
  result.message =
      std::string("Ceres ") +
      (result.termination == WristLineTermination::kConverged ? "converged"
                                                              : "reached the iteration limit") +
      " on " + std::to_string(points.size()) + " points";
  result.line = ToLine2d(main.line, points);
  result.residuals = LineResiduals(result.line, points);
  result.final_cost = main.cost;
  result.plain_line = ToLine2d(plain.line, points);
  result.plain_residuals = LineResiduals(result.plain_line, points);
  result.cgal_line = FitWithCgal(points);
  result.cgal_residuals = LineResiduals(result.cgal_line, points);
  result.cgal_difference = CompareLines(result.plain_line, result.cgal_line);
  result.cgal_agrees = result.cgal_difference.angle <= options.cgal_angle_tolerance &&
                       result.cgal_difference.offset <= options.cgal_offset_tolerance;
  return result;
}

RadialModelResult FitRadialModel(const std::vector<double>& theta,
                                 const std::vector<Eigen::Vector2d>& points) {
  GS_DEMAND(theta.size() == points.size(), "FitRadialModel: one theta per point");
  RadialModelResult result;
  if (points.empty()) {
    result.message = "no points";
    return result;
  }
  // sum |p_i - d u(theta_i + c)|^2 = sum |p_i|^2 - 2 d Re(S e^{-ic}) + n d^2, minimal at
  // c = arg S, d = |S| / n.
  std::complex<double> s = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    s += std::complex<double>(points[i].x(), points[i].y()) * std::polar(1.0, -theta[i]);
  }
  const double n = static_cast<double>(points.size());
  result.valid = true;
  result.d = std::abs(s) / n;
  result.c = std::abs(s) > 0.0 ? std::arg(s) : 0.0;
  result.message = "least-squares radial model on " + std::to_string(points.size()) + " points";
  double sum = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double eta = theta[i] + result.c;
    const Eigen::Vector2d model = result.d * Eigen::Vector2d(std::cos(eta), std::sin(eta));
    const double e = (points[i] - model).norm();
    result.residuals.per_point.push_back(e);
    result.residuals.max = std::max(result.residuals.max, e);
    sum += e * e;
  }
  result.residuals.rms = std::sqrt(sum / n);
  return result;
}

AngularRanges ComputeAngularRanges(const std::vector<double>& theta,
                                   const std::vector<Eigen::Vector2d>& points) {
  AngularRanges ranges;
  if (!theta.empty()) {
    const auto [lo, hi] = std::minmax_element(theta.begin(), theta.end());
    ranges.object_theta = *hi - *lo;
  }
  if (!points.empty()) {
    // angles about the mean direction, so that a set straddling +-180 deg does not wrap.
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& p : points) mean += p.normalized();
    const double centre = std::atan2(mean.y(), mean.x());
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Eigen::Vector2d& p : points) {
      const double eta = std::remainder(std::atan2(p.y(), p.x()) - centre, 2.0 * M_PI);
      lo = std::min(lo, eta);
      hi = std::max(hi, eta);
    }
    ranges.position_eta = hi - lo;
  }
  return ranges;
}

}  // namespace graspsynth
