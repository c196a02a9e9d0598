// The collision scene (collision/collision_scene.hpp) per call: moving the FCL scene to a state,
// robot-versus-world collision through the broad phase, and the hand-object signed distance.
// Run: build/benchmarks/collision_benchmark (figures in benchmarks/README.md).

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include "benchmarks/bench_fixtures.hpp"
#include "collision/collision_scene.hpp"

namespace graspsynth::bench {
namespace {

constexpr int kStateCount = 256;
constexpr double kTheta = 60.0 * M_PI / 180.0;

const SceneModel& Scene() {
  static const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  return scene;
}

const CollisionModel& Model() {
  static const CollisionModel model(Robot(), Scene());
  return model;
}

HandVector RandomHand(std::mt19937_64* rng) {
  HandVector f;
  for (int i = 0; i < kHandDof; ++i) {
    f[i] = std::uniform_real_distribution<double>(Robot().hand.lower()[i],
                                                  Robot().hand.upper()[i])(*rng);
  }
  return f;
}

// an in-limit IK solution for hand-mount pose X_WH (arm angle mid-way in the widest feasible
// interval of the first branch that has one).
std::optional<Vector7d> SolveWrist(const Eigen::Isometry3d& X_WH) {
  const auto s = SolveArmIkMidArc(Robot().arm, X_WH * Robot().X_FH.inverse());
  if (!s) return std::nullopt;
  return s->q;
}

// approach states: the hand palm down across the handle (pan at theta = 60 deg), its mount
// 0.08-0.25 m above the handle's axis anywhere along it, random finger joints. Mostly
// collision-free, some fingers touching the handle: the grasp refinement's queries.
const std::vector<RobotState>& ApproachStates() {
  static const std::vector<RobotState> states = [] {
    std::mt19937_64 rng(20261125);
    const HandleAxis& o = Scene().object.Handle("the collision benchmark");
    const double phi = kTheta + Scene().object_yaw_offset;
    const Eigen::Isometry3d X_WO = Scene().ObjectPose(kTheta);
    Eigen::Matrix3d R_WH;
    const Eigen::Vector3d x(0, 0, -1), z(-std::sin(phi), std::cos(phi), 0);
    R_WH << x, z.cross(x), z;
    std::vector<RobotState> out;
    while (static_cast<int>(out.size()) < kStateCount) {
      const double r =
          std::uniform_real_distribution<double>(o.start_radius + 0.05, o.end_radius - 0.03)(rng);
      const double h = std::uniform_real_distribution<double>(0.08, 0.25)(rng);
      Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
      X_WH.linear() = R_WH;
      X_WH.translation() =
          X_WO.translation() + r * Eigen::Vector3d(std::cos(phi), std::sin(phi), 0);
      X_WH.translation().z() = Scene().table.top_z + o.axis_height + h;
      const std::optional<Vector7d> q = SolveWrist(X_WH);
      if (q) out.push_back({*q, RandomHand(&rng)});
    }
    return out;
  }();
  return states;
}

// uniformly random in-limit states: many put the arm through the table.
const std::vector<RobotState>& RandomStates() {
  static const std::vector<RobotState> states = [] {
    std::vector<RobotState> out;
    std::mt19937_64 rng(7);
    for (const ArmTarget& t : ReachableTargets(kStateCount, 20261125)) {
      out.push_back({t.q, RandomHand(&rng)});
    }
    return out;
  }();
  return states;
}

const std::vector<RobotState>& States(const benchmark::State& state) {
  return state.range(0) == 0 ? ApproachStates() : RandomStates();
}

void BM_SetState(benchmark::State& state) {
  const CollisionModel& model = Model();
  const std::vector<RobotState>& states = States(state);
  CollisionData data(model);
  size_t k = 0;
  for (auto _ : state) {
    const RobotState& s = states[k++ % states.size()];
    SetState(model, s.q_arm, s.f, kTheta, &data);
    benchmark::DoNotOptimize(data.X_WG(0).data());
  }
}
BENCHMARK(BM_SetState)->Arg(0)->Repetitions(5)->ReportAggregatesOnly(true);

// SetState + every colliding pair of robot (arm, hand) against world (object, table).
void BM_SetStateCollideRobotVsWorld(benchmark::State& state) {
  const CollisionModel& model = Model();
  const std::vector<RobotState>& states = States(state);
  CollisionData data(model);
  int64_t calls = 0, in_collision = 0;
  size_t k = 0;
  for (auto _ : state) {
    const RobotState& s = states[k++ % states.size()];
    SetState(model, s.q_arm, s.f, kTheta, &data);
    const CollisionReport report = Collide(model, GroupSet::Robot(), GroupSet::World(), &data);
    ++calls;
    in_collision += report.collision();
  }
  state.counters["collision_rate"] = calls > 0 ? static_cast<double>(in_collision) / calls : 0.0;
}
BENCHMARK(BM_SetStateCollideRobotVsWorld)
    ->Arg(0)
    ->Arg(1)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

// SignedDistance(hand, object) alone: one data per state, each set once outside the loop.
void BM_SignedDistanceHandVsObject(benchmark::State& state) {
  const CollisionModel& model = Model();
  const std::vector<RobotState>& states = States(state);
  std::vector<std::unique_ptr<CollisionData>> data;
  for (const RobotState& s : states) {
    data.push_back(std::make_unique<CollisionData>(model));
    SetState(model, s.q_arm, s.f, kTheta, data.back().get());
  }
  int64_t calls = 0, evaluated = 0, penetrating = 0;
  size_t k = 0;
  for (auto _ : state) {
    const SignedDistanceResult r = SignedDistance(
        model, CollisionGroup::kHand, CollisionGroup::kObject, data[k++ % data.size()].get());
    ++calls;
    evaluated += r.pairs_evaluated;
    penetrating += r.distance < 0.0;
  }
  state.counters["pairs_evaluated"] = calls > 0 ? static_cast<double>(evaluated) / calls : 0.0;
  state.counters["penetrating_rate"] = calls > 0 ? static_cast<double>(penetrating) / calls : 0.0;
}
BENCHMARK(BM_SignedDistanceHandVsObject)->Arg(0)->Repetitions(5)->ReportAggregatesOnly(true);

// one state of a clearance profile: SetState + SignedDistance(robot, world).
void BM_SetStateSignedDistanceRobotVsWorld(benchmark::State& state) {
  const CollisionModel& model = Model();
  const std::vector<RobotState>& states = States(state);
  CollisionData data(model);
  size_t k = 0;
  for (auto _ : state) {
    const RobotState& s = states[k++ % states.size()];
    SetState(model, s.q_arm, s.f, kTheta, &data);
    const SignedDistanceResult r =
        SignedDistance(model, GroupSet::Robot(), GroupSet::World(), &data);
    benchmark::DoNotOptimize(r.distance);
  }
}
BENCHMARK(BM_SetStateSignedDistanceRobotVsWorld)
    ->Arg(0)
    ->Arg(1)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);

}  // namespace
}  // namespace graspsynth::bench

BENCHMARK_MAIN();
