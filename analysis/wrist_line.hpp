#pragma once

/// @file
/// The operator's wrist-positioning strategy (paper section III-D, Fig. 8): a straight line fitted
/// to the grasp positions in the object-centred table plane, and the alternative a reader might
/// expect, the radial strategy (the wrist turning with the handle about the object centre).
///
/// All positions are object-centred table-plane positions: world x and y axes, origin at the
/// object centre, metres. Angles are radians (degrees only in reports).

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

namespace graspsynth {

/// A line in the plane: `point` on it and a unit `direction`.
struct Line2d {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();       ///< m
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();  ///< unit

  /// The unit normal, `direction` turned by +90 deg.
  Eigen::Vector2d normal() const { return {-direction.y(), direction.x()}; }
  /// Angle of `direction` from +x, radians in [-pi, pi].
  double angle() const;
  /// Signed distance of the line from the origin along normal(), m.
  double offset() const { return normal().dot(point); }
  /// Distance of `p` from the line, m.
  double Distance(const Eigen::Vector2d& p) const { return std::abs(normal().dot(p - point)); }
};

/// Residuals of a model at each point, m.
struct FitResiduals {
  std::vector<double> per_point;  ///< |residual| of each point, m, in input order
  double rms = 0.0;               ///< root mean square, m (0 when there are no points)
  double max = 0.0;               ///< largest, m
};

/// Orthogonal distances of `points` from `line`.
FitResiduals LineResiduals(const Line2d& line, const std::vector<Eigen::Vector2d>& points);

/// How far apart two lines are, as undirected lines.
struct LineDifference {
  double angle = 0.0;   ///< angle between them, radians in [0, pi/2]
  double offset = 0.0;  ///< difference of their signed distances from the origin (normals
                        ///< aligned), m
};

/// The difference between lines `a` and `b`.
LineDifference CompareLines(const Line2d& a, const Line2d& b);

/// Robust loss of the line fit: rho applied to the squared orthogonal distance.
enum class LineLoss {
  kNone,    ///< plain total least squares
  kHuber,   ///< Huber: quadratic up to loss_scale, linear beyond
  kCauchy,  ///< Cauchy: log(1 + (r / loss_scale)^2), redescending
};

/// "none", "huber" or "cauchy".
const char* ToString(LineLoss loss);

/// Inputs of FitWristLine().
struct WristLineOptions {
  LineLoss loss = LineLoss::kNone;  ///< robust loss of the main fit
  double loss_scale = 0.01;         ///< m: residual at which the robust loss turns over
  int max_iterations = 200;         ///< Ceres iterations per solve
  /// The Ceres plain fit and the CGAL fit agree when their lines differ by at most these.
  double cgal_angle_tolerance = 1e-6;   ///< rad
  double cgal_offset_tolerance = 1e-6;  ///< m

  /// True when loss_scale, the tolerances are finite and > 0 and max_iterations > 0.
  bool IsValid(std::string* why) const;
};

/// How the wrist-line fit ended.
enum class WristLineTermination {
  kConverged,         ///< Ceres converged
  kNoConvergence,     ///< iteration limit reached; the line is usable but may not be optimal
  kFailed,            ///< Ceres failed; no line
  kInsufficientData,  ///< fewer than two distinct points; no line
};

/// "converged", "no convergence", "failed" or "insufficient data".
const char* ToString(WristLineTermination termination);

/// The wrist line and its cross-check.
struct WristLineResult {
  WristLineTermination termination = WristLineTermination::kInsufficientData;
  std::string message;  ///< what happened, in words
  LineLoss loss = LineLoss::kNone;
  double loss_scale = 0.0;  ///< m

  /// The fitted line (Ceres, total least squares with `loss`). `point` is the projection of the
  /// points' centroid; `direction` points from the first input point's side to the last's (the
  /// points' input order, e.g. increasing object orientation).
  Line2d line;
  FitResiduals residuals;   ///< orthogonal distances of every point from `line`, m
  double final_cost = 0.0;  ///< Ceres cost (1/2 sum rho(r^2)) of `line`

  /// The Ceres fit without a robust loss (the same as `line` when loss is kNone).
  Line2d plain_line;
  FitResiduals plain_residuals;
  /// CGAL::linear_least_squares_fitting_2 on the same points, the cross-check of plain_line.
  Line2d cgal_line;
  FitResiduals cgal_residuals;
  LineDifference cgal_difference;  ///< plain_line against cgal_line
  bool cgal_agrees = false;        ///< cgal_difference within the options' tolerances
  int iterations = 0;              ///< Ceres iterations, all solves together

  /// True when `line` holds a fitted line (converged or not).
  bool usable() const {
    return termination == WristLineTermination::kConverged ||
           termination == WristLineTermination::kNoConvergence;
  }
  /// One line: termination, angle, offset, residuals and the CGAL difference.
  std::string BriefReport() const;
};

/// Fits a line to `points` (object-centred, m) by total least squares with Ceres: parameters
/// the normal angle a and the offset c, residual r_i = (cos a, sin a) . p_i - c (the orthogonal
/// distance). The plain fit starts from the chord through the two points farthest apart; the
/// robust fit starts from the plain fit and from the line through every pair of points (up to
/// 300 points are paired), the start with the least robust cost first, and keeps the solve of
/// least cost. The plain fit is cross-checked against CGAL's least-squares line. Too few points
/// is a result (kInsufficientData), not an exception. Aborts (GS_DEMAND) when `options` is not
/// valid or a point is not finite.
WristLineResult FitWristLine(const std::vector<Eigen::Vector2d>& points,
                             const WristLineOptions& options);

/// The radial strategy: the wrist keeps its distance and turns with the object,
/// p(theta) = d (cos(theta + c), sin(theta + c)).
struct RadialModelResult {
  bool valid = false;      ///< false when there are no points
  std::string message;     ///< what happened, in words
  double d = 0.0;          ///< m
  double c = 0.0;          ///< rad, eta = theta + c, in [-pi, pi]
  FitResiduals residuals;  ///< |p_i - p(theta_i)| of every point, m
};

/// Fits the radial model to positions `points` (object-centred, m) observed at object
/// orientations `theta` (rad), minimizing the sum of squared position errors. Closed form: with
/// S = sum_i (x_i + i y_i) exp(-i theta_i), c = arg S and d = |S| / n. Aborts (GS_DEMAND) when
/// the sizes differ.
RadialModelResult FitRadialModel(const std::vector<double>& theta,
                                 const std::vector<Eigen::Vector2d>& points);

/// The spread of the positions' polar angle against the spread of the object's orientation.
struct AngularRanges {
  double position_eta = 0.0;  ///< max - min eta of the points, rad (about their mean direction)
  double object_theta = 0.0;  ///< max - min theta, rad
};

/// The angular ranges of `points` (object-centred, m) and `theta` (rad); zero when empty.
AngularRanges ComputeAngularRanges(const std::vector<double>& theta,
                                   const std::vector<Eigen::Vector2d>& points);

}  // namespace graspsynth
