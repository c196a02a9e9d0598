// Analytic arm-angle IK against orocos KDL on the same PA-10-7C chain and the same reachable
// targets. Run: build/benchmarks/ik_benchmark (figures in benchmarks/README.md).

#include <benchmark/benchmark.h>

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>

#include "benchmarks/bench_fixtures.hpp"

namespace graspsynth::bench {
namespace {

constexpr int kTargetCount = 2000;
// a solver "succeeds" when its answer reproduces the target to this tolerance.
constexpr double kPoseTol = 1e-5;

const std::vector<ArmTarget>& Targets() {
  static const std::vector<ArmTarget> targets = ReachableTargets(kTargetCount);
  return targets;
}

bool Reproduces(const Vector7d& q, const Eigen::Isometry3d& X_WF) {
  const Eigen::Isometry3d X = ArmFlangePose(Robot().arm, q);
  return (X.translation() - X_WF.translation()).norm() < kPoseTol &&
         (X.linear() - X_WF.linear()).cwiseAbs().maxCoeff() < kPoseTol;
}

// the same chain for KDL, from the model's DH lengths (standard DH, joint about z).
KDL::Chain KdlChain() {
  const SrsLengths& l = Robot().arm.lengths();
  const double d[kArmDof] = {l.d_bs, 0.0, l.d_se, 0.0, l.d_ew, 0.0, l.d_wt};
  const double alpha[kArmDof] = {-M_PI / 2, M_PI / 2, -M_PI / 2, M_PI / 2, -M_PI / 2, M_PI / 2, 0};
  KDL::Chain chain;
  for (int i = 0; i < kArmDof; ++i) {
    chain.addSegment(
        KDL::Segment(KDL::Joint(KDL::Joint::RotZ), KDL::Frame::DH(0.0, alpha[i], d[i], 0.0)));
  }
  return chain;
}

KDL::Frame ToKdl(const Eigen::Isometry3d& X) {
  const Eigen::Matrix3d& R = X.linear();
  return KDL::Frame(KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0),
                                  R(2, 1), R(2, 2)),
                    KDL::Vector(X.translation().x(), X.translation().y(), X.translation().z()));
}

Vector7d FromKdl(const KDL::JntArray& q) {
  Vector7d out;
  for (int i = 0; i < kArmDof; ++i) out[i] = q(i);
  return out;
}

void ReportSuccess(benchmark::State& state, int64_t solved, int64_t attempts) {
  state.counters["success_rate"] =
      attempts > 0 ? static_cast<double>(solved) / static_cast<double>(attempts) : 0.0;
}

// Every in-limit solution over the eight branches at the target's own arm angle, timed over
// `targets` of `arm`; success means the branch of the configuration that made the target is
// among them with an answer that passes `accept(answer, target)`. The check runs after the
// timed loop, on the kept answers.
template <class Accept>
void TimeAllBranches(benchmark::State& state, const ArmModel& arm,
                     const std::vector<ArmTarget>& targets, Accept accept) {
  std::vector<std::vector<Vector7d>> answers(targets.size());
  size_t k = 0;
  for (auto _ : state) {
    const size_t i = k++ % targets.size();
    answers[i] = SolveArmIkAllBranches(arm, targets[i].X_WF, targets[i].psi);
  }
  int64_t solved = 0;
  for (size_t i = 0; i < std::min(k, targets.size()); ++i) {
    for (const Vector7d& q : answers[i]) {
      if (BranchOf(arm, q) == BranchOf(arm, targets[i].q) && accept(q, targets[i])) {
        ++solved;
        break;
      }
    }
  }
  ReportSuccess(state, solved, static_cast<int64_t>(std::min(k, targets.size())));
}

void BM_AnalyticIkAllBranches(benchmark::State& state) {
  TimeAllBranches(state, Robot().arm, Targets(),
                  [](const Vector7d& q, const ArmTarget& t) { return Reproduces(q, t.X_WF); });
}
BENCHMARK(BM_AnalyticIkAllBranches)->Repetitions(5)->ReportAggregatesOnly(true);

// the same on the KUKA LBR iiwa 14 (its robot file; A4's sign turned against the DH table, so
// the IK maps limits and solutions).
void BM_AnalyticIkAllBranchesIiwa(benchmark::State& state) {
  const ArmModel& arm = IiwaArm();
  static const std::vector<ArmTarget> targets = ReachableTargets(arm, kTargetCount);
  TimeAllBranches(state, arm, targets, [](const Vector7d& q, const ArmTarget& t) {
    return (q - t.q).cwiseAbs().maxCoeff() < kPoseTol;
  });
}
BENCHMARK(BM_AnalyticIkAllBranchesIiwa)->Repetitions(5)->ReportAggregatesOnly(true);

// one branch at one arm angle (the teleoperation case: branch and psi held continuous).
void BM_AnalyticIkOneBranch(benchmark::State& state) {
  const ArmModel& arm = Robot().arm;
  const std::vector<ArmTarget>& targets = Targets();
  std::vector<ArmIkSolution> answers(targets.size());
  size_t k = 0;
  for (auto _ : state) {
    const size_t i = k++ % targets.size();
    answers[i] =
        SolveArmIk(arm, targets[i].X_WF, targets[i].psi, BranchOf(targets[i].q), &targets[i].q);
  }
  int64_t solved = 0;
  for (size_t i = 0; i < std::min(k, targets.size()); ++i) {
    solved += answers[i].status == IkStatus::kOk && Reproduces(answers[i].q, targets[i].X_WF);
  }
  ReportSuccess(state, solved, static_cast<int64_t>(std::min(k, targets.size())));
}
BENCHMARK(BM_AnalyticIkOneBranch)->Repetitions(5)->ReportAggregatesOnly(true);

