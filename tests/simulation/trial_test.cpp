#include "simulation/trial.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using ::testing::HasSubstr;
using testing::ShippedSimulationModel;

TEST(TrialOptions, DefaultsAreValidAndBadValuesAreNamed) {
  std::string why;
  EXPECT_TRUE(TrialOptions{}.IsValid(&why)) << why;
  EXPECT_DOUBLE_EQ(TrialOptions{}.step(), 0.004);
  TrialOptions o;
  o.fidelity = Fidelity::kFull;
  EXPECT_DOUBLE_EQ(o.step(), 0.001);
  o.hold = -1.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("hold"));
  GS_EXPECT_THROW_WITH(RunTrial(ShippedSimulationModel(), ExampleTrajectory(), o), InputError,
                       "hold");
}

TEST(RunTrial, TheExampleLiftsTheObject) {
  const TrialResult r = RunTrial(ShippedSimulationModel(), ExampleTrajectory());
  EXPECT_EQ(r.outcome, TrialOutcome::kSuccess) << r.BriefReport();
  EXPECT_TRUE(r.success());
  EXPECT_GE(r.lift, 0.05);
  EXPECT_NEAR(r.lift, 0.10, 0.01);  // the wrist rises 10 cm and the pan stays level
  EXPECT_LT(r.max_penetration, 0.002);
  EXPECT_NEAR(r.simulated_time, ExampleTrajectory().duration() + 1.0, 1e-6);
  EXPECT_THAT(r.reason, HasSubstr("touching only the hand"));
  // the pan hangs level in the hand.
  EXPECT_GT(r.final_object_pose.linear()(2, 2), std::cos(5.0 * M_PI / 180.0));
  // free space was not simulated in contact detail.
  EXPECT_GT(r.statistics.kinematic_steps, 0);
  EXPECT_GT(r.statistics.dynamic_steps, 0);
  EXPECT_EQ(r.counts.bodies, 28);
  EXPECT_EQ(r.counts.joints, 20);
}

TEST(RunTrial, FullFidelityAgreesOnTheExample) {
  TrialOptions full;
  full.fidelity = Fidelity::kFull;
  const TrialResult r = RunTrial(ShippedSimulationModel(), ExampleTrajectory(), full);
  EXPECT_EQ(r.outcome, TrialOutcome::kSuccess) << r.BriefReport();
  EXPECT_NEAR(r.lift, 0.10, 0.01);
  EXPECT_EQ(r.statistics.kinematic_steps, 0);
  EXPECT_EQ(r.counts.joints, 27);  // the arm's seven motor-driven hinges too
  const TrialResult fast = RunTrial(ShippedSimulationModel(), ExampleTrajectory());
  EXPECT_NEAR(r.lift, fast.lift, 0.005);
  EXPECT_NEAR((r.final_object_pose.translation() - fast.final_object_pose.translation()).norm(),
              0.0, 0.01);
}

// The fast path with a dynamic wrist: E2, W1 and W2 are motor-driven hinges (their 10-15 N m
// motors can yield to the grasp), the rest of the arm kinematic; at 1 ms it lifts the example as
// full detail does.
TEST(RunTrial, TheDynamicWristFastPathAgreesWithFullDetail) {
  TrialOptions wrist;
  wrist.fidelity = Fidelity::kFastWristDynamic;
  EXPECT_DOUBLE_EQ(wrist.step(), 0.004);
  wrist.time_step = 0.001;
  const TrialResult r = RunTrial(ShippedSimulationModel(), ExampleTrajectory(), wrist);
  EXPECT_EQ(r.outcome, TrialOutcome::kSuccess) << r.BriefReport();
  EXPECT_EQ(r.counts.joints, 20 + 3);
  EXPECT_EQ(r.counts.dynamic_bodies, 21 + 3);
  EXPECT_GT(r.statistics.kinematic_steps, 0);  // free space is still skipped
  TrialOptions full;
  full.fidelity = Fidelity::kFull;
  const TrialResult f = RunTrial(ShippedSimulationModel(), ExampleTrajectory(), full);
  EXPECT_NEAR(r.lift, f.lift, 0.002);
}

