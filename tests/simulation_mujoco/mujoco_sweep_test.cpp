// The MuJoCo sweep: each contact setting changes the exported model as its comment says, and a
// sweep gives the same runs whatever its thread count.

#include "simulation_mujoco/mujoco_sweep.hpp"

#include <gtest/gtest.h>

#include <map>

#include "common/errors.hpp"
#include "simulation_mujoco/mujoco_world.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using testing::ShippedSimulationModel;

// The value of attribute `name` in the first element of `xml` that starts with `element`.
std::string Attribute(const std::string& xml, const std::string& element, const std::string& name) {
  const size_t at = xml.find(element);
  if (at == std::string::npos) return "<no element " + element + ">";
  const size_t end = xml.find('>', at);
  const std::string tag = xml.substr(at, end - at);
  const size_t a = tag.find(" " + name + "=\"");
  if (a == std::string::npos) return "<no attribute " + name + ">";
  const size_t begin = a + name.size() + 3;
  return tag.substr(begin, tag.find('"', begin) - begin);
}

// The attributes the sweep may change: the option's, the contacts' defaults, an object geom's.
std::map<std::string, std::string> ContactAttributes(const std::string& xml) {
  return {{"timestep", Attribute(xml, "<option ", "timestep")},
          {"cone", Attribute(xml, "<option ", "cone")},
          {"impratio", Attribute(xml, "<option ", "impratio")},
          {"solref", Attribute(xml, "<geom contype=\"0\"", "solref")},
          {"solimp", Attribute(xml, "<geom contype=\"0\"", "solimp")},
          {"pair_solref", Attribute(xml, "<pair solref", "solref")},
          {"pair_solimp", Attribute(xml, "<pair solref", "solimp")},
          {"object_friction", Attribute(xml, "<geom name=\"object/0\"", "friction")}};
}

std::string ModelOf(MujocoContactSetting setting) {
  TrialOptions trial;
  MujocoTrialOptions mujoco;
  mujoco.time_step = 0.001;
  ApplyMujocoContactSetting(setting, &trial, &mujoco);
  return ExportMjcf(ShippedSimulationModel(), Placement{}, MujocoTrialMjcfOptions(trial, mujoco))
      .xml;
}

double First(const std::string& numbers) { return std::stod(numbers); }

TEST(MujocoSweep, EachSettingChangesTheModelAsStated) {
  const auto nominal = ContactAttributes(ModelOf(MujocoContactSetting::kNominal));
  EXPECT_EQ(nominal.at("timestep"), "0.001");
  EXPECT_EQ(nominal.at("cone"), "elliptic");
  EXPECT_EQ(nominal.at("impratio"), "10");
  EXPECT_EQ(nominal.at("solimp"), "0.95 0.99 0.001");
  EXPECT_DOUBLE_EQ(First(nominal.at("solref")), 0.002);  // the floor of two steps
  // what each setting changes; every other attribute stays the nominal's.
  const std::map<MujocoContactSetting, std::map<std::string, std::string>> changed = {
      {MujocoContactSetting::kMujocoImpedance,
       {{"solimp", "0.9 0.95 0.001"}, {"pair_solimp", "0.9 0.95 0.001"}}},
      {MujocoContactSetting::kPyramidalCone, {{"cone", "pyramidal"}}},
      {MujocoContactSetting::kSoftFriction, {{"impratio", "1"}}},
      {MujocoContactSetting::kCoarseStep, {{"timestep", "0.002"}}},
      {MujocoContactSetting::kFineStep, {{"timestep", "0.00050000000000000001"}}},
  };
  for (MujocoContactSetting setting : AllMujocoContactSettings()) {
    SCOPED_TRACE(std::string(ToString(setting)));
    const auto got = ContactAttributes(ModelOf(setting));
    for (const auto& [name, value] : nominal) {
      const std::string& v = got.at(name);
      if (changed.count(setting) && changed.at(setting).count(name)) {
        EXPECT_EQ(v, changed.at(setting).at(name)) << name;
      } else if (name == "solref" || name == "pair_solref") {
        // the time constant: x2 for the soft reference, the floor of two steps for the steps
        // (0.5 ms: the mapped 1.16 ms is above its floor of 1 ms); the damping ratio kept.
        const double expected = setting == MujocoContactSetting::kSoftReference ? 0.004
                                : setting == MujocoContactSetting::kCoarseStep  ? 0.004
                                : setting == MujocoContactSetting::kFineStep    ? -1.0
                                                                                : 0.002;
        if (expected > 0) {
          EXPECT_DOUBLE_EQ(First(v), expected) << name;
        } else {
          EXPECT_GT(First(v), 0.001);
          EXPECT_LT(First(v), 0.002);
        }
        EXPECT_EQ(v.substr(v.find(' ')), value.substr(value.find(' '))) << name;
      } else if (name == "object_friction" && setting == MujocoContactSetting::kLowFriction) {
        EXPECT_DOUBLE_EQ(First(v), 0.75 * First(value));
      } else {
        EXPECT_EQ(v, value) << name;
      }
    }
  }
}

