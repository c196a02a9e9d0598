#include "learning_data/segmentation.hpp"

#include <cmath>
#include <sstream>

#include "common/demand.hpp"
#include "common/format.hpp"
#include "common/valid_options.hpp"

namespace graspsynth {
namespace {

constexpr double kLiftSlack = 1e-9;  // m

}  // namespace

bool SegmentationOptions::IsValid(std::string* why) const {
  const auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (!(std::isfinite(region.radius) && region.radius > 0.0)) {
    return fail("grasp region radius must be finite and > 0 m");
  }
  if (region.shape == GraspRegionModel::Shape::kCylinder &&
      !(std::isfinite(region.height) && region.height > 0.0)) {
    return fail("grasp region cylinder height must be finite and > 0 m");
  }
  if (!(std::isfinite(success_lift) && success_lift >= 0.0)) {
    return fail("success_lift must be finite and >= 0 m");
  }
  return true;
}

bool InsideGraspRegion(const GraspRegionModel& region, const Eigen::Vector3d& p_WO,
                       const Eigen::Vector3d& p_WH) {
  const Eigen::Vector3d p_OH = p_WH - p_WO;
  if (region.shape == GraspRegionModel::Shape::kSphere) {
    return p_OH.squaredNorm() <= region.radius * region.radius;
  }
  return p_OH.head<2>().squaredNorm() <= region.radius * region.radius &&
         std::abs(p_OH.z()) <= 0.5 * region.height;
}

const char* ToString(SegmentationStatus status) {
  switch (status) {
    case SegmentationStatus::kOk:
      return "ok";
    case SegmentationStatus::kNeverEntersRegion:
      return "never enters the grasp region";
    case SegmentationStatus::kEntersAfterGrasp:
      return "enters the grasp region after the grasp event";
    case SegmentationStatus::kEntersAtGrasp:
      return "enters the grasp region at the grasp sample";
    case SegmentationStatus::kMalformedMotion:
      return "malformed grasping motion";
  }
  return "unknown";
}

SegmentedTrial Segment(const DemoLog& log, const SegmentationOptions& options) {
  RequireValid(options, "invalid segmentation options");
  std::string why;
  GS_DEMAND(!log.samples.empty(), "Segment: the log has no samples");
  const std::optional<size_t> grasp = FindEvent(log, DemoEvent::kGrasp);
  GS_DEMAND(grasp.has_value(), "Segment: the log has no grasp event");

  SegmentedTrial trial;
  trial.source = log.source;
  trial.theta_deg = log.metadata.theta_deg;
  const DemoSample& first = log.samples.front();
  const DemoSample& last = log.samples.back();
  trial.lift = last.p_WO.z() - first.p_WO.z();
  // 1 nm of slack, so that a lift of exactly success_lift is not lost to rounding.
  trial.success = trial.lift >= options.success_lift - kLiftSlack;

  // the region is centred on the object centre as recorded at the first sample (at rest).
  const Eigen::Vector3d p_WO = first.p_WO;
  size_t entry = log.samples.size();
  for (size_t i = 0; i < log.samples.size(); ++i) {
    if (InsideGraspRegion(options.region, p_WO, log.samples[i].p_WH)) {
      entry = i;
      break;
    }
  }
  const auto fail = [&](SegmentationStatus status, const std::string& detail) {
    trial.status = status;
    trial.message = log.source + ": " + detail;
    return trial;
  };
  const std::string region_text =
      (options.region.shape == GraspRegionModel::Shape::kSphere ? "sphere" : "cylinder") +
      std::string(" of radius ") + StreamNumber(options.region.radius) + " m";
  if (entry == log.samples.size()) {
    return fail(SegmentationStatus::kNeverEntersRegion,
                "the wrist never enters the grasp region (" + region_text + ")");
  }
  if (entry > *grasp) {
    return fail(SegmentationStatus::kEntersAfterGrasp,
                "the wrist first enters the grasp region (" + region_text + ") at sample " +
                    std::to_string(entry) + ", after the grasp event at sample " +
                    std::to_string(*grasp));
  }
  if (entry == *grasp) {
    return fail(SegmentationStatus::kEntersAtGrasp,
                "the wrist first enters the grasp region (" + region_text +
                    ") at the grasp sample " + std::to_string(*grasp) +
                    ": the grasping motion would have a single waypoint");
  }

  GraspingMotion& motion = trial.motion;
  motion.theta = Radians(log.metadata.theta_deg);
  motion.p_WO = p_WO;
  motion.source = log.source;
  if (log.metadata.trial) motion.source += " (trial " + *log.metadata.trial + ")";
  const double t0 = log.samples[entry].t;
  for (size_t i = entry; i <= *grasp; ++i) {
    const DemoSample& s = log.samples[i];
    MotionWaypoint w;
    w.t = s.t - t0;
    w.p_WH = s.p_WH;
    w.q_WH = s.q_WH.normalized();
    w.f = s.f;
    motion.waypoints.push_back(w);
  }
  // only absurd inputs get here (e.g. times near 1e16 s that collide once shifted to 0).
  if (!IsWellFormed(motion, &why)) {
    trial.motion = GraspingMotion();
    return fail(SegmentationStatus::kMalformedMotion, "the grasping motion is malformed: " + why);
  }
  trial.pregrasp = entry;
  trial.grasp = *grasp;
  trial.end = log.samples.size() - 1;
  trial.reach = {0, entry};
  trial.grasping = {entry, *grasp + 1};
  trial.lifting = {*grasp + 1, log.samples.size()};
  return trial;
}

}  // namespace graspsynth
