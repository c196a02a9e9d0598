// graspsynth simulate: a joint trajectory through the ODE world (nominal trial + perturbed
// replays), written as a graspsynth-simulation/1 report. graspsynth scripted-grasp: the
// hand-made grasp trajectory of motion/scripted_grasp.hpp.

#include "apps/simulate_command.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "apps/cli_helpers.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "kinematics/pose_math.hpp"
#include "motion/joint_trajectory.hpp"
#include "motion/scripted_grasp.hpp"
#include "simulation/robustness.hpp"
#include "simulation/trial.hpp"
#include "solver/grasp_file.hpp"
#include "studies/trial_json.hpp"

namespace graspsynth::apps {
namespace {

using json = nlohmann::ordered_json;

constexpr std::string_view kReportFormat = "graspsynth-simulation/1";

struct SimulateOptions {
  std::string trajectory;
  std::string out;
  std::string record;
  double record_interval = 0.01;
  int perturb = 0;
  int sensitivity = 0;
  // the defaults are the library's, so that the command and the library cannot drift apart.
  uint64_t seed = RobustnessOptions{}.seed;
  int threads = RobustnessOptions{}.threads;
  std::string fidelity = "fast";
  double time_step = TrialOptions{}.time_step;
  double hold = TrialOptions{}.hold;
  double time_scale_min = PerturbationOptions{}.time_scale_min;
  double time_scale_max = PerturbationOptions{}.time_scale_max;
  double position_noise = PerturbationOptions{}.position_sigma;
  double orientation_noise_deg = PerturbationOptions{}.orientation_sigma / kDeg;
  double finger_noise_deg = PerturbationOptions{}.finger_sigma / kDeg;
  std::string at;  // --at X,Y: the object elsewhere than the file says
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
  PhysicsPerturbationOptions physics = PerturbationOptions{}.physics;
};

struct ScriptedOptions {
  double theta = 60.0;
  double grasp_radius = ScriptedGraspOptions{}.grasp_radius;
  bool keep_open = false;
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

SimulationModel LoadModel(const std::string& robot, const std::string& scene,
                          const std::string& object, std::string_view needs_handle = {}) {
  return SimulationModel(
      LoadRobotModel(robot.empty() ? DefaultRobotDescriptionPath() : std::filesystem::path(robot)),
      LoadScene(scene, object, needs_handle));
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

// The perturbed replays' options from the flags; throws InputError for invalid ones.
RobustnessOptions RobustnessOptionsOf(const SimulateOptions& o, const TrialOptions& trial) {
  RobustnessOptions ro;
  ro.trials = std::max(o.perturb, 1);
  ro.seed = o.seed;
  ro.threads = o.threads;
  ro.trial = trial;
  ro.perturbation.time_scale_min = o.time_scale_min;
  ro.perturbation.time_scale_max = o.time_scale_max;
  ro.perturbation.position_sigma = o.position_noise;
  ro.perturbation.orientation_sigma = o.orientation_noise_deg * kDeg;
  ro.perturbation.finger_sigma = o.finger_noise_deg * kDeg;
  ro.perturbation.physics = o.physics;
  std::string why;
  if (!ro.IsValid(&why)) throw InputError("bad perturbation option: " + why);

  return ro;
}

// Runs the perturbed replays (when --perturb > 0) and adds `robustness` and `trials` to the
// report; prints their summary on stderr.
void AddPerturbedTrials(const SimulationModel& model, const JointTrajectory& trajectory,
                        const RobustnessOptions& ro, const SimulateOptions& o, json* report_out) {
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
                    RobustnessOptions ro, const SimulateOptions& o, json* report) {
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

int RunSimulate(const SimulateOptions& o) {
  if (o.fidelity != "fast" && o.fidelity != "full" && o.fidelity != "fast-wrist") {
    throw InputError("--fidelity must be 'fast', 'fast-wrist' or 'full', not '" + o.fidelity + "'");
  }
  const SimulationModel model = LoadModel(o.robot, o.scene, o.object);
  // a graspsynth-trajectory/1 file, or the "trajectory" member of a graspsynth-grasp/1 file.
  JointTrajectory trajectory =
      LoadTrajectoryOrGraspFile(o.trajectory, model.robot().arm, model.robot().hand);
  PlaceTrajectoryObject(model.scene(), ParseAt(o.at), o.trajectory, &trajectory);

  TrialOptions trial;
  trial.fidelity = o.fidelity == "full"         ? Fidelity::kFull
                   : o.fidelity == "fast-wrist" ? Fidelity::kFastWristDynamic
                                                : Fidelity::kFast;
  trial.time_step = o.time_step;
  trial.hold = o.hold;
  std::string why;
  if (!trial.IsValid(&why)) throw InputError("bad simulation option: " + why);
  const RobustnessOptions ro = RobustnessOptionsOf(o, trial);  // every flag checked first
  TrialOptions nominal_options = trial;
  if (!o.record.empty()) nominal_options.record_interval = o.record_interval;
  const TrialResult nominal = RunTrial(model, trajectory, nominal_options);
  std::cerr << "nominal trial: " << nominal.BriefReport() << "\n";

  json report;
  report["format"] = kReportFormat;
  report["trajectory"] = o.trajectory;
  report["theta_deg"] = trajectory.theta_deg;
  if (trajectory.object_xy) {
    report["object_xy"] = {trajectory.object_xy->x(), trajectory.object_xy->y()};
  }
  report["settings"] = {{"fidelity", o.fidelity},
                        {"time_step_s", trial.step()},
                        {"hold_s", trial.hold},
                        {"lift_threshold_m", trial.lift_threshold}};
  report["nominal"] = {{"success", nominal.success()},
                       {"outcome", ToString(nominal.outcome)},
                       {"reason", nominal.reason},
                       {"lift_m", Round(nominal.lift)},
                       {"max_lift_m", Round(nominal.max_lift)},
                       {"max_penetration_m", Round(nominal.max_penetration)},
                       {"simulated_s", Round(nominal.simulated_time)},
                       {"final_object_pose", PoseJson(nominal.final_object_pose)},
                       {"hold", HoldQualityJson<json>(nominal.hold)}};
  AddPerturbedTrials(model, trajectory, ro, o, &report);
  AddSensitivity(model, trajectory, ro, o, &report);
  WriteFileAtomically(o.out, report.dump(2) + "\n");
  if (!o.record.empty()) WriteFileAtomically(o.record, StatesCsv(nominal.states));
  return nominal.success() ? 0 : 1;
}

int RunScripted(const ScriptedOptions& o) {
  const SimulationModel model = LoadModel(o.robot, o.scene, o.object, "the scripted grasp");
  ScriptedGraspOptions g;
  g.theta_deg = o.theta;
  g.grasp_radius = o.grasp_radius;
  if (o.keep_open) g.closed = g.open;
  const ScriptedGraspResult r = BuildScriptedGrasp(model.robot(), model.scene(), g);
  if (!r.ok)
    throw InputError("no scripted grasp for theta = " + std::to_string(o.theta) +
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
      "Write the scripted (hand-made) grasp-and-lift trajectory for an object orientation:\n"
      "reach from a rest pose, approach from above, close the hand on the handle (fingertips\n"
      "on its far face, thumb on its near face), lift 10 cm. examples/grasp_60deg.json is\n"
      "its output for --theta 60.");
  scripted->add_option("--theta", sopts->theta, "Object orientation, deg")->capture_default_str();
  scripted
      ->add_option("--grasp-radius", sopts->grasp_radius,
                   "Grasp point along the handle from the object centre, m")
      ->capture_default_str();
  scripted->add_flag("--keep-open", sopts->keep_open,
                     "Keep the hand open (a trajectory that must fail)");
  scripted->add_option("--out", sopts->out, "Trajectory file to write")->required();
  scripted->add_option("--robot", sopts->robot, "Robot description (URDF)");
  scripted->add_option("--scene", sopts->scene, "Scene description (JSON)");
  AddObjectFlag(scripted, &sopts->object);
  scripted->callback([sopts, exit_code] { *exit_code = RunScripted(*sopts); });
}

}  // namespace

void AddSimulateCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<SimulateOptions>();
  CLI::App* sim = app.add_subcommand(
      "simulate",
      "Play a joint trajectory in the ODE simulation (PA-10 arm, Gifu Hand III, table, pan)\n"
      "and judge the grasp: after the lift and a hold (--hold, default 1 s) the object's\n"
      "centre must be >= 5 cm above its rest height and touch only the hand. Friction alone\n"
      "holds the object. With --perturb N, N replays with time scaling (uniform in\n"
      "[--time-scale-min, --time-scale-max]), Gaussian waypoint noise and, with --physics on\n"
      "(the default), perturbed physics (friction, contact stiffness and damping, the\n"
      "object's mass and centre of mass, the finger servos' force, the step) give a\n"
      "robustness score (success fraction with a 95% Wilson interval); --sensitivity N adds\n"
      "N replays per end of each physics factor's range, that factor alone varied. Every\n"
      "trial reports its hold quality (tilt, slip, contacts, the fingers carrying the load);\n"
      "a pan held but tilted more than 30 deg at the end is 'tilted', a failure. The same\n"
      "--seed gives the same report whatever --threads is.\n\n"
      "TRAJECTORY: graspsynth-trajectory/1 JSON: {\"format\", \"theta_deg\", \"samples\":\n"
      "[{\"t\": s, \"arm\": [7 rad], \"hand\": [16 rad]}, ...], \"waypoints\" (optional)}.\n"
      "The report (--out, graspsynth-simulation/1 JSON) has \"nominal\" {success, outcome,\n"
      "reason, lift_m, hold, ...}, \"robustness\" {trials, successes, score, ci95, ...},\n"
      "\"trials\" [{index, time_scale, success, outcome, reason, lift_m, physics, hold}] and,\n"
      "with --sensitivity, \"sensitivity\" (docs/formats.md). Exit status: 0 when the\n"
      "nominal trial succeeds, 1 when it fails, 2 on bad input.\n\n"
      "Example:\n"
      "  graspsynth simulate examples/grasp_60deg.json --perturb 100 --out report.json");
  sim->add_option("trajectory", opts->trajectory, "Trajectory file (graspsynth-trajectory/1)")
      ->required()
      ->check(CLI::ExistingFile);
  sim->add_option("--out", opts->out, "Report file to write (JSON)")->required();
  sim->add_option("--at", opts->at,
                  "X,Y: play it with the object centre here on the table (world, m) instead of "
                  "where the file puts it (its \"object_xy\", else the scene's object centre)");
  sim->add_option("--perturb", opts->perturb, "Number of perturbed replays (0: nominal only)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sim->add_option("--sensitivity", opts->sensitivity,
                  "Replays per end of each physics factor's range, that factor alone varied "
                  "(0: no sensitivity table)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sim->add_option("--seed", opts->seed, "Seed of the perturbations")->capture_default_str();
  sim->add_option("--threads", opts->threads, "Worker threads for the replays (0: all cores)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1024));
  sim->add_option("--record", opts->record,
                  "Write the nominal trial's simulated states as CSV: t, arm q1..q7 (rad), hand "
                  "f0..f15 (rad), object and wrist pose (m, quaternion w first)");
  sim->add_option("--record-interval", opts->record_interval, "Seconds between recorded states")
      ->capture_default_str()
      ->check(PositiveValue());
  sim->add_option("--fidelity", opts->fidelity,
                  "fast: kinematic arm, free space without contact detail, 4 ms steps, early "
                  "stop; fast-wrist: fast with the wrist joints (E2, W1, W2) dynamic, so that "
                  "their 10-15 N m motors yield; full: dynamic motor-driven arm, every step "
                  "simulated at 1 ms")
      ->capture_default_str();
  sim->add_option("--time-step", opts->time_step, "Physics step in s (0: the fidelity's default)")
      ->capture_default_str();
  sim->add_option("--hold", opts->hold, "Seconds the last command is held after the trajectory")
      ->capture_default_str();
  sim->add_option("--time-scale-min", opts->time_scale_min, "Smallest time scale of a replay")
      ->capture_default_str();
  sim->add_option("--time-scale-max", opts->time_scale_max, "Largest time scale of a replay")
      ->capture_default_str();
  sim->add_option("--position-noise", opts->position_noise,
                  "Wrist position noise, m (standard deviation per axis)")
      ->capture_default_str();
  sim->add_option("--orientation-noise", opts->orientation_noise_deg,
                  "Wrist orientation noise, deg (standard deviation per axis)")
      ->capture_default_str();
  sim->add_option("--finger-noise", opts->finger_noise_deg,
                  "Finger joint noise, deg (standard deviation per joint)")
      ->capture_default_str();
  sim->add_option("--robot", opts->robot, "Robot description (URDF); default: the shipped one");
  sim->add_option("--scene", opts->scene, "Scene description (JSON); default: models/scene.json");
  AddObjectFlag(sim, &opts->object);
  const auto physics = AddPhysicsPerturbationFlags(sim);
  sim->callback([opts, physics, exit_code] {
    opts->physics = physics->Build();
    *exit_code = RunSimulate(*opts);
  });

  AddScriptedGraspCommand(app, exit_code);
}

}  // namespace graspsynth::apps
