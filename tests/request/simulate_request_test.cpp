// Tests of the requests of simulate, Python's simulate and robustness, and scripted-grasp
// (request/simulate_request.hpp): their options are described once, with the library's
// defaults, are checked naming the option, are read from a config file, and map onto the
// library's options.

#include "request/simulate_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::request {
namespace {

TEST(SimulateRequest, EveryOptionIsWellDescribed) {
  ExpectWellDescribed(SimulateOptions());
  ExpectWellDescribed(TrialRequestOptions());
  ExpectWellDescribed(RobustnessRequestOptions());
  ExpectWellDescribed(ScriptedGraspRequestOptions());
}

TEST(SimulateRequest, TheDefaultsAreTheLibrarys) {
  const RobustnessOptions library;
  const RobustnessOptions ro = ToRobustnessOptions(SimulateRequest{});
  EXPECT_EQ(ro.trials, 1);  // --perturb 0: the nominal trial only
  EXPECT_EQ(ro.seed, library.seed);
  EXPECT_EQ(ro.threads, library.threads);
  EXPECT_EQ(ro.perturbation.time_scale_min, library.perturbation.time_scale_min);
  EXPECT_EQ(ro.perturbation.time_scale_max, library.perturbation.time_scale_max);
  EXPECT_EQ(ro.perturbation.position_sigma, library.perturbation.position_sigma);
  EXPECT_DOUBLE_EQ(ro.perturbation.orientation_sigma, library.perturbation.orientation_sigma);
  EXPECT_DOUBLE_EQ(ro.perturbation.finger_sigma, library.perturbation.finger_sigma);
  EXPECT_EQ(ro.perturbation.physics.enabled, library.perturbation.physics.enabled);
  EXPECT_EQ(ro.perturbation.physics.friction, library.perturbation.physics.friction);
  EXPECT_EQ(ro.trial.fidelity, library.trial.fidelity);
  EXPECT_EQ(ro.trial.time_step, library.trial.time_step);
  EXPECT_EQ(ro.trial.hold, library.trial.hold);

  const TrialOptions trial = ToTrialOptions(TrialRequest{});
  EXPECT_EQ(trial.fidelity, TrialOptions{}.fidelity);
  EXPECT_EQ(trial.record_interval, TrialOptions{}.record_interval);

  const RobustnessOptions python = ToRobustnessOptions(RobustnessRequest{});
  EXPECT_EQ(python.trials, 20);
  EXPECT_EQ(python.seed, library.seed);
  EXPECT_EQ(python.perturbation.position_sigma, library.perturbation.position_sigma);
  EXPECT_EQ(python.perturbation.physics.mass, library.perturbation.physics.mass);

  const ScriptedGraspOptions scripted = ToScriptedGraspOptions(ScriptedGraspRequest{});
  EXPECT_EQ(scripted.theta_deg, ScriptedGraspOptions{}.theta_deg);
  EXPECT_EQ(scripted.grasp_radius, ScriptedGraspOptions{}.grasp_radius);
  EXPECT_FALSE(scripted.closed.has_value());  // the robot's
  EXPECT_FALSE(scripted.keep_open);
}

TEST(SimulateRequest, OptionsMapOntoTheLibrarys) {
  const OptionList<SimulateRequest>& options = SimulateOptions();
  SimulateRequest r;
  Apply(*FindOption(options, "perturb"), Value(int64_t{5}), "perturb", &r);
  Apply(*FindOption(options, "fidelity"), Value(std::string("full")), "fidelity", &r);
  Apply(*FindOption(options, "orientation_noise"), Value(4.0), "orientation_noise", &r);
  Apply(*FindOption(options, "mass_spread"), Value(0.5), "mass_spread", &r);
  Apply(*FindOption(options, "at"), Value(std::vector<double>{-0.3, 0.9}), "at", &r);
  const RobustnessOptions ro = ToRobustnessOptions(r);
  EXPECT_EQ(ro.trials, 5);
  EXPECT_EQ(ro.trial.fidelity, Fidelity::kFull);
  EXPECT_EQ(ro.perturbation.orientation_sigma, 4.0 * kDeg);
  EXPECT_EQ(ro.perturbation.physics.mass, 0.5);
  ASSERT_TRUE(r.at.has_value());
  EXPECT_EQ(*r.at, Eigen::Vector2d(-0.3, 0.9));

  RobustnessRequest p;
  p.noise_scale = 2.0;
  p.physics.enabled = false;
  const RobustnessOptions scaled = ToRobustnessOptions(p);
  EXPECT_EQ(scaled.perturbation.position_sigma, 2.0 * PerturbationOptions{}.position_sigma);
  EXPECT_FALSE(scaled.perturbation.physics.enabled);

  ScriptedGraspRequest s;
  s.keep_open = true;
  EXPECT_TRUE(ToScriptedGraspOptions(s).keep_open);
}

TEST(SimulateRequest, AValueOutOfRangeIsAnInputErrorNamingTheOption) {
  SimulateRequest r;
  const OptionList<SimulateRequest>& options = SimulateOptions();
  GS_EXPECT_THROW_WITH(Apply(*FindOption(options, "perturb"), Value(int64_t{-1}), "--perturb", &r),
                       InputError, "--perturb: must be >= 0 (got -1)");
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(options, "fidelity"), Value(std::string("exact")), "--fidelity", &r),
      InputError, "--fidelity: 'exact' is not one of fast, fast-wrist, full");
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(options, "threads"), Value(int64_t{2000}), "--threads", &r), InputError,
      "--threads: must be [0, 1024]");
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(options, "record_interval"), Value(0.0), "--record-interval", &r),
      InputError, "--record-interval: must be > 0");
  // the checks that span options are the library's, through RequireValid.
  r.time_scale_min = 2.0;
  GS_EXPECT_THROW_WITH(ToRobustnessOptions(r), InputError, "bad perturbation option",
                       "time scale range");
  r = SimulateRequest{};
  r.trial.time_step = 0.5;
  GS_EXPECT_THROW_WITH(ToRobustnessOptions(r), InputError, "bad simulation option", "time_step");
  RobustnessRequest p;
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(RobustnessRequestOptions(), "trials"), Value(int64_t{0}), "trials", &p),
      InputError, "trials: must be >= 1 (got 0)");
  ScriptedGraspRequest s;
  GS_EXPECT_THROW_WITH(Apply(*FindOption(ScriptedGraspRequestOptions(), "grasp_radius"), Value(0.0),
                             "--grasp-radius", &s),
                       InputError, "--grasp-radius: must be > 0 (got 0)");
}

TEST(SimulateRequest, AConfigFileSetsOptionsByName) {
  SimulateRequest r;
  const auto set =
      ApplyConfig(SimulateOptions(),
                  WriteConfig("simulate.json",
                              R"({"perturb": 3, "fidelity": "fast-wrist", "at": [-0.3, 0.9],
                      "stiffness_range": [0.25, 4], "physics": false})"),
                  &r);
  EXPECT_EQ(set.size(), 5u);
  EXPECT_EQ(r.perturb, 3);
  EXPECT_EQ(r.trial.fidelity, "fast-wrist");
  EXPECT_EQ(r.physics.stiffness_max, 4.0);
  EXPECT_FALSE(r.physics.enabled);
  ASSERT_TRUE(r.at.has_value());
  GS_EXPECT_THROW_WITH(
      ApplyConfig(SimulateOptions(), WriteConfig("bad.json", R"({"fidelty": "full"})"), &r),
      InputError, "field 'fidelty' is not an option", "did you mean 'fidelity'?");
  GS_EXPECT_THROW_WITH(
      ApplyConfig(SimulateOptions(), WriteConfig("range.json", R"({"sensitivity": -2})"), &r),
      InputError, "field 'sensitivity'");
}

}  // namespace
}  // namespace graspsynth::request
