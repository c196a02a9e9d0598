// Each stage of the synthesis pipeline (solver/synthesis.hpp) on its own.
#include <gtest/gtest.h>

#include "scene/rest_pose.hpp"
#include "motion/scripted_grasp.hpp"
#include "solver/motion_generation.hpp"
#include "solver/reach_planning.hpp"
#include "solver/refinement.hpp"
#include "solver/synthesis.hpp"
#include "tests/solver/synthesis_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Library406080;
using testing::Model406080;
using testing::SideSwitchModel;

TEST(SynthesisTask, ThePlacementEntersOnceWithTheObjectPose) {
  const SynthesisTask task = MakeSynthesisTask(Model406080().scene(), 55.0);
  EXPECT_EQ(task.theta_deg, 55.0);
  EXPECT_EQ(task.placement.theta, 55.0 * kDeg);
  EXPECT_TRUE(task.X_WO.isApprox(Model406080().scene().ObjectPose(55.0 * kDeg), 0.0));
  EXPECT_TRUE(Model406080().scene().ObjectPose(task.placement).isApprox(task.X_WO, 0.0));
}

TEST(MotionGeneration, InsideTheRangeBlendsWithoutFallback) {
  const SynthesisTask task = MakeSynthesisTask(Model406080().scene(), 50.0);
  const MotionGenerationResult g = GenerateGraspingMotion(Model406080(), task, {});
  ASSERT_TRUE(g.ok()) << g.message;
  EXPECT_EQ(g.used, SynthesisMethod::kInterp);
  EXPECT_EQ(g.fallback.kind, FallbackKind::kNone);
  EXPECT_EQ(g.fallback.Text(), "");
  ASSERT_EQ(g.sources.size(), 2u);
  EXPECT_EQ(g.motion.theta, task.placement.theta);
}

TEST(MotionGeneration, OutsideTheRangeIsAResultNamingTheRange) {
  const SynthesisTask task = MakeSynthesisTask(Model406080().scene(), 20.0);
  const MotionGenerationResult g = GenerateGraspingMotion(Model406080(), task, {});
  EXPECT_EQ(g.status, MotionGenerationStatus::kOutOfRange);
  EXPECT_NE(g.message.find("[40, 80]"), std::string::npos) << g.message;
}

TEST(MotionGeneration, HardCasePicksAFallbackWithATypedReason) {
  const SynthesisTask task = MakeSynthesisTask(SideSwitchModel().scene(), 45.0);
  const MotionGenerationResult g = GenerateGraspingMotion(SideSwitchModel(), task, {});
  ASSERT_TRUE(g.ok()) << g.message;
  EXPECT_FALSE(g.bracket.blendable);
  EXPECT_NE(g.fallback.kind, FallbackKind::kNone);
  EXPECT_NE(g.fallback.kind, FallbackKind::kRobustNeighbour);
  EXPECT_NE(g.fallback.bracket_reason.find("sides of the handle"), std::string::npos);
  EXPECT_EQ(g.fallback.lower_deg, SideSwitchModel().library().entries[g.bracket.lower].theta_deg);
  EXPECT_NE(g.fallback.Text().find("cannot be blended"), std::string::npos) << g.fallback.Text();
  if (g.fallback.kind == FallbackKind::kTurnedDemo) {
    EXPECT_EQ(g.used, SynthesisMethod::kNearest);
    ASSERT_EQ(g.sources.size(), 1u);
    EXPECT_EQ(g.fallback.used_deg, g.sources[0].theta_deg);
  }
  EXPECT_EQ(g.motion.theta, task.placement.theta);
}

TEST(FallbackReason, TextNamesWhatWasTriedInOrder) {
  FallbackReason f;
  f.kind = FallbackKind::kPlainBlend;
  f.bracket_reason = "the wrist changes sides of the handle between 40 and 60 deg";
  f.lower_deg = 40.0;
  f.upper_deg = 60.0;
  f.min_psi_width = 10.0 * kDeg;
  f.line_unreachable = true;
  EXPECT_EQ(f.Text(),
            "the bracket 40 - 60 deg cannot be blended (the wrist changes sides of the handle "
            "between 40 and 60 deg); the nearer demonstration turned with the object is not "
            "reachable with 10 deg of arm angle; the line principle's grasp is not reachable "
            "either; used the plain blend, left to the refinement");
  f.kind = FallbackKind::kRobustNeighbour;
  f.bracket_reason = "the 60 deg representative is weak";
  f.used_deg = 80.0;
  EXPECT_EQ(f.Text(),
            "the 60 deg representative is weak; used its robust neighbour (80 deg) turned with "
            "the object");
}

