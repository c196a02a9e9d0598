// graspsynth demos: the synthetic operator (learning_data/synthetic_operator.hpp) from the
// command line - generate a demonstration set, or calibrate the operator against Table I.

#include "apps/demos_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "analysis/analysis_report.hpp"
#include "analysis/table_analysis.hpp"
#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "common/errors.hpp"
#include "common/json_reader.hpp"
#include "common/orientation_list.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"
#include "learning_data/segmentation.hpp"
#include "learning_data/synthetic_operator.hpp"
#include "request/demos_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"

namespace graspsynth::apps {
namespace {

namespace fs = std::filesystem;

// The command's own options; the operator's overrides are the request's
// (request/demos_request.hpp).
struct DemosOptions {
  std::string out;
  std::string operator_file;  // --operator: the operator file; empty: the shipped one
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
  bool quiet = false;
  bool resume = false;
};

// The operator file of --operator, or the shipped one of the scene's object.
fs::path OperatorPath(const DemosOptions& o, const SceneModel& scene) {
  return o.operator_file.empty() ? DefaultOperatorOptionsPath(scene.object.name)
                                 : fs::path(o.operator_file);
}

// The operator of --operator (or the shipped one) with the request's overrides.
OperatorOptions LoadOperator(const DemosOptions& o, const request::DemosRequest& r,
                             const SceneModel& scene) {
  return request::ApplyToOperator(r, ReadOperatorOptions(OperatorPath(o, scene)));
}

// --config is a file of options; the operator file it was before is refused, saying where it
// went.
void RefuseOperatorConfig(const std::string& config) {
  RefuseFormerConfig(config, kOperatorFormat, "an operator file", "operator file", "--operator");
}

std::unique_ptr<SimulationModel> LoadModel(const DemosOptions& o) {
  RobotModel robot = LoadRobotOption(o.robot);
  RequireDefaultRobot(robot, "--robot: demos",
                      "the synthetic operator (its operator file and glove map)");
  SceneModel scene = LoadScene(o.scene, o.object, "the synthetic operator's grip");
  return std::make_unique<SimulationModel>(std::move(robot), std::move(scene));
}

TableAnalysis Analyze(const SimulationModel& model, const std::vector<OperatorTrial>& trials) {
  SegmentationOptions segmentation;
  segmentation.region = model.scene().grasp_region;
  std::vector<SegmentedTrial> segmented;
  for (const OperatorTrial& t : trials) segmented.push_back(Segment(t.log, segmentation));
  return AnalyzeTable(segmented);
}

// Prints the per-orientation summary: successes, and the means (beside the paper's for the
// paper's pan, `paper_object`).
void PrintSummary(const TableAnalysis& table, const std::vector<OperatorTrial>& trials,
                  bool paper_object) {
  std::map<double, std::pair<int, int>> counts;  // theta -> (trials, successes)
  std::map<double, std::map<std::string, int>> failures;
  for (const OperatorTrial& t : trials) {
    ++counts[t.theta_deg].first;
    if (t.success) {
      ++counts[t.theta_deg].second;
    } else {
      ++failures[t.theta_deg][std::string(OutcomeName(t))];
    }
  }
  std::map<double, PaperTableRow> paper;
  if (paper_object) {
    for (const PaperTableRow& r : PaperTableI()) paper[r.theta_deg] = r;
    std::printf(
        "theta  trials  ok   grasp d  (paper)   eta    (paper)  pre-grasp eta (paper)  "
        "failures\n");
  } else {
    std::printf("theta  trials  ok   grasp d      eta   pre-grasp eta  failures\n");
  }
  for (const auto& [theta, c] : counts) {
    std::printf("%5.0f  %6d  %2d", theta, c.first, c.second);
    const OrientationStats* row = nullptr;
    for (const OrientationStats& s : table.orientations) {
      if (s.theta_deg == theta) row = &s;
    }
    if (row && paper.count(theta)) {
      const PaperTableRow& p = paper[theta];
      std::printf("   %.3f  (%.3f)  %6.1f  (%6.1f)  %6.1f  (%6.1f)     ", row->grasp.d, p.grasp_d,
                  row->grasp.eta_deg, p.grasp_eta_deg, row->pregrasp.eta_deg, p.pregrasp_eta_deg);
    } else if (row && !paper_object) {
      std::printf("   %.3f  %6.1f  %13.1f   ", row->grasp.d, row->grasp.eta_deg,
                  row->pregrasp.eta_deg);
    } else if (!paper_object) {
      std::printf("   %-33s", "-");
    } else {
      std::printf("   %-54s", "-");
    }
    for (const auto& [outcome, n] : failures[theta]) std::printf(" %s %d", outcome.c_str(), n);
    std::printf("\n");
  }
}

// Successes per object position (a grid of positions; the table above pools them).
void PrintPositions(const std::vector<OperatorTrial>& trials) {
  std::map<std::pair<double, double>, std::pair<int, int>> counts;  // (y, x) -> (trials, ok)
  for (const OperatorTrial& t : trials) {
    if (!t.position) continue;
    auto& c = counts[{t.position->y(), t.position->x()}];
    ++c.first;
    c.second += t.success ? 1 : 0;
  }
  std::printf("      x       y  trials   ok\n");
  for (const auto& [yx, c] : counts) {
    std::printf("%7.3f %7.3f  %6d %4d\n", yx.second, yx.first, c.first, c.second);
  }
}

int Generate(const DemosOptions& o, const request::DemosRequest& r, const CLI::App& command) {
  const std::unique_ptr<SimulationModel> model = LoadModel(o);
  const OperatorOptions options = LoadOperator(o, r, model->scene());
  RunIdentity identity = CommandIdentity(command);
  AddRequestIdentity(request::DemosGenerateOptions(), r, &identity);
  identity.AddFile("operator file", OperatorPath(o, model->scene()));
  AddModelFiles(o.robot, o.scene, o.object, &identity);
  RunCheckpoint checkpoint(fs::path(o.out) / ".demos.resume", identity, o.resume);
  ProgressBar bar;
  const std::vector<OperatorTrial> trials = GenerateDemonstrations(
      *model, options, r.threads,
      [&](int done, int total) {
        if (!o.quiet) bar.Update("simulating trials", done, total, "");
      },
      &ProcessRunner());
  bar.Finish();
  if (!ProcessRunner().writes_outputs()) return 0;
  fs::create_directories(o.out);
  for (const OperatorTrial& t : trials) WriteDemoLog(fs::path(o.out) / t.log.source, t.log);
  OperatorOptions used = options;
  WriteOperatorOptions(used, fs::path(o.out) / "operator.json");
  PrintSummary(Analyze(*model, trials), trials, model->scene().object.paper_object);
  if (!options.positions.empty()) PrintPositions(trials);
  std::printf("wrote %zu logs and operator.json to %s\n", trials.size(), o.out.c_str());
  checkpoint.Done();
  return 0;
}

// Moves every strategy of `plan` by the horizontal offset (dx, dy).
void Shift(OrientationPlan* plan, const Eigen::Vector2d& delta) {
  for (GraspStrategy& s : plan->strategies) {
    Eigen::Vector2d p(s.d * std::cos(s.eta_deg * kDeg), s.d * std::sin(s.eta_deg * kDeg));
    p += delta;
    s.d = p.norm();
    s.eta_deg = std::atan2(p.y(), p.x()) / kDeg;
  }
}

// How far an orientation's row is from the paper's, in units of the tolerances (5 mm, 2 deg),
// with a penalty when its number of successful trials is outside 5..10. Lower is better.
double RowError(const OrientationStats& s, const PaperTableRow& p) {
  const double error =
      std::max({std::abs(s.grasp.d - p.grasp_d) / 0.005,
                std::abs(std::remainder(s.grasp.eta_deg - p.grasp_eta_deg, 360.0)) / 2.0,
                std::abs(std::remainder(s.pregrasp.eta_deg - p.pregrasp_eta_deg, 360.0)) / 2.0});
  return error + (s.n < 5 || s.n > 10 ? 10.0 : 0.0);
}

// Each orientation's trials depend only on its own plan (and the seed), so every plan is
// calibrated on its own: after each round, the plan's strategies are shifted by a damped
// difference between the paper's row and the mean of its successful trials, and the best plan
// seen (RowError) is kept.
int Calibrate(const DemosOptions& o, const request::DemosRequest& r) {
  const std::unique_ptr<SimulationModel> model = LoadModel(o);
  if (!model->scene().object.paper_object) {
    throw InputError("demos calibrate: the object '" + model->scene().object.name +
                     "' is not the paper's pan; only the pan has a published Table I to "
                     "calibrate to (another object's operator is planned from its geometry: "
                     "experiments/make_operator.py)");
  }
  OperatorOptions options = LoadOperator(o, r, model->scene());
  std::map<double, PaperTableRow> paper;
  for (const PaperTableRow& r : PaperTableI()) paper[r.theta_deg] = r;
  std::vector<OrientationPlan> best = options.plans;
  std::vector<double> best_error(options.plans.size(), 1e300);
  ProgressBar bar;
  for (int iteration = 1; iteration <= r.iterations; ++iteration) {
    const std::vector<OperatorTrial> trials =
        GenerateDemonstrations(*model, options, r.threads, [&](int done, int total) {
          if (!o.quiet) bar.Update("round " + std::to_string(iteration), done, total, "");
        });
    bar.Finish();
    const TableAnalysis table = Analyze(*model, trials);
    PrintSummary(table, trials, true);
    for (size_t k = 0; k < options.plans.size(); ++k) {
      OrientationPlan& plan = options.plans[k];
      if (!paper.count(plan.theta_deg)) continue;
      const PaperTableRow& p = paper[plan.theta_deg];
      for (const OrientationStats& s : table.orientations) {
        if (s.theta_deg != plan.theta_deg || s.n == 0) continue;
        const double error = RowError(s, p);
        if (error < best_error[k]) {
          best_error[k] = error;
          best[k] = plan;
        }
        const Eigen::Vector2d target(p.grasp_d * std::cos(p.grasp_eta_deg * kDeg),
                                     p.grasp_d * std::sin(p.grasp_eta_deg * kDeg));
        Shift(&plan, r.damping * (target - s.grasp.mean_xy));
        plan.pregrasp_eta_deg += r.damping * (p.pregrasp_eta_deg - s.pregrasp.eta_deg);
      }
    }
  }
  options.plans = best;
  WriteOperatorOptions(options, o.out);
  std::printf("best error per orientation (1 = at the tolerance):");
  for (size_t k = 0; k < best.size(); ++k) {
    std::printf(" %g: %.2f", best[k].theta_deg, best_error[k]);
  }
  std::printf("\nwrote the calibrated operator to %s\n", o.out.c_str());
  return 0;
}

// The flags generate and calibrate share beside the request's.
void AddCommonOptions(CLI::App* cmd, DemosOptions* o) {
  cmd->add_option("--operator", o->operator_file,
                  "Operator file (graspsynth-operator/1); default: the shipped, calibrated "
                  "learning_data/demos/operator.json");
  AddRobotOption(cmd, &o->robot);
  cmd->add_option("--scene", o->scene, "Scene description (JSON)");
  AddObjectFlag(cmd, &o->object);
  cmd->add_flag("--quiet", o->quiet, "No progress bar");
}

}  // namespace

void AddDemosCommand(CLI::App& app, int* exit_code) {
  auto* demos = app.add_subcommand(
      "demos",
      "Make demonstrations with the synthetic operator (generate, calibrate)\n"
      "The synthetic operator: a model of the paper's human operator that makes teleoperation "
      "trials (60 Hz logs, format graspsynth-demo/1) for the orientations of its config, runs "
      "each one in the ODE simulation through the arm's IK and labels it with what happened to "
      "the pan there. --operator FILE is the operator file (graspsynth-operator/1); "
      "--config FILE a file of the command's options.");
  demos->require_subcommand(1);
  auto o = std::make_shared<DemosOptions>();

  auto* generate = demos->add_subcommand(
      "generate",
      "Generate a demonstration set, one log per trial, into --out\n"
      "Writes one CSV log per trial (theta020_trial01.csv, ...) and the operator.json that made\n"
      "it into --out. The same operator file and seed give the same bytes, whatever --threads is "
      "and whatever the number of processes under mpirun\n"
      "(docs/scale-out.md). Finished trials are kept in OUT/.demos.resume/ until the end:\n"
      "--resume after a kill runs only the others.\n"
      "Example:\n  graspsynth demos generate --out demos/ --seed 7 --trials-per-orientation 10");
  auto generate_flags = std::make_shared<RequestFlags<request::DemosRequest>>(
      generate, request::DemosGenerateOptions());
  generate->add_option("--out", o->out, "Output folder")->required();
  AddCommonOptions(generate, o.get());
  AddResumeFlag(generate, &o->resume);
  generate->callback([o, generate_flags, exit_code, generate] {
    RefuseOperatorConfig(generate_flags->config());
    *exit_code = Generate(*o, generate_flags->Build(), *generate);
  });

  auto* calibrate = demos->add_subcommand(
      "calibrate",
      "Calibrate an operator file against the paper's Table I\n"
      "Shift each orientation's intended grasp positions and entry angle by the difference "
      "between the paper's Table I and the mean of the successful trials, --iterations times, "
      "and write the calibrated operator file.");
  auto calibrate_flags = std::make_shared<RequestFlags<request::DemosRequest>>(
      calibrate, request::DemosCalibrateOptions());
  calibrate->add_option("--out", o->out, "Calibrated operator file to write")->required();
  AddCommonOptions(calibrate, o.get());
  calibrate->callback([o, calibrate_flags, exit_code] {
    RefuseOperatorConfig(calibrate_flags->config());
    *exit_code = Calibrate(*o, calibrate_flags->Build());
  });
}

}  // namespace graspsynth::apps
