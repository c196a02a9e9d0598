#pragma once

/// @file
/// The synthetic operator: a model of the paper's human operator that stands in for the
/// original (unpublished) demonstrations. For each object orientation it makes complete
/// teleoperation trials at 60 Hz - rest, a reach with minimum-jerk sub-movements, entry into the
/// grasp workspace region, the approach from above, finger closure, the grasp button, the lift,
/// the hold and the end event - with trial-to-trial variability in path, timing, wrist placement
/// and hand shape. Every trial is then executed in the ODE simulation through the arm's IK
/// (demo_replay.hpp) and its object columns are what happened to the object there: a trial is
/// successful only when physics says the pan was lifted and held.
///
/// The operator's grasp is a hook (learning_data/README.md): palm down, the handle under the
/// fingers `hook_reach` ahead of the wrist, the fingers curling around its far side and under
/// it. Where the wrist goes is the operator's intention for the orientation: a few grasp
/// strategies, each an intended wrist position in the paper's polar form (d, eta) around the
/// object centre, and the grip the hand takes there (GraspStyle: a skilled operator holds the
/// handle differently on either side of it and where the wrist is near its line). The shipped
/// plans (learning_data/demos/operator.json) are calibrated so that the successful trials
/// reproduce the paper's Table I (`graspsynth demos calibrate`), and their grips were tuned in
/// the simulator for robustness (experiments/tune_operator.py).

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/job_runner.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/demo_log.hpp"
#include "learning_data/operator_options.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial.hpp"

namespace graspsynth {

/// One generated trial and what the simulation made of it.
struct OperatorTrial {
  /// Where the object stood: OperatorOptions::positions' entry, empty for the scene's centre.
  std::optional<Eigen::Vector2d> position;
  double theta_deg = 0.0;
  int index = 0;         ///< 1-based trial number within the orientation
  int strategy = 0;      ///< index into the plan's strategies
  bool sloppy = false;   ///< drawn with the enlarged noise
  bool success = false;  ///< the log's label: object centre >= 5 cm up at the end
  /// What the simulation made of it; empty when the arm could not execute the trial.
  std::optional<TrialOutcome> outcome;
  std::string reason;
  int attempts = 1;  ///< draws needed for a trial the arm can execute
  /// source = the file name it gets: theta020_trial03.csv, or at a position of
  /// OperatorOptions::positions x-0300_y+0800_theta020_trial03.csv (mm).
  DemoLog log;
};

/// The trial's outcome as reports name it: ToString(*outcome), or "not_executable" when the
/// arm could not execute the trial.
std::string_view OutcomeName(const OperatorTrial& trial);

/// Called after each trial with the number done and the total.
using OperatorProgress = std::function<void(int done, int total)>;

/// Generates and simulates every trial of every plan at every position (positions in their
/// order, orientations in plan order, trials in index order). Trials run on `threads` workers
/// (0: all cores), as the jobs of stage "demos" of `runner` (common/job_runner.hpp: spread over
/// an MPI job's processes, kept in a resume folder; nullptr: this process's threads); the
/// result does not depend on either. Throws InputError for invalid options.
std::vector<OperatorTrial> GenerateDemonstrations(const SimulationModel& model,
                                                  const OperatorOptions& options, int threads = 0,
                                                  const OperatorProgress& progress = {},
                                                  JobRunner* runner = nullptr);

/// The layout of EncodeOperatorTrial's bytes, kept with them in resume folders; change it with
/// the layout.
inline constexpr const char* kOperatorTrialLayout = "operator-trial/1";

/// The bytes of a trial (common/byte_codec.hpp), for the job runner, and back. Decode throws
/// InputError naming `source` for bytes that are not one.
std::string EncodeOperatorTrial(const OperatorTrial& trial);
OperatorTrial DecodeOperatorTrial(std::string_view bytes, const std::string& source);

}  // namespace graspsynth
