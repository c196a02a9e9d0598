#include "simulation/robustness.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using testing::ShippedSimulationModel;

TEST(WilsonInterval, MatchesKnownValues) {
  const Interval all = WilsonInterval(10, 10);
  EXPECT_NEAR(all.lo, 0.7225, 1e-4);
  EXPECT_DOUBLE_EQ(all.hi, 1.0);
  const Interval none = WilsonInterval(0, 10);
  EXPECT_DOUBLE_EQ(none.lo, 0.0);
  EXPECT_NEAR(none.hi, 0.2775, 1e-4);
  const Interval half = WilsonInterval(50, 100);
  EXPECT_NEAR(half.lo, 0.4038, 1e-4);
  EXPECT_NEAR(half.hi, 0.5962, 1e-4);
  const Interval empty = WilsonInterval(0, 0);
  EXPECT_EQ(empty.lo, 0.0);
  EXPECT_EQ(empty.hi, 1.0);
}

TEST(RobustnessOptions, RejectsBadValues) {
  RobustnessOptions o;
  o.trials = 0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  GS_EXPECT_THROW_WITH(EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o),
                       InputError, "trials");
}

// ODE is not instrumented for ThreadSanitizer, and two worlds stepped on two threads crash
// Debian's ODE without per-world threading implementations: the proof of the parallel scheme
// is that many trials run concurrently give, bit for bit, what they give one after another.
TEST(EvaluateRobustness, TheThreadCountChangesNoBitOfAnyTrial) {
  RobustnessOptions o;
  o.trials = testing::Scaled(12, 4);
  o.seed = 42;
  o.threads = 1;
  o.perturbation.physics.enabled = false;  // the motion's noise alone (see below for both)
  std::vector<int> reported;
  const RobustnessResult one = EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o,
                                                  [&](int done, int total) {
                                                    EXPECT_EQ(total, o.trials);
                                                    reported.push_back(done);
                                                  });
  ASSERT_EQ(static_cast<int>(reported.size()), o.trials);
  EXPECT_EQ(reported.back(), o.trials);
  EXPECT_EQ(one.threads, 1);
  for (int threads : {2, 3}) {
    o.threads = threads;
    const RobustnessResult many =
        EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
    EXPECT_EQ(many.threads, threads);
    ASSERT_EQ(many.trials.size(), one.trials.size());
    for (size_t i = 0; i < one.trials.size(); ++i) {
      const RobustnessTrial& a = one.trials[i];
      const RobustnessTrial& b = many.trials[i];
      EXPECT_EQ(a.index, b.index);
      EXPECT_EQ(a.time_scale, b.time_scale);
      EXPECT_EQ(a.outcome, b.outcome) << i;
      EXPECT_EQ(a.reason, b.reason) << i;
      EXPECT_EQ(a.lift, b.lift) << i;
      EXPECT_EQ(a.dynamic_steps, b.dynamic_steps) << i;
      // final object poses exactly equal
      EXPECT_TRUE(a.final_object_pose.matrix() == b.final_object_pose.matrix())
          << i << "\n"
          << a.final_object_pose.matrix() << "\n"
          << b.final_object_pose.matrix();
    }
    EXPECT_EQ(many.successes, one.successes);
    EXPECT_EQ(many.score, one.score);
  }
  // the example is robust (its perturbed replays in benchmarks/README.md, "Simulation").
  EXPECT_GE(one.score, 0.75);
  EXPECT_GT(one.ci95.hi, one.score - 1e-12);
  EXPECT_LT(one.ci95.lo, one.score + 1e-12);
}