// What the refinement stages need, on the 60 deg demonstration.
struct StageCase {
  const SynthesisModel& model = Model406080();
  GraspingMotion motion = Library406080().entries[1].motion;
  RefinementInputs inputs;
  StageCase() {
    inputs.X_WO = model.scene().ObjectPose(motion.theta);
    inputs.q_start = DefaultRestConfiguration(model.robot(), model.scene(),
                                              motion.grasp().q_WH.toRotationMatrix());
    inputs.wrist_line = model.line().wrist_line.line;
    inputs.handle_in_hand = model.line().handle_in_hand;
  }
};

TEST(CeresStage, ReducesItsCostAndKeepsOrientationsFingersAndTimes) {
  StageCase s;
  // a line 3 cm beside the grasp: the line prior has something to pull.
  Line2d line = *s.inputs.wrist_line;
  const Eigen::Vector2d p = (s.motion.grasp().p_WH - s.motion.p_WO).head<2>();
  line.point = p + 0.03 * line.normal() - line.direction.dot(p) * line.direction;
  s.inputs.wrist_line = line;
  RefinementOptions o;
  o.line_sigma = 0.005;
  const CeresStageResult r = RunCeresStage(s.model.robot(), s.motion, s.inputs, o);
  EXPECT_TRUE(r.usable);
  EXPECT_TRUE(r.report.run);
  EXPECT_LT(r.report.final_cost, r.report.initial_cost);
  EXPECT_GT(r.report.iterations, 0);
  ASSERT_EQ(r.motion.waypoints.size(), s.motion.waypoints.size());
  for (size_t i = 0; i < r.motion.waypoints.size(); ++i) {
    EXPECT_EQ(r.motion.waypoints[i].t, s.motion.waypoints[i].t);
    EXPECT_TRUE(
        r.motion.waypoints[i].q_WH.coeffs().isApprox(s.motion.waypoints[i].q_WH.coeffs(), 0.0));
    EXPECT_TRUE(r.motion.waypoints[i].f.isApprox(s.motion.waypoints[i].f, 0.0));
  }
  // the grasp moves toward the line; the pre-grasp, far from it along the motion, moves less.
  EXPECT_LT(line.Distance((r.motion.grasp().p_WH - s.motion.p_WO).head<2>()), line.Distance(p));
  EXPECT_LT((r.motion.pregrasp().p_WH - s.motion.pregrasp().p_WH).norm(),
            (r.motion.grasp().p_WH - s.motion.grasp().p_WH).norm());
}

TEST(NloptStage, SatisfiesTheClearanceConstraintsOfALoweredMotion) {
  StageCase s;
  for (MotionWaypoint& w : s.motion.waypoints) w.p_WH.z() -= 0.04;  // fingers into the handle
  const RefinementOptions o;
  CollisionData data(s.model.collision());
  const RefinementConstraints before = EvaluateRefinementConstraints(
      s.model.robot(), s.model.scene(), s.model.collision(), s.motion, s.inputs, o, &data);
  ASSERT_FALSE(before.feasible);
  const NloptStageResult r = RunNloptStage(s.model.robot(), s.model.scene(), s.model.collision(),
                                           s.motion, s.inputs, o, &data);
  EXPECT_TRUE(r.report.run);
  EXPECT_GT(r.report.evaluations, 0);
  EXPECT_TRUE(r.constraints.feasible) << r.report.termination;
  EXPECT_GE(r.constraints.approach_clearance, o.clearance_margin - 1e-4);
  EXPECT_GE(r.constraints.grasp_clearance, -o.penetration_tolerance - 1e-4);
  EXPECT_GT(r.report.shift.z(), 0.0);  // lifted back up
}

TEST(ThresholdsFromSources, LoosensOnlyWhereTheSourcesWentPastTheOptions) {
  RefinementOptions o;
  RefinementConstraints a, b;
  a.approach_clearance = 0.002;  // below the 5 mm margin: loosens it
  a.grasp_clearance = 0.0;       // no penetration: keeps the tolerance
  a.contact_error = NAN;         // unknown: ignored
  b.approach_clearance = 0.02;
  b.grasp_clearance = -0.004;  // 4 mm deep: loosens the tolerance
  b.contact_error = 0.015;
  const RefinementOptions r = ThresholdsFromSources(o, {a, b});
  EXPECT_EQ(r.clearance_margin, 0.002);
  EXPECT_EQ(r.penetration_tolerance, 0.004);
  EXPECT_EQ(r.contact_tolerance, 0.015);
  EXPECT_EQ(r.min_psi_width, o.min_psi_width);
  const RefinementOptions same = ThresholdsFromSources(o, {});
  EXPECT_EQ(same.clearance_margin, o.clearance_margin);
}

