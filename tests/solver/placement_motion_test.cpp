// Tests of the synthesis over placements (solver/placement_motion.hpp) on a library of scripted
// grasps demonstrated at four object positions.

#include "solver/placement_motion.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "common/errors.hpp"
#include "kinematics/pose_math.hpp"
#include "simulation/trial.hpp"
#include "tests/solver/synthesis_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::Library406080;
using testing::MatricesNear;
using testing::Model406080;
using testing::ShippedSimulationModel;

const std::vector<Eigen::Vector2d>& Positions() {
  static const std::vector<Eigen::Vector2d> p = {
      {-0.28, 0.82}, {-0.28, 0.88}, {-0.22, 0.82}, {-0.22, 0.88}};
  return p;
}

// The scripted 40, 60, 80 deg grasps demonstrated at every position (moved with the object).
const SynthesisModel& PlacementsModel() {
  static const SynthesisModel model = [] {
    GraspLibrary library = Library406080();
    library.entries.clear();
    for (const Eigen::Vector2d& xy : Positions()) {
      for (LibraryEntry e : Library406080().entries) {
        e.motion = TurnWithObject(e.motion, Placement{e.motion.theta, xy});
        library.entries.push_back(e);
      }
    }
    return SynthesisModel(ShippedSimulationModel().robot(), ShippedSimulationModel().scene(),
                          library);
  }();
  return model;
}

MotionGenerationResult Generate(const SynthesisModel& model, double theta_deg,
                                const Eigen::Vector2d& at,
                                SynthesisMethod method = SynthesisMethod::kInterp) {
  MotionGenerationOptions options;
  options.method = method;
  return GenerateGraspingMotion(model, MakeSynthesisTask(model.scene(), theta_deg, at), options);
}

TEST(PlacementMotion, TheModelKnowsItsPlacements) {
  const SynthesisModel& model = PlacementsModel();
  ASSERT_TRUE(model.placements());
  EXPECT_EQ(model.triangulation().placements().size(), 12u);
  EXPECT_EQ(model.theta_min_deg(), 40.0);
  EXPECT_EQ(model.theta_max_deg(), 80.0);
  EXPECT_FALSE(Model406080().placements());
  // the line principle is fitted over one position's entries, the first three.
  EXPECT_EQ(model.LineEntries(), (std::vector<int>{0, 1, 2}));
}

TEST(PlacementMotion, ADemonstratedPlacementIsThatDemonstrationExactly) {
  const SynthesisModel& model = PlacementsModel();
  const MotionGenerationResult r = Generate(model, 60.0, Positions()[2]);
  ASSERT_TRUE(r.ok()) << r.message;
  ASSERT_EQ(r.sources.size(), 1u);
  EXPECT_EQ(r.sources[0].entry, 7);
  EXPECT_EQ(r.sources[0].weight, 1.0);
  const GraspingMotion& e = model.library().entries[7].motion;
  ASSERT_EQ(r.motion.waypoints.size(), e.waypoints.size());
  for (size_t i = 0; i < e.waypoints.size(); ++i) {
    EXPECT_EQ(r.motion.waypoints[i].p_WH, e.waypoints[i].p_WH);
    EXPECT_EQ(r.motion.waypoints[i].q_WH.coeffs(), e.waypoints[i].q_WH.coeffs());
  }
}