TEST(MujocoSweep, NamesReadBackAndBadOptionsAreInputErrors) {
  for (MujocoContactSetting s : AllMujocoContactSettings()) {
    EXPECT_EQ(ParseMujocoContactSetting(ToString(s), "x"), s);
  }
  EXPECT_THROW(ParseMujocoContactSetting("hard", "--x"), InputError);
  MujocoSweepOptions o;
  EXPECT_TRUE(o.IsValid(nullptr));
  EXPECT_EQ(o.settings.size() * o.servos.size(), 16u);
  o.settings = {MujocoContactSetting::kNominal, MujocoContactSetting::kNominal};
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("twice"), std::string::npos);
  o.settings.clear();
  EXPECT_THROW(EvaluateMujocoSweep(ShippedSimulationModel(), ExampleTrajectory(), o), InputError);
}

TEST(MujocoSweep, SummaryTakesTheSuccessfulRunsSlip) {
  std::vector<MujocoSweepRun> runs(4);
  runs[0].outcome = runs[1].outcome = runs[2].outcome = TrialOutcome::kSuccess;
  runs[0].slip = 0.003;
  runs[1].slip = 0.001;
  runs[2].slip = 0.010;
  runs[3].slip = 0.5;  // a failure's slip counts for nothing
  runs[3].outcome = TrialOutcome::kDropped;
  runs[3].setting = MujocoContactSetting::kPyramidalCone;
  runs[3].servo = MujocoServo::kSoft;
  const MujocoSweepSummary s = SummarizeMujocoSweep(runs);
  EXPECT_EQ(s.runs, 4);
  EXPECT_EQ(s.successes, 3);
  EXPECT_DOUBLE_EQ(s.success_fraction, 0.75);
  EXPECT_DOUBLE_EQ(s.slip_median, 0.003);
  EXPECT_DOUBLE_EQ(s.slip_worst, 0.010);
  EXPECT_EQ(s.failing, "pyramidal/soft");
}

TEST(MujocoSweep, SameRunsWhateverTheThreadCount) {
  if (!MujocoAvailable()) GTEST_SKIP() << "built without MuJoCo";
  // the example grasp's first second (the hand closing on the handle) and a short hold: cheap,
  // and in contact.
  JointTrajectory shortened = ExampleTrajectory();
  while (shortened.samples.size() > 2 && shortened.samples.back().t > 1.0)
    shortened.samples.pop_back();
  MujocoSweepOptions o;
  o.trial.hold = 0.2;
  o.settings = {MujocoContactSetting::kPyramidalCone, MujocoContactSetting::kCoarseStep};
  o.threads = 1;
  const MujocoSweepResult one = EvaluateMujocoSweep(ShippedSimulationModel(), shortened, o);
  o.threads = 2;
  const MujocoSweepResult two = EvaluateMujocoSweep(ShippedSimulationModel(), shortened, o);
  ASSERT_EQ(one.runs.size(), 4u);
  ASSERT_EQ(two.runs.size(), 4u);
  for (size_t i = 0; i < one.runs.size(); ++i) {
    const MujocoSweepRun &a = one.runs[i], &b = two.runs[i];
    EXPECT_EQ(a.Label(), b.Label());
    EXPECT_EQ(a.outcome, b.outcome);
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_EQ(a.lift, b.lift);  // to the bit
    EXPECT_EQ(a.slip, b.slip);
    EXPECT_EQ(a.slip_angle, b.slip_angle);
  }
  EXPECT_EQ(one.runs[0].Label(), "pyramidal/stiff");
  EXPECT_EQ(one.runs[3].Label(), "step_2ms/soft");
  EXPECT_EQ(one.summary.failing, two.summary.failing);
  EXPECT_EQ(one.summary.successes, two.summary.successes);
}

}  // namespace
}  // namespace graspsynth
