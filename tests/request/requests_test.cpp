// Tests of the requests of synthesize, generalize, run and select (request/*_request.hpp):
// their options are described once, with the library's defaults, and map onto the library's
// options; the checks that span options; a file of options.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "learning_data/demo_directory.hpp"
#include "request/generalize_request.hpp"
#include "request/run_request.hpp"
#include "request/select_request.hpp"
#include "request/synthesize_request.hpp"
#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth::request {
namespace {

TEST(SynthesizeRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(SynthesizeOptions()); }

TEST(GeneralizeRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(GeneralizeOptions()); }

TEST(RunRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(RunOptions()); }

TEST(SelectRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(SelectOptions()); }

TEST(SynthesizeRequest, TheDefaultsAreTheLibrarys) {
  SynthesizeRequest r;
  r.theta = 45.0;
  const ValidatedSynthesisOptions vo = ToValidatedSynthesisOptions(r);
  const ValidatedSynthesisOptions library;
  EXPECT_EQ(vo.gate.robustness.trials, library.gate.robustness.trials);
  EXPECT_EQ(vo.gate.robustness.seed, library.gate.robustness.seed);
  EXPECT_EQ(vo.gate.min_robustness, library.gate.min_robustness);
  EXPECT_EQ(vo.gate.robustness.perturbation.physics.friction,
            library.gate.robustness.perturbation.physics.friction);
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
  EXPECT_EQ(vo.gate.robustness.trials, 4);
  EXPECT_EQ(vo.gate.robustness.perturbation.physics.friction, 0.5);
  EXPECT_EQ(vo.gate.robustness.perturbation.physics.stiffness_min, 0.25);
  EXPECT_EQ(vo.gate.robustness.perturbation.physics.stiffness_max, 4.0);
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
  EXPECT_EQ(table.gate.robustness.trials, kStudyGatePerturbations);
  EXPECT_TRUE(table.positions.empty());
  EXPECT_EQ(table.gate.robustness.perturbation.physics.mass,
            SynthesisTableOptions{}.gate.robustness.perturbation.physics.mass);
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

const SceneModel& ShippedScene() {
  static const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  return scene;
}

// The study's options the request sets, equal in `a` and `b`.
void ExpectSameStudy(const StudyOptions& a, const StudyOptions& b) {
  EXPECT_EQ(a.demos, b.demos);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.threads, b.threads);
  EXPECT_EQ(a.selection_perturbations, b.selection_perturbations);
  EXPECT_EQ(a.selection_early_stop, b.selection_early_stop);
  EXPECT_EQ(a.gate_perturbations, b.gate_perturbations);
  EXPECT_EQ(a.sensitivity_trials, b.sensitivity_trials);
  EXPECT_EQ(a.min_robustness, b.min_robustness);
  EXPECT_EQ(a.physics_fallback, b.physics_fallback);
  EXPECT_EQ(a.orientations, b.orientations);
  EXPECT_EQ(a.perturbation.physics.enabled, b.perturbation.physics.enabled);
  EXPECT_EQ(a.perturbation.physics.friction, b.perturbation.physics.friction);
  EXPECT_EQ(a.perturbation.physics.fine_step, b.perturbation.physics.fine_step);
}

TEST(RunRequest, TheDefaultsAreTheStudysAndQuickIsTheQuickStudys) {
  const SceneModel& scene = ShippedScene();
  StudyOptions study;
  study.demos = DefaultDemoDirectory(scene.object.name);
  const StudyOptions options = ToStudyOptions(RunRequest{}, scene);
  ExpectSameStudy(options, study);
  EXPECT_EQ(options.analysis.segmentation.region.radius, scene.grasp_region.radius);
  EXPECT_TRUE(options.paper_object);
  RunRequest quick;
  quick.quick = true;
  study.UseQuickStudy();
  ExpectSameStudy(ToStudyOptions(quick, scene), study);
  // a count given wins over --quick's; one left out keeps it.
  quick.perturb = 0;
  quick.sensitivity = 1;
  const StudyOptions given = ToStudyOptions(quick, scene);
  EXPECT_EQ(given.gate_perturbations, 0);
  EXPECT_EQ(given.sensitivity_trials, 1);
  EXPECT_EQ(given.selection_perturbations, study.selection_perturbations);
}

TEST(RunRequest, OptionsMapOntoTheStudysAndBadOnesNameTheOption) {
  const OptionList<RunRequest>& options = RunOptions();
  RunRequest r;
  Apply(*FindOption(options, "orientations"), Value(std::string("40:50:5")), "orientations", &r);
  Apply(*FindOption(options, "all_replays"), Value(true), "all_replays", &r);
  Apply(*FindOption(options, "physics_fallback"), Value(false), "physics_fallback", &r);
  Apply(*FindOption(options, "mass_spread"), Value(0.5), "mass_spread", &r);
  const StudyOptions study = ToStudyOptions(r, ShippedScene());
  EXPECT_EQ(study.orientations, (std::vector<double>{40, 45, 50}));
  EXPECT_FALSE(study.selection_early_stop);
  EXPECT_FALSE(study.physics_fallback);
  EXPECT_EQ(study.perturbation.physics.mass, 0.5);
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(options, "select_perturb"), Value(int64_t{0}), "--select-perturb", &r),
      InputError, "--select-perturb: must be >= 1 (got 0)");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(options, "perturb"), Value(int64_t{-1}), "--perturb", &r),
                       InputError, "--perturb: must be >= 0 (got -1)");
  // none is the study's default (Python's None, JSON's null).
  Apply(*FindOption(options, "perturb"), Value(std::monostate{}), "perturb", &r);
  EXPECT_FALSE(r.perturb.has_value());
  GS_EXPECT_THROW_WITH(Apply(*FindOption(options, "threads"), Value(int64_t{5000}), "threads", &r),
                       InputError, "threads: must be [0, 1024]");
  r.orientations = "40,40";
  GS_EXPECT_THROW_WITH(ToStudyOptions(r, ShippedScene()), InputError, "run: orientations",
                       "given twice");
  r.orientations = "";
  GS_EXPECT_THROW_WITH(ToStudyOptions(r, ShippedScene()), InputError, "orientations");
  r.orientations.reset();
  GS_EXPECT_THROW_WITH(ToStudyOptions(r, ShippedScene(), "/nonexistent/demos"), InputError,
                       "run: demos '/nonexistent/demos' is not a folder");
}