TEST(PlacementMotion, BetweenPlacementsItIsThePapersBlendMovedWithTheObject) {
  // every position holds the same grasps relative to the object, so the blend over a cell is
  // the one-position library's blend, moved to the query's position.
  const Eigen::Vector2d at(-0.26, 0.855);
  for (double theta : {47.0, 53.0, 71.0}) {
    const MotionGenerationResult r = Generate(PlacementsModel(), theta, at);
    ASSERT_TRUE(r.ok()) << r.message;
    EXPECT_EQ(r.used, SynthesisMethod::kInterp);
    EXPECT_GE(r.sources.size(), 2u);
    double sum = 0.0;
    for (const SourceDemo& s : r.sources) sum += s.weight;
    EXPECT_NEAR(sum, 1.0, 1e-12);
    MotionGenerationResult paper = Generate(Model406080(), theta, at);
    ASSERT_TRUE(paper.ok());
    EXPECT_TRUE(MatricesNear(r.motion.p_WO.head<2>(), at, 1e-12));
    EXPECT_NEAR(r.motion.theta, theta * kDeg, 1e-12);
    ASSERT_EQ(r.motion.waypoints.size(), paper.motion.waypoints.size());
    for (size_t i = 0; i < r.motion.waypoints.size(); ++i) {
      EXPECT_TRUE(MatricesNear(r.motion.waypoints[i].p_WH, paper.motion.waypoints[i].p_WH, 1e-9))
          << theta << " " << i;
      EXPECT_LT(AngleBetween(r.motion.waypoints[i].q_WH, paper.motion.waypoints[i].q_WH), 1e-9);
    }
  }
}

// A library over placements queried without a position (synthesize without --at, Python's
// at=None): the object stands at the scene's centre, and that is where the grasp is made for,
// the same grasp as with the centre given (decided and documented: issue 43).
TEST(PlacementMotion, WithoutAPositionTheGraspIsForTheScenesCentreWhereTheObjectStands) {
  const SynthesisModel& model = PlacementsModel();
  const Eigen::Vector2d centre = model.scene().CentreXY(Placement{});
  for (double theta : {47.0, 60.0}) {
    MotionGenerationOptions options;
    const SynthesisTask task = MakeSynthesisTask(model.scene(), theta, std::nullopt);
    EXPECT_TRUE(MatricesNear(task.X_WO.translation().head<2>(), centre, 0.0));
    const MotionGenerationResult without = GenerateGraspingMotion(model, task, options);
    const MotionGenerationResult with = Generate(model, theta, centre);
    ASSERT_TRUE(without.ok()) << without.message;
    ASSERT_TRUE(with.ok()) << with.message;
    EXPECT_TRUE(MatricesNear(without.motion.p_WO.head<2>(), centre, 1e-12));
    ASSERT_EQ(without.motion.waypoints.size(), with.motion.waypoints.size());
    for (size_t i = 0; i < with.motion.waypoints.size(); ++i) {
      EXPECT_TRUE(
          MatricesNear(without.motion.waypoints[i].p_WH, with.motion.waypoints[i].p_WH, 1e-12))
          << theta << " " << i;
    }
  }
}

TEST(PlacementMotion, OutsideTheHullInterpIsRefusedAndNearestMovesTheNearest) {
  const Eigen::Vector2d outside(-0.35, 0.85);
  const MotionGenerationResult r = Generate(PlacementsModel(), 60.0, outside);
  EXPECT_EQ(r.status, MotionGenerationStatus::kOutOfRange);
  EXPECT_THAT(r.message, HasSubstr("outside the convex hull"));
  EXPECT_THAT(r.message, HasSubstr("'nearest'"));

  const MotionGenerationResult n =
      Generate(PlacementsModel(), 62.0, outside, SynthesisMethod::kNearest);
  ASSERT_TRUE(n.ok());
  ASSERT_EQ(n.sources.size(), 1u);
  EXPECT_EQ(n.sources[0].entry, 1);  // (-0.28, 0.82, 60): the nearest in (x, y, theta)
  // the grasp keeps its place relative to the object.
  const GraspingMotion& e = PlacementsModel().library().entries[1].motion;
  const SceneModel& scene = PlacementsModel().scene();
  const Eigen::Isometry3d X_from =
      scene.ObjectPose(Placement{e.theta, Eigen::Vector2d(-0.28, 0.82)});
  const Eigen::Isometry3d X_to = scene.ObjectPose(Placement{62.0 * kDeg, outside});
  const Eigen::Isometry3d X_OG_from = X_from.inverse() * WaypointPose(e.grasp());
  const Eigen::Isometry3d X_OG_to = X_to.inverse() * WaypointPose(n.motion.grasp());
  EXPECT_TRUE(MatricesNear(X_OG_from.matrix(), X_OG_to.matrix(), 1e-12));
}

