#pragma once

/// @file
/// A synthesized grasp checked in physics, with the interp method's last fallback: the
/// synthesis (synthesis.hpp) then the physics gate (physics_gate.hpp) on its trajectory. When
/// the interp method blended a bracket (no fallback) and the blend's nominal trial fails, the
/// bracket is treated as one that cannot be blended: the synthesis runs again with the blend
/// rejected (MotionGenerationOptions::reject_blend) and takes the unblendable bracket's
/// fallbacks (motion_generation.hpp: the nearer demonstration turned with the object, then the
/// line principle), and that grasp is gated. Only the nominal trial decides, never the
/// perturbed replays, so the robustness that is reported is that of the grasp returned, scored
/// on replays that chose nothing. Measured on the shipped library: every blend of the 60 and
/// 70 deg representatives at 63-65 deg drops the pan, while the 60 deg one turned with the
/// object lifts it (docs/architecture.md, "Robustness under the contact model"). Likewise, a grasp
/// whose grip was slid (SynthesisOptions::grip_slide) and whose nominal trial fails is synthesized
/// again without the slide and that grasp is gated, before the blend's fallback is considered.

#include <string>

#include "gate/physics_gate.hpp"
#include "solver/synthesis.hpp"

namespace graspsynth {

/// Options of SynthesizeAndValidate.
struct ValidatedSynthesisOptions {
  SynthesisOptions synthesis;
  PhysicsGateOptions gate;
  /// A blend whose nominal trial fails gives way to the unblendable bracket's fallbacks.
  bool physics_fallback = true;
};

/// The grasp that was kept and its gate.
struct ValidatedSynthesis {
  SynthesisResult synthesis;  ///< the grasp (the fallback's, when the blend was rejected)
  bool gate_run = false;      ///< false when the synthesis failed (synthesis.status says why)
  PhysicsGateResult gate;
  /// The rejected blend's nominal outcome and reason ("" when no blend was rejected).
  std::string rejected_blend;
  /// The slid grip's nominal outcome and reason when it gave way to the unslid one (the kept
  /// grasp's; "" when no slide was rejected).
  std::string rejected_slide;
  double synthesis_s = 0.0;  ///< wall time of the synthesis (both runs), s
  double gate_s = 0.0;       ///< wall time of the gate (both runs), s
};

/// Synthesizes the grasp for theta_deg and gates it, with the physics fallback of the file
/// comment. `progress` gets the gate's replays. Throws InputError for invalid gate options.
ValidatedSynthesis SynthesizeAndValidate(const SimulationModel& simulation,
                                         const SynthesisModel& model, double theta_deg,
                                         const ValidatedSynthesisOptions& options,
                                         SynthesisData* data,
                                         const ProgressCallback& progress = {});
/// The same for a task made by MakeSynthesisTask (the object at a placement of its own).
ValidatedSynthesis SynthesizeAndValidate(const SimulationModel& simulation,
                                         const SynthesisModel& model, const SynthesisTask& task,
                                         const ValidatedSynthesisOptions& options,
                                         SynthesisData* data,
                                         const ProgressCallback& progress = {});

}  // namespace graspsynth