// The grip slide moves every waypoint the same way, along the handle toward the object's
// centre, by the grip's excess over the handle's end less the tip margin, or by the longest of
// its halvings whose motion keeps the refinement's constraints and the arm's clearance.
TEST(GripSlide, SlidesAGripAtTheHandlesEndInAlongTheHandle) {
  const SynthesisModel& model = Model406080();
  ASSERT_TRUE(model.line().valid);
  const SynthesisTask task = MakeSynthesisTask(model.scene(), 60.0);
  const GraspingMotion& m = Library406080().entries[1].motion;  // 60 deg: the scripted grasp
  const Vector7d start =
      DefaultRestConfiguration(model.robot(), model.scene(), m.grasp().q_WH.toRotationMatrix());
  SynthesisData data(model);
  const Eigen::Vector3d h = model.scene().object.HandleDirection(task.X_WO);
  const double end = model.scene().object.Handle("the test").end_radius;
  const auto slid_by = [&](const GripSlideResult& r) {
    EXPECT_EQ(r.motion.waypoints.size(), m.waypoints.size());
    double along = 0.0;
    for (size_t i = 0; i < m.waypoints.size(); ++i) {
      const Eigen::Vector3d d = r.motion.waypoints[i].p_WH - m.waypoints[i].p_WH;
      along = -d.dot(h);
      EXPECT_NEAR((d + along * h).norm(), 0.0, 1e-12) << i;  // only along the handle
      EXPECT_NEAR(along, r.distance, 1e-12) << i;
      EXPECT_TRUE(r.motion.waypoints[i].q_WH.isApprox(m.waypoints[i].q_WH, 0.0));
      EXPECT_EQ(r.motion.waypoints[i].f, m.waypoints[i].f);
    }
    return along;
  };
  RefinementInputs in;
  in.X_WO = task.X_WO;
  in.q_start = start;
  const RefinementOptions thresholds;
  const auto slide = [&](double tip_margin, double max_distance, int halvings,
                         double min_arm_clearance = 0.02) {
    return SlideGrip(model, task, m, start, thresholds,
                     {tip_margin, max_distance, halvings, min_arm_clearance}, data.collision());
  };

  // the scripted pinch holds the handle well inside its end: the defaults leave it.
  const GripSlideResult kept = SlideGrip(model, task, m, start, thresholds, {}, data.collision());
  const double grip = kept.grip_radius;
  EXPECT_GT(grip, model.scene().object.Handle("the test").start_radius);
  EXPECT_LT(grip, end - GripSlideOptions{}.tip_margin);
  EXPECT_EQ(kept.distance, 0.0);
  EXPECT_EQ(slid_by(kept), 0.0);

  // a margin that puts the grip 2 cm too far out slides it in by 2 cm.
  const GripSlideResult two_cm = slide(end - grip + 0.02, 0.05, 2);
  EXPECT_NEAR(two_cm.distance, 0.02, 1e-12);
  EXPECT_NEAR(slid_by(two_cm), two_cm.distance, 1e-12);
  EXPECT_TRUE(EvaluateRefinementConstraints(model.robot(), model.scene(), model.collision(),
                                            two_cm.motion, in, thresholds, data.collision())
                  .feasible);
  EXPECT_EQ(slide(end - grip + 0.2, 0.02, 2).distance, 0.02);  // at most max_distance

  // 30 cm toward the centre puts the hand in the pan's body: refused, the motion is kept.
  const GripSlideResult far = slide(end + 0.3, 0.3, 0);
  EXPECT_EQ(far.distance, 0.0);
  EXPECT_EQ(slid_by(far), 0.0);
  // the first feasible halving is taken: 30 cm, 15 cm and 7.5 cm do not fit, 3.75 cm does.
  const GripSlideResult halved = slide(end + 0.3, 0.3, 3);
  EXPECT_EQ(halved.distance, 0.0375);
  EXPECT_NEAR(slid_by(halved), 0.0375, 1e-12);

  // a slide that keeps the constraints but not the arm's clearance from the object is refused.
  const double arm = EvaluateRefinementConstraints(model.robot(), model.scene(), model.collision(),
                                                   two_cm.motion, in, thresholds, data.collision())
                         .arm_object_clearance;
  EXPECT_GE(arm, 0.02);
  EXPECT_EQ(slide(end - grip + 0.02, 0.05, 0, arm + 0.001).distance, 0.0);
}

