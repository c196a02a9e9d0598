#include "analysis/placement_line.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>

#include <Eigen/SVD>

#include "kinematics/types.hpp"

namespace graspsynth {
namespace {

constexpr double kPositionTolerance = 5e-3;  // m: one position (the simulated object settles)
constexpr double kThetaTolerance = 1e-6;     // rad: one orientation

// Observed minus fitted wrist offset of one sample: r - (b + a_x dx + a_y dy + a_theta theta).
struct AffineResidual {
  AffineResidual(const Eigen::Vector3d& features, const Eigen::Vector3d& wrist)
      : f(features), r(wrist) {}
  template <typename T>
  bool operator()(const T* b, const T* a_x, const T* a_y, const T* a_theta, T* out) const {
    for (int k = 0; k < 3; ++k) {
      out[k] = T(r[k]) - (b[k] + a_x[k] * f[0] + a_y[k] * f[1] + a_theta[k] * f[2]);
    }
    return true;
  }
  Eigen::Vector3d f;  // (x - x_ref, y - y_ref, theta)
  Eigen::Vector3d r;
};

std::unique_ptr<ceres::LossFunction> MakeLoss(LineLoss loss, double scale) {
  if (loss == LineLoss::kHuber) return std::make_unique<ceres::HuberLoss>(scale);
  if (loss == LineLoss::kCauchy) return std::make_unique<ceres::CauchyLoss>(scale);
  return nullptr;
}

// The number of independent columns of the design matrix [1, dx, dy, theta] (`with_position`)
// or [1, theta], each column scaled to unit length first.
int DesignRank(const std::vector<Eigen::Vector3d>& features, bool with_position) {
  const int n = static_cast<int>(features.size());
  Eigen::MatrixXd m(n, with_position ? 4 : 2);
  for (int i = 0; i < n; ++i) {
    if (with_position) {
      m.row(i) << 1.0, features[i][0], features[i][1], features[i][2];
    } else {
      m.row(i) << 1.0, features[i][2];
    }
  }
  for (int c = 0; c < m.cols(); ++c) {
    const double norm = m.col(c).norm();
    if (norm > 0.0) m.col(c) /= norm;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(m);
  svd.setThreshold(1e-9);
  return static_cast<int>(svd.rank());
}

PlacementLineResiduals Residuals(const std::vector<Eigen::Vector3d>& features,
                                 const std::vector<PlacementLineSample>& samples,
                                 const PlacementLineFit& fit) {
  PlacementLineResiduals out;
  double sum_xy = 0.0, sum_z = 0.0;
  for (size_t i = 0; i < samples.size(); ++i) {
    const Eigen::Vector3d& f = features[i];
    const Eigen::Vector3d e =
        samples[i].wrist - (fit.b + fit.a_x * f[0] + fit.a_y * f[1] + fit.a_theta * f[2]);
    out.per_sample.push_back(e);
    const double xy = e.head<2>().norm();
    sum_xy += xy * xy;
    sum_z += e.z() * e.z();
    out.max_xy = std::max(out.max_xy, xy);
  }
  const double n = static_cast<double>(samples.size());
  out.rms_xy = std::sqrt(sum_xy / n);
  out.rms_z = std::sqrt(sum_z / n);
  return out;
}

// Fits b, a_x, a_y, a_theta of `fit` in place (a_x, a_y held at zero unless `with_position`).
int Solve(const std::vector<Eigen::Vector3d>& features,
          const std::vector<PlacementLineSample>& samples, const WristLineOptions& options,
          bool with_position, PlacementLineFit* fit) {
  ceres::Problem::Options problem_options;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  const std::unique_ptr<ceres::LossFunction> rho = MakeLoss(options.loss, options.loss_scale);
  for (size_t i = 0; i < samples.size(); ++i) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AffineResidual, 3, 3, 3, 3, 3>(
                                 new AffineResidual(features[i], samples[i].wrist)),
                             rho.get(), fit->b.data(), fit->a_x.data(), fit->a_y.data(),
                             fit->a_theta.data());
  }
  if (!with_position) {
    problem.SetParameterBlockConstant(fit->a_x.data());
    problem.SetParameterBlockConstant(fit->a_y.data());
  }
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);
  return static_cast<int>(summary.iterations.size());
}

}  // namespace

std::vector<PlacementLineSample> MeanPerPlacement(const std::vector<PlacementLineSample>& samples) {
  // a group is known by its first sample's placement; the sums are divided at the end
  std::vector<Eigen::Vector3d> keys;
  std::vector<PlacementLineSample> means;
  for (const PlacementLineSample& s : samples) {
    size_t g = 0;
    while (g < keys.size() &&
           ((keys[g].head<2>() - s.placement.head<2>()).norm() > kPositionTolerance ||
            std::abs(keys[g].z() - s.placement.z()) > kThetaTolerance)) {
      ++g;
    }
    if (g == keys.size()) {
      keys.push_back(s.placement);
      means.push_back(s);
      means.back().trials = 1;
      continue;
    }
    means[g].wrist += s.wrist;
    means[g].placement += s.placement;
    means[g].trials += 1;
  }
  for (PlacementLineSample& m : means) {
    m.wrist /= m.trials;
    m.placement /= m.trials;
  }
  return means;
}

PlacementLineFit FitPlacementLine(const std::vector<PlacementLineSample>& samples,
                                  const WristLineOptions& options) {
  PlacementLineFit fit;
  fit.samples = static_cast<int>(samples.size());
  std::vector<Eigen::Vector2d> positions;
  for (const PlacementLineSample& s : samples) {
    fit.reference += s.placement.head<2>();
    bool known = false;
    for (const Eigen::Vector2d& p : positions) {
      known = known || (p - s.placement.head<2>()).norm() <= kPositionTolerance;
    }
    if (!known) positions.push_back(s.placement.head<2>());
  }
  fit.positions = static_cast<int>(positions.size());
  if (samples.empty()) {
    fit.message = "no successful, segmented grasps to fit";
    return fit;
  }
  fit.reference /= static_cast<double>(samples.size());
  std::vector<Eigen::Vector3d> features;
  for (const PlacementLineSample& s : samples) {
    features.emplace_back(s.placement.x() - fit.reference.x(), s.placement.y() - fit.reference.y(),
                          s.placement.z());
  }
  if (DesignRank(features, true) < 4) {
    fit.message = "the grasps' placements (" + std::to_string(fit.positions) +
                  " position(s)) do not determine the model: it needs positions not all on one "
                  "line and two or more orientations";
    return fit;
  }

  PlacementLineFit theta_only = fit;
  Solve(features, samples, options, false, &theta_only);
  fit.theta_only = Residuals(features, samples, theta_only);
  fit.iterations = Solve(features, samples, options, true, &fit);
  fit.residuals = Residuals(features, samples, fit);
  if (fit.a_theta.head<2>().norm() > 0.0) {
    // a line's direction: folded into (-90, 90]
    double angle = Degrees(std::atan2(fit.a_theta.y(), fit.a_theta.x()));
    if (angle > 90.0) angle -= 180.0;
    if (angle <= -90.0) angle += 180.0;
    fit.line_angle_deg = angle;
  } else {
    fit.line_angle_deg = std::numeric_limits<double>::quiet_NaN();
  }
  fit.valid = true;
  return fit;
}

}  // namespace graspsynth