TEST(EvaluateRobustnessUntil, StopsAfterTheFirstPrefixTheRuleAcceptsOnAnyThreadCount) {
  RobustnessOptions o;
  o.trials = testing::Scaled(6, 4);
  o.seed = 7;
  o.perturbation.physics.enabled = false;
  o.threads = 1;
  const RobustnessResult full =
      EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
  // the rule: two successes are enough. The expected end is just after the second success.
  int expected = o.trials;
  for (int i = 0, s = 0; i < o.trials; ++i) {
    s += full.trials[static_cast<size_t>(i)].success();
    if (s == 2) {
      expected = i + 1;
      break;
    }
  }
  ASSERT_LT(expected, o.trials) << "the example should succeed at least twice";
  std::vector<int> seen;  // the prefix lengths the rule was asked about
  for (int threads : {1, 2, 3}) {
    SCOPED_TRACE(threads);
    o.threads = threads;
    seen.clear();
    int last_done = -1, last_total = -1;
    const RobustnessResult r = EvaluateRobustnessUntil(
        ShippedSimulationModel(), ExampleTrajectory(), o,
        [&](int successes, int failures) {
          seen.push_back(successes + failures);
          return successes >= 2;
        },
        [&](int done, int total) {
          last_done = done;
          last_total = total;
        });
    ASSERT_EQ(static_cast<int>(r.trials.size()), expected);
    for (int k = 0; k < expected; ++k) {
      EXPECT_EQ(seen[static_cast<size_t>(k)], k + 1);  // every prefix, in order, once
      const RobustnessTrial& a = full.trials[static_cast<size_t>(k)];
      const RobustnessTrial& b = r.trials[static_cast<size_t>(k)];
      EXPECT_EQ(a.outcome, b.outcome);
      EXPECT_TRUE(a.final_object_pose.matrix() == b.final_object_pose.matrix());
    }
    EXPECT_EQ(static_cast<int>(seen.size()), expected);
    EXPECT_EQ(r.successes, 2);
    EXPECT_EQ(r.score, 2.0 / expected);
    EXPECT_EQ(r.ci95.lo, WilsonInterval(2, expected).lo);
    EXPECT_EQ(last_done, expected);
    EXPECT_EQ(last_total, expected);
  }
  // a rule that never holds runs them all.
  const RobustnessResult never = EvaluateRobustnessUntil(
      ShippedSimulationModel(), ExampleTrajectory(), o, [](int, int) { return false; });
  EXPECT_EQ(never.trials.size(), full.trials.size());
  EXPECT_EQ(never.successes, full.successes);
}

TEST(FailureSummary, CountsFailedReplaysByOutcomeInEnumOrder) {
  RobustnessResult result;
  for (TrialOutcome o : {TrialOutcome::kNotLifted, TrialOutcome::kSuccess, TrialOutcome::kDropped,
                         TrialOutcome::kNotLifted}) {
    RobustnessTrial t;
    t.outcome = o;
    result.trials.push_back(t);
  }
  EXPECT_EQ(FailureSummary(result), "not_lifted 2, dropped 1");
  result.trials = {RobustnessTrial{}};
  result.trials[0].outcome = TrialOutcome::kSuccess;
  EXPECT_EQ(FailureSummary(result), "");
}

void ExpectTheSameSuccesses(const RobustnessResult& fast, const RobustnessResult& full) {
  ASSERT_EQ(fast.trials.size(), full.trials.size());
  for (size_t i = 0; i < fast.trials.size(); ++i) {
    EXPECT_EQ(fast.trials[i].success(), full.trials[i].success())
        << "trial " << i << ": fast " << fast.trials[i].reason << " | full "
        << full.trials[i].reason;
  }
}

// A small version of benchmarks/simulation_benchmark.cpp's agreement study: the fast path
// (kinematic arm, kinematic free space, 4 ms, early stop) and the full-detail simulation
// (dynamic arm, 1 ms, everything simulated) agree on the success of every replay, which is what
// the robustness score counts. Twice the default noise, so that some replays fail. The failure
// category can differ on a borderline failure: a pan pushed 31 mm by the fast path and a little
// less by the full one is "knocked_over" in one and "not_lifted" in the other (the 30 mm
// threshold of TrialOptions::knocked_shift); benchmarks/README.md counts those cases.
TEST(EvaluateRobustness, FastAndFullDetailAgreeOnEveryOutcome) {
  RobustnessOptions o;
  o.trials = testing::Scaled(6, 2);
  o.seed = 7;
  o.threads = 2;
  o.perturbation.position_sigma *= 2.0;
  o.perturbation.orientation_sigma *= 2.0;
  o.perturbation.finger_sigma *= 2.0;
  o.perturbation.physics.enabled = false;  // the motion's noise alone (see below for both)
  const RobustnessResult fast =
      EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
  o.trial.fidelity = Fidelity::kFull;
  const RobustnessResult full =
      EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
  ExpectTheSameSuccesses(fast, full);
}

