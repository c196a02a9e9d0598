#include "solver/refinement.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "tests/solver/synthesis_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Library406080;
using testing::Model406080;
using testing::ShippedSimulationModel;

struct RefineCase {
  const SynthesisModel& model = Model406080();
  GraspingMotion motion = Library406080().entries[1].motion;  // 60 deg
  RefinementInputs inputs;
  RefineCase() {
    inputs.X_WO = model.scene().ObjectPose(motion.theta);
    inputs.q_start = DefaultRestConfiguration(model.robot(), model.scene(),
                                              motion.grasp().q_WH.toRotationMatrix());
    inputs.wrist_line = model.line().wrist_line.line;
    inputs.handle_in_hand = model.line().handle_in_hand;
  }
  RefinementResult Refine(const RefinementOptions& o = {},
                          const RefinementStages& stages = {RefinementStage::kCeres,
                                                            RefinementStage::kNlopt}) const {
    CollisionData data(model.collision());
    return RefineGraspingMotion(model.robot(), model.scene(), model.collision(), motion, inputs, o,
                                &data, stages);
  }
};

TEST(Refinement, FeasibleInputStaysFeasibleAndReportsItsConstraints) {
  const RefineCase s;
  const RefinementResult r = s.Refine();
  const RefinementReport& rep = r.report;
  EXPECT_TRUE(rep.before.feasible) << rep.BriefReport();
  EXPECT_TRUE(rep.after.feasible) << rep.BriefReport();
  EXPECT_TRUE(rep.before.reachable);
  EXPECT_GE(rep.before.approach_clearance, RefinementOptions{}.clearance_margin);
  EXPECT_GT(rep.before.states, 2);
  EXPECT_GE(rep.after.min_psi_width, RefinementOptions{}.min_psi_width);
  EXPECT_LE(rep.after.contact_error, RefinementOptions{}.contact_tolerance);
  EXPECT_TRUE(rep.ceres.run);
  EXPECT_LE(rep.ceres.final_cost, rep.ceres.initial_cost + 1e-12);
  EXPECT_FALSE(rep.nlopt.run);
  EXPECT_NE(rep.nlopt.termination.find("satisfies"), std::string::npos);
  EXPECT_FALSE(rep.BriefReport().empty());
  // orientations and fingers are left alone; positions move little.
  ASSERT_EQ(r.motion.waypoints.size(), s.motion.waypoints.size());
  for (size_t i = 0; i < r.motion.waypoints.size(); ++i) {
    EXPECT_LT((r.motion.waypoints[i].p_WH - s.motion.waypoints[i].p_WH).norm(), 0.01);
    EXPECT_TRUE(r.motion.waypoints[i].f.isApprox(s.motion.waypoints[i].f));
  }
}

TEST(Refinement, LinePriorPullsTheGraspTowardTheLine) {
  RefineCase s;
  // a line 3 cm beside the grasp, along the hand's long axis projected on the table.
  const Eigen::Vector2d p = (s.motion.grasp().p_WH - s.motion.p_WO).head<2>();
  Line2d line;
  line.direction = Eigen::Vector2d(1.0, 0.3).normalized();
  line.point = p + 0.03 * line.normal();
  s.inputs.wrist_line = line;
  s.inputs.handle_in_hand.reset();
  RefinementOptions o;
  o.line_sigma = 0.005;  // as strong as the fidelity term: about half-way
  const RefinementResult r = s.Refine(o, {RefinementStage::kCeres});
  const double before = line.Distance(p);
  const double after = line.Distance((r.motion.grasp().p_WH - s.motion.p_WO).head<2>());
  EXPECT_NEAR(before, 0.03, 1e-9);
  EXPECT_LT(after, before - 0.002) << r.report.BriefReport();
  EXPECT_GT(r.report.ceres.line, 0.0);
  // the pre-grasp, far from the grasp along the motion, moves less than the grasp.
  EXPECT_LT((r.motion.pregrasp().p_WH - s.motion.pregrasp().p_WH).norm(),
            (r.motion.grasp().p_WH - s.motion.grasp().p_WH).norm());
}

// A motion 4 cm too low drives the open fingers into the handle and the table.
GraspingMotion Lowered(const GraspingMotion& m, double dz) {
  GraspingMotion out = m;
  for (MotionWaypoint& w : out.waypoints) w.p_WH.z() -= dz;
  return out;
}

