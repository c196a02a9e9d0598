#include "solver/bracket.hpp"

#include <gtest/gtest.h>

#include "tests/solver/synthesis_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Library406080;
using testing::ShippedSimulationModel;
using testing::SideSwitchLibrary;

const SceneModel& Scene() { return ShippedSimulationModel().scene(); }

TEST(Bracket, InsideTheRangeTakesTheNearestOrientationsOnEachSide) {
  const Bracket b = SelectBracket(Library406080(), Scene(), 65.0);
  EXPECT_EQ(b.kind, BracketKind::kInside);
  EXPECT_EQ(b.lower, 1);
  EXPECT_EQ(b.upper, 2);
  EXPECT_DOUBLE_EQ(b.t, 0.25);
  EXPECT_EQ(b.nearest, 1);
  EXPECT_TRUE(b.blendable) << b.reason;
  EXPECT_EQ(b.side_lower, 1);
  EXPECT_EQ(b.side_upper, 1);
  // the same hold turned with the object: the same orientation relative to it.
  EXPECT_LT(b.orientation_change, 1e-6);
}

TEST(Bracket, ExactHitAndOutsideTheRange) {
  const Bracket exact = SelectBracket(Library406080(), Scene(), 40.0);
  EXPECT_EQ(exact.kind, BracketKind::kExact);
  EXPECT_EQ(exact.lower, 0);
  EXPECT_EQ(exact.upper, 0);
  const Bracket below = SelectBracket(Library406080(), Scene(), 39.0);
  EXPECT_EQ(below.kind, BracketKind::kBelowRange);
  EXPECT_EQ(below.nearest, 0);
  const Bracket above = SelectBracket(Library406080(), Scene(), 120.0);
  EXPECT_EQ(above.kind, BracketKind::kAboveRange);
  EXPECT_EQ(above.nearest, 2);
  EXPECT_EQ(SelectBracket(GraspLibrary{}, Scene(), 50.0).kind, BracketKind::kEmpty);
}

TEST(Bracket, TieGoesToTheLowerEntry) {
  EXPECT_EQ(SelectBracket(Library406080(), Scene(), 50.0).nearest, 0);
}

TEST(Bracket, SideSwitchingPairCannotBeBlended) {
  const Bracket b = SelectBracket(SideSwitchLibrary(), Scene(), 45.0);
  EXPECT_EQ(b.kind, BracketKind::kInside);
  EXPECT_EQ(b.side_lower, -1);
  EXPECT_EQ(b.side_upper, 1);
  EXPECT_FALSE(b.blendable);
  EXPECT_NE(b.reason.find("changes sides"), std::string::npos) << b.reason;
  EXPECT_GT(b.orientation_change, 60.0 * M_PI / 180.0);
  // its neighbours on one side blend.
  EXPECT_TRUE(SelectBracket(SideSwitchLibrary(), Scene(), 35.0).blendable);
  EXPECT_TRUE(SelectBracket(SideSwitchLibrary(), Scene(), 55.0).blendable);
}

TEST(Bracket, OrientationThresholdAloneMakesABracketUnblendable) {
  // the same library and query with a threshold below the turn between the sides' holds, and
  // a dead band so wide that no side is found: only the orientation test can refuse it.
  BracketOptions o;
  o.side_dead_band = 1.0;
  const Bracket b = SelectBracket(SideSwitchLibrary(), Scene(), 45.0, o);
  EXPECT_EQ(b.side_lower, 0);
  EXPECT_FALSE(b.blendable);
  EXPECT_NE(b.reason.find("orientations"), std::string::npos) << b.reason;
  o.max_orientation_change = M_PI;
  EXPECT_TRUE(SelectBracket(SideSwitchLibrary(), Scene(), 45.0, o).blendable);
}

TEST(Bracket, OptionsAreChecked) {
  BracketOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why));
  o.max_orientation_change = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("max_orientation_change"), std::string::npos);
}

TEST(Bracket, HandleSideFollowsTheScriptedGraspsSide) {
  for (int side : {-1, 1}) {
    ScriptedGraspOptions o;
    o.theta_deg = 60.0;
    o.side = side;
    const Eigen::Isometry3d X = GraspWristPose(ShippedSimulationModel().robot(), Scene(), o);
    EXPECT_EQ(HandleSide(Scene(), 60.0 * M_PI / 180.0, X.translation(), 0.01), side);
  }
}

TEST(Bracket, OneWeakEndMakesABracketUnblendable) {
  GraspLibrary library = Library406080();
  library.entries[0].score = 0.2;  // 40 deg: its best demonstration failed 8 of 10 replays
  const Bracket b = SelectBracket(library, Scene(), 50.0);
  EXPECT_TRUE(b.weak_lower);
  EXPECT_FALSE(b.weak_upper);
  EXPECT_FALSE(b.blendable);
  EXPECT_NE(b.reason.find("the 40 deg representative is weak"), std::string::npos) << b.reason;
  EXPECT_TRUE(SelectBracket(library, Scene(), 70.0).blendable);
  const Bracket exact = SelectBracket(library, Scene(), 40.0);
  EXPECT_EQ(exact.kind, BracketKind::kExact);
  EXPECT_TRUE(exact.weak_lower);
  EXPECT_EQ(exact.substitute, 1);  // 60 deg stands in for it
  EXPECT_NE(exact.reason.find("the 40 deg representative is weak"), std::string::npos);
  EXPECT_EQ(SelectBracket(library, Scene(), 60.0).substitute, -1);  // a robust entry is itself
  // both ends weak: nothing better to use, the bracket blends.
  library.entries[1].score = 0.3;
  EXPECT_TRUE(SelectBracket(library, Scene(), 50.0).blendable);
  EXPECT_EQ(SelectBracket(library, Scene(), 40.0).substitute, -1);
  // min_score 0: no representative is weak.
  BracketOptions o;
  o.min_score = 0.0;
  EXPECT_TRUE(SelectBracket(library, Scene(), 50.0, o).blendable);
  o.min_score = 1.5;
  EXPECT_FALSE(o.IsValid(nullptr));
}

}  // namespace
}  // namespace graspsynth
