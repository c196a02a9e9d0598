// graspsynth generalize: grasps for many orientations from a grasp library by several methods,
// each validated in physics (studies/study.hpp's SynthesisTable), as CSV and markdown; with
// --leave-one-out, each inner demonstrated orientation synthesized from the library without it.

#include "apps/generalize_command.hpp"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"
#include "learning_data/grasp_library.hpp"
#include "request/generalize_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "studies/study.hpp"
#include "studies/study_report.hpp"

namespace graspsynth::apps {
namespace {

namespace fs = std::filesystem;

// The command's own options; the table's are the request's (request/generalize_request.hpp).
struct GeneralizeOptions {
  std::string library;
  std::string name = "generalization";
  std::string out;
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
  bool resume = false;
};

int RunGeneralize(const GeneralizeOptions& o, const request::GeneralizeRequest& r,
                  const CLI::App& command) {
  SynthesisTableOptions table = request::ToSynthesisTableOptions(r);
  if (o.out.empty()) throw InputError("--out is required");
  if (fs::exists(o.out) && !fs::is_directory(o.out)) {
    throw InputError("--out '" + o.out + "' exists and is not a folder");
  }
  if (o.name.empty() || o.name.find('/') != std::string::npos) {
    throw InputError("--name '" + o.name + "' must be a plain file name stem");
  }
  SceneModel scene = LoadScene(o.scene, o.object, kSynthesisNeedsHandle);
  const fs::path library_path =
      o.library.empty() ? DefaultGraspLibraryPath(scene.object.name) : fs::path(o.library);
  const std::string library_name =
      o.library.empty() ? "the shipped library" : "`" + o.library + "`";
  const GraspLibrary library = ReadGraspLibrary(library_path);
  const SimulationModel model(LoadRobotOption(o.robot), std::move(scene));
  RequireDefaultRobot(model.robot(), "--robot: generalize", "a grasp library (graspsynth-library)");

  table.runner = &ProcessRunner();
  RunIdentity identity = CommandIdentity(command);
  AddRequestIdentity(request::GeneralizeOptions(), r, &identity);
  identity.AddFile("library file", library_path);
  AddModelFiles(o.robot, o.scene, o.object, &identity);
  RunCheckpoint checkpoint(fs::path(o.out) / ("." + o.name + ".resume"), identity, o.resume);

  ProgressBar bar;
  std::vector<StudyRow> rows;
  std::ostringstream what;
  if (r.leave_one_out) {
    what << "Leave-one-out on " << library_name
         << ": each inner demonstrated orientation synthesized from the library without it.";
    rows = LeaveOneOutTable(model, library, table,
                            [&](const std::string& stage, int done, int total,
                                const std::string& w) { bar.Update(stage, done, total, w); });
  } else {
    what << "Library: " << library_name << ", orientations " << r.orientations << " deg";
    if (!table.positions.empty()) {
      what << " at " << table.positions.size() << " object positions (x " << r.x << " m, y " << r.y
           << " m)";
    }
    what << ".";
    rows = SynthesisTable(model, library, table, [&](int done, int total, const std::string& w) {
      bar.Update("synthesis", done, total, w);
    });
  }
  bar.Finish();
  if (!ProcessRunner().writes_outputs()) return 0;

  std::ostringstream md;
  md << "# " << o.name << "\n\n"
     << what.str() << " Seed " << r.seed << ", " << r.perturb
     << " perturbed replays per grasp (noise x" << r.noise_scale
     << "; gate: nominal success and robustness >= 0.80).\n\n"
     << "## Summary\n\n"
     << SummaryMarkdown(rows) << "\n## Where a method falls short\n\n"
     << ShortfallMarkdown(rows) << "\n## Every grasp\n\n"
     << SynthesisTableMarkdown(rows) << "## Hold quality and sensitivity to the physics\n\n"
     << HoldAndSensitivityMarkdown(rows) << "\n## Hold margin\n\n"
     << HoldMarginMarkdown(rows, table.gate.hold_margin);
  if (const std::string engines = EnginesMarkdown(rows); !engines.empty()) {
    md << "\n## ODE and MuJoCo side by side\n\n" << engines;  // with --engines ode,mujoco
  }
  const fs::path out = o.out;
  WriteFileAtomically(out / (o.name + ".csv"), StudySynthesisCsv(rows));
  WriteFileAtomically(out / (o.name + ".md"), md.str());
  for (const StudyMethodSummary& s : SummarizeStudy(rows)) {
    std::printf(
        "%s: %d/%d nominal successes (%.1f%%), %d passed the gate, mean robustness %.2f over "
        "all rows\n",
        s.method.c_str(), s.nominal_successes, s.rows, 100.0 * s.nominal_successes / s.rows,
        s.passed, s.mean_robustness_all);
  }
  std::printf("wrote %s and %s\n", (out / (o.name + ".csv")).string().c_str(),
              (out / (o.name + ".md")).string().c_str());
  checkpoint.Done();
  return 0;
}

}  // namespace

void AddGeneralizeCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<GeneralizeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generalize",
      "Synthesize and validate grasps for many orientations, positions and methods\n"
      "Synthesizes a grasp for every orientation of --orientations by every method of\n"
      "--methods from a grasp library, and validate each in physics (a nominal trial and\n"
      "--perturb perturbed replays; the gate: nominal success and robustness >= 0.8).\n"
      "With --leave-one-out, each inner orientation of the library is synthesized from the\n"
      "library without it. Writes OUT/NAME.csv (the study's synthesis CSV layout) and\n"
      "OUT/NAME.md (summary per method, the shortfalls with the simulator's reasons, every\n"
      "grasp), atomically; the CSV is the same bytes for the same seed whatever --threads is,\n"
      "and whatever the number of processes under mpirun (docs/scale-out.md).\n"
      "Each finished grasp is kept in OUT/.NAME.resume/ until the end: --resume after a\n"
      "kill runs only the grasps that were not finished.\n"
      "Methods: interp, line or nearest, then +refine (both refinement stages), +ceres or\n"
      "+nlopt (one stage), then /arc (arc-length resampling of the blend), /spline or\n"
      "/joint (the reach; default auto), /strict (the refinement's default thresholds\n"
      "even where the sources break them) and /slide (with a refinement: a grip at the\n"
      "handle's end slid toward the object's centre), e.g. interp+refine/arc.\n"
      "With --x and --y, every orientation at every position of the grid: the object\n"
      "elsewhere on the table (a library over placements interpolates between them; the\n"
      "CSV then starts with the columns x and y).\n"
      "Experiments 2 and 3 (experiments/generalization.sh, experiments/ablations.sh) and the\n"
      "placements study (experiments/placements.sh) run it.\n"
      "Example:\n"
      "  graspsynth generalize --orientations 20:100:1 --out results");
  auto flags =
      std::make_shared<RequestFlags<request::GeneralizeRequest>>(cmd, request::GeneralizeOptions());
  cmd->add_option(
      "--library", opts->library,
      "Grasp library (graspsynth-library/1, or /2 over placements; default: the shipped one)");
  cmd->add_option("--name", opts->name, "Stem of the output files")->capture_default_str();
  cmd->add_option("--out", opts->out, "Output folder")->required();
  AddResumeFlag(cmd, &opts->resume);
  AddRobotOption(cmd, &opts->robot);
  cmd->add_option("--scene", opts->scene, "Scene description (JSON); default: models/scene.json");
  AddObjectFlag(cmd, &opts->object);
  cmd->callback(
      [opts, flags, exit_code, cmd] { *exit_code = RunGeneralize(*opts, flags->Build(), *cmd); });
}

}  // namespace graspsynth::apps