TEST(Refinement, NloptRemovesAPlantedPenetration) {
  for (NloptAlgorithm algorithm : {NloptAlgorithm::kSlsqp, NloptAlgorithm::kCobyla}) {
    RefineCase s;
    s.motion = Lowered(s.motion, 0.04);
    RefinementOptions o;
    o.algorithm = algorithm;
    const RefinementResult r = s.Refine(o);
    const RefinementReport& rep = r.report;
    EXPECT_FALSE(rep.before.feasible);
    EXPECT_LT(rep.before.grasp_clearance, -o.penetration_tolerance);
    EXPECT_TRUE(rep.nlopt.run);
    EXPECT_EQ(rep.kept, RefinementStage::kNlopt) << rep.BriefReport();
    EXPECT_TRUE(rep.after.feasible) << ToString(algorithm) << ": " << rep.BriefReport();
    EXPECT_GE(rep.after.grasp_clearance, -o.penetration_tolerance - 1e-4);
    EXPECT_GE(rep.after.approach_clearance, o.clearance_margin - 1e-4);
    EXPECT_LE(rep.after.contact_error, o.contact_tolerance + 1e-4);
    EXPECT_GT(rep.nlopt.evaluations, 0);
    EXPECT_GT(rep.nlopt.shift.z(), 0.02);  // it went back up
    EXPECT_FALSE(rep.nlopt.termination.empty());
  }
}

TEST(Refinement, NeverReturnsAMotionWorseThanItsInput) {
  RefineCase s;
  s.motion = Lowered(s.motion, 0.04);
  RefinementOptions o;
  o.max_evaluations = 1;  // the optimizer cannot get anywhere
  o.cobyla_fallback = false;
  const RefinementResult r = s.Refine(o);
  EXPECT_LE(r.report.after.violation, r.report.before.violation + 1e-9) << r.report.BriefReport();
}

TEST(Refinement, ConstraintsSeeTheTableAndTheReach) {
  RefineCase s;
  // 0.3 m below the table: penetration everywhere near the grasp; far away: unreachable.
  CollisionData data(s.model.collision());
  const RefinementConstraints low =
      EvaluateRefinementConstraints(s.model.robot(), s.model.scene(), s.model.collision(),
                                    Lowered(s.motion, 0.1), s.inputs, {}, &data);
  EXPECT_FALSE(low.feasible);
  EXPECT_LT(low.grasp_clearance, 0.0);
  GraspingMotion far = s.motion;
  for (MotionWaypoint& w : far.waypoints) w.p_WH += Eigen::Vector3d(0.0, 2.0, 0.0);
  const RefinementConstraints out = EvaluateRefinementConstraints(
      s.model.robot(), s.model.scene(), s.model.collision(), far, s.inputs, {}, &data);
  EXPECT_FALSE(out.reachable);
  EXPECT_EQ(out.min_psi_width, 0.0);
  EXPECT_FALSE(out.feasible);
}

TEST(Refinement, RunsOnlyTheStagesNamedInOrder) {
  using S = RefinementStage;
  std::string why;
  EXPECT_TRUE(IsValidRefinementStages({}, &why)) << why;
  EXPECT_TRUE(IsValidRefinementStages({S::kNlopt}, &why)) << why;
  EXPECT_FALSE(IsValidRefinementStages({S::kNlopt, S::kCeres}, &why));
  EXPECT_NE(why.find("ceres, then nlopt"), std::string::npos) << why;
  EXPECT_FALSE(IsValidRefinementStages({S::kCeres, S::kCeres}, &why));
  EXPECT_FALSE(IsValidRefinementStages({S::kInput}, &why));
  const RefineCase s;
  EXPECT_THROW(s.Refine({}, {S::kNlopt, S::kCeres}), InputError);
  // no stage: the input is returned, evaluated, with neither optimizer run.
  const RefinementResult none = s.Refine({}, {});
  EXPECT_FALSE(none.report.ceres.run);
  EXPECT_FALSE(none.report.nlopt.run);
  EXPECT_EQ(none.report.nlopt.termination, "not run (disabled)");
  EXPECT_EQ(none.report.kept, S::kInput);
  EXPECT_EQ(none.motion.grasp().p_WH, s.motion.grasp().p_WH);
  const RefinementResult ceres = s.Refine({}, {S::kCeres});
  EXPECT_TRUE(ceres.report.ceres.run);
  EXPECT_EQ(ceres.report.nlopt.termination, "not run (disabled)");
}

TEST(Refinement, OptionsAreChecked) {
  RefinementOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.min_closure = 1.5;
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.reach_stride = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_STREQ(ToString(NloptAlgorithm::kMma), "mma");
}

}  // namespace
}  // namespace graspsynth
