#include "gate/validated_synthesis.hpp"

#include <gtest/gtest.h>

#include "common/data_dir.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ShippedSimulationModel;

// The shipped library: its 60 and 70 deg representatives blend into a grasp that drops the
// pan at 65 deg, while the 60 deg one turned with the object holds it.
const SynthesisModel& ShippedModel() {
  static const GraspLibrary library = ReadGraspLibrary(DefaultGraspLibraryPath());
  static const SynthesisModel model(ShippedSimulationModel().robot(),
                                    ShippedSimulationModel().scene(), library);
  return model;
}

ValidatedSynthesis Validate(double theta_deg, bool physics_fallback) {
  ValidatedSynthesisOptions o;
  o.physics_fallback = physics_fallback;
  o.gate.robustness.trials = 0;  // the nominal trial decides
  SynthesisData data(ShippedModel());
  return SynthesizeAndValidate(ShippedSimulationModel(), ShippedModel(), theta_deg, o, &data);
}

TEST(ValidatedSynthesis, ABlendThatDropsThePanGivesWayToTheNearerDemonstration) {
  const ValidatedSynthesis kept = Validate(65.0, false);
  ASSERT_TRUE(kept.gate_run) << kept.synthesis.message;
  EXPECT_EQ(kept.synthesis.used, SynthesisMethod::kInterp);
  EXPECT_FALSE(kept.synthesis.fallback);
  EXPECT_FALSE(kept.gate.nominal.success()) << "the shipped blend at 65 deg now holds the pan";
  EXPECT_TRUE(kept.rejected_blend.empty());

  const ValidatedSynthesis v = Validate(65.0, true);
  ASSERT_TRUE(v.gate_run) << v.synthesis.message;
  EXPECT_EQ(v.synthesis.used, SynthesisMethod::kNearest);
  EXPECT_TRUE(v.synthesis.fallback);
  EXPECT_TRUE(v.synthesis.fallback_reason.blend_failed);
  EXPECT_EQ(v.synthesis.fallback_reason.kind, FallbackKind::kTurnedDemo);
  EXPECT_DOUBLE_EQ(v.synthesis.fallback_reason.used_deg, 60.0);
  ASSERT_EQ(v.synthesis.sources.size(), 1u);
  EXPECT_DOUBLE_EQ(v.synthesis.sources[0].theta_deg, 60.0);
  // the reason names the rejected blend's outcome, and the kept grasp's gate is its own.
  EXPECT_EQ(v.rejected_blend.rfind(ToString(kept.gate.nominal.outcome), 0), 0u) << v.rejected_blend;
  const std::string text = v.synthesis.fallback_reason.Text();
  EXPECT_NE(text.find("its blend failed its nominal trial in physics: " + v.rejected_blend),
            std::string::npos)
      << text;
  EXPECT_TRUE(v.gate.nominal.success()) << v.gate.nominal.reason;
  EXPECT_GT(v.gate_s, v.gate.time_s);  // both gates are counted
}

TEST(ValidatedSynthesis, ABlendThatHoldsIsKept) {
  const ValidatedSynthesis v = Validate(68.0, true);
  ASSERT_TRUE(v.gate_run) << v.synthesis.message;
  EXPECT_EQ(v.synthesis.used, SynthesisMethod::kInterp);
  EXPECT_FALSE(v.synthesis.fallback);
  EXPECT_TRUE(v.gate.nominal.success()) << v.gate.nominal.reason;
  EXPECT_TRUE(v.rejected_blend.empty());
  EXPECT_EQ(v.synthesis.sources.size(), 2u);
}

TEST(ValidatedSynthesis, ASynthesisThatFailsRunsNoGate) {
  const ValidatedSynthesis v = Validate(120.0, true);  // outside the library's 20-100 deg
  EXPECT_EQ(v.synthesis.status, SynthesisStatus::kOutOfRange);
  EXPECT_FALSE(v.gate_run);
}

TEST(ValidatedSynthesis, ASlidGripWhoseNominalTrialFailsGivesWayToTheUnslidOne) {
  // The shipped placements library at (-0.25, 0.82 m, 43 deg): the hand holds the handle 24 cm
  // out, well inside its end, and the forearm passes 3 cm over the pan's rim. A slide forced 3
  // cm further in (no tip margin to respect, no arm clearance) brings the forearm onto the rim,
  // and the lifted pan rests on the arm; the unslid blend holds it.
  static const GraspLibrary library =
      ReadGraspLibrary(DataDirectory() / "learning_data" / "placements" / "library.json");
  static const SynthesisModel model(ShippedSimulationModel().robot(),
                                    ShippedSimulationModel().scene(), library);
  ValidatedSynthesisOptions o;
  o.gate.robustness.trials = 0;
  o.synthesis.grip_slide = GripSlideOptions{0.3, 0.03, 0, 0.0};
  SynthesisData data(model);
  const SynthesisTask task = MakeSynthesisTask(model.scene(), 43.0, Eigen::Vector2d(-0.25, 0.82));
  const ValidatedSynthesis v =
      SynthesizeAndValidate(ShippedSimulationModel(), model, task, o, &data);
  ASSERT_TRUE(v.gate_run) << v.synthesis.message;
  EXPECT_EQ(v.rejected_slide.rfind("touches_other", 0), 0u) << v.rejected_slide;
  EXPECT_EQ(v.synthesis.grip_slide, 0.0);
  EXPECT_NEAR(v.synthesis.grip_radius, 0.24, 0.01);  // the grip, as it was before the slide
  EXPECT_EQ(v.synthesis.used, SynthesisMethod::kInterp);
  EXPECT_TRUE(v.rejected_blend.empty());
  EXPECT_TRUE(v.gate.nominal.success()) << v.gate.nominal.reason;

  // with the defaults the grip is where it should be, and nothing is slid or rejected.
  o.synthesis.grip_slide = GripSlideOptions{};
  const ValidatedSynthesis kept =
      SynthesizeAndValidate(ShippedSimulationModel(), model, task, o, &data);
  ASSERT_TRUE(kept.gate_run) << kept.synthesis.message;
  EXPECT_NEAR(kept.synthesis.grip_radius, 0.24, 0.01);
  EXPECT_EQ(kept.synthesis.grip_slide, 0.0);
  EXPECT_TRUE(kept.rejected_slide.empty()) << kept.rejected_slide;
  EXPECT_TRUE(kept.gate.nominal.success()) << kept.gate.nominal.reason;
}

}  // namespace
}  // namespace graspsynth
