// graspsynth run: the main job. The end-to-end study on a folder of demonstrations (by default
// the shipped ones): Table I against the paper, Fig. 8, the representative selection, the
// synthesis of a grasp for every study orientation by each method and its physics validation,
// written into one output folder (studies/study.hpp computes, studies/study_report.hpp
// renders; this file shows and writes).

#include "apps/run_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli_helpers.hpp"
#include "apps/figure8.hpp"
#include "apps/request_flags.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"
#include "learning_data/demo_directory.hpp"
#include "learning_data/grasp_library.hpp"
#include "request/run_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "studies/study.hpp"
#include "studies/study_report.hpp"

namespace graspsynth::apps {
namespace {

namespace fs = std::filesystem;

// The command's own options; the study's are the request's (request/run_request.hpp).
struct RunOptions {
  std::string out = "study";
  std::string demos;  // empty: learning_data/demos of the data folder
  std::string gnuplot = "gnuplot";
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
  bool resume = false;
};

// The files; every one is written atomically, the report last (with Fig. 8 when drawn).
void WriteStudyFiles(const SceneModel& scene, const std::string& gnuplot, const fs::path& out,
                     StudyResult* result) {
  WriteFileAtomically(out / "analysis.json",
                      AnalysisReportJson(result->analysis, result->options.PaperComparison()));
  WriteGraspLibrary(result->selection.library, out / "library.json");
  WriteFileAtomically(out / "synthesis.json", StudySynthesisJson(*result));
  WriteFileAtomically(out / "synthesis.csv", StudySynthesisCsv(result->rows));
  WriteFileAtomically(out / "timing.json", StudyTimingJson(*result));
  try {
    DrawFigure8(result->analysis, scene, gnuplot, out / "fig8.svg");
    result->figure = "fig8.svg";
  } catch (const InputError& e) {
    result->figure_note = e.what();
    std::cerr << "graspsynth run: Fig. 8 not drawn: " << e.what() << "\n";
  }
  WriteFileAtomically(out / "report.md", StudyReportMarkdown(*result));
}

// The short summary on stdout.
void PrintStudySummary(const StudyResult& result, const fs::path& out) {
  const StudyOptions& options = result.options;
  const PaperComparisonOptions& comparison = options.comparison;
  int within = 0, paper_rows = 0;
  for (const PaperComparisonRow& row : result.comparison) {
    paper_rows += row.paper ? 1 : 0;
    within += row.within_tolerance ? 1 : 0;
  }
  std::printf("graspsynth run: %s, seed %llu, %.1f s\n", options.DemosName().c_str(),
              static_cast<unsigned long long>(options.seed), result.total_s);
  std::printf("  analysis: %d logs, %d trials used; ", result.analysis.files,
              result.analysis.table.used);
  if (options.paper_object) {
    std::printf("Table I %d of %d orientations within %g mm / %g deg\n", within, paper_rows,
                comparison.distance_tolerance * 1e3, comparison.angle_tolerance_deg);
  } else {
    std::printf("Table I over %zu orientations (no paper table for this object)\n",
                result.analysis.table.orientations.size());
  }
  if (result.analysis.line.usable()) {
    std::printf("  wrist line: rms %.1f mm, max %.1f mm\n",
                result.analysis.line.residuals.rms * 1e3, result.analysis.line.residuals.max * 1e3);
  }
  std::printf("  library: %zu orientation(s) selected, %d perturbed replays per demonstration\n",
              result.selection.library.entries.size(), options.selection_perturbations);
  for (const StudyMethodSummary& s : SummarizeStudy(result.rows)) {
    std::printf(
        "  %s: %d/%d nominal successes, %d/%d passed the gate, mean robustness %.2f (%d "
        "perturbed replays each)\n",
        s.method.c_str(), s.nominal_successes, s.rows, s.passed, s.rows, s.mean_robustness,
        options.gate_perturbations);
  }
  std::printf(
      "wrote %s (report.md, analysis.json, library.json, synthesis.json, synthesis.csv, "
      "timing.json%s)\n",
      out.string().c_str(), result.figure.empty() ? "" : ", fig8.svg");
  std::fflush(stdout);
}

int RunStudyCommand(const RunOptions& o, const request::RunRequest& r, const CLI::App& command) {
  const SceneModel scene = LoadScene(o.scene, o.object, kSynthesisNeedsHandle);
  const SimulationModel model(LoadRobotOption(o.robot), scene);
  RequireDefaultRobot(model.robot(), "--robot: run",
                      "the demonstration logs (graspsynth-demo/1) and the study's grasp library");
  StudyOptions options = request::ToStudyOptions(r, scene, o.demos);
  options.runner = &ProcessRunner();
  RunIdentity identity = CommandIdentity(command);
  AddRequestIdentity(request::RunOptions(), r, &identity);
  identity.AddFile("demonstrations", options.demos);
  AddModelFiles(o.robot, o.scene, o.object, &identity);
  RunCheckpoint checkpoint(fs::path(o.out) / ".run.resume", identity, o.resume);

  ProgressBar bar;
  StudyResult result =
      RunStudy(model, options, [&](StudyStage stage, int done, int total, const std::string& w) {
        bar.Update(ToString(stage), done, total, w);
      });
  bar.Finish();
  if (!ProcessRunner().writes_outputs()) return 0;

  const fs::path out = o.out;
  WriteStudyFiles(scene, o.gnuplot, out, &result);
  PrintStudySummary(result, out);
  checkpoint.Done();
  if (result.selection.library.entries.empty()) {
    std::fprintf(stderr, "graspsynth run: no orientation could be selected; nothing synthesized\n");
    return 1;
  }
  return 0;
}

}  // namespace

void AddRunCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* run = app.add_subcommand(
      "run",
      "The main job: the whole study on the shipped demonstrations\n"
      "1. analysis: segment every log of --demos, build the paper's Table I (for the paper's\n"
      "   pan: compare it with the paper, 5 mm / 2 deg, and check that the paper's grasp\n"
      "   wrist poses are reachable), fit the wrist line and the radial strategy, draw\n"
      "   Fig. 8 (gnuplot);\n"
      "2. selection: score every successful demonstration by perturbed replays in ODE and\n"
      "   pick the most robust per orientation (the study's grasp library);\n"
      "3. synthesis: a grasp for every orientation (default 20, 25, ..., 100 deg) by each\n"
      "   method (interp+refine: the paper's blend with the refinement; line+refine: the line\n"
      "   principle), validated in physics: a nominal trial and --perturb perturbed replays\n"
      "   (the gate: nominal success and robustness >= 0.8).\n"
      "Writes into --out (each file atomically): report.md (every table, the summary and the\n"
      "failure reasons), analysis.json (graspsynth-analysis/1), library.json\n"
      "(graspsynth-library/1), synthesis.json (graspsynth-study-synthesis/1), synthesis.csv,\n"
      "timing.json (wall times) and fig8.svg. A progress bar per stage on stderr, a summary on\n"
      "stdout. The same --seed gives the same analysis, library, synthesis and figure files,\n"
      "byte for byte, whatever --threads is (report.md and timing.json hold wall times).\n"
      "Defaults: 20 selection replays, as the shipped library, 20 gate replays and 2 replays\n"
      "per end of each physics factor in the sensitivity tables, 17 orientations, 2 methods,\n"
      "every replay with the physics perturbed (--physics). With the shipped demonstrations the\n"
      "selection rebuilds learning_data/library.json's choices.\n"
      "--quick runs 40, 45, 60, 85 deg with 2 selection and 3 gate replays.\n"
      "Under mpirun the replays are spread over the processes, the files the same bytes\n"
      "(docs/scale-out.md); finished jobs are kept in OUT/.run.resume/ until the\n"
      "end, and --resume after a kill runs only the others.\n"
      "Exit status: 0 when the study ran (failed grasps are results in the report), 1 when no\n"
      "orientation could be selected, 2 on bad input.\n"
      "Example:\n"
      "  graspsynth run --quick --out study-quick");
  run->add_option("--out", opts->out, "Output folder")->capture_default_str();
  run->add_option("--demos", opts->demos,
                  "Folder of demonstration logs (default: the shipped learning_data/demos)");
  auto flags = std::make_shared<RequestFlags<request::RunRequest>>(run, request::RunOptions());
  run->add_option("--gnuplot", opts->gnuplot, "The gnuplot program for Fig. 8")
      ->capture_default_str();
  AddRobotOption(run, &opts->robot);
  run->add_option("--scene", opts->scene, "Scene description (JSON); default: models/scene.json");
  AddObjectFlag(run, &opts->object);
  AddResumeFlag(run, &opts->resume);
  run->callback(
      [opts, flags, exit_code, run] { *exit_code = RunStudyCommand(*opts, flags->Build(), *run); });
}

}  // namespace graspsynth::apps
