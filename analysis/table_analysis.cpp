#include "analysis/table_analysis.hpp"

#include <cmath>
#include <map>
#include <sstream>

#include "common/demand.hpp"

namespace graspsynth {
namespace {

// Sample standard deviation from deviations about the mean (n - 1; 0 for fewer than two).
double SampleStd(const std::vector<double>& deviations) {
  if (deviations.size() < 2) return 0.0;
  double sum = 0.0;
  for (double v : deviations) sum += v * v;
  return std::sqrt(sum / static_cast<double>(deviations.size() - 1));
}

}  // namespace

PolarMean ComputePolarMean(const std::vector<Eigen::Vector2d>& points) {
  GS_DEMAND(!points.empty(), "ComputePolarMean needs at least one point");
  PolarMean m;
  for (const Eigen::Vector2d& p : points) m.mean_xy += p;
  m.mean_xy /= static_cast<double>(points.size());
  m.d = m.mean_xy.norm();
  const double eta = std::atan2(m.mean_xy.y(), m.mean_xy.x());
  m.eta_deg = eta / kDeg;

  double mean_d = 0.0;
  for (const Eigen::Vector2d& p : points) mean_d += p.norm();
  mean_d /= static_cast<double>(points.size());
  std::vector<double> dx, dy, dd, deta;
  for (const Eigen::Vector2d& p : points) {
    dx.push_back(p.x() - m.mean_xy.x());
    dy.push_back(p.y() - m.mean_xy.y());
    dd.push_back(p.norm() - mean_d);
    // angles measured about the mean direction, so that +-180 deg does not wrap.
    deta.push_back(std::remainder(std::atan2(p.y(), p.x()) - eta, 2.0 * M_PI) / kDeg);
  }
  m.std_xy = Eigen::Vector2d(SampleStd(dx), SampleStd(dy));
  m.std_d = SampleStd(dd);
  m.std_eta_deg = SampleStd(deta);
  return m;
}

TableAnalysis AnalyzeTable(const std::vector<SegmentedTrial>& trials) {
  TableAnalysis table;
  table.trials = static_cast<int>(trials.size());
  std::map<double, OrientationStats> rows;
  for (const SegmentedTrial& trial : trials) {
    if (!trial.success) {
      std::ostringstream reason;
      reason << "unsuccessful: the object rose " << trial.lift << " m by the end";
      table.unsuccessful.push_back({trial.source, reason.str()});
      continue;
    }
    if (!trial.ok()) {
      table.unsegmentable.push_back({trial.source, trial.message});
      continue;
    }
    OrientationStats& row = rows[trial.theta_deg];
    row.theta_deg = trial.theta_deg;
    const Eigen::Vector3d& p_WO = trial.motion.p_WO;
    row.pregrasp_points.push_back((trial.motion.pregrasp().p_WH - p_WO).head<2>());
    row.grasp_points.push_back((trial.motion.grasp().p_WH - p_WO).head<2>());
    row.sources.push_back(trial.source);
    ++table.used;
  }
  for (auto& [theta, row] : rows) {
    row.n = static_cast<int>(row.grasp_points.size());
    row.pregrasp = ComputePolarMean(row.pregrasp_points);
    row.grasp = ComputePolarMean(row.grasp_points);
    table.orientations.push_back(std::move(row));
  }
  return table;
}

}  // namespace graspsynth
