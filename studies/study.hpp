#pragma once

/// @file
/// The end-to-end study of `graspsynth run` (issue 6): on a folder of demonstrations, the
/// paper's Table I analysis compared with the paper, the representative selection (the grasp
/// library), the synthesis of a grasp for every study orientation by each study method, and
/// the physics validation of every synthesized grasp (nominal and perturbed replays).
///
/// RunStudy() computes; the report builders (studies/study_report.hpp) are pure functions of its
/// result, so the command decides where they go (the library never prints or writes files).
///
/// Determinism: the selection seeds each demonstration from (seed, file name) and the physics
/// gate of each synthesis row from StudyRowSeed(seed, theta, method); every replay is
/// independent of the thread count. Every builder but StudyReportMarkdown's timing columns is
/// a function of those results alone, so analysis, library, synthesis JSON and CSV are the same
/// bytes for the same options whatever `threads` is. The markdown report and StudyTimingJson
/// carry wall-clock times.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/analysis_report.hpp"
#include "common/job_runner.hpp"
#include "gate/physics_gate.hpp"
#include "learning_data/representative_selection.hpp"
#include "simulation/perturbation.hpp"
#include "simulation/robustness.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial.hpp"
#include "solver/synthesis.hpp"
#include "studies/study_method.hpp"

namespace graspsynth {

/// `format` of the study's synthesis table (synthesis.json).
inline constexpr std::string_view kStudySynthesisFormat = "graspsynth-study-synthesis/1";
/// `format` of the study's timing file (timing.json).
inline constexpr std::string_view kStudyTimingFormat = "graspsynth-study-timing/1";
/// Header row of the study's synthesis CSV (synthesis.csv).
inline constexpr std::string_view kStudySynthesisCsvHeader =
    "theta_deg,method,status,used,fallback,refined,nominal_success,nominal_outcome,trials,"
    "successes,robustness,ci_low,ci_high,passed,epsilon,force_closure,failures";

/// Perturbed replays of each synthesized grasp's physics gate in the study and in `generalize`
/// (StudyOptions::gate_perturbations says why 20).
inline constexpr int kStudyGatePerturbations = 20;

/// The stages of the study, in order.
enum class StudyStage { kAnalysis, kSelection, kSynthesis };

/// "analysis", "selection" or "synthesis".
const char* ToString(StudyStage stage);

/// Inputs of RunStudy().
struct StudyOptions {
  /// Folder of demonstration logs (*.csv, graspsynth-demo/1).
  std::filesystem::path demos;
  /// How the outputs name `demos` and its files (report.md, synthesis.json, analysis.json, the
  /// library): empty for `demos` as given; the shipped folder's name relative to the project root
  /// when a default chose it (request::ToStudyOptions: "learning_data/demos").
  std::string demos_name;
  /// Seed of the whole study (selection and physics gates).
  uint64_t seed = 1;
  /// Worker threads of the replays (0: one per hardware thread). Changes no result.
  int threads = 0;
  /// Perturbed replays per demonstration in the representative selection, >= 1. 20, as the
  /// shipped library (with 10, more demonstrations tie at 10 of 10 and the tie rule picks
  /// others at 40, 60, 80 and 90 deg: a weaker study).
  int selection_perturbations = 20;
  /// SelectionOptions::early_stop of the selection: the same representatives and scores, the
  /// losers' scores over the replays that ran.
  bool selection_early_stop = true;
  /// Perturbed replays of each synthesized grasp's physics gate, >= 0 (0: nominal only). 20,
  /// as the selection: from 10 replays a grasp that holds 9 times in 10 reads 7 of 10 (below
  /// the gate's 0.8) once in 14 draws, and 8 of 10 spans 0.49-0.94 at 95%, too wide to say
  /// whether a grasp is above 0.8; from 20, 16 of 20 spans 0.58-0.92.
  int gate_perturbations = kStudyGatePerturbations;
  /// Replays per end of each physics factor's range in each synthesized grasp's sensitivity
  /// table, >= 0 (0: none). 2: 32 replays per grasp, a coarse but complete picture of what
  /// each grasp depends on (simulate --sensitivity gives a finer one).
  int sensitivity_trials = 2;
  /// Success fraction the gate needs under perturbation, [0, 1].
  double min_robustness = 0.8;
  /// The perturbation of every replay, in the selection and the gates: the motion's noise and
  /// time scaling and the physics' ranges.
  PerturbationOptions perturbation;
  /// The gates' hold margin: its thresholds, and whether they are required (off by default).
  HoldMarginOptions hold_margin;
  /// An interp blend whose nominal trial fails gives way to the unblendable bracket's
  /// fallbacks (gate/validated_synthesis.hpp).
  bool physics_fallback = true;
  /// MuJoCo as the gate's second engine (`--engines ode,mujoco`; off: ODE alone).
  MujocoGateOptions mujoco_gate;
  /// Object orientations to synthesize, deg, each finite (the study's: 20, 25, ..., 100).
  std::vector<double> orientations = DefaultStudyOrientations();
  /// The methods, each run at every orientation (default: interp with refinement, the line
  /// principle with refinement).
  std::vector<StudyMethod> methods = {{SynthesisMethod::kInterp, true},
                                      {SynthesisMethod::kLine, true}};
  /// Analysis settings (grasp region, wrist-line fit); commands take the region from the scene.
  AnalysisOptions analysis;
  /// Tolerances of the comparison with the paper's Table I.
  PaperComparisonOptions comparison;
  /// The object is the paper's pan (ObjectModel::paper_object): compare Table I with the
  /// paper's and check the paper's grasp wrist poses. Otherwise the study reports its own
  /// Table I, `comparison` and `reachability` of the result stay empty, and analysis.json's
  /// paper_comparison is null.
  bool paper_object = true;
  /// Where the selection's and the synthesis' jobs run (common/job_runner.hpp): spread over
  /// an MPI job's processes, kept in a resume folder; nullptr: this process's threads. Not
  /// owned.
  JobRunner* runner = nullptr;

