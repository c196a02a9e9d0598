// graspsynth analyze: reads a folder of demonstration logs, segments them, builds the paper's
// Table I, fits the wrist line (Ceres, CGAL cross-check) and the radial model, writes the
// graspsynth-analysis/1 report, and optionally the paper-comparison table (markdown) and the
// paper's Fig. 8 (SVG, drawn by gnuplot).

#include "apps/analyze_command.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/analysis_report.hpp"
#include "apps/cli_helpers.hpp"
#include "apps/figure8.hpp"
#include "apps/request_flags.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "learning_data/demo_directory.hpp"
#include "request/analyze_request.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::apps {
namespace {

namespace fs = std::filesystem;

// The command's own options; the analysis's are the request's (request/analyze_request.hpp).
struct AnalyzeOptions {
  std::string directory;
  std::string out;
  std::string plot;
  std::string table;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
  std::string gnuplot = "gnuplot";
};

// The line principle over placements: the model's terms and residuals, with and without the
// position terms.
void PrintPlacementLine(const PlacementLineFit& fit, std::ostream& out) {
  out << "line principle over placements (" << fit.samples << " sample(s) at " << fit.positions
      << " position(s)): ";
  if (!fit.valid) {
    out << "not fitted: " << fit.message << "\n";
    return;
  }
  char line[600];
  std::snprintf(line, sizeof(line),
                "wrist - object = b + A_x dx + A_y dy + A_theta theta\n"
                "  A_theta (%.3f, %.3f, %.3f) m/rad: the wrist line at %.1f deg\n"
                "  A_x (%.3f, %.3f, %.3f), A_y (%.3f, %.3f, %.3f) m/m: the grasp's shift as "
                "the object moves\n"
                "  residuals: rms %.4f m (max %.4f m) on the table, %.4f m in height; without "
                "A_x, A_y: rms %.4f m (max %.4f m)\n",
                fit.a_theta.x(), fit.a_theta.y(), fit.a_theta.z(), fit.line_angle_deg, fit.a_x.x(),
                fit.a_x.y(), fit.a_x.z(), fit.a_y.x(), fit.a_y.y(), fit.a_y.z(),
                fit.residuals.rms_xy, fit.residuals.max_xy, fit.residuals.rms_z,
                fit.theta_only.rms_xy, fit.theta_only.max_xy);
  out << line;
}

// `comparison` is null for an object that is not the paper's.
void PrintSummary(const DemonstrationAnalysis& a, const PaperComparisonOptions* comparison,
                  std::ostream& out) {
  const TableAnalysis& t = a.table;
  out << "read " << a.files << " demonstration log(s) from " << a.directory << " ("
      << a.rejected.size() << " rejected)\n";
  out << "trials: " << t.used << " used, " << t.unsuccessful.size() << " unsuccessful, "
      << t.unsegmentable.size() << " unsegmentable; " << t.orientations.size()
      << " orientation(s)\n";
  char line[160];
  if (!t.orientations.empty()) {
    out << "  theta   n   pre-grasp d (m)  eta (deg)   grasp d (m)  eta (deg)\n";
    for (const OrientationStats& row : t.orientations) {
      std::snprintf(line, sizeof(line), "  %5.1f %3d   %15.3f %10.1f   %11.3f %10.1f\n",
                    row.theta_deg, row.n, row.pregrasp.d, row.pregrasp.eta_deg, row.grasp.d,
                    row.grasp.eta_deg);
      out << line;
    }
  }
  out << a.line.BriefReport() << "\n";
  if (a.radial.valid) {
    std::snprintf(line, sizeof(line),
                  "radial model: d = %.4f m, eta = theta %+.2f deg, rms %.4f m, max %.4f m\n",
                  a.radial.d, a.radial.c / kDeg, a.radial.residuals.rms, a.radial.residuals.max);
    out << line;
  }
  if (!t.orientations.empty()) {
    std::snprintf(line, sizeof(line),
                  "angular range: grasp eta %.1f deg for object theta %.1f deg\n",
                  a.grasp_ranges.position_eta / kDeg, a.grasp_ranges.object_theta / kDeg);
    out << line;
  }
  if (a.placement_line) PrintPlacementLine(*a.placement_line, out);
  if (!comparison) {
    out << "paper Table I: none for this object (not the paper's pan)\n";
    return;
  }
  int within = 0;
  const std::vector<PaperComparisonRow> rows = CompareWithPaper(t, *comparison);
  for (const PaperComparisonRow& row : rows) within += row.within_tolerance ? 1 : 0;
  out << "paper Table I: " << within << " of " << rows.size() << " orientations within "
      << comparison->distance_tolerance * 1000.0 << " mm / " << comparison->angle_tolerance_deg
      << " deg\n";
}

// Runs the analysis of `o.directory`; the exit status (1 when some files were rejected).
int RunAnalyze(const AnalyzeOptions& o, const request::AnalyzeRequest& r) {
  const SceneModel scene = LoadScene(o.scene, o.object);
  const AnalysisOptions options = request::ToAnalysisOptions(r, scene.grasp_region);
  const PaperComparisonOptions paper_tolerances;
  // only the paper's pan has a published Table I to compare with.
  const PaperComparisonOptions* comparison =
      scene.object.paper_object ? &paper_tolerances : nullptr;

  const DemoDirectory demos = ReadDemoDirectory(o.directory);
  for (const RejectedDemoFile& r : demos.rejected) {
    std::cerr << "graspsynth: analyze: rejected " << r.file << ": " << r.reason << "\n";
  }
  if (demos.logs.empty() && demos.rejected.empty()) {
    throw InputError("analyze: no demonstration logs (*.csv) in '" + o.directory + "'");
  }
  const DemonstrationAnalysis analysis = AnalyzeDemonstrations(demos, options);
  WriteFileAtomically(o.out, AnalysisReportJson(analysis, comparison));
  if (!o.table.empty()) WriteFileAtomically(o.table, TableIMarkdown(analysis.table, comparison));
  PrintSummary(analysis, comparison, std::cout);
  std::cout << "wrote " << o.out << "\n";
  if (!o.table.empty()) std::cout << "wrote " << o.table << "\n";
  std::cout.flush();
  if (!o.plot.empty()) {
    DrawFigure8(analysis, scene, o.gnuplot, o.plot);
    std::cout << "wrote " << o.plot << "\n";
  }
  if (!demos.rejected.empty()) return 1;
  return 0;
}

}  // namespace

void AddAnalyzeCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<AnalyzeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "analyze",
      "Analyze a folder of demonstration logs: Table I, the wrist line (paper III-D)\n"
      "Reads every *.csv log (format graspsynth-demo/1) in DIR; a malformed file is named on\n"
      "stderr with the reason (file, line, column) and the others are analyzed. Each trial is\n"
      "labelled (success: the object centre ends >= --success-lift above its first sample) and\n"
      "segmented (pre-grasp = first wrist sample inside the grasp region, grasp = the grasp\n"
      "event). From the successful trials it builds the paper's Table I (mean pre-grasp and grasp\n"
      "positions per orientation, polar, object-centred), fits the wrist line (Ceres total least\n"
      "squares, optionally robust; CGAL cross-check) and the radial model (eta = theta + c, d\n"
      "constant), and writes the graspsynth-analysis/1 report (JSON) to --out.\n"
      "Exit status: 0 on success, 1 when some files were rejected (the report is still\n"
      "written), 2 on an error (missing folder, bad option, gnuplot failure).");
  auto flags =
      std::make_shared<RequestFlags<request::AnalyzeRequest>>(cmd, request::AnalyzeOptions());
  cmd->add_option("DIR", opts->directory, "Folder of demonstration logs (*.csv)")->required();
  cmd->add_option("--out", opts->out, "Report file to write (JSON, graspsynth-analysis/1)")
      ->required();
  cmd->add_option("--plot", opts->plot,
                  "Also draw the paper's Fig. 8 to this SVG file with gnuplot: mean pre-grasp "
                  "and grasp positions per orientation, the wrist line, the grasp region and "
                  "the object outline, object-centred, equal axes");
  cmd->add_option("--table", opts->table,
                  "Also write the Table I (markdown) to this file: for the paper's pan beside "
                  "the paper's, rows beyond 5 mm / 2 deg marked; for another object its own");
  cmd->add_option("--scene", opts->scene,
                  "Scene description (graspsynth-scene/2) for the default grasp region and the "
                  "object outline; default: models/scene.json");
  AddObjectFlag(cmd, &opts->object);
  cmd->add_option("--gnuplot", opts->gnuplot, "The gnuplot program used by --plot")
      ->capture_default_str();

  cmd->callback([opts, flags, exit_code] { *exit_code = RunAnalyze(*opts, flags->Build()); });
}

}  // namespace graspsynth::apps
