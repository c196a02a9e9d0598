// Latency of grasp synthesis without the physics gate (grasping motion + refinement + reach +
// lift + joint conversion through the IK), per query, and the physics gate's time separately.
// The library: scripted grasps at 40, 60 and 80 deg (tests/utils/scripted_library.hpp), and
// the hard-case library 30/40 deg left of the handle, 50/60 deg right of it.
//
//   build/benchmarks/synthesis_benchmark --benchmark_repetitions=5
//
// Goal (issue 5): median <= 16.7 ms for the synthesis, one tick at 60 Hz. Figures in
// benchmarks/README.md, "Synthesis".

#include <benchmark/benchmark.h>

#include "gate/physics_gate.hpp"
#include "learning_data/grasp_library.hpp"
#include "simulation/simulation_model.hpp"
#include "solver/synthesis.hpp"
#include "tests/utils/scripted_library.hpp"

namespace graspsynth::bench {
namespace {

const SimulationModel& Sim() {
  static const SimulationModel model = LoadDefaultSimulationModel();
  return model;
}

const SynthesisModel& Library406080() {
  static const SynthesisModel model(
      Sim().robot(), Sim().scene(),
      testing::ScriptedLibrary(Sim().robot(), Sim().scene(), {40.0, 60.0, 80.0}));
  return model;
}

const SynthesisModel& SideSwitch() {
  static const SynthesisModel model = [] {
    GraspLibrary l;
    for (auto [theta, side] : {std::pair{30.0, -1}, {40.0, -1}, {50.0, 1}, {60.0, 1}}) {
      l.entries.push_back(testing::ScriptedEntry(Sim().robot(), Sim().scene(), theta, side));
    }
    return SynthesisModel(Sim().robot(), Sim().scene(), std::move(l));
  }();
  return model;
}

// One synthesis per iteration; counters: the stages' shares and whether NLopt ran.
void Synthesize(benchmark::State& state, const SynthesisModel& model, double theta,
                SynthesisMethod method, bool refine) {
  SynthesisOptions o;
  o.generation.method = method;
  if (!refine) o.refinement_stages.clear();
  SynthesisData data(model);
  double generate = 0.0, refine_s = 0.0, joints = 0.0;
  int nlopt = 0, ok = 0;
  for (auto _ : state) {
    SynthesisResult r = SynthesizeGrasp(model, theta, o, &data);
    benchmark::DoNotOptimize(r.trajectory.samples.data());
    generate += r.generate_s;
    refine_s += r.refine_s;
    joints += r.joints_s;
    nlopt += r.refinement.nlopt.run ? 1 : 0;
    ok += r.ok() ? 1 : 0;
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["generate_ms"] = 1e3 * generate / n;
  state.counters["refine_ms"] = 1e3 * refine_s / n;
  state.counters["joints_ms"] = 1e3 * joints / n;
  state.counters["nlopt_runs"] = nlopt / n;
  state.counters["ok"] = ok / n;
}

void BM_SynthesizeInterp50(benchmark::State& s) {
  Synthesize(s, Library406080(), 50.0, SynthesisMethod::kInterp, true);
}
void BM_SynthesizeInterp50NoRefine(benchmark::State& s) {
  Synthesize(s, Library406080(), 50.0, SynthesisMethod::kInterp, false);
}
void BM_SynthesizeNearest70(benchmark::State& s) {
  Synthesize(s, Library406080(), 70.0, SynthesisMethod::kNearest, true);
}
void BM_SynthesizeLine30(benchmark::State& s) {
  Synthesize(s, Library406080(), 30.0, SynthesisMethod::kLine, true);
}
// outside the range: the line grasp needs NLopt's contact constraint.
void BM_SynthesizeLine110(benchmark::State& s) {
  Synthesize(s, Library406080(), 110.0, SynthesisMethod::kLine, true);
}
void BM_SynthesizeHardCase45(benchmark::State& s) {
  Synthesize(s, SideSwitch(), 45.0, SynthesisMethod::kInterp, true);
}

// The shipped library (learning_data/library.json: the synthetic operator's representatives at
// 20, 30, ..., 100 deg): one query per orientation 20, 25, ..., 100 deg, interp and line with
// the refinement.
const SynthesisModel& Shipped() {
  static const SynthesisModel model(Sim().robot(), Sim().scene(),
                                    ReadGraspLibrary(DefaultGraspLibraryPath()));
  return model;
}
void BM_ShippedInterp(benchmark::State& s) {
  Synthesize(s, Shipped(), static_cast<double>(s.range(0)), SynthesisMethod::kInterp, true);
}
void BM_ShippedLine(benchmark::State& s) {
  Synthesize(s, Shipped(), static_cast<double>(s.range(0)), SynthesisMethod::kLine, true);
}

// The gate of the 50 deg grasp: the nominal trial alone, and with 10 perturbed replays on one
// thread (the command's default of 30 replays spreads over every core).
void Gate(benchmark::State& state, int perturbations) {
  SynthesisOptions o;
  SynthesisData data(Library406080());
  const SynthesisResult r = SynthesizeGrasp(Library406080(), 50.0, o, &data);
  PhysicsGateOptions g;
  g.robustness.trials = perturbations;
  g.robustness.threads = 1;
  int passed = 0;
  for (auto _ : state) passed += RunPhysicsGate(Sim(), r.trajectory, g).passed ? 1 : 0;
  state.counters["passed"] = passed / static_cast<double>(state.iterations());
}
void BM_GateNominal(benchmark::State& s) { Gate(s, 0); }
void BM_GateNominalPlus10(benchmark::State& s) { Gate(s, 10); }

BENCHMARK(BM_SynthesizeInterp50)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SynthesizeInterp50NoRefine)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SynthesizeNearest70)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SynthesizeLine30)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SynthesizeLine110)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SynthesizeHardCase45)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShippedInterp)->DenseRange(20, 100, 5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ShippedLine)->DenseRange(20, 100, 5)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GateNominal)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_GateNominalPlus10)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace graspsynth::bench

BENCHMARK_MAIN();