  /// The comparison with the paper's Table I: null for an object that is not the paper's.
  const PaperComparisonOptions* PaperComparison() const {
    return paper_object ? &comparison : nullptr;
  }

  /// 20, 25, ..., 100 deg.
  static std::vector<double> DefaultStudyOrientations();

  /// Makes these options the reduced study of `graspsynth run --quick` (tests, a first look):
  /// orientations 40, 45, 60 and 85 deg, 3 perturbed replays per gate, 2 per demonstration in
  /// the selection, no sensitivity table.
  void UseQuickStudy();

  /// True when every value is in range (and the nested options are valid); otherwise false
  /// with the reason, naming the field and the value, in `why` (if given).
  bool IsValid(std::string* why) const;

  /// `demos_name`, or `demos` as given when it is empty.
  std::string DemosName() const { return demos_name.empty() ? demos.string() : demos_name; }
};

/// Reachability of the paper's Table I grasp wrist pose at one orientation (a cheap kinematics
/// check of the scene: the wrist palm down across the handle at the paper's (d, eta)).
struct ReachabilityRow {
  double theta_deg = 0.0;      ///< deg
  double d = 0.0;              ///< paper's grasp distance, m
  double eta_deg = 0.0;        ///< paper's grasp polar angle, deg
  bool reachable = false;      ///< an IK solution within the limits on the elbow-up branch
  double psi_width_deg = 0.0;  ///< total width of the feasible arm-angle set, deg
  double fk_error = 0.0;       ///< FK(IK) position error at the middle of the widest arc, m
  std::string reason;          ///< why not, when unreachable
};

/// One row of the synthesis table: one orientation, one method, and its physics validation.
struct StudyRow {
  double theta_deg = 0.0;  ///< deg
  /// The object centre on the table, world, m; empty: the scene's object centre (the files
  /// then have no position columns).
  std::optional<Eigen::Vector2d> at;
  std::string method;   ///< StudyMethod::Label()
  std::string message;  ///< the synthesis' message when status is not "ok"
  /// The method used; unset when the synthesis did not succeed (the files write "").
  std::optional<SynthesisMethod> used;
  bool fallback = false;           ///< a method other than the requested one was used
  FallbackReason fallback_reason;  ///< why (kind kNone without a fallback)
  bool refined = false;            ///< the refinement ran
  bool gate_run = false;           ///< the physics gate ran (status "ok")
  /// The synthesis' status ("ok" is SynthesisStatus::kOk); unset when the synthesis did not run
  /// for want of a library (the files write "no_library").
  std::optional<SynthesisStatus> status;
  bool nominal_success = false;
  /// The outcome of the nominal trial; unset when the gate did not run.
  std::optional<TrialOutcome> nominal_outcome;
  std::string nominal_reason;          ///< its reason sentence
  int trials = 0;                      ///< perturbed replays
  int successes = 0;                   ///< of which succeeded
  double robustness = 0.0;             ///< successes / trials (0 without replays)
  double ci_low = 0.0, ci_high = 1.0;  ///< Wilson 95% interval
  bool passed = false;                 ///< the physics gate passed
  std::string gate_reason;             ///< the gate's sentence
  double epsilon = 0.0;                ///< Ferrari-Canny epsilon of the nominal hold
  bool force_closure = false;
  std::string failures;      ///< perturbed failures by outcome, e.g. "dropped 2, not_lifted 1"
  HoldQuality nominal_hold;  ///< how the object sat in the hand at the end of the nominal trial
  HoldMargin hold_margin;    ///< the nominal hold's margin (gate/hold_margin.hpp)
  /// The margin's thresholds it misses (HoldMarginShortfall); "" when it meets them all.
  std::string hold_margin_shortfall;
  /// The gate's sensitivity table (when the study asks for one and the replays ran).
  std::optional<SensitivityResult> sensitivity;
  /// The MuJoCo sweep's summary, when MuJoCo was among the gate's engines and its sweep ran.
  std::optional<MujocoSweepSummary> mujoco;
  uint64_t seed = 0;         ///< seed of the gate's perturbations
  double synthesis_s = 0.0;  ///< wall time of the synthesis (not in the deterministic files)
  double gate_s = 0.0;       ///< wall time of the gate (not in the deterministic files)
  /// Orientations of the demonstrations the grasp was made from, deg, in the synthesis' order
  /// (SynthesisResult::sources; empty when not synthesized). Not in the files.
  std::vector<double> source_thetas_deg;
};

/// Per-method totals of the synthesis table.
struct StudyMethodSummary {
  std::string method;
  int rows = 0;                    ///< orientations tried
  int synthesized = 0;             ///< with status "ok"
  int nominal_successes = 0;       ///< nominal trial succeeded
  int passed = 0;                  ///< passed the gate
  int fallbacks = 0;               ///< used another method
  double mean_robustness = 0;      ///< over the synthesized rows (0 when none)
  double mean_robustness_all = 0;  ///< over every row, a row not synthesized counting 0
};

/// Everything the study found.
struct StudyResult {
  StudyOptions options;
  DemonstrationAnalysis analysis;
  std::vector<PaperComparisonRow> comparison;
  SelectionResult selection;
  std::vector<ReachabilityRow> reachability;
  std::vector<StudyRow> rows;  ///< by orientation, then method in options' order
  /// Wall time of each stage, s (analysis, selection, synthesis), and of the whole study.
  double analysis_s = 0.0, selection_s = 0.0, synthesis_s = 0.0, total_s = 0.0;
  /// The Fig. 8 image file name relative to the report ("" when it was not drawn), and why not.
  std::string figure;
  std::string figure_note;
};

/// Progress of a study: the stage, steps done and their total within it, and what is being
/// worked on. Called from worker threads, one call at a time.
using StudyProgress =
    std::function<void(StudyStage stage, int done, int total, const std::string& what)>;

/// The seed of the physics gate of the row (theta_deg, method) in a study with `seed`.
uint64_t StudyRowSeed(uint64_t seed, double theta_deg, const std::string& method);

/// The reachability of the paper's Table I grasp wrist poses in `scene` (see ReachabilityRow).
std::vector<ReachabilityRow> TableIReachability(const RobotModel& robot, const SceneModel& scene);

/// The physics gate of the study's rows: the gate's defaults with kStudyGatePerturbations
/// replays.
inline PhysicsGateOptions StudyGateOptions() {
  PhysicsGateOptions gate;
  gate.robustness.trials = kStudyGatePerturbations;
  return gate;
}

/// Options of the synthesis table (the study's stage 3; experiments 2 and 3).
struct SynthesisTableOptions {
  std::vector<double> orientations;  ///< deg
  /// Object positions on the table (world, m): every orientation at each, rows by position
  /// first; empty: the scene's object centre only.
  std::vector<Eigen::Vector2d> positions;
  std::vector<StudyMethod> methods;
  /// Each row's physics gate, passed down whole: its replays (`robustness.trials` per row, 0:
  /// nominal only, and their perturbation), its sensitivity table's replays per end of each
  /// physics factor's range (0: none) and its threshold. The rows' own seed
  /// (StudyRowSeed(seed, theta, label)) and share of `threads` replace its robustness.seed and
  /// robustness.threads.
  PhysicsGateOptions gate = StudyGateOptions();
  uint64_t seed = 1;  ///< rows are seeded by StudyRowSeed(seed, theta, label)
  int threads = 0;
  /// An interp blend whose nominal trial fails gives way to the unblendable bracket's
  /// fallbacks (gate/validated_synthesis.hpp).
  bool physics_fallback = true;
  /// Where the rows run (common/job_runner.hpp): spread over the processes of an MPI job, or
  /// kept in a resume folder as they finish; nullptr: on this process's threads. Not owned.
  JobRunner* runner = nullptr;
  /// The job stage's name (each table of one run has its own, for the resume folder).
  std::string stage = "synthesis";
};

/// Progress of the synthesis table: replays done of their total, and the row being worked on.
using SynthesisTableProgress = std::function<void(int done, int total, const std::string& what)>;

/// A grasp for every position, orientation and method from `library`, each validated by the
/// physics gate: rows by position, then orientation, then method. Rows whose synthesis fails keep
/// its status and message. Throws InputError for a library the synthesis cannot use.
std::vector<StudyRow> SynthesisTable(const SimulationModel& model, const GraspLibrary& library,
                                     const SynthesisTableOptions& options,
                                     const SynthesisTableProgress& progress = {});

/// Leave-one-out (experiment 3): for each inner entry of `library` (every entry but the first
/// and the last), the synthesis table at that entry's orientation from the library without
/// it; `options.orientations` is ignored. Rows by held-out orientation, then method. `progress`
/// gets the stage ("without 40"), then the synthesis table's progress. Throws InputError for a
/// library with fewer than 3 entries or one the synthesis cannot use.
std::vector<StudyRow> LeaveOneOutTable(
    const SimulationModel& model, const GraspLibrary& library, const SynthesisTableOptions& options,
    const std::function<void(const std::string& stage, int done, int total,
                             const std::string& what)>& progress = {});

/// Runs the study. Throws InputError for invalid options or a demonstration folder that cannot
/// be read; everything that fails inside (files rejected, orientations not selected, grasps
/// not synthesized or failing in physics) is a result.
StudyResult RunStudy(const SimulationModel& model, const StudyOptions& options,
                     const StudyProgress& progress = {});

/// Per-method totals of `rows`, methods in the order they first appear.
std::vector<StudyMethodSummary> SummarizeStudy(const std::vector<StudyRow>& rows);

}  // namespace graspsynth
