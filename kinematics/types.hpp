#pragma once

/// @file
/// Vocabulary types and the frame notation used across graspsynth.
///
/// Notation (after Drake's monogram notation):
/// - `X_AB` is the pose (rigid transform) of frame B measured in frame A, so that a point
///   `p_B` expressed in B is `X_AB * p_B` in A. `R_AB` is its rotation, `p_AB` its translation.
/// - `p_AQ` is the position of point Q in frame A.
/// - Frames: W world (the PA-10 base, z up), B arm base, L<i> arm link i, F flange (DH frame 7),
///   H hand mount ("wrist" in the paper's sense), P palm, O object centre.
/// - Quaternions are Eigen (w, x, y, z) unit quaternions; files always store w first.
/// SI units everywhere; angles in radians inside the code.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace graspsynth {

/// One degree in radians: degrees (files, flags, reports) times kDeg are radians.
inline constexpr double kDeg = M_PI / 180.0;

/// `deg` degrees in radians, computed as deg * pi / 180. Its rounding can differ from
/// deg * kDeg in the last bit, and the shipped results were made with each where it is used:
/// Radians() where a value read in degrees (a file's theta_deg, a default written in degrees)
/// becomes radians, kDeg where a literal angle is written as `30 * kDeg`.
constexpr double Radians(double deg) { return deg * M_PI / 180.0; }

/// `rad` radians in degrees, computed as rad * 180 / pi (for reports and messages).
constexpr double Degrees(double rad) { return rad * 180.0 / M_PI; }

/// Number of arm joints (PA-10-7C: S1 S2 S3 E1 E2 W1 W2).
inline constexpr int kArmDof = 7;
/// Number of actuated hand joints (Gifu Hand III), the order f0..f15 of every file format.
inline constexpr int kHandDof = 16;

/// Arm joint vector q = (S1, S2, S3, E1, E2, W1, W2) in radians.
using Vector7d = Eigen::Matrix<double, kArmDof, 1>;
/// Actuated finger joints f0..f15 in radians (order: models/README.md).
using HandVector = Eigen::Matrix<double, kHandDof, 1>;

/// A closed interval [lo, hi].
struct Interval {
  double lo = 0.0;
  double hi = 0.0;
  double width() const { return hi - lo; }
  bool Contains(double x) const { return lo <= x && x <= hi; }
};

}  // namespace graspsynth

namespace graspsynth {

/// The union of `intervals` as sorted, disjoint intervals (touching ones are merged).
inline std::vector<Interval> MergeIntervals(std::vector<Interval> intervals) {
  std::sort(intervals.begin(), intervals.end(),
            [](const Interval& a, const Interval& b) { return a.lo < b.lo; });
  std::vector<Interval> merged;
  for (const Interval& iv : intervals) {
    if (!merged.empty() && iv.lo <= merged.back().hi) {
      merged.back().hi = std::max(merged.back().hi, iv.hi);
    } else {
      merged.push_back(iv);
    }
  }
  return merged;
}

}  // namespace graspsynth
