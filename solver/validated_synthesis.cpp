#include "solver/validated_synthesis.hpp"

#include "common/stopwatch.hpp"

namespace graspsynth {

namespace {

// True for an interp grasp that is the plain blend of a bracket (no fallback taken).
bool IsBlend(const SynthesisResult& s) {
  const bool blended = !s.fallback || s.fallback_reason.kind == FallbackKind::kPartialBlend;
  return s.ok() && s.requested == SynthesisMethod::kInterp && blended &&
         s.bracket.kind == BracketKind::kInside;
}

}  // namespace

ValidatedSynthesis SynthesizeAndValidate(const SimulationModel& simulation,
                                         const SynthesisModel& model, double theta_deg,
                                         const ValidatedSynthesisOptions& options,
                                         SynthesisData* data, const ProgressCallback& progress) {
  return SynthesizeAndValidate(simulation, model, MakeSynthesisTask(model.scene(), theta_deg),
                               options, data, progress);
}

ValidatedSynthesis SynthesizeAndValidate(const SimulationModel& simulation,
                                         const SynthesisModel& model, const SynthesisTask& task,
                                         const ValidatedSynthesisOptions& options,
                                         SynthesisData* data, const ProgressCallback& progress) {
  ValidatedSynthesis v;
  auto t0 = WallClock::now();
  v.synthesis = SynthesizeGrasp(model, task, options.synthesis, data);
  v.synthesis_s = SecondsSince(t0);
  if (!v.synthesis.ok()) return v;
  v.gate = RunPhysicsGate(simulation, v.synthesis.trajectory, options.gate, progress);
  v.gate_run = true;
  v.gate_s = v.gate.time_s;
  if (!options.physics_fallback || !IsBlend(v.synthesis) || v.gate.nominal.success()) return v;
  SynthesisOptions retry = options.synthesis;
  retry.generation.reject_blend = true;
  t0 = WallClock::now();
  SynthesisResult fallback = SynthesizeGrasp(model, task, retry, data);
  v.synthesis_s += SecondsSince(t0);
  if (!fallback.ok()) return v;  // the blend, with its failed gate, is what there is
  v.rejected_blend =
      std::string(ToString(v.gate.nominal.outcome)) + " (" + v.gate.nominal.reason + ")";
  fallback.fallback_reason.bracket_reason += ": " + v.rejected_blend;
  v.synthesis = std::move(fallback);
  v.gate = RunPhysicsGate(simulation, v.synthesis.trajectory, options.gate, progress);
  v.gate_s += v.gate.time_s;
  return v;
}

}  // namespace graspsynth
