#pragma once

/// @file
/// A demonstration set that reproduces the paper's Table I exactly: for every row, row.n
/// successful trials whose pre-grasp sample sits at the paper's pre-grasp position (just inside
/// the 0.41 m cylinder) and whose grasp positions scatter symmetrically about the paper's mean.

#include <cmath>
#include <string>
#include <vector>

#include "analysis/analysis_report.hpp"
#include "tests/learning_data/demo_fixtures.hpp"

namespace graspsynth::testing {

/// The logs of the Table I set, named "theta<T>_<k>.csv". `grasp_shift` (object-centred, m) is
/// added to the grasp positions of orientation `shifted_theta_deg` only.
inline std::vector<DemoLog> TableIDemos(double shifted_theta_deg = -1.0,
                                        const Eigen::Vector2d& grasp_shift = {0.0, 0.0}) {
  std::vector<DemoLog> logs;
  for (const PaperTableRow& row : PaperTableI()) {
    for (int k = 0; k < row.n; ++k) {
      TrialSpec spec;
      spec.theta_deg = row.theta_deg;
      spec.pregrasp_xy = Polar(row.pregrasp_d - 1e-7, row.pregrasp_eta_deg);
      // offsets of 4 mm in n evenly spread directions: they sum to zero.
      const double a = 2.0 * M_PI * k / row.n;
      spec.grasp_xy = Polar(row.grasp_d, row.grasp_eta_deg) +
                      (row.n > 1 ? 0.004 : 0.0) * Eigen::Vector2d(std::cos(a), std::sin(a));
      if (row.theta_deg == shifted_theta_deg) spec.grasp_xy += grasp_shift;
      spec.t0 = 0.2 + 0.01 * k;
      spec.grasp_samples = 4 + k % 3;
      spec.trial = std::to_string(k);
      DemoLog log = MakeTrial(spec);
      log.source = "theta" + std::to_string(static_cast<int>(row.theta_deg)) + "_" +
                   std::to_string(k) + ".csv";
      logs.push_back(std::move(log));
    }
  }
  return logs;
}

}  // namespace graspsynth::testing
