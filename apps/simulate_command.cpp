// graspsynth simulate: a joint trajectory through the ODE world (nominal trial + perturbed
// replays), written as a graspsynth-simulation/1 report. graspsynth scripted-grasp: the
// hand-made grasp trajectory of motion/scripted_grasp.hpp.

#include "apps/simulate_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/field_text.hpp"
#include "common/format.hpp"
#include "common/valid_options.hpp"
#include "gate/grasp_file.hpp"
#include "gate/hold_margin.hpp"
#include "gate/physics_gate.hpp"
#include "kinematics/pose_math.hpp"
#include "kinematics/robot_file.hpp"
#include "motion/joint_trajectory.hpp"
#include "motion/scripted_grasp.hpp"
#include "request/simulate_request.hpp"
#include "simulation/robustness.hpp"
#include "simulation/simulation_fields.hpp"
#include "simulation/trial.hpp"
#include "simulation/trial_record.hpp"
#include "simulation_mujoco/mujoco_fields.hpp"
#include "simulation_mujoco/mujoco_sweep.hpp"
#include "simulation_mujoco/mujoco_trial.hpp"
#include "simulation_mujoco/mujoco_world.hpp"
#include "studies/trial_json.hpp"

namespace graspsynth::apps {
namespace {

using json = nlohmann::ordered_json;

constexpr std::string_view kReportFormat = "graspsynth-simulation/1";

// The command's own options; the simulation's are the request's (request/simulate_request.hpp).
struct SimulateOptions {
  std::string trajectory;
  std::string out;
  std::string record;
  std::string trial_record;  // --trial-record: a graspsynth-trial-record/1 file
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
};

// The scripted grasp's own options; the grasp's are the request's.
struct ScriptedOptions {
  std::string out;
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
};

// Rounds for the report: the figures are physical, 1e-9 is far below their accuracy, and
// short numbers keep the file readable.
double Round(double x) { return RoundForReport(x); }

json PoseJson(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q = Canonical(Eigen::Quaterniond(X.linear()));
  const Eigen::Vector3d& p = X.translation();
  return {{"position", {Round(p.x()), Round(p.y()), Round(p.z())}},
          {"quaternion", {Round(q.w()), Round(q.x()), Round(q.y()), Round(q.z())}}};
}

// The trajectory and grasp files a simulation plays, made for the PA-10 + Gifu Hand III.
constexpr std::string_view kTrajectoryData =
    "a trajectory or grasp file (graspsynth-trajectory/1, graspsynth-grasp/1)";

// The model of --robot, --scene and --object; `data` is what the command reads that only the
// PA-10 + Gifu Hand III can use yet (RequireDefaultRobot; empty: nothing, every robot is taken).
SimulationModel LoadModel(const std::string& robot, const std::string& scene,
                          const std::string& object, std::string_view command,
                          std::string_view data, std::string_view needs_handle = {}) {
  RobotModel robot_model = LoadRobotOption(robot);
  if (!data.empty()) RequireDefaultRobot(robot_model, "--robot: " + std::string(command), data);
  return SimulationModel(std::move(robot_model), LoadScene(scene, object, needs_handle));
}

std::string StatesCsv(const std::vector<TrialState>& states) {
  std::ostringstream s;
  s.precision(9);
  s << "t";
  for (int i = 1; i <= kArmDof; ++i) s << ",q" << i;
  for (int k = 0; k < kHandDof; ++k) s << ",f" << k;
  s << ",object_x,object_y,object_z,object_qw,object_qx,object_qy,object_qz";
  s << ",wrist_x,wrist_y,wrist_z,wrist_qw,wrist_qx,wrist_qy,wrist_qz\n";
  for (const TrialState& st : states) {
    s << st.t;
    for (int i = 0; i < kArmDof; ++i) s << "," << st.arm[i];
    for (int k = 0; k < kHandDof; ++k) s << "," << st.hand[k];
    for (const Eigen::Isometry3d* X : {&st.X_WO, &st.X_WH}) {
      const Eigen::Quaterniond q = Canonical(Eigen::Quaterniond(X->linear()));
      const Eigen::Vector3d& p = X->translation();
      s << "," << p.x() << "," << p.y() << "," << p.z() << "," << q.w() << "," << q.x() << ","
        << q.y() << "," << q.z();
    }
    s << "\n";
  }
  return s.str();
}

// Runs the perturbed replays (when --perturb > 0) and adds `robustness` and `trials` to the
// report; prints their summary on stderr.
void AddPerturbedTrials(const SimulationModel& model, const JointTrajectory& trajectory,
                        const RobustnessOptions& ro, const request::SimulateRequest& o,
                        json* report_out) {
  json& report = *report_out;
  json trials = json::array();
  if (o.perturb > 0) {
    ProgressBar bar;
    const RobustnessResult r = EvaluateRobustness(model, trajectory, ro, [&](int done, int total) {
      bar.Update("simulating", done, total, "perturbed trials");
    });
    bar.Finish();
    report["robustness"] = {{"trials", o.perturb},
                            {"successes", r.successes},
                            {"score", Round(r.score)},
                            {"ci95", {Round(r.ci95.lo), Round(r.ci95.hi)}},
                            {"seed", o.seed},
                            {"time_scale_range", {o.time_scale_min, o.time_scale_max}},
                            {"position_sigma_m", o.position_noise},
                            {"orientation_sigma_deg", o.orientation_noise_deg},
                            {"finger_sigma_deg", o.finger_noise_deg},
                            {"physics", o.physics.enabled ? "on" : "off"}};
    for (const RobustnessTrial& t : r.trials) {
      trials.push_back({{"index", t.index},
                        {"time_scale", Round(t.time_scale)},
                        {"success", t.success()},
                        {"outcome", ToString(t.outcome)},
                        {"reason", t.reason},
                        {"lift_m", Round(t.lift)},
                        {"physics", PhysicsDrawJson<json>(t.physics, ro.trial.step())},
                        {"hold", HoldQualityJson<json>(t.hold)}});
    }
    std::fprintf(stderr,
                 "robustness: %d of %d trials succeeded, score %.3f, 95%% interval [%.3f, %.3f] "
                 "(%d threads, %.1f s; %.1fx real time per core)\n",
                 r.successes, o.perturb, r.score, r.ci95.lo, r.ci95.hi, r.threads, r.wall_time,
                 r.cpu_time > 0 ? r.simulated_time / r.cpu_time : 0.0);
  } else {
    report["robustness"] = {
        {"trials", 0}, {"successes", 0}, {"score", nullptr}, {"ci95", nullptr}, {"seed", o.seed}};
  }
  report["trials"] = trials;
}

// Runs the sensitivity table (when --sensitivity > 0), adds it to the report and prints it.
void AddSensitivity(const SimulationModel& model, const JointTrajectory& trajectory,
                    RobustnessOptions ro, const request::SimulateRequest& o, json* report) {
  if (o.sensitivity <= 0) return;
  ro.trials = o.sensitivity;
  ProgressBar bar;
  const SensitivityResult s = EvaluateSensitivity(model, trajectory, ro, [&](int done, int total) {
    bar.Update("sensitivity", done, total, "one factor at a time");
  });
  bar.Finish();
  std::fprintf(stderr, "sensitivity (%d replays per end; success at the low end / high end):\n",
               s.trials_per_cell);
  for (const SensitivityRow& row : s.rows) {
    std::fprintf(stderr, "  %-18s %d/%d  %d/%d\n", std::string(ToString(row.factor)).c_str(),
                 row.low.successes, row.low.trials, row.high.successes, row.high.trials);
  }
  (*report)["sensitivity"] = SensitivityJson<json>(s, ro.trial.step());
}

// The report in words, for stdout when there is no --out: the nominal trial's outcome, reason
// and lift, and the perturbed replays' score.
std::string ReportSummary(const json& report) {
  const json& n = report["nominal"];
  std::string text = report["trajectory"].get<std::string>() + ": nominal trial " +
                     (n["success"].get<bool>() ? "succeeded" : "FAILED") + " (" +
                     n["outcome"].get<std::string>() + "): " + n["reason"].get<std::string>() +
                     "\n" +
                     Format("  lift %.1f mm (highest %.1f mm), %.2f s simulated\n",
                            1e3 * n["lift_m"].get<double>(), 1e3 * n["max_lift_m"].get<double>(),
                            n["simulated_s"].get<double>());
  const json& rb = report["robustness"];
  if (rb["trials"].get<int>() > 0) {
    text += Format(
        "robustness: %d of %d perturbed trials succeeded, score %.3f, 95%% interval "
        "[%.3f, %.3f]\n",
        rb["successes"].get<int>(), rb["trials"].get<int>(), rb["score"].get<double>(),
        rb["ci95"][0].get<double>(), rb["ci95"][1].get<double>());
  }
  return text;
}

// --engine mujoco: the MuJoCo trial's options; what it cannot do yet is refused up front.
std::optional<MujocoTrialOptions> MujocoOptionsOf(const SimulateOptions& o,
                                                  const request::SimulateRequest& r) {
  if (r.engine.engine != "mujoco") return std::nullopt;
  auto refuse = [](const std::string& what) {
    throw InputError("--engine mujoco: " + what + " is ODE's only (docs/mujoco.md)");
  };
  if (r.perturb > 0) refuse("--perturb");
  if (r.sensitivity > 0) refuse("--sensitivity");
  if (!o.trial_record.empty()) refuse("--trial-record");
  if (!MujocoAvailable()) {
    throw InputError(
        "--engine mujoco: this graspsynth is built without MuJoCo (install "
        "libmujoco-dev, or run scripts/setup.sh, and build again)");
  }
  return request::ToMujocoTrialOptions(r.engine, r.trial.time_step);
}

// --engine mujoco --mujoco-sweep: the trial under each MuJoCo contact setting and servo mapping
// (simulation_mujoco/mujoco_sweep.hpp), one line per run on stderr and, with --out, a
// graspsynth-mujoco-sweep/1 report. Exit 0 when the runs that held reach the gate's share.
int RunMujocoSweepCommand(const SimulateOptions& o, const request::SimulateRequest& r,
                          const TrialOptions& trial, const MujocoTrialOptions& mujoco) {
  if (!o.record.empty()) throw InputError("--mujoco-sweep: --record is the one trial's only");
  MujocoSweepOptions sweep;
  sweep.trial = trial;
  sweep.time_step = mujoco.time_step > 0.0 ? mujoco.time_step : sweep.time_step;
  sweep.threads = r.threads;
  const SimulationModel model = LoadModel(o.robot, o.scene, o.object, "simulate", kTrajectoryData);
  JointTrajectory trajectory =
      LoadTrajectoryOrGraspFile(o.trajectory, model.robot().arm, model.robot().hand);
  PlaceTrajectoryObject(model.scene(), r.at, o.trajectory, &trajectory);
  ProgressBar bar;
  const MujocoSweepResult result = EvaluateMujocoSweep(
      model, trajectory, sweep,
      [&](int done, int total) { bar.Update("MuJoCo sweep", done, total, "runs"); });
  bar.Finish();
  std::fprintf(stderr, "%-16s %-5s %-13s %9s %9s %9s  %s\n", "setting", "servo", "outcome",
               "lift mm", "slip mm", "slip deg", "reason");
  for (const MujocoSweepRun& run : result.runs) {
    std::fprintf(stderr, "%-16s %-5s %-13s %9.1f %9.1f %9.1f  %s\n",
                 std::string(ToString(run.setting)).c_str(),
                 std::string(ToString(run.servo)).c_str(),
                 std::string(ToString(run.outcome)).c_str(), 1e3 * run.lift, 1e3 * run.slip,
                 run.slip_angle / kDeg, run.reason.c_str());
  }
  std::fprintf(stderr, "%s (%d threads, %.1f s)\n", result.BriefReport().c_str(), result.threads,
               result.wall_time);
  if (!o.out.empty()) {
    json report;
    report["format"] = "graspsynth-mujoco-sweep/1";
    report["trajectory"] = o.trajectory;
    report["theta_deg"] = trajectory.theta_deg;
    if (trajectory.object_xy) {
      report["object_xy"] = {trajectory.object_xy->x(), trajectory.object_xy->y()};
    }
    report["settings"] = {{"engine", "mujoco"},
                          {"time_step_s", sweep.time_step},
                          {"hold_s", trial.hold},
                          {"lift_threshold_m", trial.lift_threshold}};
    report.update(MujocoSweepJson<json>(result));
    WriteFileAtomically(o.out, report.dump(2) + "\n");
  }
  return result.summary.success_fraction >= MujocoGateOptions{}.min_success ? 0 : 1;
}

int RunSimulate(const SimulateOptions& o, const request::SimulateRequest& r) {
  const TrialOptions trial = request::ToTrialOptions(r);
  RequireValid(r.hold_margin, "bad hold margin option");
  const RobustnessOptions ro = request::ToRobustnessOptions(r);  // every option checked first
  const std::optional<MujocoTrialOptions> mujoco = MujocoOptionsOf(o, r);
  if (r.engine.mujoco_sweep) {
    if (!mujoco) throw InputError("--mujoco-sweep needs --engine mujoco");
    return RunMujocoSweepCommand(o, r, trial, *mujoco);
  }
  const SimulationModel model = LoadModel(o.robot, o.scene, o.object, "simulate", kTrajectoryData);
  // a graspsynth-trajectory/1 file, or the "trajectory" member of a graspsynth-grasp/1 file.
  JointTrajectory trajectory =
      LoadTrajectoryOrGraspFile(o.trajectory, model.robot().arm, model.robot().hand);
  PlaceTrajectoryObject(model.scene(), r.at, o.trajectory, &trajectory);

  TrialOptions nominal_options = trial;
  const bool records = !o.record.empty() || !o.trial_record.empty();
  if (records) nominal_options.record_interval = r.record_interval;
  // with --trial-record the same trial, observed (simulation/trial_record.hpp).
  std::optional<RecordedTrial> recorded;
  if (!o.trial_record.empty()) {
    recorded = RunRecordedTrial(model, trajectory, nominal_options, o.trajectory);
  }
  const TrialResult nominal = mujoco ? RunMujocoTrial(model, trajectory, nominal_options, *mujoco)
                              : recorded ? recorded->result
                                         : RunTrial(model, trajectory, nominal_options);
  std::cerr << "nominal trial" << (mujoco ? " (MuJoCo)" : "") << ": " << nominal.BriefReport()
            << "\n";

  json report;
  report["format"] = kReportFormat;
  report["trajectory"] = o.trajectory;
  report["theta_deg"] = trajectory.theta_deg;
  if (trajectory.object_xy) {
    report["object_xy"] = {trajectory.object_xy->x(), trajectory.object_xy->y()};
  }
  report["settings"] = {{"fidelity", r.trial.fidelity},
                        {"time_step_s", trial.step()},
                        {"hold_s", trial.hold},
                        {"lift_threshold_m", trial.lift_threshold}};
  if (mujoco) {
    // the ODE report's bytes are unchanged; a MuJoCo trial says so, with its own step.
    report["settings"]["engine"] = "mujoco";
    report["settings"]["mujoco_servo"] = std::string(ToString(mujoco->servo));
    report["settings"]["time_step_s"] = mujoco->time_step > 0.0 ? mujoco->time_step : 0.001;
    report["settings"].erase("fidelity");
  }
  // the trial's figures (its field list's, rounded), then this report's own.
  json& n = report["nominal"] = {{"success", nominal.success()}};
  struct Rounded {
    json operator()(double x) const { return Round(x); }
  };
  n.update(FieldsJson<json>(nominal, Rounded{}));
  n["simulated_s"] = Round(nominal.simulated_time);
  n["final_object_pose"] = PoseJson(nominal.final_object_pose);
  n["hold"] = HoldQualityJson<json>(nominal.hold);
  // the hold margin (gate/hold_margin.hpp), the thresholds it misses and their reasons.
  const HoldMargin margin = MeasureHoldMargin(model, nominal);
  const std::string shortfall = HoldMarginShortfall(margin, r.hold_margin);
  n["hold_margin"] = HoldMarginReportJson<json>(margin, shortfall, r.hold_margin, Round);
  std::cerr << "hold margin: " << HoldMarginBrief(margin)
            << (shortfall.empty() ? "" : "; misses " + shortfall) << "\n";
  AddPerturbedTrials(model, trajectory, ro, r, &report);
  AddSensitivity(model, trajectory, ro, r, &report);
  if (!o.out.empty()) {
    WriteFileAtomically(o.out, report.dump(2) + "\n");
  } else {
    std::cout << ReportSummary(report);
  }
  if (!o.record.empty()) WriteFileAtomically(o.record, StatesCsv(nominal.states));
  if (recorded) WriteTrialRecord(o.trial_record, recorded->record);
  const bool margin_missed = r.hold_margin.require && !shortfall.empty();
  return nominal.success() && !margin_missed ? 0 : 1;
}

int RunScripted(const ScriptedOptions& o, const request::ScriptedGraspRequest& request) {
  const ScriptedGraspOptions g = request::ToScriptedGraspOptions(request);
  // the finger shapes and the grip are the robot file's (its grasp part): any robot with one.
  const SimulationModel model =
      LoadModel(o.robot, o.scene, o.object, "scripted-grasp", "", "the scripted grasp");
  const ScriptedGraspResult r = BuildScriptedGrasp(model.robot(), model.scene(), g);
  if (!r.ok)
    throw InputError("no scripted grasp for theta = " + std::to_string(request.theta) +
                     " deg: " + r.message);
  WriteJointTrajectory(o.out, r.trajectory);
  std::cerr << "wrote " << o.out << ": " << r.trajectory.samples.size() << " samples, "
            << r.trajectory.duration() << " s\n";
  return 0;
}

// graspsynth scripted-grasp: the hand-made grasp trajectory (motion/scripted_grasp.hpp).
void AddScriptedGraspCommand(CLI::App& app, int* exit_code) {
  auto sopts = std::make_shared<ScriptedOptions>();
  CLI::App* scripted = app.add_subcommand(
      "scripted-grasp",
      "Write the scripted (hand-made) grasp-and-lift trajectory for an orientation\n"
      "The trajectory: reach from a rest pose, approach from above, close the hand on the handle "
      "(fingertips on its far face, thumb on its near face), lift 10 cm. "
      "examples/grasp_60deg.json is its output for --theta 60.");
  auto flags = std::make_shared<RequestFlags<request::ScriptedGraspRequest>>(
      scripted, request::ScriptedGraspRequestOptions());
  scripted->add_option("--out", sopts->out, "Trajectory file to write")->required();
  AddRobotOption(scripted, &sopts->robot);
  scripted->add_option("--scene", sopts->scene, "Scene description (JSON)");
  AddObjectFlag(scripted, &sopts->object);
  scripted->callback(
      [sopts, flags, exit_code] { *exit_code = RunScripted(*sopts, flags->Build()); });
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<SimulateOptions>();
  CLI::App* sim = app.add_subcommand(
      "simulate",
      "Play a trajectory in the ODE simulation and judge the grasp\n"
      "Plays a joint trajectory in the ODE simulation (PA-10 arm, Gifu Hand III, table, pan)\n"
      "and judges the grasp: after the lift and a hold (--hold, default 1 s) the object's\n"
      "centre must be >= 5 cm above its rest height and touch only the hand. Friction alone\n"
      "holds the object. With --perturb N, N replays with time scaling (uniform in\n"
      "[--time-scale-min, --time-scale-max]), Gaussian waypoint noise and, with --physics on\n"
      "(the default), perturbed physics give a robustness score (success fraction with a 95%\n"
      "Wilson interval); --sensitivity adds a table of each physics factor's effect on its\n"
      "own. Every trial reports its hold quality (tilt, slip, contacts, the fingers carrying\n"
      "the load); a pan held but tilted more than 30 deg at the end is 'tilted', a failure.\n"
      "The same --seed gives the same report whatever --threads is.\n\n"
      "TRAJECTORY: graspsynth-trajectory/1 JSON: {\"format\", \"theta_deg\", \"samples\":\n"
      "[{\"t\": s, \"arm\": [7 rad], \"hand\": [16 rad]}, ...], \"waypoints\" (optional)}.\n"
      "TRAJECTORY may also be a graspsynth-grasp/1 file (its \"trajectory\" is played).\n"
      "The report (--out, graspsynth-simulation/1 JSON; without --out its essentials go to\n"
      "stdout and no file is written) has \"nominal\" {success, outcome, reason, lift_m,\n"
      "hold, ...}, \"robustness\" {trials, successes, score, ci95, ...}, \"trials\" [{index,\n"
      "time_scale, success, outcome, reason, lift_m, physics, hold}] and,\n"
      "with --sensitivity, \"sensitivity\" (docs/formats.md). Exit status: 0 when the\n"
      "nominal trial succeeds, 1 when it fails, 2 on bad input.\n\n"
      "With --engine mujoco the nominal trial is replayed in MuJoCo instead (the same\n"
      "controller and judgement; --mujoco-servo stiff|soft maps ODE's finger motor onto a\n"
      "MuJoCo servo; docs/mujoco.md); with --mujoco-sweep, 16 runs are printed one per line\n"
      "(exit 0 when at least 95% of them hold; --out writes a graspsynth-mujoco-sweep/1\n"
      "report).\n\n"
      "Examples:\n"
      "  graspsynth simulate examples/grasp_60deg.json\n"
      "  graspsynth simulate examples/grasp_60deg.json --perturb 100 --out report.json\n"
      "  graspsynth simulate examples/grasp_60deg.json --trial-record trial.json\n"
      "  graspsynth simulate examples/grasp_60deg.json --engine mujoco");
  auto flags =
      std::make_shared<RequestFlags<request::SimulateRequest>>(sim, request::SimulateOptions());
  sim->add_option("trajectory", opts->trajectory,
                  "Trajectory or grasp file (graspsynth-trajectory/1, graspsynth-grasp/1)")
      ->required()
      ->check(CLI::ExistingFile);
  sim->add_option("--out", opts->out,
                  "Report file to write (JSON); without it the report's essentials are printed "
                  "on stdout and no file is written");
  sim->add_option("--record", opts->record,
                  "Write the nominal trial's simulated states as CSV: t, arm q1..q7 (rad), hand "
                  "f0..f15 (rad), object and wrist pose (m, quaternion w first)");
  sim->add_option("--trial-record", opts->trial_record,
                  "Write the nominal trial as simulated, for `graspsynth view --trial`: "
                  "graspsynth-trial-record/1 JSON (joints, object pose and object-hand contacts "
                  "every --record-interval s, the outcome)");
  AddRobotOption(sim, &opts->robot);
  sim->add_option("--scene", opts->scene, "Scene description (JSON); default: models/scene.json");
  AddObjectFlag(sim, &opts->object);
  sim->callback([opts, flags, exit_code] { *exit_code = RunSimulate(*opts, flags->Build()); });

  AddScriptedGraspCommand(app, exit_code);
}

}  // namespace graspsynth::apps
