#include "studies/study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "analysis/analysis_report.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/parallel.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"
#include "gate/validated_synthesis.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "studies/study_codec.hpp"
#include "studies/study_report.hpp"

namespace graspsynth {
namespace {

// wrist height above the table for a grasp of the handle (reference/scene.md: 0.08-0.11 m).
constexpr double kWristHeight = 0.095;

// Wrist (hand-mount) pose for a grasp: palm down (x_H = -z_W), the hand's long axis z_H
// horizontal, across the handle and pointing from the wrist toward the handle's line.
Eigen::Isometry3d GraspWristPose(const SceneModel& scene, const PaperTableRow& row) {
  const double eta = row.grasp_eta_deg * kDeg;
  const Eigen::Vector2d p_OW = row.grasp_d * Eigen::Vector2d(std::cos(eta), std::sin(eta));
  const Eigen::Vector2d handle = scene.ObjectPose(row.theta_deg * kDeg).linear().col(0).head<2>();
  Eigen::Vector2d toward = p_OW.dot(handle) * handle - p_OW;  // foot of the perpendicular
  if (toward.norm() < 1e-6) toward = Eigen::Vector2d(-handle.y(), handle.x());
  toward.normalize();
  Eigen::Matrix3d R;
  R.col(0) = -Eigen::Vector3d::UnitZ();
  R.col(2) = Eigen::Vector3d(toward.x(), toward.y(), 0.0);
  R.col(1) = R.col(2).cross(R.col(0));
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
  X_WH.linear() = R;
  X_WH.translation() << scene.object_centre_xy + p_OW, scene.table.top_z + kWristHeight;
  return X_WH;
}

}  // namespace

const char* ToString(StudyStage stage) {
  switch (stage) {
    case StudyStage::kAnalysis:
      return "analysis";
    case StudyStage::kSelection:
      return "selection";
    case StudyStage::kSynthesis:
      return "synthesis";
  }
  return "?";
}

std::vector<double> StudyOptions::DefaultStudyOrientations() {
  std::vector<double> thetas;
  for (int t = 20; t <= 100; t += 5) thetas.push_back(t);
  return thetas;
}

void StudyOptions::UseQuickStudy() {
  orientations = {40, 45, 60, 85};
  gate_perturbations = 3;
  selection_perturbations = 2;
  sensitivity_trials = 0;
}

bool StudyOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (demos.empty()) return fail("demos: no demonstration folder given");
  if (threads < 0) return fail("threads: " + std::to_string(threads) + " is negative");
  if (selection_perturbations < 1) {
    return fail("selection_perturbations: " + std::to_string(selection_perturbations) +
                " (needs >= 1)");
  }
  if (gate_perturbations < 0) {
    return fail("gate_perturbations: " + std::to_string(gate_perturbations) + " (needs >= 0)");
  }
  if (sensitivity_trials < 0) {
    return fail("sensitivity_trials: " + std::to_string(sensitivity_trials) + " (needs >= 0)");
  }
  if (!(min_robustness >= 0.0 && min_robustness <= 1.0)) {
    return fail("min_robustness: " + StreamNumber(min_robustness, 17) + " (needs [0, 1])");
  }
  if (std::string mujoco_why; !mujoco_gate.IsValid(&mujoco_why)) return fail(mujoco_why);
  if (std::string margin; !hold_margin.IsValid(&margin)) return fail(margin);
  if (orientations.empty()) return fail("orientations: none given");
  for (size_t i = 0; i < orientations.size(); ++i) {
    if (!std::isfinite(orientations[i])) {
      return fail("orientations[" + std::to_string(i) + "]: " + StreamNumber(orientations[i], 17) +
                  " is not a finite number of degrees");
    }
    for (size_t k = 0; k < i; ++k) {
      if (orientations[k] == orientations[i]) {
        return fail("orientations[" + std::to_string(i) + "]: " + StreamNumber(orientations[i]) +
                    " deg is given twice");
      }
    }
  }
  if (methods.empty()) return fail("methods: none given");
  for (size_t i = 0; i < methods.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (methods[k].Label() == methods[i].Label()) {
        return fail("methods[" + std::to_string(i) + "]: " + methods[i].Label() +
                    " is given twice");
      }
    }
  }
  std::string nested;
  if (!perturbation.IsValid(&nested)) return fail("perturbation: " + nested);
  if (!analysis.IsValid(&nested)) return fail("analysis: " + nested);
  if (!comparison.IsValid(&nested)) return fail("comparison: " + nested);
  return true;
}

uint64_t StudyRowSeed(uint64_t seed, double theta_deg, const std::string& method) {
  return DemoSeed(seed, "theta " + StreamNumber(theta_deg, 17) + " " + method);
}

