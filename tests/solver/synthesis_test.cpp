#include "solver/synthesis.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "kinematics/pose_math.hpp"
#include "learning_data/grasp_library.hpp"
#include "motion/scripted_grasp.hpp"
#include "simulation/trial.hpp"
#include "tests/solver/synthesis_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Library406080;
using testing::Model406080;
using testing::ShippedSimulationModel;
using testing::SideSwitchModel;

SynthesisResult Synthesize(const SynthesisModel& model, double theta_deg,
                           SynthesisMethod method = SynthesisMethod::kInterp, bool refine = true) {
  SynthesisOptions o;
  o.generation.method = method;
  if (!refine) o.refinement_stages.clear();
  SynthesisData data(model);
  return SynthesizeGrasp(model, theta_deg, o, &data);
}

TEST(Synthesis, InterpolatesInsideTheRangeWithBlendWeights) {
  const SynthesisResult r = Synthesize(Model406080(), 50.0);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.used, SynthesisMethod::kInterp);
  EXPECT_FALSE(r.fallback);
  ASSERT_EQ(r.sources.size(), 2u);
  EXPECT_DOUBLE_EQ(r.sources[0].theta_deg, 40.0);
  EXPECT_NEAR(r.sources[0].weight, 0.5, 1e-12);
  EXPECT_NEAR(r.sources[1].weight, 0.5, 1e-12);
  EXPECT_EQ(r.trajectory.theta_deg, 50.0);
  EXPECT_GE(r.trajectory.waypoints.size(), 4u);
  // the trajectory starts at the start configuration and ends lifted above the grasp.
  EXPECT_TRUE(r.trajectory.samples.front().arm.isApprox(r.start));
  EXPECT_GT(r.path.back().p_WH.z(), r.motion.grasp().p_WH.z() + 0.05);
  std::string why;
  EXPECT_TRUE(IsWellFormed(r.motion, &why)) << why;
}

TEST(Synthesis, ExactHitIsThatDemonstration) {
  const SynthesisResult r = Synthesize(Model406080(), 60.0, SynthesisMethod::kInterp, false);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.sources.size(), 1u);
  EXPECT_DOUBLE_EQ(r.sources[0].weight, 1.0);
  const MotionWaypoint& g = Library406080().entries[1].motion.grasp();
  EXPECT_LT((r.motion.grasp().p_WH - g.p_WH).norm(), 1e-12);
}

