// Tests of the requests of synthesize and generalize (request/synthesize_request.hpp,
// request/generalize_request.hpp): their options are described once, with the library's
// defaults, and map onto the library's options; the checks that span options.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "request/generalize_request.hpp"
#include "request/synthesize_request.hpp"
#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::request {
namespace {

TEST(SynthesizeRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(SynthesizeOptions()); }

TEST(GeneralizeRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(GeneralizeOptions()); }

TEST(SynthesizeRequest, TheDefaultsAreTheLibrarys) {
  SynthesizeRequest r;
  r.theta = 45.0;
  const ValidatedSynthesisOptions vo = ToValidatedSynthesisOptions(r);
  const ValidatedSynthesisOptions library;
  EXPECT_EQ(vo.gate.perturbations, library.gate.perturbations);
  EXPECT_EQ(vo.gate.seed, library.gate.seed);
  EXPECT_EQ(vo.gate.min_robustness, library.gate.min_robustness);
  EXPECT_EQ(vo.gate.perturbation.physics.friction, library.gate.perturbation.physics.friction);
  EXPECT_EQ(vo.synthesis.generation.method, SynthesisMethod::kInterp);
  EXPECT_EQ(vo.synthesis.refinement_stages, library.synthesis.refinement_stages);
  EXPECT_TRUE(vo.synthesis.source_thresholds.has_value());
  EXPECT_FALSE(vo.synthesis.grip_slide.has_value());
  EXPECT_TRUE(vo.physics_fallback);
}

TEST(SynthesizeRequest, OptionsMapOntoTheLibrarysThroughNestedOptions) {
  SynthesizeRequest r;
  const OptionList<SynthesizeRequest>& options = SynthesizeOptions();
  Apply(*FindOption(options, "theta"), Value(62.5), "theta", &r);
  Apply(*FindOption(options, "method"), Value(std::string("line")), "method", &r);
  Apply(*FindOption(options, "refine"), Value(false), "refine", &r);
  Apply(*FindOption(options, "perturb"), Value(int64_t{4}), "perturb", &r);
  Apply(*FindOption(options, "friction_spread"), Value(0.5), "friction_spread", &r);
  Apply(*FindOption(options, "stiffness_range"), Value(std::vector<double>{0.25, 4.0}),
        "stiffness_range", &r);
  Apply(*FindOption(options, "at"), Value(std::vector<double>{-0.3, 0.9}), "at", &r);
  Apply(*FindOption(options, "start"), Value(std::vector<double>(7, 0.1)), "start", &r);
  const ValidatedSynthesisOptions vo = ToValidatedSynthesisOptions(r);
  EXPECT_EQ(r.theta, 62.5);
  EXPECT_EQ(vo.synthesis.generation.method, SynthesisMethod::kLine);
  EXPECT_TRUE(vo.synthesis.refinement_stages.empty());
  EXPECT_EQ(vo.gate.perturbations, 4);
  EXPECT_EQ(vo.gate.perturbation.physics.friction, 0.5);
  EXPECT_EQ(vo.gate.perturbation.physics.stiffness_min, 0.25);
  EXPECT_EQ(vo.gate.perturbation.physics.stiffness_max, 4.0);
  ASSERT_TRUE(r.at.has_value());
  EXPECT_EQ(*r.at, Eigen::Vector2d(-0.3, 0.9));
  ASSERT_TRUE(vo.synthesis.start.has_value());
  EXPECT_EQ((*vo.synthesis.start)[6], 0.1);
  Apply(*FindOption(options, "at"), Value(std::vector<double>{}), "at", &r);
  EXPECT_FALSE(r.at.has_value());
}

TEST(SynthesizeRequest, AGripSlideNeedsTheRefinement) {
  SynthesizeRequest r;
  r.grip_slide = true;
  r.refine = false;
  GS_EXPECT_THROW_WITH(ToValidatedSynthesisOptions(r), InputError,
                       "grip_slide needs the refinement");
  r.refine = true;
  EXPECT_TRUE(ToValidatedSynthesisOptions(r).synthesis.grip_slide.has_value());
}

TEST(GeneralizeRequest, TheDefaultsAreTheStudysAndListsParseOnce) {
  const GeneralizeRequest r;
  const SynthesisTableOptions table = ToSynthesisTableOptions(r);
  EXPECT_EQ(table.orientations.size(), 81u);
  EXPECT_EQ(table.methods.size(), 4u);
  EXPECT_EQ(table.gate_perturbations, kStudyGatePerturbations);
  EXPECT_TRUE(table.positions.empty());
  EXPECT_EQ(table.perturbation.physics.mass, SynthesisTableOptions{}.perturbation.physics.mass);
}

TEST(GeneralizeRequest, ChecksThatSpanOptionsNameThem) {
  const OptionList<GeneralizeRequest>& options = GeneralizeOptions();
  GeneralizeRequest r;
  GS_EXPECT_THROW_WITH(Apply(*FindOption(options, "methods"),
                             Value(std::vector<std::string>{"interp", "interp"}), "--methods", &r),
                       InputError, "--methods: 'interp' is given twice");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(options, "orientations"), Value(std::string("30:20:1")),
                             "orientations", &r),
                       InputError, "orientations", "needs FROM <= TO");
  r.x = "-0.3";
  GS_EXPECT_THROW_WITH(ToSynthesisTableOptions(r), InputError, "x and y go together");
  r.y = "0.8,0.9";
  EXPECT_EQ(ToSynthesisTableOptions(r).positions.size(), 2u);
  r.leave_one_out = true;
  GS_EXPECT_THROW_WITH(ToSynthesisTableOptions(r), InputError, "takes no x or y");
}

}  // namespace
}  // namespace graspsynth::request
