#include "gate/hold_margin.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using ::testing::HasSubstr;
using testing::ShippedSimulationModel;

// A trial that ended holding the object at rest (X_WO = identity) with one contact on each face
// of a 10 cm cube about its centre of mass, each pushing `fn` N along its normal, on the links
// given (HandJointVector indices, 20 the palm).
TrialResult CubeHeld(double fn, const std::array<int, 6>& links = {3, 7, 11, 15, 19, 20}) {
  TrialResult t;
  t.outcome = TrialOutcome::kSuccess;
  const Eigen::Vector3d p_WC = ShippedSimulationModel().object_inertia().p_OC;
  int k = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) {
      HandObjectContact c;
      const Eigen::Vector3d u = sign * Eigen::Vector3d::Unit(axis);
      c.p_WC = p_WC + 0.05 * u;
      c.n_W = -u;  // into the object
      c.f_W = fn * c.n_W;
      c.friction = 0.8;
      c.hand_link = links[static_cast<size_t>(k++)];
      t.end_contacts.push_back(c);
    }
  }
  return t;
}

TEST(HoldMargin, EpsilonGrowsWithTheMeasuredNormalForces) {
  const SimulationModel& model = ShippedSimulationModel();
  const HoldMargin one = MeasureHoldMargin(model, CubeHeld(1.0));
  const HoldMargin two = MeasureHoldMargin(model, CubeHeld(2.0));
  ASSERT_TRUE(one.measured);
  EXPECT_GT(one.epsilon_weight, 0.0);
  // the cones are scaled by the forces: the margin is linear in them.
  EXPECT_NEAR(two.epsilon_weight, 2.0 * one.epsilon_weight, 1e-9 * two.epsilon_weight);
  const double weight = model.object_inertia().mass * model.options().gravity;
  EXPECT_NEAR(one.normal_force_weight, 6.0 / weight, 1e-12);
  EXPECT_EQ(one.load_bearing_links, 6);
  EXPECT_FALSE(one.fingertips_only);     // the palm carries a sixth
  EXPECT_EQ(one.friction_use_max, 0.0);  // pure normal forces
  EXPECT_NEAR(one.torque_scale_m, 0.05, 1e-12);
  // one contact on each finger (kLoadShareGroups order), one on the palm.
  EXPECT_THAT(one.contacts, ::testing::ElementsAre(1, 1, 1, 1, 1, 1));
}

TEST(HoldMargin, AContactThatCarriesNothingCountsNothing) {
  const SimulationModel& model = ShippedSimulationModel();
  const HoldMargin before = MeasureHoldMargin(model, CubeHeld(1.0));
  TrialResult t = CubeHeld(1.0);
  HandObjectContact idle = t.end_contacts.front();
  idle.p_WC.z() += 0.3;  // far off, where it would raise the torque scale if it counted
  idle.f_W.setZero();
  idle.hand_link = 2;
  t.end_contacts.push_back(idle);
  const HoldMargin after = MeasureHoldMargin(model, t);
  EXPECT_EQ(after.epsilon_weight, before.epsilon_weight);
  EXPECT_EQ(after.torque_scale_m, before.torque_scale_m);
  EXPECT_EQ(after.load_bearing_links, before.load_bearing_links);
  EXPECT_EQ(after.contacts[0], 2);  // but it is a contact point of the thumb
  // with the face's contact carrying nothing, the cube is held from five sides only: less.
  TrialResult five = CubeHeld(1.0);
  five.end_contacts[5].f_W.setZero();
  EXPECT_LT(MeasureHoldMargin(model, five).epsilon_weight, before.epsilon_weight);
}

TEST(HoldMargin, FrictionUseIsTheTangentialForceOverTheCone) {
  TrialResult t = CubeHeld(1.0);
  // the first contact pushes 1 N and rubs 0.4 N sideways: 0.4 / (0.8 * 1) = 0.5.
  HandObjectContact& c = t.end_contacts.front();
  c.f_W += 0.4 * Eigen::Vector3d::UnitY();
  const HoldMargin m = MeasureHoldMargin(ShippedSimulationModel(), t);
  EXPECT_NEAR(m.friction_use_max, 0.5, 1e-12);
  // force-weighted: 0.5 with weight |f| = sqrt(1.16), the five others 0 with weight 1.
  EXPECT_NEAR(m.friction_use_mean, 0.5 * std::sqrt(1.16) / (std::sqrt(1.16) + 5.0), 1e-12);
}