TEST(Synthesis, InterpOutsideTheRangeNamesTheRangeAndSuggestsLine) {
  const SynthesisResult r = Synthesize(Model406080(), 100.0);
  EXPECT_EQ(r.status, SynthesisStatus::kOutOfRange);
  EXPECT_NE(r.message.find("[40, 80]"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("'line'"), std::string::npos) << r.message;
}

TEST(Synthesis, LineAndNearestWorkOutsideTheRange) {
  for (double theta : {10.0, 20.0, 100.0, 110.0}) {
    const SynthesisResult r = Synthesize(Model406080(), theta, SynthesisMethod::kLine);
    ASSERT_TRUE(r.ok()) << theta << ": " << r.message;
    EXPECT_EQ(r.used, SynthesisMethod::kLine);
    EXPECT_DOUBLE_EQ(r.trajectory.theta_deg, theta);
    EXPECT_EQ(r.sources.size(), 3u);
  }
  for (double theta : {30.0, 100.0}) {
    const SynthesisResult r = Synthesize(Model406080(), theta, SynthesisMethod::kNearest);
    ASSERT_TRUE(r.ok()) << theta << ": " << r.message;
    ASSERT_EQ(r.sources.size(), 1u);
    EXPECT_DOUBLE_EQ(r.sources[0].theta_deg, theta < 60.0 ? 40.0 : 80.0);
  }
}

TEST(Synthesis, UnplayableGraspIsAResultNotAnException) {
  // a right-side grasp turned 30 deg below the range leaves the arm's reach on the way.
  const SynthesisResult r = Synthesize(Model406080(), 10.0, SynthesisMethod::kNearest);
  ASSERT_FALSE(r.ok()) << "the grasp at 10 deg was playable: " << r.message;
  EXPECT_EQ(r.status, SynthesisStatus::kUnreachable);
  EXPECT_FALSE(r.message.empty());
}

TEST(Synthesis, HardCaseFallsBackAndSaysWhy) {
  const SynthesisResult r = Synthesize(SideSwitchModel(), 45.0);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_FALSE(r.bracket.blendable);
  EXPECT_TRUE(r.fallback);
  EXPECT_NE(r.used, SynthesisMethod::kInterp);
  EXPECT_NE(r.fallback_reason.Text().find("sides of the handle"), std::string::npos)
      << r.fallback_reason.Text();
  // the hand lies across the handle: its long axis z_H at least 60 deg from the handle.
  const Eigen::Vector3d h =
      ShippedSimulationModel().scene().ObjectPose(45.0 * kDeg).linear().col(0);
  const Eigen::Vector3d z_H = r.motion.grasp().q_WH * Eigen::Vector3d::UnitZ();
  EXPECT_LT(std::abs(z_H.dot(h)), std::cos(60.0 * kDeg));
}

TEST(Synthesis, PlainBlendOfTheHardCaseLaysTheHandAlongTheHandle) {
  // what the fallback avoids: the blend turns the hand by about 90 deg from either demo.
  const GraspLibrary& l = testing::SideSwitchLibrary();
  const GraspingMotion m = BlendMotions(l.entries[1].motion, l.entries[2].motion, 0.5);
  const Eigen::Vector3d h =
      ShippedSimulationModel().scene().ObjectPose(45.0 * kDeg).linear().col(0);
  const Eigen::Vector3d z_H = m.grasp().q_WH * Eigen::Vector3d::UnitZ();
  EXPECT_GT(std::abs(z_H.dot(h)), std::cos(60.0 * kDeg));
}

TEST(Synthesis, AReusedWorkspaceGivesTheResultsOfAFreshOne) {
  const SynthesisModel& model = Model406080();
  SynthesisData reused(model);
  // a query that runs every stage, then others through the same workspace.
  ASSERT_TRUE(SynthesizeGrasp(model, 50.0, {}, &reused).ok());
  for (double theta : {60.0, 47.0}) {
    SynthesisData fresh(model);
    const SynthesisResult a = SynthesizeGrasp(model, theta, {}, &reused);
    const SynthesisResult b = SynthesizeGrasp(model, theta, {}, &fresh);
    ASSERT_TRUE(a.ok()) << a.message;
    ASSERT_EQ(a.trajectory.samples.size(), b.trajectory.samples.size());
    for (size_t i = 0; i < a.trajectory.samples.size(); ++i) {
      EXPECT_EQ(a.trajectory.samples[i].t, b.trajectory.samples[i].t) << theta << " " << i;
      EXPECT_EQ(a.trajectory.samples[i].arm, b.trajectory.samples[i].arm) << theta << " " << i;
      EXPECT_EQ(a.trajectory.samples[i].hand, b.trajectory.samples[i].hand) << theta << " " << i;
    }
    EXPECT_EQ(a.refinement.after.approach_clearance, b.refinement.after.approach_clearance);
    EXPECT_EQ(a.refinement.nlopt.evaluations, b.refinement.nlopt.evaluations);
  }
}

TEST(Synthesis, BadStartIsAResult) {
  SynthesisOptions o;
  Vector7d start = Vector7d::Zero();
  start[3] = 10.0;  // E1 far beyond its limit
  o.start = start;
  SynthesisData data(Model406080());
  const SynthesisResult r = SynthesizeGrasp(Model406080(), 50.0, o, &data);
  EXPECT_EQ(r.status, SynthesisStatus::kBadStart);
  EXPECT_NE(r.message.find("joint 4"), std::string::npos) << r.message;
}

TEST(Synthesis, TurnWithObjectKeepsTheHoldRelativeToTheObject) {
  const GraspingMotion& m = Library406080().entries[0].motion;
  const GraspingMotion t = TurnWithObject(m, Placement{55.0 * kDeg, {}});
  const SceneModel& scene = ShippedSimulationModel().scene();
  const Eigen::Isometry3d X_OH_a =
      scene.ObjectPose(m.theta).inverse() * (Eigen::Translation3d(m.grasp().p_WH) * m.grasp().q_WH);
  const Eigen::Isometry3d X_OH_b = scene.ObjectPose(55.0 * kDeg).inverse() *
                                   (Eigen::Translation3d(t.grasp().p_WH) * t.grasp().q_WH);
  const PoseDistance d = DistanceBetween(X_OH_a, X_OH_b);
  EXPECT_LT(d.translation, 1e-12);
  EXPECT_LT(d.rotation, 1e-9);
}

// A grasp synthesized at an orientation absent from the library lifts the object.
TEST(Synthesis, SynthesizedGraspLiftsTheObject) {
  for (double theta : {50.0, 70.0}) {
    const SynthesisResult r = Synthesize(Model406080(), theta);
    ASSERT_TRUE(r.ok()) << r.message;
    const TrialResult t = RunTrial(ShippedSimulationModel(), r.trajectory);
    EXPECT_TRUE(t.success()) << theta << ": " << t.BriefReport();
  }
}

TEST(Synthesis, HardCaseGraspLiftsTheObject) {
  const SynthesisResult r = Synthesize(SideSwitchModel(), 45.0);
  ASSERT_TRUE(r.ok()) << r.message;
  const TrialResult t = RunTrial(ShippedSimulationModel(), r.trajectory);
  EXPECT_TRUE(t.success()) << t.BriefReport();
}

// A start across the robot from the object (S1 1.5 rad to the other side of the base): the
// paper's spline reach, a straight-ish wrist path from there to the pre-grasp, passes where
// the arm has no solution on the start's branch.
Vector7d StartAcrossTheRobot(double theta_deg) {
  const LibraryEntry& e = Library406080().entries[theta_deg == 40.0 ? 0 : 1];
  Vector7d q =
      DefaultRestConfiguration(ShippedSimulationModel().robot(), ShippedSimulationModel().scene(),
                               e.motion.grasp().q_WH.toRotationMatrix());
  q[0] = -1.5;
  return q;
}

SynthesisResult WithReach(double theta_deg, ReachMethod reach,
                          const std::optional<Vector7d>& start = std::nullopt) {
  SynthesisOptions o;
  o.reach.method = reach;
  o.start = start;
  SynthesisData data(Model406080());
  return SynthesizeGrasp(Model406080(), theta_deg, o, &data);
}

TEST(SynthesisReach, AutoUsesTheJointReachWhereTheSplineCannotBePlayed) {
  const Vector7d start = StartAcrossTheRobot(60.0);
  const SynthesisResult spline = WithReach(60.0, ReachMethod::kSpline, start);
  EXPECT_EQ(spline.status, SynthesisStatus::kUnreachable);
  const SynthesisResult r = WithReach(60.0, ReachMethod::kAuto, start);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.reach_used, ReachMethod::kJoint);
  EXPECT_NE(r.reach_reason.find("cannot be played"), std::string::npos) << r.reach_reason;
  // the trajectory starts at the start, passes the pre-grasp and grasp poses, is continuous.
  const JointTrajectory& t = r.trajectory;
  EXPECT_EQ(t.samples.front().arm, start);
  ASSERT_EQ(t.waypoints.size(), 5u);
  for (size_t k = 1; k < t.samples.size(); ++k) {
    ASSERT_GT(t.samples[k].t, t.samples[k - 1].t);
    EXPECT_LE((t.samples[k].arm - t.samples[k - 1].arm).cwiseAbs().maxCoeff(), 0.1) << k;
  }
  const RobotModel& robot = ShippedSimulationModel().robot();
  for (const WristWaypoint& w : t.waypoints) {
    const TrajectorySample s = SampleAt(t, w.t);
    const Eigen::Isometry3d X = ArmFlangePose(robot.arm, s.arm) * robot.X_FH;
    EXPECT_LT((X.translation() - w.p_WH).norm(), 1e-6) << w.t;
  }
  EXPECT_LT((t.waypoints[2].p_WH - r.motion.grasp().p_WH).norm(), 1e-9);
}