// The hold margin's options (request/hold_margin_options.hpp): one description for synthesize,
// generalize and run, onto each one's gate; a threshold out of range names the option.
TEST(HoldMarginOptions, MapOntoEachGateAndBadThresholdsNameTheOption) {
  SynthesizeRequest s;
  s.theta = 45.0;
  const OptionList<SynthesizeRequest>& so = SynthesizeOptions();
  Apply(*FindOption(so, "require_hold_margin"), Value(true), "require_hold_margin", &s);
  Apply(*FindOption(so, "max_slip_mm"), Value(12.5), "max_slip_mm", &s);
  Apply(*FindOption(so, "min_load_bearing_links"), Value(int64_t{3}), "min_load_bearing_links", &s);
  const ValidatedSynthesisOptions vo = ToValidatedSynthesisOptions(s);
  EXPECT_TRUE(vo.gate.hold_margin.require);
  EXPECT_EQ(vo.gate.hold_margin.max_slip_mm, 12.5);
  EXPECT_EQ(vo.gate.hold_margin.min_load_bearing_links, 3);
  EXPECT_FALSE(
      ToValidatedSynthesisOptions(SynthesizeRequest{.theta = 45.0}).gate.hold_margin.require);

  GeneralizeRequest g;
  Apply(*FindOption(GeneralizeOptions(), "max_friction_use_mean"), Value(0.7),
        "max_friction_use_mean", &g);
  EXPECT_EQ(ToSynthesisTableOptions(g).gate.hold_margin.max_friction_use_mean, 0.7);

  RunRequest r;
  Apply(*FindOption(RunOptions(), "min_epsilon_weight"), Value(0.2), "min_epsilon_weight", &r);
  Apply(*FindOption(RunOptions(), "require_hold_margin"), Value(true), "require_hold_margin", &r);
  const StudyOptions study = ToStudyOptions(r, ShippedScene());
  EXPECT_EQ(study.hold_margin.min_epsilon_weight, 0.2);
  EXPECT_TRUE(study.hold_margin.require);

  GS_EXPECT_THROW_WITH(Apply(*FindOption(so, "max_slip_mm"), Value(0.0), "--max-slip-mm", &s),
                       InputError, "--max-slip-mm: ");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(so, "max_slip_deg"), Value(200.0), "--max-slip-deg", &s),
                       InputError, "--max-slip-deg: ");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(RunOptions(), "min_load_bearing_links"),
                             Value(int64_t{-1}), "--min-load-bearing-links", &r),
                       InputError, "--min-load-bearing-links: ");
}