std::vector<ReachabilityRow> TableIReachability(const RobotModel& robot, const SceneModel& scene) {
  const ArmModel& arm = robot.arm;
  std::vector<ReachabilityRow> rows;
  for (const PaperTableRow& g : PaperTableI()) {
    ReachabilityRow row;
    row.theta_deg = g.theta_deg;
    row.d = g.grasp_d;
    row.eta_deg = g.grasp_eta_deg;
    const Eigen::Isometry3d X_WF = GraspWristPose(scene, g) * robot.X_FH.inverse();
    const ArmTargetForm form = PrepareArmTarget(arm, X_WF, +1);
    const std::vector<Interval> feasible = FeasibleArmAngles(arm, form, +1, +1);
    for (const Interval& iv : feasible) row.psi_width_deg += iv.width() / kDeg;
    const std::optional<Interval> widest = WidestInterval(feasible);
    if (!widest) {
      row.reason = std::string(ToString(form.status));
      rows.push_back(row);
      continue;
    }
    const double psi = 0.5 * (widest->lo + widest->hi);
    const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, ArmBranch{});
    row.fk_error = DistanceBetween(ArmFlangePose(arm, s.q), X_WF).translation;
    row.reachable = s.status == IkStatus::kOk;
    if (!row.reachable) row.reason = "no IK solution at the middle of the widest arc";
    rows.push_back(row);
  }
  return rows;
}

namespace {

// The row of (theta, method) of a table with `seed`, before anything is known of it.
StudyRow NewRow(double theta, const StudyMethod& method, uint64_t seed,
                const std::optional<Eigen::Vector2d>& at = {}) {
  StudyRow row;
  row.theta_deg = theta;
  row.at = at;
  row.method = method.Label();
  // a row at a position of its own has a stream of its own; the scene's centre keeps its seed.
  row.seed =
      at ? DemoSeed(seed, "at " + StreamNumber(at->x(), 17) + " " + StreamNumber(at->y(), 17) +
                              " theta " + StreamNumber(theta, 17) + " " + row.method)
         : StudyRowSeed(seed, theta, row.method);
  return row;
}

// The table's rows: at each position (the scene's centre without any), each orientation by
// each method; `methods` gets each row's method. Throws InputError for an off-table position.
std::vector<StudyRow> NewRows(const SceneModel& scene, const SynthesisTableOptions& options,
                              std::vector<StudyMethod>* methods) {
  std::vector<StudyRow> rows;
  std::vector<std::optional<Eigen::Vector2d>> positions(options.positions.begin(),
                                                        options.positions.end());
  if (positions.empty()) positions.emplace_back();  // the scene's centre
  for (const std::optional<Eigen::Vector2d>& at : positions) {
    if (at) MakeSynthesisTask(scene, 0.0, at);  // an off-table position: InputError
    for (double theta : options.orientations) {
      for (const StudyMethod& method : options.methods) {
        rows.push_back(NewRow(theta, method, options.seed, at));
        methods->push_back(method);
      }
    }
  }
  return rows;
}

}  // namespace

