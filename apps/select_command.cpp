// graspsynth select: scores every successful demonstration of a folder by perturbed replays in
// the ODE simulation, picks the most robust per orientation and writes the graspsynth-library/1
// file that synthesis reads.

#include "apps/select_command.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <tuple>

#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"
#include "learning_data/grasp_library.hpp"
#include "learning_data/representative_selection.hpp"
#include "request/select_request.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::apps {
namespace {

// The command's own options; the selection's are the request's (request/select_request.hpp).
struct SelectCommandOptions {
  std::string directory;
  std::string out;
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
  bool resume = false;
};

int RunSelect(const SelectCommandOptions& o, const request::SelectRequest& r,
              const CLI::App& command) {
  const SceneModel scene = LoadScene(o.scene, o.object);
  const SimulationModel model(LoadRobotOption(o.robot), scene);
  RequireDefaultRobot(model.robot(), "--robot: select", "demonstration logs (graspsynth-demo/1)");
  SelectionOptions options = request::ToSelectionOptions(r, scene);
  options.runner = &ProcessRunner();
  RunIdentity identity = CommandIdentity(command);
  AddRequestIdentity(request::SelectOptions(), r, &identity);
  identity.AddFile("demonstrations", o.directory);
  AddModelFiles(o.robot, o.scene, o.object, &identity);
  const std::filesystem::path out(o.out);
  RunCheckpoint checkpoint(out.parent_path() / ("." + out.filename().string() + ".resume"),
                           identity, o.resume);

  ProgressBar bar;
  const SelectionResult result =
      SelectRepresentatives(model, std::filesystem::path(o.directory), options,
                            [&](int done, int total, const std::string& file) {
                              bar.Update("selecting replays", done, total, file);
                            });
  bar.Finish();
  if (!ProcessRunner().writes_outputs()) return 0;
  const GraspLibrary& library = result.library;
  WriteGraspLibrary(library, o.out);
  checkpoint.Done();

  int unreadable = 0;
  for (const SelectionIssue& issue : result.issues) {
    if (issue.kind == SelectionIssueKind::kUnreadable) ++unreadable;
  }
  std::printf(
      "read %d demonstration log(s) from %s (%d rejected): %zu successful and scored, %d "
      "unsuccessful (skipped)\n",
      result.logs, o.directory.c_str(), unreadable, library.scores.size(), result.unsuccessful);
  std::printf("%d perturbed replays per demonstration, seed %llu\n", options.robustness.trials,
              static_cast<unsigned long long>(options.robustness.seed));
  const auto [ran, all, stopped] = CountSelectionReplays(library);
  if (stopped > 0) {
    std::printf(
        "%d of %d perturbed replays ran: %d demonstration(s) stopped once they could no longer "
        "win their orientation (--all-replays runs them all)\n",
        ran, all, stopped);
  }
  std::printf("\n");

  // one row per placement with successful demonstrations (the orientation alone when every
  // demonstration is at one position).
  const bool positions = library.HasPositions();
  using Key = std::tuple<double, double, double>;  // x, y, theta_deg
  const auto key = [positions](const DemoScore& s) {
    return positions ? Key{s.xy.x(), s.xy.y(), s.theta_deg} : Key{0.0, 0.0, s.theta_deg};
  };
  std::map<Key, int> successful;
  for (const DemoScore& s : library.scores) ++successful[key(s)];
  std::map<Key, const DemoScore*> selected;
  for (const DemoScore& s : library.scores) {
    if (s.selected) selected[key(s)] = &s;
  }
  if (positions) std::printf("%7s  %7s  ", "x", "y");
  std::printf("%9s  %3s  %-32s  %6s  %s\n", "theta_deg", "n", "selected", "score", "95% CI");
  for (const auto& [k, n] : successful) {
    if (positions) std::printf("%7.3f  %7.3f  ", std::get<0>(k), std::get<1>(k));
    const auto it = selected.find(k);
    if (it == selected.end()) {
      std::printf("%9.2f  %3d  %-32s\n", std::get<2>(k), n, "(none: no replay succeeded)");
      continue;
    }
    const DemoScore& s = *it->second;
    std::printf("%9.2f  %3d  %-32s  %6.3f  [%.3f, %.3f]\n", s.theta_deg, n, s.file.c_str(), s.score,
                s.ci_low, s.ci_high);
  }
  if (!result.issues.empty()) {
    std::printf("\nrejected or not replayable (%zu):\n", result.issues.size());
    for (const SelectionIssue& issue : result.issues) {
      std::printf("  %s (%s): %s\n", issue.file.c_str(), ToString(issue.kind),
                  issue.reason.c_str());
      std::fprintf(stderr, "%s %s: %s\n",
                   issue.kind == SelectionIssueKind::kUnreadable ? "rejected" : "not replayed",
                   issue.file.c_str(), issue.reason.c_str());
    }
  }
  const char* what = library.HasPositions() ? "placement" : "orientation";
  std::printf("\nwrote %s: %zu %s(s) selected\n", o.out.c_str(), library.entries.size(), what);
  if (library.entries.empty()) {
    std::fprintf(stderr, "graspsynth select: no %s could be selected\n", what);
    return 1;
  }
  return 0;
}

}  // namespace

void AddSelectCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<SelectCommandOptions>();
  CLI::App* select = app.add_subcommand(
      "select",
      "Pick the most robust demonstration per orientation: the grasp library\n"
      "Every successful demonstration of the directory (object lifted >= 5 cm at the end) that\n"
      "segments (a pre-grasp inside the scene's grasp region before the grasp event) is\n"
      "replayed as the operator made it - reach, grasping motion and lift, through the arm's\n"
      "IK - in the ODE simulation: once unperturbed and --perturb times with time scaling\n"
      "(U[0.7, 1.3]) and waypoint noise (5 mm, 2 deg wrist, 2 deg fingers). Its score is the\n"
      "success fraction with a 95% Wilson interval. A demonstration the arm cannot play scores\n"
      "0. Per orientation the representative has the highest score; ties go to the higher\n"
      "Wilson lower bound, then a successful nominal replay, then the shorter grasping motion,\n"
      "then the file name. An orientation whose best score is 0 gets no entry.\n"
      "When the logs' objects stand at several positions on the table (their object_position),\n"
      "the choice is made per placement (position and orientation) instead, and the library is\n"
      "graspsynth-library/2: every score and entry also carries its \"placement\" {x, y,\n"
      "theta_deg}, entries sorted by x, y, theta (learning_data/placements/library.json).\n"
      "Replays are spent only where they can change the choice: an orientation's\n"
      "demonstrations are scored in the tie rule's order, and one stops replaying once it has\n"
      "failed so often that it cannot win over the best fully scored one (its score then counts\n"
      "the replays that ran, and `stopped` says why). The representatives and their scores are\n"
      "those of --all-replays, which runs every replay.\n\n"
      "Each demonstration's perturbations are seeded from --seed and its file name, so the same\n"
      "--seed gives the same library, byte for byte, whatever --threads is, and whatever the\n"
      "number of processes under mpirun (docs/scale-out.md). Finished jobs are kept\n"
      "in .OUT.resume/ beside --out until the end: --resume after a kill runs only the others.\n\n"
      "The library (--out, graspsynth-library/1 or /2 JSON) holds every score (file, trial,\n"
      "theta_deg, trials, successes, score, ci_low, ci_high, nominal_success, seed, failures,\n"
      "selected; stopped when its replays stopped early) and per orientation the selected\n"
      "grasping motion (pre-grasp to grasp) with the operator's lift. The table on stdout lists\n"
      "per orientation the successful demonstrations (n), the selected file, its score and\n"
      "interval; rejected files are listed with their reasons. Exit status: 0 when at least one "
      "orientation was selected, 1 when\n"
      "none was (the library is written all the same), 2 on bad input.\n\n"
      "Example:\n"
      "  graspsynth select learning_data/demos --out out/library.json\n"
      "(learning_data/library.json, the shipped library, is this with --all-replays.)");
  select->add_option("directory", opts->directory, "Folder of demonstration logs (*.csv, v1)")
      ->required()
      ->check(CLI::ExistingDirectory);
  select->add_option("--out", opts->out, "Library file to write (JSON)")->required();
  auto flags =
      std::make_shared<RequestFlags<request::SelectRequest>>(select, request::SelectOptions());
  AddRobotOption(select, &opts->robot);
  select->add_option("--scene", opts->scene,
                     "Scene description (JSON); default: models/scene.json");
  AddObjectFlag(select, &opts->object);
  AddResumeFlag(select, &opts->resume);
  select->callback(
      [opts, flags, exit_code, select] { *exit_code = RunSelect(*opts, flags->Build(), *select); });
}

}  // namespace graspsynth::apps
