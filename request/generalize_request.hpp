#pragma once

/// @file
/// The request of `graspsynth generalize` and of Python's generalize: grasps for many
/// orientations (and object positions) by several methods from a grasp library, each validated
/// in physics, or the leave-one-out table. Its options are described once (GeneralizeOptions)
/// and turned into the study's options once (ToSynthesisTableOptions), for both front ends. The
/// library, robot, scene and object are not options, nor are the command's output folder, file
/// stem and resume folder.

#include <cstdint>
#include <string>
#include <vector>

#include "request/option.hpp"
#include "studies/study.hpp"

namespace graspsynth::request {

/// What to synthesize and how; the defaults are the command's and Python's.
struct GeneralizeRequest {
  /// Orientations, deg: numbers and ranges FROM:TO:STEP, comma-separated.
  std::string orientations = "20:100:1";
  /// Object positions: x and y of the object centre, m, in the same grammar (both or neither).
  std::string x, y;
  std::vector<std::string> methods = {"nearest", "interp", "interp+refine", "line+refine"};
  bool leave_one_out = false;  ///< each inner library orientation from the library without it
  int perturb = kStudyGatePerturbations;  ///< perturbed replays per grasp
  int sensitivity = 0;                    ///< replays per end of each physics factor's range
  double noise_scale = 1.0;               ///< factor on the replays' motion noise
  uint64_t seed = 1;
  int threads = 0;  ///< 0: all cores
  bool physics_fallback = true;
  PhysicsPerturbationOptions physics = SynthesisTableOptions{}.gate.robustness.perturbation.physics;
  MujocoGateOptions mujoco;       ///< the gate's engines: ode, or ode and MuJoCo's sweep
  HoldMarginOptions hold_margin;  ///< the gates' hold margin: thresholds, required or not
};

/// The options of GeneralizeRequest, in the order the front ends list them.
const OptionList<GeneralizeRequest>& GeneralizeOptions();

/// The study's options of `request` (without a job runner). Throws InputError, naming the
/// option, for a list that does not parse, a method given twice, x without y, or positions
/// with leave_one_out.
SynthesisTableOptions ToSynthesisTableOptions(const GeneralizeRequest& request);

}  // namespace graspsynth::request
