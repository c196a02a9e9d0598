#pragma once

/// @file
/// The line principle tested where the object moves (issue: the object anywhere on the table).
/// The paper found the operator's grasp wrist on a line as the object turned about a fixed
/// centre. Over placements (x, y, theta) the hypothesis becomes: the grasp wrist position
/// relative to the object centre is an affine function of the placement,
///
///   r = p_wrist - p_object = b + A_x (x - x_ref) + A_y (y - y_ref) + A_theta theta,
///
/// with b, A_x, A_y, A_theta in R^3 (world axes, m; m per m; m per rad), (x_ref, y_ref) the
/// mean position of the samples. At one position the model is a line in theta (the paper's
/// wrist line, moved with the object when A_x = A_y = 0); A_x and A_y say how much the
/// operator's grasp shifts relative to the object when it stands elsewhere. The model is
/// fitted by Ceres (with the wrist line's robust loss, if any); its residuals, and those of
/// the same model without the position terms, are what the report gives.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/wrist_line.hpp"

namespace graspsynth {

/// One fitted grasp: where the object stood and where the wrist grasped, relative to it.
struct PlacementLineSample {
  Eigen::Vector3d placement = Eigen::Vector3d::Zero();  ///< (x, y, theta): m, m, rad
  Eigen::Vector3d wrist = Eigen::Vector3d::Zero();      ///< wrist minus object centre, world, m
  int trials = 1;                                       ///< trials averaged into this sample
};

/// Residual figures of a fit.
struct PlacementLineResiduals {
  double rms_xy = 0.0;                      ///< m, on the table (the line's plane)
  double max_xy = 0.0;                      ///< m
  double rms_z = 0.0;                       ///< m, height
  std::vector<Eigen::Vector3d> per_sample;  ///< observed minus fitted, m
};

/// The fitted affine model and its residuals.
struct PlacementLineFit {
  bool valid = false;
  std::string message;  ///< why not valid
  int samples = 0;
  int positions = 0;                                    ///< distinct object positions (5 mm apart)
  Eigen::Vector2d reference = Eigen::Vector2d::Zero();  ///< (x_ref, y_ref), m
  Eigen::Vector3d b = Eigen::Vector3d::Zero();          ///< m
  Eigen::Vector3d a_x = Eigen::Vector3d::Zero();        ///< m per m
  Eigen::Vector3d a_y = Eigen::Vector3d::Zero();        ///< m per m
  Eigen::Vector3d a_theta = Eigen::Vector3d::Zero();    ///< m per rad
  PlacementLineResiduals residuals;                     ///< of the full model
  /// The model with A_x = A_y = 0 (one wrist line for every position, moved with the object):
  /// its residuals against the full model's say what the position terms explain.
  PlacementLineResiduals theta_only;
  /// The direction of the wrist line on the table (A_theta's xy), deg from world +x in (-90, 90];
  /// NaN when A_theta has no xy part.
  double line_angle_deg = 0.0;
  int iterations = 0;  ///< Ceres iterations of the full fit
};

/// Groups `samples` by placement (positions within 5 mm, the settling of a simulated object, and
/// orientations within 1e-6 rad) into their means, in the order of first appearance; `trials`
/// counts the samples of each.
std::vector<PlacementLineSample> MeanPerPlacement(const std::vector<PlacementLineSample>& samples);

/// Fits the affine model over `samples` with the loss of `options` (loss, loss_scale,
/// max_iterations). Needs samples at two or more positions not all on one line and at two or
/// more orientations (else the position or theta terms are not determined): otherwise the fit
/// is not valid, with the reason. Options assumed valid.
PlacementLineFit FitPlacementLine(const std::vector<PlacementLineSample>& samples,
                                  const WristLineOptions& options);

}  // namespace graspsynth