// Runs trajectory t with options a and b, which must solve the same physics: the same outcome
// and step counts, the object within object_m and the fingers within hand_rad at every
// recorded state.
void ExpectTheSameTrial(const JointTrajectory& t, TrialOptions a_options, TrialOptions b_options,
                        double object_m, double hand_rad, TrialResult* a_out, TrialResult* b_out) {
  a_options.record_interval = b_options.record_interval = 0.1;
  const TrialResult a = RunTrial(ShippedSimulationModel(), t, a_options);
  const TrialResult b = RunTrial(ShippedSimulationModel(), t, b_options);
  EXPECT_EQ(b.outcome, a.outcome) << b.BriefReport();
  EXPECT_EQ(b.statistics.dynamic_steps, a.statistics.dynamic_steps);
  EXPECT_EQ(b.statistics.kinematic_steps, a.statistics.kinematic_steps);
  EXPECT_NEAR(b.lift, a.lift, object_m);
  ASSERT_EQ(b.states.size(), a.states.size());
  for (size_t i = 0; i < a.states.size(); ++i) {
    EXPECT_LT((b.states[i].X_WO.translation() - a.states[i].X_WO.translation()).norm(), object_m)
        << "at " << a.states[i].t << " s";
    EXPECT_LT((b.states[i].hand - a.states[i].hand).cwiseAbs().maxCoeff(), hand_rad)
        << "at " << a.states[i].t << " s";
  }
  *a_out = a;
  *b_out = b;
}

// The fingers on kinematic mounts of their own (the default) and on the one wrist body are the
// same constraints solved as different systems: the same trial, step for step, to roundoff
// (1e-13 m measured).
TEST(RunTrial, TheFingerMountsChangeTheSolveNotTheTrial) {
  TrialOptions shared;
  shared.finger_mounts = false;
  shared.structured_solver = false;  // ODE's islands are what the mounts change
  TrialOptions mounted = shared;
  mounted.finger_mounts = true;
  TrialResult a, b;
  ExpectTheSameTrial(ExampleTrajectory(), shared, mounted, 1e-6, 1e-5, &a, &b);
  EXPECT_EQ(a.outcome, TrialOutcome::kSuccess) << a.BriefReport();
  // the mounts are no bodies of the robot's.
  EXPECT_EQ(b.counts.bodies, a.counts.bodies);
}

// The structured solve (WorldOptions::structured_solver) solves ODE's problem of each step
// with the fingers' joint rows eliminated first: the same trial as dWorldStep, step for step.
// The example's grasp (3e-12 m and 8e-11 rad measured on the final code of 2026-12-06;
// leaving out the gyroscopic torque alone moves it by 8e-7 m), and a hand driven through the
// table, whose fingers press on their stops with their motors and whose palm (a kinematic
// body) pushes the object (1.2e-10 m and 1.1e-8 rad measured).
TEST(RunTrial, TheStructuredSolverStepsAsOdeDoes) {
  TrialOptions ode;
  ode.structured_solver = false;
  TrialOptions structured = ode;
  structured.structured_solver = true;
  TrialResult a, b;
  ExpectTheSameTrial(ExampleTrajectory(), ode, structured, 1e-9, 1e-7, &a, &b);
  EXPECT_EQ(a.outcome, TrialOutcome::kSuccess) << a.BriefReport();
  ExpectTheSameTrial(testing::HandThroughTable(), ode, structured, 1e-6, 1e-5, &a, &b);
  EXPECT_EQ(a.outcome, TrialOutcome::kCollision) << a.BriefReport();
}

// The broad phase (the pairs of geoms whose categories may touch, in the order of ODE's simple
// space) finds the contacts dSpaceCollide finds, in its order: the same trial, bit for bit, in
// a grasp and in a hand driven through the table.
TEST(RunTrial, TheBroadPhaseFindsOdesPairsInOdesOrder) {
  TrialOptions ode;
  ode.ode_broad_phase = true;
  ode.record_interval = 0.004;
  TrialOptions ours = ode;
  ours.ode_broad_phase = false;
  for (const JointTrajectory& t : {ExampleTrajectory(), testing::HandThroughTable()}) {
    const TrialResult a = RunTrial(ShippedSimulationModel(), t, ode);
    const TrialResult b = RunTrial(ShippedSimulationModel(), t, ours);
    EXPECT_EQ(b.outcome, a.outcome);
    EXPECT_EQ(b.reason, a.reason);
    EXPECT_EQ(b.statistics.dynamic_steps, a.statistics.dynamic_steps);
    EXPECT_EQ(b.statistics.max_contacts, a.statistics.max_contacts);
    ASSERT_EQ(b.states.size(), a.states.size());
    for (size_t i = 0; i < a.states.size(); ++i) {
      ASSERT_EQ(b.states[i].X_WO.matrix(), a.states[i].X_WO.matrix()) << "at " << a.states[i].t;
      ASSERT_EQ(b.states[i].hand, a.states[i].hand) << "at " << a.states[i].t;
    }
  }
}