// the exact feasible arm-angle set of the target's branch; success means it contains the
// target's own arm angle.
void BM_FeasibleArmAngles(benchmark::State& state) {
  const ArmModel& arm = Robot().arm;
  int64_t solved = 0, attempts = 0;
  size_t k = 0;
  for (auto _ : state) {
    const ArmTarget& t = Targets()[k++ % Targets().size()];
    const ArmBranch b = BranchOf(t.q);
    const ArmTargetForm form = PrepareArmTarget(arm, t.X_WF, b.gc4);
    const std::vector<Interval> intervals = FeasibleArmAngles(arm, form, b.gc2, b.gc6);
    benchmark::DoNotOptimize(intervals.data());
    ++attempts;
    for (const Interval& iv : intervals) {
      if (iv.lo - 1e-9 <= t.psi && t.psi <= iv.hi + 1e-9) {
        ++solved;
        break;
      }
    }
  }
  ReportSuccess(state, solved, attempts);
}
BENCHMARK(BM_FeasibleArmAngles)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_AnalyticFk(benchmark::State& state) {
  const ArmModel& arm = Robot().arm;
  size_t k = 0;
  for (auto _ : state) {
    const Eigen::Isometry3d X = ArmFlangePose(arm, Targets()[k++ % Targets().size()].q);
    benchmark::DoNotOptimize(X.data());
  }
}
BENCHMARK(BM_AnalyticFk)->Repetitions(5)->ReportAggregatesOnly(true);

void BM_KdlFk(benchmark::State& state) {
  const KDL::Chain chain = KdlChain();
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::JntArray q(kArmDof);
  KDL::Frame X;
  size_t k = 0;
  for (auto _ : state) {
    const ArmTarget& t = Targets()[k++ % Targets().size()];
    for (int i = 0; i < kArmDof; ++i) q(i) = t.q[i];
    fk.JntToCart(q, X);
    benchmark::DoNotOptimize(X.p.data);
  }
}
BENCHMARK(BM_KdlFk)->Repetitions(5)->ReportAggregatesOnly(true);

// Newton-Raphson with joint limits from a fixed seed (all joints zero but a bent elbow, so the
// start is not singular), as a user of KDL would call it.
void BM_KdlIkNrJl(benchmark::State& state) {
  const ArmModel& arm = Robot().arm;
  const KDL::Chain chain = KdlChain();
  KDL::JntArray q_min(kArmDof), q_max(kArmDof), q_seed(kArmDof), q_out(kArmDof);
  for (int i = 0; i < kArmDof; ++i) {
    q_min(i) = arm.lower()[i];
    q_max(i) = arm.upper()[i];
  }
  q_seed(3) = 1.0;
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::ChainIkSolverVel_pinv ik_vel(chain);
  KDL::ChainIkSolverPos_NR_JL ik(chain, q_min, q_max, fk, ik_vel, 100, 1e-6);
  int64_t solved = 0, attempts = 0;
  size_t k = 0;
  for (auto _ : state) {
    const ArmTarget& t = Targets()[k++ % Targets().size()];
    const int rc = ik.CartToJnt(q_seed, ToKdl(t.X_WF), q_out);
    ++attempts;
    solved +=
        rc >= 0 && arm.WithinLimits(FromKdl(q_out), 1e-9) && Reproduces(FromKdl(q_out), t.X_WF);
  }
  ReportSuccess(state, solved, attempts);
}
BENCHMARK(BM_KdlIkNrJl)->Unit(benchmark::kMicrosecond)->Repetitions(3)->ReportAggregatesOnly(true);

// Levenberg-Marquardt (ignores joint limits) from the same seed; "success" here only asks that
// the pose is reproduced to kPoseTol, and the in-limit share is reported separately.
void BM_KdlIkLma(benchmark::State& state) {
  const ArmModel& arm = Robot().arm;
  const KDL::Chain chain = KdlChain();
  // equal weights on position (m) and orientation (rad): the default weights orientation by
  // 0.01, which stops with orientation errors near 1e-3 rad.
  Eigen::Matrix<double, 6, 1> weights = Eigen::Matrix<double, 6, 1>::Ones();
  KDL::ChainIkSolverPos_LMA ik(chain, weights, 1e-10, 500);
  KDL::JntArray q_seed(kArmDof), q_out(kArmDof);
  q_seed(3) = 1.0;
  int64_t solved = 0, in_limits = 0, converged = 0, attempts = 0;
  size_t k = 0;
  for (auto _ : state) {
    const ArmTarget& t = Targets()[k++ % Targets().size()];
    const int rc = ik.CartToJnt(q_seed, ToKdl(t.X_WF), q_out);
    ++attempts;
    converged += rc >= 0;
    const bool ok = rc >= 0 && Reproduces(FromKdl(q_out), t.X_WF);
    solved += ok;
    in_limits += ok && arm.WithinLimits(FromKdl(q_out), 1e-9);
  }
  ReportSuccess(state, solved, attempts);
  state.counters["converged_rate"] =
      attempts > 0 ? static_cast<double>(converged) / static_cast<double>(attempts) : 0.0;
  state.counters["in_limits_rate"] =
      attempts > 0 ? static_cast<double>(in_limits) / static_cast<double>(attempts) : 0.0;
}
BENCHMARK(BM_KdlIkLma)->Unit(benchmark::kMicrosecond)->Repetitions(3)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace graspsynth::bench

BENCHMARK_MAIN();