TEST(PlacementMotion, AGraspAtAHeldOutPlacementIsPlayedWithTheObjectThere) {
  SynthesisData data(PlacementsModel());
  const SynthesisTask task =
      MakeSynthesisTask(PlacementsModel().scene(), 55.0, Eigen::Vector2d(-0.25, 0.85));
  const SynthesisResult s = SynthesizeGrasp(PlacementsModel(), task, SynthesisOptions{}, &data);
  ASSERT_TRUE(s.ok()) << s.message;
  ASSERT_TRUE(s.trajectory.object_xy.has_value());
  EXPECT_EQ(*s.trajectory.object_xy, Eigen::Vector2d(-0.25, 0.85));
  const TrialResult trial = RunTrial(ShippedSimulationModel(), s.trajectory);
  EXPECT_TRUE(trial.success()) << trial.BriefReport();
}

TEST(PlacementMotion, ACellWithAWeakVertexBlendsItsOtherVerticesAndAFailedBlendTakesOne) {
  // the 60 deg grasp at (-0.28, 0.82) is weak: a cell that holds it with the robust ones cannot
  // be blended, and its robust vertices are blended instead, with their weights scaled.
  static const SynthesisModel model = [] {
    GraspLibrary library = PlacementsModel().library();
    library.entries[1].score = 0.2;
    return SynthesisModel(ShippedSimulationModel().robot(), ShippedSimulationModel().scene(),
                          library);
  }();
  const Eigen::Vector2d at(-0.27, 0.83);
  const SynthesisTask task = MakeSynthesisTask(model.scene(), 57.0, at);
  const PlacementCell cell =
      model.triangulation().Locate(PlacementCoordinates(model.scene(), task.placement));
  ASSERT_THAT(cell.vertices, ::testing::Contains(1));
  ASSERT_GE(cell.vertices.size(), 3u);

  MotionGenerationOptions options;
  const MotionGenerationResult r = GenerateGraspingMotion(model, task, options);
  ASSERT_TRUE(r.ok()) << r.message;
  EXPECT_EQ(r.used, SynthesisMethod::kInterp);
  EXPECT_EQ(r.fallback.kind, FallbackKind::kPartialBlend);
  EXPECT_THAT(r.fallback.Text(), HasSubstr("a vertex is weak"));
  EXPECT_THAT(r.fallback.Text(), HasSubstr("blended the vertices that can be"));
  ASSERT_EQ(r.sources.size(), cell.vertices.size() - 1);
  double kept = 0.0;
  for (size_t k = 0; k < cell.vertices.size(); ++k)
    kept += cell.vertices[k] == 1 ? 0.0 : cell.weights[k];
  double sum = 0.0;
  for (const SourceDemo& source : r.sources) {
    EXPECT_NE(source.entry, 1);
    const auto k =
        static_cast<size_t>(std::find(cell.vertices.begin(), cell.vertices.end(), source.entry) -
                            cell.vertices.begin());
    ASSERT_LT(k, cell.vertices.size());
    EXPECT_NEAR(source.weight, cell.weights[k] / kept, 1e-12);
    sum += source.weight;
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_TRUE(MatricesNear(r.motion.p_WO.head<2>(), at, 1e-12));

  // when that blend has failed its nominal trial, the heaviest robust vertex is used alone.
  options.reject_blend = true;
  const MotionGenerationResult again = GenerateGraspingMotion(model, task, options);
  ASSERT_TRUE(again.ok()) << again.message;
  EXPECT_EQ(again.fallback.kind, FallbackKind::kTurnedDemo);
  ASSERT_EQ(again.sources.size(), 1u);
  EXPECT_NE(again.sources[0].entry, 1);
}

TEST(PlacementMotion, AnObjectOffTheTableIsRefused) {
  EXPECT_THROW(MakeSynthesisTask(PlacementsModel().scene(), 60.0, Eigen::Vector2d(2.0, 0.85)),
               InputError);
  EXPECT_THROW(MakeSynthesisTask(PlacementsModel().scene(), 60.0, Eigen::Vector2d(NAN, 0.85)),
               InputError);
}

}  // namespace
}  // namespace graspsynth
