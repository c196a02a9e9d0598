#pragma once

/// @file
/// The grasp file, format `graspsynth-grasp/1`, written by `graspsynth synthesize`:
///
///     {"format": "graspsynth-grasp/1",
///      "theta_deg": 45.0,
///      "method": {"requested": "interp", "used": "nearest", "fallback": true, "reason": "..."},
///      "bracket": {"kind", "theta1_deg", "theta2_deg", "t", "blendable", "reason",
///                  "orientation_change_deg", "sides": [s1, s2]},
///      "sources": [{"theta_deg", "file", "trial", "weight"}],
///      "start": [7 rad],
///      "reach": {"used": "spline" | "joint", "reason": "..."},
///      "waypoints": [{"t", "position", "quaternion", "fingers": [16 rad]}],  the grasping
///                   motion from the pre-grasp to the grasp (after refinement)
///      "trajectory": {graspsynth-trajectory/1 document},   what `graspsynth simulate` plays
///      "refinement": {"refined", "kept", "time_s", "thresholds": {"clearance_margin_m",
///                     "penetration_tolerance_m", "contact_tolerance_m"}, "before": {...},
///                     "after_ceres": {...}, "after": {...}, "ceres": {...}, "nlopt": {...}},
///      "quality": {"contacts", "force_closure", "epsilon", "volume", "wrenches", "facets",
///                  "message"},
///      "validation": {"passed", "forced", "reason", "nominal": {...}, "robustness": {...}},
///      "timing": {"generate_s", "refine_s", "joints_s", "gate_s"}}
///
/// Positions in metres (world), quaternions (w, x, y, z) canonical, angles of joints in rad,
/// the user-facing orientations in degrees. Constraint values: "approach_clearance_m",
/// "grasp_clearance_m", "contact_error_m" (null when not used), "min_psi_width_deg",
/// "reachable", "feasible", "violation".

#include <filesystem>
#include <string>
#include <string_view>

#include "gate/physics_gate.hpp"
#include "kinematics/arm_model.hpp"
#include "kinematics/hand_model.hpp"
#include "motion/joint_trajectory.hpp"
#include "solver/synthesis.hpp"

namespace graspsynth {

/// The `format` value of a grasp file.
inline constexpr std::string_view kGraspFileFormat = "graspsynth-grasp/1";

/// The grasp file's text (pretty JSON). `gate` may be null (no validation was run).
std::string GraspFileToJson(const SynthesisResult& synthesis, const PhysicsGateResult* gate,
                            bool forced);

/// Writes GraspFileToJson atomically. Throws InputError when the file cannot be written.
void WriteGraspFile(const std::filesystem::path& path, const SynthesisResult& synthesis,
                    const PhysicsGateResult* gate, bool forced);

/// Reads a joint trajectory from `path`: a `graspsynth-trajectory/1` file, or the
/// "trajectory" member of a `graspsynth-grasp/1` file; then checks the joint limits. Throws
/// InputError naming the file and the field (`trajectory.samples[3].t` in a grasp file).
JointTrajectory LoadTrajectoryOrGraspFile(const std::filesystem::path& path, const ArmModel& arm,
                                          const HandModel& hand);
/// The same from the text of such a file; `source` names it in messages.
JointTrajectory ParseTrajectoryOrGraspFile(std::string_view json_text, const std::string& source,
                                           const ArmModel& arm, const HandModel& hand);

}  // namespace graspsynth