TEST(RunRequest, AFileOfOptionsSetsThem) {
  const testing::TestFolder folder;
  const std::filesystem::path file = folder.path() / "run.json";
  std::ofstream(file) << R"({"format": "graspsynth-options/1", "quick": true, "perturb": 2,)"
                      << R"( "orientations": [45, 60], "physics": false})";
  RunRequest r;
  ApplyConfig(RunOptions(), file, &r);
  const StudyOptions study = ToStudyOptions(r, ShippedScene());
  EXPECT_EQ(study.gate_perturbations, 2);
  EXPECT_EQ(study.selection_perturbations, 2);  // --quick's
  EXPECT_EQ(study.orientations, (std::vector<double>{45, 60}));
  EXPECT_FALSE(study.perturbation.physics.enabled);
  std::ofstream(file) << R"({"select_perturb": 0})";
  GS_EXPECT_THROW_WITH(ApplyConfig(RunOptions(), file, &r), InputError, "field 'select_perturb'",
                       "must be >= 1");
}

TEST(SelectRequest, TheDefaultsAreTheLibrarysAndOptionsNestInTheSelections) {
  const SceneModel& scene = ShippedScene();
  const SelectionOptions library;
  SelectionOptions options = ToSelectionOptions(SelectRequest{}, scene);
  EXPECT_EQ(options.robustness.trials, library.robustness.trials);
  EXPECT_EQ(options.robustness.seed, library.robustness.seed);
  EXPECT_EQ(options.robustness.threads, library.robustness.threads);
  EXPECT_EQ(options.early_stop, library.early_stop);
  EXPECT_EQ(options.robustness.perturbation.physics.friction,
            library.robustness.perturbation.physics.friction);
  EXPECT_EQ(options.segmentation.region.radius, scene.grasp_region.radius);
  const OptionList<SelectRequest>& list = SelectOptions();
  SelectRequest r;
  Apply(*FindOption(list, "perturb"), Value(int64_t{3}), "perturb", &r);
  Apply(*FindOption(list, "seed"), Value(uint64_t{9}), "seed", &r);
  Apply(*FindOption(list, "all_replays"), Value(true), "all_replays", &r);
  Apply(*FindOption(list, "physics"), Value(false), "physics", &r);
  options = ToSelectionOptions(r, scene);
  EXPECT_EQ(options.robustness.trials, 3);
  EXPECT_EQ(options.robustness.seed, 9u);
  EXPECT_FALSE(options.early_stop);
  EXPECT_FALSE(options.robustness.perturbation.physics.enabled);
  GS_EXPECT_THROW_WITH(Apply(*FindOption(list, "perturb"), Value(int64_t{0}), "--perturb", &r),
                       InputError, "--perturb: must be >= 1 (got 0)");
}

TEST(SelectRequest, AFileOfOptionsSetsThem) {
  const testing::TestFolder folder;
  const std::filesystem::path file = folder.path() / "select.json";
  std::ofstream(file) << R"({"perturb": 4, "all_replays": true, "friction_spread": 0.1})";
  SelectRequest r;
  ApplyConfig(SelectOptions(), file, &r);
  const SelectionOptions options = ToSelectionOptions(r, ShippedScene());
  EXPECT_EQ(options.robustness.trials, 4);
  EXPECT_FALSE(options.early_stop);
  EXPECT_EQ(options.robustness.perturbation.physics.friction, 0.1);
  std::ofstream(file) << R"({"perturbs": 4})";
  GS_EXPECT_THROW_WITH(ApplyConfig(SelectOptions(), file, &r), InputError,
                       "field 'perturbs' is not an option", "did you mean 'perturb'?");
}

}  // namespace
}  // namespace graspsynth::request