TEST(SynthesisReach, AutoKeepsTheSplineWithRoomToSpare) {
  const SynthesisResult r = WithReach(60.0, ReachMethod::kAuto);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.reach_used, ReachMethod::kSpline);
  const SynthesisResult spline = WithReach(60.0, ReachMethod::kSpline);
  ASSERT_TRUE(spline.ok());
  EXPECT_EQ(spline.trajectory.samples.size(), r.trajectory.samples.size());
}

TEST(SynthesisReach, JointReachGraspLiftsTheObject) {
  const SynthesisResult r = WithReach(50.0, ReachMethod::kJoint, StartAcrossTheRobot(40.0));
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.reach_used, ReachMethod::kJoint);
  const TrialResult t = RunTrial(ShippedSimulationModel(), r.trajectory);
  EXPECT_TRUE(t.success()) << t.BriefReport();
}

TEST(SynthesisReach, ParsesItsNames) {
  for (ReachMethod m : {ReachMethod::kSpline, ReachMethod::kJoint, ReachMethod::kAuto}) {
    EXPECT_EQ(ParseReachMethod(ToString(m)), m);
  }
  EXPECT_THROW(ParseReachMethod("dmp"), InputError);
}

// Library406080 with the 60 deg grasp pose 3 cm lower: the geometric model sees the hand
// deeper in the handle or the table than the default 2 mm penetration tolerance at the grasp
// (as it sees the shipped hooks, whose fingers stall on the handle in physics).
const SynthesisModel& DeepGraspModel() {
  static const SynthesisModel model = [] {
    GraspLibrary library = Library406080();
    library.entries[1].motion.waypoints.back().p_WH.z() -= 0.03;
    return SynthesisModel(ShippedSimulationModel().robot(), ShippedSimulationModel().scene(),
                          library);
  }();
  return model;
}