// The physics perturbation draws per replay from the replay's own stream: the thread count
// changes none of its draws and none of its results.
TEST(EvaluateRobustness, PhysicsPerturbedReplaysAreTheSameOnAnyThreadCount) {
  RobustnessOptions o;
  o.trials = testing::Scaled(6, 3);
  o.seed = 9;
  o.threads = 1;
  ASSERT_TRUE(o.perturbation.physics.enabled);  // the default
  const RobustnessResult one = EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
  o.threads = 2;
  const RobustnessResult two = EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
  bool varied = false;
  for (size_t i = 0; i < one.trials.size(); ++i) {
    const RobustnessTrial& a = one.trials[i];
    const RobustnessTrial& b = two.trials[i];
    EXPECT_EQ(a.outcome, b.outcome) << i;
    EXPECT_EQ(a.physics.variation.object_hand_friction, b.physics.variation.object_hand_friction);
    EXPECT_EQ(a.physics.time_step, b.physics.time_step);
    EXPECT_EQ(a.hold.end_tilt, b.hold.end_tilt) << i;
    EXPECT_TRUE(a.final_object_pose.matrix() == b.final_object_pose.matrix()) << i;
    varied = varied || !a.physics.variation.IsNominal();
  }
  EXPECT_TRUE(varied);
  // the motion's draws come first: the time scales are those of the motion-only replays.
  o.perturbation.physics.enabled = false;
  EXPECT_EQ(RunRobustnessTrial(ShippedSimulationModel(), ExampleTrajectory(), o, 1).time_scale,
            one.trials[1].time_scale);
}

TEST(EvaluateSensitivity, OneCellPerFactorEndWithItsOwnPhysics) {
  RobustnessOptions o;
  o.trials = 1;
  o.seed = 3;
  o.threads = 2;
  int last = 0;
  const SensitivityResult s = EvaluateSensitivity(ShippedSimulationModel(), ExampleTrajectory(), o,
                                                  [&](int done, int) { last = done; });
  ASSERT_EQ(s.rows.size(), AllPhysicsFactors().size());
  EXPECT_EQ(last, static_cast<int>(2 * s.rows.size()));
  for (size_t f = 0; f < s.rows.size(); ++f) {
    EXPECT_EQ(s.rows[f].factor, AllPhysicsFactors()[f]);
    for (const SensitivityCell* cell : {&s.rows[f].low, &s.rows[f].high}) {
      EXPECT_EQ(cell->trials, 1);
      EXPECT_LE(cell->successes, 1);
      EXPECT_EQ(cell->failures.empty(), cell->successes == 1);
    }
    const PhysicsFactor factor = s.rows[f].factor;
    const Eigen::Vector3d com = SensitivityComDirection(ShippedSimulationModel());
    EXPECT_EQ(s.rows[f].low.physics.variation,
              PhysicsAtEnd(o.perturbation.physics, factor, false, com).variation);
    EXPECT_EQ(s.rows[f].high.physics.variation,
              PhysicsAtEnd(o.perturbation.physics, factor, true, com).variation);
  }
  // a cell's replay is the robustness replay of the same index with the cell's physics.
  const SensitivityCell& fine = s.rows[static_cast<size_t>(PhysicsFactor::kStep)].high;
  EXPECT_EQ(fine.physics.time_step, o.perturbation.physics.fine_step);
  const RobustnessTrial same =
      RunReplayWithPhysics(ShippedSimulationModel(), ExampleTrajectory(), o, 0, fine.physics);
  EXPECT_EQ(same.success() ? 1 : 0, fine.successes);
}

// The fidelities also agree under the physics perturbation (a full trial runs at 1 ms, so a
// replay drawn at the fine step differs from its fast twin only in the arm model).
TEST(EvaluateRobustness, FastAndFullDetailAgreeUnderThePhysicsPerturbation) {
  RobustnessOptions o;
  o.trials = testing::Scaled(6, 2);
  o.seed = 13;
  o.threads = 2;
  ASSERT_TRUE(o.perturbation.physics.enabled);
  const RobustnessResult fast =
      EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
  o.trial.fidelity = Fidelity::kFull;
  o.perturbation.physics.fine_step_probability = 0.0;  // full detail is at 1 ms throughout
  const RobustnessResult full =
      EvaluateRobustness(ShippedSimulationModel(), ExampleTrajectory(), o);
  ExpectTheSameSuccesses(fast, full);
}

}  // namespace
}  // namespace graspsynth