std::vector<StudyRow> SynthesisTable(const SimulationModel& model, const GraspLibrary& library,
                                     const SynthesisTableOptions& options,
                                     const SynthesisTableProgress& progress) {
  const SynthesisModel synthesis(model.robot(), model.scene(), library);
  // the nominal trial, the perturbed replays and the sensitivity table's replays.
  const int per_row =
      options.gate.robustness.trials + 1 +
      2 * static_cast<int>(AllPhysicsFactors().size()) * options.gate.sensitivity_trials;
  std::vector<StudyMethod> methods;  // of each row
  std::vector<StudyRow> rows = NewRows(model.scene(), options, &methods);
  ProgressCounter counter(static_cast<int>(rows.size()) * per_row, progress);
  // rows are independent jobs: they run side by side, each on its share of the threads (one,
  // when there are more rows than threads), so that no thread waits for another's nominal trial
  // or last replay but at the very end; with an MPI runner, on every process.
  const ThreadSplit split = SplitThreads(options.threads, static_cast<int>(rows.size()));
  JobStage stage;
  stage.name = options.stage;
  stage.count = static_cast<int>(rows.size());
  stage.threads = split.outer;
  stage.payload = kStudyRowLayout;
  // job i's row from its bytes: a kept one is checked with it, and every one read back.
  const auto decode = [&](int i, std::string_view bytes) {
    return DecodeStudyRow(bytes, stage.name + " job " + std::to_string(i));
  };
  stage.check = decode;
  stage.finished = [&](int i, bool here) {
    if (!here) counter.Add(per_row, rows[static_cast<size_t>(i)].method);
  };
  stage.run = [&](int i) {
    StudyRow row = rows[static_cast<size_t>(i)];
    const double theta = row.theta_deg;
    const std::string what =
        (row.at ? "at " + StreamNumber(row.at->x()) + "," + StreamNumber(row.at->y()) + " "
                : std::string()) +
        "theta " + StreamNumber(theta) + " " + row.method;
    counter.Add(0, what);
    ValidatedSynthesisOptions vo;
    vo.synthesis = methods[static_cast<size_t>(i)].Options();
    vo.physics_fallback = options.physics_fallback;
    vo.gate = options.gate;
    vo.gate.robustness.seed = row.seed;
    vo.gate.robustness.threads = split.inner;
    SynthesisData data(synthesis);
    int counted = 0;  // of the row's per_row (a fallback's second gate counts no further)
    const ValidatedSynthesis v =
        SynthesizeAndValidate(model, synthesis, MakeSynthesisTask(model.scene(), theta, row.at), vo,
                              &data, [&](int done, int) {
                                const int now = std::clamp(1 + done, counted, per_row);
                                counter.Add(now - counted, what);
                                counted = now;
                              });
    const SynthesisResult& s = v.synthesis;
    const PhysicsGateResult& gate = v.gate;
    row.synthesis_s = v.synthesis_s;
    row.status = s.status;
    row.message = s.message;
    if (v.gate_run) {
      row.used = s.used;
      row.fallback = s.fallback;
      row.fallback_reason = s.fallback_reason;
      row.refined = s.refined;
      for (const SourceDemo& d : s.sources) row.source_thetas_deg.push_back(d.theta_deg);
      row.gate_run = true;
      row.gate_s = v.gate_s;
      row.nominal_success = gate.nominal.success();
      row.nominal_outcome = gate.nominal.outcome;
      row.nominal_reason = gate.nominal.reason;
      row.nominal_hold = gate.nominal.hold;
      row.hold_margin = gate.hold_margin;
      row.hold_margin_shortfall = gate.hold_margin_shortfall;
      row.sensitivity = gate.sensitivity;
      if (gate.mujoco) row.mujoco = gate.mujoco->summary;
      if (gate.robustness_run) {
        row.trials = static_cast<int>(gate.robustness.trials.size());
        row.successes = gate.robustness.successes;
        row.robustness = gate.robustness.score;
        row.ci_low = gate.robustness.ci95.lo;
        row.ci_high = gate.robustness.ci95.hi;
        row.failures = FailureSummary(gate.robustness);
      }
      row.passed = gate.passed;
      row.gate_reason = gate.reason;
      row.epsilon = gate.quality.epsilon;
      row.force_closure = gate.quality.force_closure;
    }
    counter.Add(per_row - counted, what);
    return EncodeStudyRow(row);
  };
  LocalJobRunner local;
  const std::vector<std::string> done = (options.runner ? *options.runner : local).Run(stage);
  for (size_t i = 0; i < rows.size(); ++i) {
    rows[i] = decode(static_cast<int>(i), done[i]);
  }
  return rows;
}

std::vector<StudyRow> LeaveOneOutTable(
    const SimulationModel& model, const GraspLibrary& library, const SynthesisTableOptions& options,
    const std::function<void(const std::string& stage, int done, int total,
                             const std::string& what)>& progress) {
  if (library.entries.size() < 3) {
    throw InputError("leave-one-out needs a library with at least 3 orientations ('" +
                     library.source + "' has " + std::to_string(library.entries.size()) + ")");
  }
  SynthesisTableOptions table = options;
  std::vector<StudyRow> rows;
  for (size_t k = 1; k + 1 < library.entries.size(); ++k) {
    GraspLibrary without = library;
    without.entries.erase(without.entries.begin() + static_cast<long>(k));
    table.orientations = {library.entries[k].theta_deg};
    std::ostringstream stage;
    stage << "without " << library.entries[k].theta_deg;
    table.stage = options.stage + "-without-" + std::to_string(k);
    const std::vector<StudyRow> part =
        SynthesisTable(model, without, table, [&](int done, int total, const std::string& w) {
          if (progress) progress(stage.str(), done, total, w);
        });
    rows.insert(rows.end(), part.begin(), part.end());
  }
  return rows;
}