TEST(SynthesisThresholds, TheSourcesLoosenOnlyWhatTheyBreakThemselves) {
  const SynthesisModel& model = DeepGraspModel();
  const RefinementConstraints& c60 = model.entry_constraints()[1];
  ASSERT_EQ(model.library().entries[1].theta_deg, 60.0);
  ASSERT_GT(-c60.grasp_clearance, RefinementOptions{}.penetration_tolerance);
  SynthesisData data(model);
  SynthesisOptions o;
  const SynthesisResult r = SynthesizeGrasp(model, 60.0, o, &data);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_DOUBLE_EQ(r.penetration_tolerance, -c60.grasp_clearance);
  EXPECT_DOUBLE_EQ(r.clearance_margin, std::min(0.005, c60.approach_clearance));
  EXPECT_TRUE(r.refinement.before.feasible);
  // the demonstration is left where it is: no NLopt, at most Ceres' sub-millimetre smoothing.
  EXPECT_FALSE(r.refinement.nlopt.run);
  EXPECT_LT((r.motion.grasp().p_WH - r.unrefined.grasp().p_WH).norm(), 1e-3);
  // with the default thresholds the same demonstration counts as infeasible and is changed.
  o.source_thresholds.reset();
  const SynthesisResult strict = SynthesizeGrasp(model, 60.0, o, &data);
  ASSERT_TRUE(strict.ok()) << strict.message;
  EXPECT_FALSE(strict.refinement.before.feasible);
  EXPECT_TRUE(strict.refinement.nlopt.run);
  EXPECT_GT((strict.motion.grasp().p_WH - strict.unrefined.grasp().p_WH).norm() +
                (strict.motion.grasp().f - strict.unrefined.grasp().f).cwiseAbs().maxCoeff(),
            1e-3);
  EXPECT_EQ(strict.penetration_tolerance, RefinementOptions{}.penetration_tolerance);
  // sources within every default change nothing: the unmodified scripted library keeps them.
  SynthesisData plain(Model406080());
  const SynthesisResult r60 = SynthesizeGrasp(Model406080(), 60.0, SynthesisOptions{}, &plain);
  ASSERT_TRUE(r60.ok());
  EXPECT_EQ(r60.penetration_tolerance, RefinementOptions{}.penetration_tolerance);
  EXPECT_EQ(r60.clearance_margin, RefinementOptions{}.clearance_margin);
  EXPECT_EQ(r60.contact_tolerance, RefinementOptions{}.contact_tolerance);
}

// A library whose 20 deg representative is weak: the scripted grasp 0.30 m out along the
// handle, where the pan's weight pitches it out of the hand (it drops it), scored as the
// selection would score such a grasp; scripted grasps near the pan at 30 and 40 deg.
const SynthesisModel& WeakModel() {
  static const SynthesisModel model = [] {
    const RobotModel& robot = ShippedSimulationModel().robot();
    const SceneModel& scene = ShippedSimulationModel().scene();
    ScriptedGraspOptions far;
    far.grasp_radius = 0.30;
    GraspLibrary library;
    library.entries.push_back(testing::ScriptedEntry(robot, scene, 20.0, +1, far));
    library.entries.back().score = 0.1;
    library.entries.push_back(testing::ScriptedEntry(robot, scene, 30.0, +1));
    library.entries.push_back(testing::ScriptedEntry(robot, scene, 40.0, +1));
    return SynthesisModel(robot, scene, library);
  }();
  return model;
}

TEST(SynthesisWeak, AWeakRepresentativeGivesWayToItsRobustNeighbour) {
  const SynthesisModel& model = WeakModel();
  for (double theta : {20.0, 25.0}) {
    const SynthesisResult r = Synthesize(model, theta);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_TRUE(r.fallback) << theta;
    EXPECT_EQ(r.used, SynthesisMethod::kNearest) << theta;
    ASSERT_EQ(r.sources.size(), 1u);
    EXPECT_EQ(r.sources[0].theta_deg, 30.0) << theta;
    EXPECT_NE(r.fallback_reason.Text().find("weak"), std::string::npos) << r.fallback_reason.Text();
  }
  // the 20 deg grasp itself drops the pan; its neighbour turned by -10 deg lifts it.
  const TrialResult t = RunTrial(ShippedSimulationModel(), Synthesize(model, 20.0).trajectory);
  EXPECT_TRUE(t.success()) << t.BriefReport();
  const SynthesisResult own = Synthesize(model, 20.0, SynthesisMethod::kNearest, false);
  ASSERT_TRUE(own.ok()) << own.message;
  EXPECT_EQ(own.sources[0].theta_deg, 20.0);
  EXPECT_FALSE(RunTrial(ShippedSimulationModel(), own.trajectory).success());
}

}  // namespace
}  // namespace graspsynth