TEST(RunTrial, TheHandKeptOpenDoesNotLift) {
  for (Fidelity fidelity : {Fidelity::kFast, Fidelity::kFull}) {
    TrialOptions o;
    o.fidelity = fidelity;
    const TrialResult r = RunTrial(ShippedSimulationModel(), testing::HandKeptOpen(), o);
    EXPECT_EQ(r.outcome, TrialOutcome::kNotLifted) << r.BriefReport();
    EXPECT_FALSE(r.success());
    EXPECT_THAT(r.reason, HasSubstr("not lifted"));
    EXPECT_LT(r.lift, 0.005);
    if (fidelity == Fidelity::kFast) break;  // the full run is the slow one; once is enough
  }
}

TEST(RunTrial, DrivingTheHandThroughTheTableIsACollision) {
  const TrialResult r = RunTrial(ShippedSimulationModel(), testing::HandThroughTable());
  EXPECT_EQ(r.outcome, TrialOutcome::kCollision) << r.BriefReport();
  EXPECT_THAT(r.reason, HasSubstr("hit the table"));
  // decided at the collision: the rest is not simulated.
  EXPECT_LT(r.simulated_time, r.planned_time);
}

TEST(RunTrial, ACommandBeyondAJointLimitStopsTheTrial) {
  JointTrajectory t = ExampleTrajectory();
  // E1 beyond its +-137 deg halfway through the reach (the file check would refuse this).
  for (size_t i = 40; i < t.samples.size(); ++i) t.samples[i].arm[3] = 2.5;
  const TrialResult r = RunTrial(ShippedSimulationModel(), t);
  EXPECT_EQ(r.outcome, TrialOutcome::kJointLimit) << r.BriefReport();
  EXPECT_THAT(r.reason, HasSubstr("E1 commanded to 2.5"));
}

TEST(RunTrial, InstabilityIsAFailedTrialNeverACrash) {
  // a runaway object (energy check) and a NaN state (finite check) half-way through.
  for (double v : {50.0, std::numeric_limits<double>::quiet_NaN()}) {
    bool injected = false;
    const TrialResult r =
        RunTrial(ShippedSimulationModel(), ExampleTrajectory(), {}, [&](SimulationData& data) {
          if (!injected && data.time() > 4.5) {
            data.SetObjectVelocity(Eigen::Vector3d(v, 0, 0), Eigen::Vector3d::Zero());
            injected = true;
          }
        });
    EXPECT_EQ(r.outcome, TrialOutcome::kUnstable) << r.BriefReport();
    EXPECT_THAT(r.reason, HasSubstr("numerical instability"));
    EXPECT_FALSE(r.success());
  }
}

TEST(RunTrial, RecordsTheStates) {
  TrialOptions o;
  o.record_interval = 0.1;
  const TrialResult r = RunTrial(ShippedSimulationModel(), ExampleTrajectory(), o);
  ASSERT_GE(r.states.size(), 60u);
  EXPECT_EQ(r.states.front().t, 0.0);
  for (size_t i = 1; i < r.states.size(); ++i) {
    EXPECT_NEAR(r.states[i].t - r.states[i - 1].t, 0.1, 0.0041);
  }
  EXPECT_TRUE(
      testing::MatricesNear(r.states.front().arm, ExampleTrajectory().samples[0].arm, 1e-12));
  EXPECT_TRUE(testing::PosesNear(r.states.back().X_WO, r.final_object_pose, 1e-3));
}

}  // namespace
}  // namespace graspsynth
