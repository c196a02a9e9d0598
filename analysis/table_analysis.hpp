#pragma once

/// @file
/// The paper's Table I (section III-D): for each object orientation and all successful trials,
/// the average pre-grasp and grasp wrist positions relative to the object centre in the table
/// plane, in polar form (DESIGN.md: d = horizontal distance, eta = atan2(dy, dx) from world +x).

#include <string>
#include <vector>

#include "learning_data/segmentation.hpp"

namespace graspsynth {

/// Mean and spread of a set of object-centred table-plane positions (world axes, origin at the
/// object centre, metres).
struct PolarMean {
  Eigen::Vector2d mean_xy = Eigen::Vector2d::Zero();  ///< mean of the (dx, dy) vectors, m
  double d = 0.0;                                     ///< |mean_xy|, m
  double eta_deg = 0.0;  ///< atan2(mean dy, mean dx), degrees from world +x, in [-180, 180]
  Eigen::Vector2d std_xy = Eigen::Vector2d::Zero();  ///< sample std of dx and dy, m
  double std_d = 0.0;        ///< sample std of the per-trial distances |(dx, dy)|, m
  double std_eta_deg = 0.0;  ///< sample std of the per-trial angles, measured about eta_deg, deg
};

/// The mean of `points` (object-centred, m) and its polar form; standard deviations use n - 1
/// and are 0 for a single point. Aborts (GS_DEMAND) when `points` is empty.
PolarMean ComputePolarMean(const std::vector<Eigen::Vector2d>& points);

/// One row of the table: the successful, segmented trials of one object orientation.
struct OrientationStats {
  double theta_deg = 0.0;                        ///< object orientation, degrees
  int n = 0;                                     ///< number of trials averaged
  PolarMean pregrasp;                            ///< the pre-grasp wrist positions
  PolarMean grasp;                               ///< the grasp wrist positions
  std::vector<Eigen::Vector2d> pregrasp_points;  ///< per trial, object-centred, m
  std::vector<Eigen::Vector2d> grasp_points;     ///< per trial, object-centred, m
  std::vector<std::string> sources;              ///< the trials' files
};

/// A trial left out of the table, and why.
struct SkippedTrial {
  std::string file;
  std::string reason;
};

/// Table I of our demonstrations.
struct TableAnalysis {
  std::vector<OrientationStats> orientations;  ///< sorted by theta_deg
  int trials = 0;                              ///< trials given
  int used = 0;                                ///< trials averaged (successful and segmented)
  std::vector<SkippedTrial> unsuccessful;      ///< the object was not lifted: skipped
  std::vector<SkippedTrial> unsegmentable;     ///< successful but not segmentable: skipped
};

/// Builds the table from segmented trials. Unsuccessful trials (SegmentedTrial::success false)
/// are skipped and listed, whether segmented or not; successful trials that could not be
/// segmented are skipped and listed with the segmentation message. Trials are grouped by their
/// exact theta_deg. Positions are the wrist (p_WH) minus the trial's object centre at rest (the
/// motion's p_WO), horizontal components only.
TableAnalysis AnalyzeTable(const std::vector<SegmentedTrial>& trials);

}  // namespace graspsynth
