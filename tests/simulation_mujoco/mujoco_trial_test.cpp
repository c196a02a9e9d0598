// A trial in MuJoCo, judged by the ODE trial's judgement.

#include "simulation_mujoco/mujoco_trial.hpp"

#include <gtest/gtest.h>

#include "simulation_mujoco/mujoco_world.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using testing::HandKeptOpen;
using testing::ShippedSimulationModel;

class MujocoTrial : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!MujocoAvailable()) GTEST_SKIP() << "built without MuJoCo";
  }
};

TEST_F(MujocoTrial, AnOpenHandDoesNotLiftThePan) {
  const TrialResult r = RunMujocoTrial(ShippedSimulationModel(), HandKeptOpen(), TrialOptions{});
  EXPECT_EQ(r.outcome, TrialOutcome::kNotLifted) << r.BriefReport();
  EXPECT_LT(r.max_lift, 0.01);
  EXPECT_GT(r.statistics.dynamic_steps, 1000);
}

}  // namespace
}  // namespace graspsynth