TEST(CheckStart, TheRestPoseIsFreeAndAStartBeyondTheLimitsIsNamed) {
  const SynthesisModel& model = Model406080();
  const SynthesisTask task = MakeSynthesisTask(model.scene(), 60.0);
  const GraspingMotion& motion = Library406080().entries[1].motion;
  CollisionData data(model.collision());
  const StartCheckResult rest = CheckStart(model, task, motion, {}, &data);
  EXPECT_TRUE(rest.ok) << rest.message;
  EXPECT_TRUE(rest.start.isApprox(DefaultRestConfiguration(
      model.robot(), model.scene(), motion.grasp().q_WH.toRotationMatrix())));
  StartCheckOptions beyond;
  Vector7d q = rest.start;
  q[0] = model.robot().arm.upper()[0] + 0.1;
  beyond.start = q;
  const StartCheckResult bad = CheckStart(model, task, motion, beyond, &data);
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.message.find("joint 1"), std::string::npos) << bad.message;
}

// Generation, start, tail and reach of the 50 deg blend, as SynthesizeGrasp chains them.
struct ReachCase {
  const SynthesisModel& model = Model406080();
  SynthesisTask task = MakeSynthesisTask(model.scene(), 50.0);
  MotionGenerationResult generated = GenerateGraspingMotion(model, task, {});
  CollisionData data{model.collision()};
  StartCheckResult start = CheckStart(model, task, generated.motion, {}, &data);
  GraspAndLiftPath tail = GraspAndLift(model.library(), generated.sources, generated.motion, {});
  ReachPlanResult Plan(ReachMethod method) {
    ReachPlanOptions o;
    o.method = method;
    return PlanReach(model, task, generated.motion, tail.path, start.start, o, &data);
  }
};

TEST(ReachStage, ReturnsAPlayableTrajectoryFromTheStart) {
  for (ReachMethod method : {ReachMethod::kSpline, ReachMethod::kJoint}) {
    ReachCase c;
    ASSERT_TRUE(c.start.ok) << c.start.message;
    const ReachPlanResult r = c.Plan(method);
    ASSERT_TRUE(r.ok()) << ToString(method) << ": " << r.reason << " " << r.joints.message;
    EXPECT_EQ(r.used, method);
    EXPECT_FALSE(r.reason.empty());
    EXPECT_EQ(r.path.size(), r.reach_samples + c.tail.path.size() - 1);
    ASSERT_EQ(r.joints.trajectory.samples.size(), r.path.size());
    EXPECT_LT((r.joints.trajectory.samples.front().arm - r.start).cwiseAbs().maxCoeff(), 1e-6);
    // the reach ends on the pre-grasp pose.
    EXPECT_LT((r.path[r.reach_samples - 1].p_WH - c.generated.motion.pregrasp().p_WH).norm(), 1e-9);
  }
}

TEST(Assembly, JoinsReachMotionAndLiftWithTheirWaypoints) {
  ReachCase c;
  const ReachPlanResult r = c.Plan(ReachMethod::kSpline);
  ASSERT_TRUE(r.ok()) << r.reason;
  const JointTrajectory t = AssembleTrajectory(r, c.tail);
  EXPECT_EQ(t.samples.size(), r.joints.trajectory.samples.size());
  EXPECT_EQ(t.samples.front().arm, r.start);
  ASSERT_EQ(t.waypoints.size(), 5u);  // start, pre-grasp, grasp, lift start, top
  for (size_t i = 1; i < t.waypoints.size(); ++i) {
    EXPECT_GT(t.waypoints[i].t, t.waypoints[i - 1].t);
  }
  EXPECT_LT((t.waypoints[1].p_WH - c.generated.motion.pregrasp().p_WH).norm(), 1e-9);
  EXPECT_LT((t.waypoints[2].p_WH - c.generated.motion.grasp().p_WH).norm(), 1e-9);
  EXPECT_NEAR(t.waypoints[4].p_WH.z() - t.waypoints[2].p_WH.z(), c.tail.lift.height, 1e-6);
}

}  // namespace
}  // namespace graspsynth
