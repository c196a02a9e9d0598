#pragma once

/// @file
/// The request of `graspsynth synthesize` and of Python's Synthesizer.synthesize: one grasp for
/// an object orientation (and, optionally, a position on the table), through the physics gate.
/// Its options are described once (SynthesizeOptions) and turned into the library's options
/// once (ToValidatedSynthesisOptions), for both front ends. The library, robot, scene and object
/// are not options: the command takes files, Python takes objects.

#include <cmath>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "gate/validated_synthesis.hpp"
#include "kinematics/types.hpp"
#include "request/option.hpp"

namespace graspsynth::request {

/// What to synthesize and how; the defaults are the command's and Python's.
struct SynthesizeRequest {
  double theta = NAN;                 ///< object orientation, deg (required)
  std::optional<Eigen::Vector2d> at;  ///< the object centre on the table, m; none: the scene's
  std::string method = "interp";      ///< interp, line or nearest
  bool refine = true;                 ///< the Ceres and NLopt refinement
  std::string reach = "auto";         ///< spline, joint or auto
  double clearance_margin = 0.005;    ///< the refinement's clearance along the approach, m
  bool strict_thresholds = false;     ///< the refinement's default thresholds, always
  bool grip_slide = false;            ///< slide a grip at the handle's end toward the centre
  std::optional<Vector7d> start;      ///< start configuration, rad; none: the rest pose
  bool physics_fallback = true;       ///< a blend that fails in physics gives way
  PhysicsGateOptions gate;            ///< the gate: replays, seed, threads, robustness, physics
};

/// The options of SynthesizeRequest, in the order the front ends list them.
const OptionList<SynthesizeRequest>& SynthesizeOptions();

/// The library's options of `request`. Throws InputError for a combination the options alone
/// do not catch (grip_slide without refine).
ValidatedSynthesisOptions ToValidatedSynthesisOptions(const SynthesizeRequest& request);

}  // namespace graspsynth::request