namespace {

// The study's stage 3: the synthesis table of `options` from `library`, or, when the library is
// empty or unusable, one row per orientation and method that says why (status unset).
std::vector<StudyRow> SynthesisStage(const SimulationModel& model, const StudyOptions& options,
                                     const GraspLibrary& library, const StudyProgress& progress) {
  std::vector<StudyRow> rows;
  SynthesisTableOptions table;
  table.orientations = options.orientations;
  table.methods = options.methods;
  table.gate.robustness.trials = options.gate_perturbations;
  table.gate.robustness.perturbation = options.perturbation;
  table.gate.sensitivity_trials = options.sensitivity_trials;
  table.gate.min_robustness = options.min_robustness;
  table.gate.hold_margin = options.hold_margin;
  table.physics_fallback = options.physics_fallback;
  table.gate.mujoco = options.mujoco_gate;
  table.seed = options.seed;
  table.threads = options.threads;
  table.runner = options.runner;
  const auto table_progress = [&](int done, int total, const std::string& what) {
    if (progress) progress(StudyStage::kSynthesis, done, total, what);
  };
  std::string no_model;
  if (library.entries.empty()) {
    no_model = "the selection made an empty library (no orientation had a robust demonstration)";
  } else {
    try {
      rows = SynthesisTable(model, library, table, table_progress);
    } catch (const InputError& e) {
      no_model = e.what();
    }
  }
  if (!no_model.empty()) {
    for (double theta : options.orientations) {
      for (const StudyMethod& method : options.methods) {
        StudyRow row = NewRow(theta, method, options.seed);
        row.status = std::nullopt;  // "no_library": the synthesis did not run
        row.message = no_model;
        rows.push_back(row);
      }
    }
  }
  return rows;
}

}  // namespace

StudyResult RunStudy(const SimulationModel& model, const StudyOptions& options,
                     const StudyProgress& progress) {
  RequireValid(options, "study");
  const auto study_start = std::chrono::steady_clock::now();
  StudyResult result;
  result.options = options;
  auto report = [&](StudyStage stage, int done, int total, const std::string& what) {
    if (progress) progress(stage, done, total, what);
  };

  // stage 1: segmentation and Table I (and the cheap kinematics check of the paper's grasps).
  auto start = std::chrono::steady_clock::now();
  report(StudyStage::kAnalysis, 0, 2, options.DemosName());
  const DemoDirectory demos = ReadDemoDirectory(options.demos, options.demos_name);
  if (demos.logs.empty()) {
    throw InputError("study: no readable demonstration logs (*.csv) in '" + options.demos.string() +
                     "' (" + std::to_string(demos.rejected.size()) + " rejected)");
  }
  result.analysis = AnalyzeDemonstrations(demos, options.analysis);
  if (options.paper_object) {
    result.comparison = CompareWithPaper(result.analysis.table, options.comparison);
    result.reachability = TableIReachability(model.robot(), model.scene());
  }
  report(StudyStage::kAnalysis, 2, 2, "Table I");
  result.analysis_s = SecondsSince(start);

  // stage 2: the representative selection makes the study's own library.
  start = std::chrono::steady_clock::now();
  SelectionOptions selection;
  selection.robustness.trials = options.selection_perturbations;
  selection.robustness.perturbation = options.perturbation;
  selection.robustness.seed = options.seed;
  selection.robustness.threads = options.threads;
  selection.early_stop = options.selection_early_stop;
  selection.runner = options.runner;
  selection.segmentation = options.analysis.segmentation;
  result.selection = SelectRepresentatives(model, demos.logs, demos.directory, selection,
                                           [&](int done, int total, const std::string& file) {
                                             report(StudyStage::kSelection, done, total, file);
                                           });
  for (const RejectedDemoFile& r : demos.rejected) {
    result.selection.issues.push_back({r.file, SelectionIssueKind::kUnreadable, r.reason});
  }
  result.selection_s = SecondsSince(start);

  // stage 3: synthesis and physics validation, one row per orientation and method.
  start = std::chrono::steady_clock::now();
  result.rows = SynthesisStage(model, options, result.selection.library, progress);
  result.synthesis_s = SecondsSince(start);
  result.total_s = SecondsSince(study_start);
  return result;
}

std::vector<StudyMethodSummary> SummarizeStudy(const std::vector<StudyRow>& rows) {
  std::vector<StudyMethodSummary> out;
  std::vector<double> robustness_sum;
  for (const StudyRow& r : rows) {
    size_t i = 0;
    while (i < out.size() && out[i].method != r.method) ++i;
    if (i == out.size()) {
      out.push_back({});
      out.back().method = r.method;
      robustness_sum.push_back(0.0);
    }
    StudyMethodSummary& s = out[i];
    ++s.rows;
    if (r.status == SynthesisStatus::kOk) {
      ++s.synthesized;
      robustness_sum[i] += r.robustness;
    }
    s.nominal_successes += r.nominal_success ? 1 : 0;
    s.passed += r.passed ? 1 : 0;
    s.fallbacks += r.fallback ? 1 : 0;
  }
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].mean_robustness = out[i].synthesized > 0 ? robustness_sum[i] / out[i].synthesized : 0;
    out[i].mean_robustness_all = robustness_sum[i] / out[i].rows;
  }
  return out;
}

}  // namespace graspsynth
