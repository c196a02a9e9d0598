// Speed of a grasp trial (reach, grasp, lift, 1 s hold) of examples/grasp_60deg.json replayed in
// MuJoCo (docs/mujoco.md) beside the same trial in ODE, fast and full detail, on one core.
//
//   build/benchmarks/mujoco_benchmark
//
// The counters: x real time (simulated s per CPU s of the thread), steps per CPU second, the
// steps of a trial, and its outcome (0: success; the TrialOutcome's number otherwise: the
// example does not lift the pan in MuJoCo, whose trial then stops once the pan lies still).

#include <benchmark/benchmark.h>

#include <string>

#include "motion/joint_trajectory.hpp"
#include "simulation/trial.hpp"
#include "simulation_mujoco/mujoco_trial.hpp"
#include "simulation_mujoco/mujoco_world.hpp"

namespace graspsynth::bench {
namespace {

const SimulationModel& Model() {
  static const SimulationModel model = LoadDefaultSimulationModel();
  return model;
}

const JointTrajectory& Example() {
  static const JointTrajectory t =
      LoadJointTrajectory(std::string(GRASPSYNTH_SOURCE_DIR) + "/examples/grasp_60deg.json",
                          Model().robot().arm, Model().robot().hand);
  return t;
}

template <class Run>
void Trials(benchmark::State& state, Run run) {
  double simulated = 0.0, cpu = 0.0;
  long steps = 0;
  TrialOutcome outcome = TrialOutcome::kSuccess;
  for (auto _ : state) {
    const TrialResult r = run();
    simulated += r.simulated_time;
    cpu += r.cpu_time;
    steps += r.statistics.dynamic_steps + r.statistics.kinematic_steps;
    outcome = r.outcome;
  }
  state.counters["x_real_time"] = simulated / cpu;
  state.counters["steps_per_s"] = steps / cpu;
  state.counters["steps"] = static_cast<double>(steps) / state.iterations();
  state.counters["simulated_s"] = simulated / state.iterations();
  state.counters["outcome"] = static_cast<double>(outcome);
}

void BM_OdeFast(benchmark::State& state) {
  Trials(state, [] { return RunTrial(Model(), Example(), TrialOptions{}); });
}
BENCHMARK(BM_OdeFast)->Unit(benchmark::kMillisecond)->MinTime(2.0);

void BM_OdeFull(benchmark::State& state) {
  TrialOptions o;
  o.fidelity = Fidelity::kFull;
  Trials(state, [&] { return RunTrial(Model(), Example(), o); });
}
BENCHMARK(BM_OdeFull)->Unit(benchmark::kMillisecond)->Iterations(2);

// Arg: the finger servos' mapping (0 stiff, 1 soft); 1 ms steps, the model compiled per trial.
void BM_Mujoco(benchmark::State& state) {
  MujocoTrialOptions o;
  o.servo = state.range(0) == 0 ? MujocoServo::kStiff : MujocoServo::kSoft;
  Trials(state, [&] { return RunMujocoTrial(Model(), Example(), TrialOptions{}, o); });
}
BENCHMARK(BM_Mujoco)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// Arg: MuJoCo's step in microseconds (stiff servos).
void BM_MujocoStep(benchmark::State& state) {
  MujocoTrialOptions o;
  o.time_step = 1e-6 * static_cast<double>(state.range(0));
  Trials(state, [&] { return RunMujocoTrial(Model(), Example(), TrialOptions{}, o); });
}
BENCHMARK(BM_MujocoStep)->Arg(1000)->Arg(2000)->Unit(benchmark::kMillisecond)->MinTime(2.0);

// What each MuJoCo trial spends before its first step: the MJCF text and its compilation.
void BM_MujocoCompile(benchmark::State& state) {
  for (auto _ : state) {
    const MujocoModel m(Model(), ExportMjcf(Model(), Example().placement(), MjcfOptions{}));
    benchmark::DoNotOptimize(&m);
  }
}
BENCHMARK(BM_MujocoCompile)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace graspsynth::bench

BENCHMARK_MAIN();
