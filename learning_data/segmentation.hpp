#pragma once

/// @file
/// Segmentation of a demonstration log into the phases of the paper (section III-B): reaching,
/// grasping and lifting, with the pre-grasp pose (first wrist sample inside the grasp workspace
/// region) and the grasp pose (the grasp-button sample), and the success label of the trial.

#include <string>

#include "learning_data/demo_log.hpp"
#include "motion/grasping_motion.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// Inputs of Segment().
struct SegmentationOptions {
  /// The grasp workspace region around the object centre (the log's first object sample):
  /// a vertical cylinder of `radius` (horizontal distance) and full `height` centred on the
  /// object centre, or a sphere of `radius` (3D distance). A sample on the boundary is inside.
  /// The defaults (cylinder, 0.41 m, 1.0 m) are those of models/scene.json.
  GraspRegionModel region;
  /// A trial succeeded when the object centre at the end sample is at least this far above its
  /// first sample (less 1e-9 m for rounding), m (DESIGN.md: 5 cm).
  double success_lift = 0.05;

  /// True when the radius and height are finite and > 0 and success_lift is finite and >= 0;
  /// otherwise false, with the reason in `why` (if given).
  bool IsValid(std::string* why) const;
};

/// Why a trial could not be segmented.
enum class SegmentationStatus {
  kOk,
  kNeverEntersRegion,  ///< the wrist is never inside the region
  kEntersAfterGrasp,   ///< the wrist is first inside the region after the grasp event
  kEntersAtGrasp,      ///< first inside at the grasp sample itself: a 1-waypoint motion
  kMalformedMotion,    ///< the waypoints break IsWellFormed (e.g. times equal after shifting)
};

/// A half-open range [begin, end) of sample indices.
struct SampleRange {
  size_t begin = 0;
  size_t end = 0;
  /// Number of samples in the range.
  size_t size() const { return end - begin; }
};

/// The segmentation of one trial.
struct SegmentedTrial {
  std::string source;      ///< the log's source (file path)
  double theta_deg = 0.0;  ///< object orientation from the metadata, degrees
  /// The trial succeeded: the object centre at the end sample is >= success_lift above the
  /// first sample. Labelled for every trial, segmented or not.
  bool success = false;
  double lift = 0.0;  ///< object centre height at the end minus at the first sample, m

  SegmentationStatus status = SegmentationStatus::kOk;
  std::string message;  ///< why the segmentation failed (empty when kOk)

  // The remaining fields are set only when status == kOk.
  size_t pregrasp = 0;   ///< index of the pre-grasp sample (first inside the region)
  size_t grasp = 0;      ///< index of the grasp-event sample
  size_t end = 0;        ///< index of the end sample (the last one)
  SampleRange reach;     ///< [0, pregrasp)
  SampleRange grasping;  ///< [pregrasp, grasp]
  SampleRange lifting;   ///< (grasp, end]
  /// Waypoints pregrasp..grasp: t relative to the pre-grasp sample (s), wrist position (world,
  /// m), normalized wrist quaternion, fingers (rad); theta = theta_deg in radians; p_WO = the
  /// first object sample; source = the log's source (and "(trial T)" when the metadata names
  /// the trial). IsWellFormed() holds.
  GraspingMotion motion;

  /// True when the trial was segmented (status kOk).
  bool ok() const { return status == SegmentationStatus::kOk; }
};

/// True when the wrist position p_WH (world, m) is inside `region` around the object centre
/// p_WO (world, m).
bool InsideGraspRegion(const GraspRegionModel& region, const Eigen::Vector3d& p_WO,
                       const Eigen::Vector3d& p_WH);

/// Segments a log that passed the reader's rules (one grasp event, end event last). A trial that
/// cannot be segmented is a result with status != kOk and a message, not an exception.
/// Aborts (GS_DEMAND) when `options` is not valid or the log has no samples or no grasp event.
SegmentedTrial Segment(const DemoLog& log, const SegmentationOptions& options);

/// Short name of a status ("ok", "never enters the region", ...).
const char* ToString(SegmentationStatus status);

}  // namespace graspsynth
