#include "gate/validated_synthesis.hpp"

#include "common/stopwatch.hpp"

namespace graspsynth {

namespace {

// True for an interp grasp that is the plain blend of a bracket (no fallback taken).
bool IsBlend(const SynthesisResult& s) {
  const bool blended = !s.fallback || s.fallback_reason.kind == FallbackKind::kPartialBlend;
  return s.ok() && s.requested == SynthesisMethod::kInterp && blended &&
         s.bracket.kind == BracketKind::kInside;
}

// A nominal trial's outcome and reason, as the rejected blend and slide report them.
std::string NominalText(const TrialResult& nominal) {
  return std::string(ToString(nominal.outcome)) + " (" + nominal.reason + ")";
}

// A synthesis and its gate.
struct GatedGrasp {
  SynthesisResult synthesis;
  PhysicsGateResult gate;
  bool gate_run = false;
  std::string rejected_slide;  ///< the slid grip's nominal outcome, when it gave way
};

// Synthesizes with `synthesis` and gates the grasp. A slid grip (SynthesisOptions::grip_slide)
// whose nominal trial fails gives way to the same synthesis without the slide. Adds the wall
// times to *v's.
GatedGrasp SynthesizeAndGate(const SimulationModel& simulation, const SynthesisModel& model,
                             const SynthesisTask& task, const SynthesisOptions& synthesis,
                             const ValidatedSynthesisOptions& options, SynthesisData* data,
                             const ProgressCallback& progress, ValidatedSynthesis* v) {
  const auto synthesize = [&](const SynthesisOptions& o) {
    const auto t0 = WallClock::now();
    SynthesisResult s = SynthesizeGrasp(model, task, o, data);
    v->synthesis_s += SecondsSince(t0);
    return s;
  };
  GatedGrasp g;
  const auto gate = [&] {
    g.gate = RunPhysicsGate(simulation, g.synthesis.trajectory, options.gate, progress);
    g.gate_run = true;
    v->gate_s += g.gate.time_s;
  };
  g.synthesis = synthesize(synthesis);
  if (!g.synthesis.ok()) return g;
  gate();
  if (g.synthesis.grip_slide > 0.0 && !g.gate.nominal.success()) {
    SynthesisOptions unslid = synthesis;
    unslid.grip_slide.reset();
    SynthesisResult plain = synthesize(unslid);
    if (plain.ok()) {
      g.rejected_slide = NominalText(g.gate.nominal);
      plain.grip_radius = g.synthesis.grip_radius;  // where the grip was, unslid
      g.synthesis = std::move(plain);
      gate();
    }
  }
  return g;
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
  GatedGrasp first =
      SynthesizeAndGate(simulation, model, task, options.synthesis, options, data, progress, &v);
  v.synthesis = std::move(first.synthesis);
  v.gate = std::move(first.gate);
  v.gate_run = first.gate_run;
  v.rejected_slide = std::move(first.rejected_slide);
  if (!v.gate_run) return v;
  if (!options.physics_fallback || !IsBlend(v.synthesis) || v.gate.nominal.success()) return v;
  SynthesisOptions retry = options.synthesis;
  retry.generation.reject_blend = true;
  GatedGrasp fallback =
      SynthesizeAndGate(simulation, model, task, retry, options, data, progress, &v);
  if (!fallback.gate_run) return v;  // the blend, with its failed gate, is what there is
  v.rejected_blend = NominalText(v.gate.nominal);
  fallback.synthesis.fallback_reason.bracket_reason += ": " + v.rejected_blend;
  v.synthesis = std::move(fallback.synthesis);
  v.gate = std::move(fallback.gate);
  v.rejected_slide = std::move(fallback.rejected_slide);
  return v;
}

}  // namespace graspsynth