TEST(HoldMargin, APinchOnTwoFingertipsIsFingertipsOnly) {
  TrialResult t = CubeHeld(1.0);
  // only the thumb's and the index finger's tips (links 3 and 7) carry load.
  for (size_t k = 2; k < t.end_contacts.size(); ++k) t.end_contacts[k].f_W.setZero();
  const HoldMargin m = MeasureHoldMargin(ShippedSimulationModel(), t);
  EXPECT_EQ(m.load_bearing_links, 2);
  EXPECT_TRUE(m.fingertips_only);
  // two point contacts cannot resist a torque about the line through them.
  EXPECT_EQ(m.epsilon_weight, 0.0);
  EXPECT_THAT(HoldMarginShortfall(m, {}), HasSubstr("epsilon 0 weights < 0.05 weights"));
}

TEST(HoldMargin, NothingInTheHandIsNotMeasured) {
  TrialResult t;
  t.outcome = TrialOutcome::kDropped;
  const HoldMargin m = MeasureHoldMargin(ShippedSimulationModel(), t);
  EXPECT_FALSE(m.measured);
  EXPECT_THAT(HoldMarginShortfall(m, {}), HasSubstr("not measured"));
}

TEST(HoldMargin, TheShortfallNamesTheFigureItsValueAndTheThreshold) {
  HoldMargin m = MeasureHoldMargin(ShippedSimulationModel(), CubeHeld(50.0));
  EXPECT_EQ(HoldMarginShortfall(m, {}), "");
  m.slip_mm = 41.7;
  m.slip_deg = 12.3;
  m.friction_use_mean = 1.2;
  m.load_bearing_links = 1;
  EXPECT_EQ(HoldMarginShortfall(m, {}),
            "slip 41.7 mm > 40 mm; slip 12.3 deg > 10 deg; 1 load-bearing links < 2; friction "
            "use mean 1.20 > 1");
}

TEST(HoldMargin, OptionsAreChecked) {
  std::string why;
  EXPECT_TRUE(HoldMarginOptions{}.IsValid(&why)) << why;
  HoldMarginOptions o;
  o.max_slip_mm = -1.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("max_slip_mm"));
  o = {};
  o.max_slip_deg = 200.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("max_slip_deg"));
  o = {};
  o.min_epsilon_weight = NAN;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.min_load_bearing_links = -1;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.max_friction_use_mean = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("max_friction_use_mean"));
  // every threshold has its reason.
  for (const HoldMarginThreshold& t : HoldMarginThresholds({})) EXPECT_FALSE(t.reason.empty());
}

// The example grasp (the scripted grasp at 60 deg) in the ODE trial: its margin is measured from
// the contacts at the end of the hold, and agrees with the trial's own hold figures.
TEST(HoldMargin, TheExampleGraspsFiguresAreThoseOfItsHold) {
  const SimulationModel& model = ShippedSimulationModel();
  const TrialResult trial = RunTrial(model, ExampleTrajectory());
  ASSERT_TRUE(trial.success()) << trial.reason;
  const HoldMargin m = MeasureHoldMargin(model, trial);
  ASSERT_TRUE(m.measured);
  int contacts = 0;
  for (int c : m.contacts) contacts += c;
  EXPECT_EQ(contacts, trial.hold.contacts);
  EXPECT_EQ(m.slip_mm, trial.hold.slip * 1e3);
  EXPECT_EQ(m.end_tilt_deg, trial.hold.end_tilt / kDeg);
  double share = 0.0;
  for (double s : m.load_share) share += s;
  EXPECT_NEAR(share, 1.0, 1e-9);
  // the scripted grasp puts its fingertips on the handle's far face and the thumb's on its near
  // face: a pinch of fingertips, which its margin says.
  EXPECT_TRUE(m.fingertips_only);
  EXPECT_GE(m.load_bearing_links, 2);
  EXPECT_GE(m.epsilon_weight, 0.0);
  // at rest in the hand, the contacts carry at least the object's weight.
  EXPECT_GT(m.normal_force_weight, 0.5);
}

}  // namespace
}  // namespace graspsynth
