#include "simulation_mujoco/mujoco_sweep.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/parallel.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"
#include "simulation_mujoco/mujoco_world.hpp"

namespace graspsynth {
namespace {

constexpr std::array<std::string_view, kMujocoContactSettings> kSettingNames = {
    "nominal",    "soft_reference", "mujoco_impedance", "pyramidal",
    "impratio_1", "step_0.5ms",     "step_2ms",         "friction_0.75"};

// The middle of sorted `values` (the mean of the middle two for an even count); 0 when empty.
double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

std::string_view ToString(MujocoContactSetting setting) {
  return kSettingNames[static_cast<size_t>(setting)];
}

MujocoContactSetting ParseMujocoContactSetting(std::string_view text, std::string_view what) {
  for (int i = 0; i < kMujocoContactSettings; ++i) {
    if (text == kSettingNames[i]) return static_cast<MujocoContactSetting>(i);
  }
  std::string names;
  for (std::string_view n : kSettingNames) names += (names.empty() ? "" : ", ") + std::string(n);
  throw InputError(std::string(what) + ": '" + std::string(text) +
                   "' is not a MuJoCo contact setting (" + names + ")");
}

std::vector<MujocoContactSetting> AllMujocoContactSettings() {
  std::vector<MujocoContactSetting> all;
  for (int i = 0; i < kMujocoContactSettings; ++i)
    all.push_back(static_cast<MujocoContactSetting>(i));
  return all;
}

void ApplyMujocoContactSetting(MujocoContactSetting setting, TrialOptions* trial,
                               MujocoTrialOptions* mujoco) {
  MjcfContact& c = mujoco->contact;
  switch (setting) {
    case MujocoContactSetting::kNominal:
      break;
    case MujocoContactSetting::kSoftReference:
      c.time_constant_scale *= 2.0;
      break;
    case MujocoContactSetting::kMujocoImpedance:
      c.solimp_dmin = 0.9;
      c.solimp_dmax = 0.95;
      c.solimp_width = 0.001;
      break;
    case MujocoContactSetting::kPyramidalCone:
      c.pyramidal = true;
      break;
    case MujocoContactSetting::kSoftFriction:
      c.impratio = 1.0;
      break;
    case MujocoContactSetting::kFineStep:
      trial->time_step = 0.0;
      mujoco->time_step = 0.0005;
      break;
    case MujocoContactSetting::kCoarseStep:
      trial->time_step = 0.0;
      mujoco->time_step = 0.002;
      break;
    case MujocoContactSetting::kLowFriction:
      trial->physics.object_hand_friction *= 0.75;
      break;
  }
}

bool MujocoSweepOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (!trial.IsValid(why)) return false;
  if (!(std::isfinite(time_step) && time_step > 0.0 && time_step <= 0.02))
    return fail("mujoco sweep time_step (s, in (0, 0.02]) = " + std::to_string(time_step));
  if (settings.empty()) return fail("the MuJoCo sweep has no contact settings");
  if (servos.empty()) return fail("the MuJoCo sweep has no servo mappings");
  if (std::set<MujocoContactSetting>(settings.begin(), settings.end()).size() != settings.size())
    return fail("a MuJoCo contact setting is given twice");
  if (std::set<MujocoServo>(servos.begin(), servos.end()).size() != servos.size())
    return fail("a MuJoCo servo mapping is given twice");
  if (threads < 0) return fail("mujoco sweep threads (>= 0) = " + std::to_string(threads));
  return true;
}

std::string MujocoSweepRun::Label() const {
  return std::string(ToString(setting)) + "/" + std::string(ToString(servo));
}

std::string MujocoSweepResult::BriefReport() const {
  const MujocoSweepSummary& s = summary;
  std::string text = Format(
      "%d/%d runs held in MuJoCo (%.3f), slip median %.1f mm / %.1f deg, "
      "worst %.1f mm / %.1f deg",
      s.successes, s.runs, s.success_fraction, 1e3 * s.slip_median, s.slip_angle_median / kDeg,
      1e3 * s.slip_worst, s.slip_angle_worst / kDeg);
  if (!s.failing.empty()) text += "; failing: " + s.failing;
  return text;
}

MujocoSweepSummary SummarizeMujocoSweep(const std::vector<MujocoSweepRun>& runs) {
  MujocoSweepSummary s;
  s.runs = static_cast<int>(runs.size());
  std::vector<double> slips, angles;
  for (const MujocoSweepRun& run : runs) {
    if (run.success()) {
      ++s.successes;
      slips.push_back(run.slip);
      angles.push_back(run.slip_angle);
    } else {
      s.failing += (s.failing.empty() ? "" : ", ") + run.Label();
    }
  }
  s.success_fraction = s.runs > 0 ? static_cast<double>(s.successes) / s.runs : 0.0;
  s.slip_median = Median(slips);
  s.slip_angle_median = Median(angles);
  if (!slips.empty()) {
    s.slip_worst = *std::max_element(slips.begin(), slips.end());
    s.slip_angle_worst = *std::max_element(angles.begin(), angles.end());
  }
  return s;
}

MujocoSweepResult EvaluateMujocoSweep(const SimulationModel& model,
                                      const JointTrajectory& trajectory,
                                      const MujocoSweepOptions& options,
                                      const ProgressCallback& progress) {
  RequireValid(options, "invalid MuJoCo sweep option");
  if (!MujocoAvailable()) {
    throw InputError(
        "the MuJoCo sweep: this graspsynth is built without MuJoCo (install libmujoco-dev, or "
        "run scripts/setup.sh, and build again)");
  }
  const auto wall_start = WallClock::now();
  // the nominal step is MuJoCo's, so that each setting's own step can replace it.
  TrialOptions base_trial = options.trial;
  MujocoTrialOptions base;
  base.time_step = base_trial.time_step > 0.0 ? base_trial.time_step : options.time_step;
  base_trial.time_step = 0.0;

  MujocoSweepResult result;
  const int servos = static_cast<int>(options.servos.size());
  const int count = static_cast<int>(options.settings.size()) * servos;
  result.runs.resize(count);
  result.threads = WorkerCount(options.threads, count);
  ParallelFor(
      count, options.threads,
      [&](int i) {
        MujocoSweepRun& run = result.runs[i];
        run.setting = options.settings[i / servos];
        run.servo = options.servos[i % servos];
        TrialOptions trial = base_trial;
        MujocoTrialOptions mujoco = base;
        mujoco.servo = run.servo;
        ApplyMujocoContactSetting(run.setting, &trial, &mujoco);
        const TrialResult r = RunMujocoTrial(model, trajectory, trial, mujoco);
        run.outcome = r.outcome;
        run.reason = r.reason;
        run.lift = r.lift;
        run.slip = r.hold.slip;
        run.slip_angle = r.hold.slip_angle;
        run.wall_time = r.wall_time;
      },
      [&](int finished) {
        if (progress) progress(finished, count);
      });
  result.summary = SummarizeMujocoSweep(result.runs);
  result.wall_time = SecondsSince(wall_start);
  return result;
}

}  // namespace graspsynth
