#include "solver/validated_synthesis.hpp"

#include <gtest/gtest.h>

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
  o.gate.perturbations = 0;  // the nominal trial decides
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

}  // namespace
}  // namespace graspsynth
