#include "gate/physics_gate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>
#include <sstream>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"

namespace graspsynth {

bool PhysicsGateOptions::IsValid(std::string* why) const {
  if (robustness.trials < 0) {
    if (why) *why = "perturbations must be >= 0";
    return false;
  }
  if (!(std::isfinite(min_robustness) && min_robustness >= 0.0 && min_robustness <= 1.0)) {
    if (why) *why = "min_robustness must be in [0, 1]";
    return false;
  }
  if (sensitivity_trials < 0) {
    if (why) *why = "sensitivity_trials must be >= 0";
    return false;
  }
  // the replays' own checks, but their count (0 is the gate's nominal only).
  RobustnessOptions replays = robustness;
  replays.trials = std::max(replays.trials, 1);
  return replays.IsValid(why) && quality.IsValid(why) && mujoco.IsValid(why) &&
         hold_margin.IsValid(why);
}

bool MujocoGateOptions::IsValid(std::string* why) const {
  if (!(std::isfinite(min_success) && min_success >= 0.0 && min_success <= 1.0)) {
    if (why) *why = "mujoco_min_success must be in [0, 1]";
    return false;
  }
  MujocoSweepOptions sweep;
  sweep.settings = settings;
  sweep.servos = servos;
  return sweep.IsValid(why);
}

namespace {

// The MuJoCo sweep of a grasp that ODE passed, with the gate's nominal trial and threads; false
// with the reason in `s` when its success fraction is below the gate's.
bool RunMujocoEngine(const SimulationModel& model, const JointTrajectory& trajectory,
                     const PhysicsGateOptions& options, PhysicsGateResult* r, std::ostream& s) {
  MujocoSweepOptions sweep;
  sweep.trial = options.robustness.trial;
  sweep.settings = options.mujoco.settings;
  sweep.servos = options.mujoco.servos;
  sweep.threads = options.robustness.threads;
  r->mujoco = EvaluateMujocoSweep(model, trajectory, sweep);
  const MujocoSweepSummary& m = r->mujoco->summary;
  if (m.success_fraction >= options.mujoco.min_success) return true;
  s << "MuJoCo held " << m.successes << "/" << m.runs << " = " << m.success_fraction
    << " of its contact settings' runs, below the threshold " << options.mujoco.min_success
    << " (failing: " << m.failing << ")";
  return false;
}

}  // namespace

PhysicsGateResult RunPhysicsGate(const SimulationModel& model, const JointTrajectory& trajectory,
                                 const PhysicsGateOptions& options,
                                 const ProgressCallback& progress) {
  RequireValid(options, "invalid physics gate option");
  const auto t0 = std::chrono::steady_clock::now();
  PhysicsGateResult r;
  // the nominal trial, keeping the last hand-object contact set and the object pose with it.
  std::vector<HandObjectContact> last;
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  r.nominal = RunTrial(model, trajectory, options.robustness.trial, [&](SimulationData& data) {
    if (!data.hand_object_contacts().empty()) {
      last = data.hand_object_contacts();
      X_WO = data.object_pose();
    }
  });
  for (const HandObjectContact& c : last) r.contacts.push_back({c.p_WC, c.n_W, c.friction});
  r.quality = EvaluateGraspQuality(r.contacts, X_WO * model.object_inertia().p_OC, options.quality);

  r.hold_margin = MeasureHoldMargin(model, r.nominal, options.quality);
  r.hold_margin_shortfall = HoldMarginShortfall(r.hold_margin, options.hold_margin);
  r.hold_margin_options = options.hold_margin;

  std::ostringstream s;
  const bool nominal_ok = r.nominal.success() || !options.require_nominal;
  // a required margin that the nominal hold misses decides the verdict before any replay.
  const bool margin_fails = nominal_ok && r.nominal.success() && options.hold_margin.require &&
                            !r.hold_margin_shortfall.empty();
  if (options.robustness.trials > 0 && nominal_ok && !margin_fails) {
    const int n = options.robustness.trials;
    r.robustness = EvaluateRobustness(model, trajectory, options.robustness, progress);
    r.robustness_run = true;
    if (options.sensitivity_trials > 0) {
      RobustnessOptions sensitivity = options.robustness;
      sensitivity.trials = options.sensitivity_trials;
      r.sensitivity = EvaluateSensitivity(model, trajectory, sensitivity, [&](int done, int total) {
        if (progress) progress(n + done, n + total);
      });
    }
  }
  if (!nominal_ok) {
    s << "the nominal trial failed: " << ToString(r.nominal.outcome) << " (" << r.nominal.reason
      << ")";
  } else if (margin_fails) {
    s << "hold margin: " << r.hold_margin_shortfall;
  } else if (r.robustness_run && r.robustness.score < options.min_robustness) {
    s << "robustness " << r.robustness.successes << "/" << r.robustness.trials.size() << " = "
      << r.robustness.score << " is below the threshold " << options.min_robustness;
  } else if (options.mujoco.enabled && !RunMujocoEngine(model, trajectory, options, &r, s)) {
    // the reason is the sweep's.
  } else {
    r.passed = true;
    s << "nominal trial " << ToString(r.nominal.outcome) << " (lift " << r.nominal.lift << " m)";
    if (r.robustness_run) {
      s << ", robustness " << r.robustness.successes << "/" << r.robustness.trials.size() << " = "
        << r.robustness.score << " >= " << options.min_robustness;
    }
    if (r.mujoco) {
      s << ", MuJoCo " << r.mujoco->summary.successes << "/" << r.mujoco->summary.runs
        << " >= " << options.mujoco.min_success;
    }
  }
  r.reason = s.str();
  r.time_s = SecondsSince(t0);
  return r;
}

}  // namespace graspsynth
