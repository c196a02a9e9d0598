// Speed of a full grasp validation trial (reach, grasp, lift, 1 s hold) of
// examples/grasp_60deg.json in the ODE world with the arm in the scene, for the fast path and
// the full-detail simulation, and the agreement of their outcomes on perturbed replays.
//
//   build/benchmarks/simulation_benchmark                      the timings
//   build/benchmarks/simulation_benchmark --agreement=100      fast vs full on 100 replays
//   build/benchmarks/simulation_benchmark --agreement=500 --noise=1
//                                                  the same at the default noise only
//
// Figures in benchmarks/README.md, "Simulation".

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "learning_data/demo_directory.hpp"
#include "learning_data/demo_log.hpp"
#include "learning_data/demo_replay.hpp"
#include "learning_data/grasp_library.hpp"
#include "motion/joint_trajectory.hpp"
#include "simulation/robustness.hpp"
#include "simulation/trial.hpp"

namespace graspsynth::bench {
namespace {

const SimulationModel& Model() {
  static const SimulationModel model = LoadDefaultSimulationModel();
  return model;
}

// The pan built from meshes (models/objects/pan_mesh.json): its body and handle ODE trimeshes.
const SimulationModel& MeshPanModel() {
  static const SimulationModel model(LoadRobotModel(DefaultRobotDescriptionPath()),
                                     LoadSceneModel(DefaultSceneModelPath(), "pan_mesh"));
  return model;
}

const JointTrajectory& Example() {
  static const JointTrajectory t =
      LoadJointTrajectory(std::string(GRASPSYNTH_SOURCE_DIR) + "/examples/grasp_60deg.json",
                          Model().robot().arm, Model().robot().hand);
  return t;
}

// One trial per iteration. Counters: x real time (simulated s per CPU s of the thread), dynamic
// steps per CPU second, the world's size, and where the time went (shares of the wall time).
void RunTrials(benchmark::State& state, const TrialOptions& options,
               const SimulationModel& model = Model(),
               const JointTrajectory& trajectory = Example()) {
  double simulated = 0.0, wall = 0.0, cpu = 0.0, collision = 0.0, solver = 0.0;
  long dynamic_steps = 0, kinematic_steps = 0;
  int max_contacts = 0;
  WorldCounts counts;
  bool all_succeeded = true;
  for (auto _ : state) {
    const TrialResult r = RunTrial(model, trajectory, options);
    all_succeeded = all_succeeded && r.success();
    simulated += r.simulated_time;
    wall += r.wall_time;
    cpu += r.cpu_time;
    collision += r.statistics.collision_s;
    solver += r.statistics.solver_s;
    dynamic_steps += r.statistics.dynamic_steps;
    kinematic_steps += r.statistics.kinematic_steps;
    max_contacts = std::max(max_contacts, r.statistics.max_contacts);
    counts = r.counts;
  }
  if (!all_succeeded) state.SkipWithError("a trial failed");
  state.counters["x_real_time"] = simulated / cpu;
  state.counters["dyn_steps_per_s"] = dynamic_steps / cpu;
  state.counters["dyn_steps"] = static_cast<double>(dynamic_steps) / state.iterations();
  state.counters["kin_steps"] = static_cast<double>(kinematic_steps) / state.iterations();
  state.counters["solver_share"] = solver / wall;
  state.counters["collision_share"] = collision / wall;
  state.counters["bodies"] = counts.bodies;
  state.counters["dyn_bodies"] = counts.dynamic_bodies;
  state.counters["joints"] = counts.joints;
  state.counters["max_contacts"] = max_contacts;
}

// The fast path as the robustness evaluation uses it (kinematic arm, free space without
// contact detail, 4 ms, early stop).
void BM_TrialFast(benchmark::State& state) { RunTrials(state, TrialOptions{}); }
BENCHMARK(BM_TrialFast)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// The same trial stepped by ODE's dWorldStep instead of the structured solve (the default,
// WorldOptions::structured_solver): what the solve wins.
void BM_TrialFastOdeStep(benchmark::State& state) {
  TrialOptions o;
  o.structured_solver = false;
  RunTrials(state, o);
}
BENCHMARK(BM_TrialFastOdeStep)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// The fast path with the pan's body and handle as triangle meshes (ODE trimeshes; the same
// trial and foot): what meshes cost against the primitives they replace.
void BM_TrialFastMeshPan(benchmark::State& state) {
  RunTrials(state, TrialOptions{}, MeshPanModel());
}
BENCHMARK(BM_TrialFastMeshPan)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// Every shipped object with demonstrations, and the mesh pan with the pan's: the demonstration
// that object's library chose at 60 deg (rest, reach, grasp, lift, hold), replayed through the
// IK, so that the objects' trials compare like for like.
struct ObjectTrial {
  const char* object;
  const char* demos;  // the object whose demonstration it replays
};
constexpr ObjectTrial kObjectTrials[] = {{"pan", "pan"},
                                         {"pan_mesh", "pan"},
                                         {"saucepan", "saucepan"},
                                         {"sugar_box", "sugar_box"},
                                         {"mug", "mug"}};

void BM_TrialFastObject(benchmark::State& state) {
  const ObjectTrial& o = kObjectTrials[state.range(0)];
  state.SetLabel(o.object);
  const SimulationModel model(LoadRobotModel(DefaultRobotDescriptionPath()),
                              LoadSceneModel(DefaultSceneModelPath(), o.object));
  std::string file;
  for (const LibraryEntry& e : ReadGraspLibrary(DefaultGraspLibraryPath(o.demos)).entries) {
    if (e.theta_deg == 60.0) file = e.file;
  }
  const DemoReplay replay =
      ReplayDemoLog(model.robot(), ReadDemoLog(DefaultDemoDirectory(o.demos) / file));
  if (!replay.ok) {
    state.SkipWithError(replay.message.c_str());
    return;
  }
  RunTrials(state, TrialOptions{}, model, replay.trajectory);
}
BENCHMARK(BM_TrialFastObject)->DenseRange(0, 4)->Unit(benchmark::kMillisecond)->MinTime(3.0);

// The fast path at other steps (arg: step in microseconds).
void BM_TrialFastStep(benchmark::State& state) {
  TrialOptions o;
  o.time_step = state.range(0) * 1e-6;
  RunTrials(state, o);
}
BENCHMARK(BM_TrialFastStep)->Arg(1000)->Arg(2000)->Arg(5000)->Unit(benchmark::kMillisecond);

// The full-detail simulation: dynamic motor-driven arm, 1 ms, every step simulated.
void BM_TrialFull(benchmark::State& state) {
  TrialOptions o;
  o.fidelity = Fidelity::kFull;
  RunTrials(state, o);
}
BENCHMARK(BM_TrialFull)->Unit(benchmark::kMillisecond)->Iterations(3);

// The fast path with the wrist's motor-driven links dynamic (--fidelity fast-wrist; arg: step
// in microseconds).
void BM_TrialFastWrist(benchmark::State& state) {
  TrialOptions o;
  o.fidelity = Fidelity::kFastWristDynamic;
  o.time_step = state.range(0) * 1e-6;
  RunTrials(state, o);
}
BENCHMARK(BM_TrialFastWrist)->Arg(1000)->Arg(4000)->Unit(benchmark::kMillisecond);

// Fast and full detail on `trials` perturbed replays (seed 1, all cores) at the default
// noise and at `noise_scale` times it; prints the agreement counts.
int Agreement(int trials, double noise_scale) {
  RobustnessOptions o;
  o.trials = trials;
  o.seed = 1;
  o.perturbation.position_sigma *= noise_scale;
  o.perturbation.orientation_sigma *= noise_scale;
  o.perturbation.finger_sigma *= noise_scale;
  const RobustnessResult fast = EvaluateRobustness(Model(), Example(), o);
  o.trial.fidelity = Fidelity::kFull;
  const RobustnessResult full = EvaluateRobustness(Model(), Example(), o);
  int agree = 0, agree_success = 0;
  std::map<std::string, int> outcomes;
  for (int i = 0; i < trials; ++i) {
    const RobustnessTrial& a = fast.trials[i];
    const RobustnessTrial& b = full.trials[i];
    agree += a.outcome == b.outcome;
    agree_success += a.success() == b.success();
    ++outcomes[std::string(ToString(a.outcome))];
    if (a.outcome != b.outcome) {
      std::printf("  trial %d differs: fast %s (%s) | full %s (%s)\n", i,
                  std::string(ToString(a.outcome)).c_str(), a.reason.c_str(),
                  std::string(ToString(b.outcome)).c_str(), b.reason.c_str());
    }
  }
  std::printf(
      "noise x%.1f: %d trials, outcomes agree on %d, success or failure on %d; fast %d "
      "successes (score %.3f, 95%% [%.3f, %.3f]), full %d successes;",
      noise_scale, trials, agree, agree_success, fast.successes, fast.score, fast.ci95.lo,
      fast.ci95.hi, full.successes);
  for (const auto& [name, n] : outcomes) std::printf(" %s %d", name.c_str(), n);
  std::printf(
      "\n  fast %.1f s wall, %.1fx real time per core; full %.1f s wall, %.1fx per core; "
      "%d threads\n",
      fast.wall_time, fast.simulated_time / fast.cpu_time, full.wall_time,
      full.simulated_time / full.cpu_time, fast.threads);
  std::fflush(stdout);
  return trials - agree;
}

}  // namespace
}  // namespace graspsynth::bench

int main(int argc, char** argv) {
  int trials = 0;
  std::vector<double> scales = {1.0, 2.0};  // of the default noise
  for (int i = 1; i < argc; ++i) {
    if (std::strncmp(argv[i], "--agreement=", 12) == 0) trials = std::atoi(argv[i] + 12);
    if (std::strncmp(argv[i], "--noise=", 8) == 0) scales = {std::atof(argv[i] + 8)};
  }
  if (trials > 0) {
    int differ = 0;
    for (double scale : scales) differ += graspsynth::bench::Agreement(trials, scale);
    return differ == 0 ? 0 : 1;
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
