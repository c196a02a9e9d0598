#include "learning_data/synthetic_operator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>

#include "common/errors.hpp"
#include "common/field_codec.hpp"
#include "common/parallel.hpp"
#include "common/valid_options.hpp"
#include "kinematics/hand_model.hpp"
#include "kinematics/pose_math.hpp"
#include "learning_data/demo_replay.hpp"
#include "learning_data/learning_data_fields.hpp"
#include "motion/reach.hpp"
#include "simulation/random.hpp"
#include "simulation/trial.hpp"

namespace graspsynth {
namespace {

constexpr int kMaxAttempts = 5;

// One sub-movement of the wrist and fingers: minimum-jerk in position, slerp in orientation,
// a linear finger blend on the same profile, and a bow (offset * sin(pi s)) off the straight
// line.
struct Segment {
  double duration = 0.0;
  Eigen::Vector3d p0, p1;
  Eigen::Quaterniond q0, q1;
  HandVector f0, f1;
  Eigen::Vector3d bow = Eigen::Vector3d::Zero();
};

struct PlannedTrial {
  std::vector<Segment> segments;
  double grasp_time = 0.0;  // end of the settle: the grasp button
};

// The hand's frame at the grasp for hand direction z_horizontal (on the table) and a
// fingers-down pitch: palm down (x_H = -z_W) at zero pitch.
Eigen::Matrix3d HandFrame(const Eigen::Vector3d& z_horizontal, double pitch) {
  const Eigen::Vector3d u = z_horizontal.normalized();
  const Eigen::Vector3d x = -std::sin(pitch) * u - std::cos(pitch) * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d z = std::cos(pitch) * u - std::sin(pitch) * Eigen::Vector3d::UnitZ();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

Eigen::Vector3d Polar(const Eigen::Vector2d& c, double d, double eta, double z) {
  return Eigen::Vector3d(c.x() + d * std::cos(eta), c.y() + d * std::sin(eta), z);
}

// The change in the object's bearing from the robot base between the scene's centre and `c`,
// rad: the turn of the operator's polar angles at a moved object.
double BearingTurn(const SceneModel& scene, const Eigen::Vector2d& c) {
  const Eigen::Vector2d& c0 = scene.object_centre_xy;
  return std::atan2(c0.x() * c.y() - c0.y() * c.x(), c0.dot(c));
}

// The closed shape with noise (std `noise` per joint, rad), kept 2 deg inside the joint ranges
// (a target at a stop makes the motor fight the stop).
HandVector NoisyClosedHand(const HandModel& hand, const GraspStyle& style, double noise,
                           SplitMix64& rng) {
  HandVector closed = style.closed_hand;
  const double inset = 2.0 * kDeg;
  for (int j = 0; j < kHandDof; ++j) {
    closed[j] = std::clamp(closed[j] + noise * rng.Normal(), hand.lower()[j] + inset,
                           hand.upper()[j] - inset);
  }
  return closed;
}

// The hand's closing at the grasp pose (w, q): from `open` to `closed` in `close` s (the
// trial's draw of the nominal `close_duration`); with the style's thumb_close_duration, the
// fingers first (the thumb held as opened) and then the thumb, in thumb_close_duration s scaled
// as the close was (no draw of its own: the trials without it keep their random streams).
void AddClosing(const GraspStyle& style, double close, double close_duration,
                const Eigen::Vector3d& w, const Eigen::Quaterniond& q, const HandVector& open,
                const HandVector& closed, PlannedTrial* t) {
  if (!(style.thumb_close_duration > 0.0)) {
    t->segments.push_back(Segment{close, w, w, q, q, open, closed});
    return;
  }
  HandVector fingers_closed = closed;
  fingers_closed.head<4>() = open.head<4>();
  t->segments.push_back(Segment{close, w, w, q, q, open, fingers_closed});
  const double thumb = style.thumb_close_duration * close / close_duration;
  t->segments.push_back(Segment{thumb, w, w, q, q, fingers_closed, closed});
}

PlannedTrial PlanTrial(const SceneModel& scene, const HandModel& hand, const OperatorOptions& o,
                       const OrientationPlan& plan, const Placement& placement,
                       const GraspStrategy& strategy, bool sloppy, SplitMix64& rng) {
  const double k = sloppy ? o.sloppy_scale : 1.0;
  const GraspStyle& style = strategy.grasp ? *strategy.grasp : o.grasp;
  const Eigen::Isometry3d X_WO = scene.ObjectPose(placement);
  const Eigen::Vector2d c = scene.CentreXY(placement);
  const double turn = placement.xy ? BearingTurn(scene, c) : 0.0;
  const Eigen::Vector3d h = scene.object.HandleDirection(X_WO);
  const Eigen::Vector3d n = Eigen::Vector3d::UnitZ().cross(h);
  const double handle_z =
      scene.table.top_z + scene.object.Handle("the synthetic operator's grip").axis_height;

  // the wrist at the grasp (its height follows from the hook below).
  Eigen::Vector3d w =
      Polar(c, strategy.d, strategy.eta_deg * kDeg + turn, k * o.height_noise * rng.Normal());
  w.x() += k * o.position_noise * rng.Normal();
  w.y() += k * o.position_noise * rng.Normal();
  const Eigen::Vector3d rel(w.x() - c.x(), w.y() - c.y(), 0.0);
  const double a = rel.dot(h);
  const double lateral = rel.dot(n);
  // the pitch that brings the handle's axis, hook_reach along z_H and wrist_above_handle
  // below it, to the wrist's horizontal distance from the handle's line (a square crossing).
  const double depth = style.wrist_above_handle;
  double pitch = 0.0;
  if (style.max_pitch > 0.0) {
    const double norm = std::hypot(style.hook_reach, depth);
    pitch = std::clamp(
        std::acos(std::min(1.0, std::abs(lateral) / norm)) - std::atan2(depth, style.hook_reach),
        0.0, style.max_pitch);
  }
  const double reach = style.hook_reach * std::cos(pitch) - depth * std::sin(pitch);
  w.z() += handle_z + depth * std::cos(pitch) + style.hook_reach * std::sin(pitch);
  // the grip point: where the handle's axis is `reach` from the wrist, on the pan's side (the
  // point under the wrist's foot for a square crossing); a wrist farther from the handle's
  // line than the reach points the hand almost square to it.
  const double l =
      std::abs(lateral) <= reach ? lateral : std::clamp(lateral, -0.98 * reach, 0.98 * reach);
  const double r = a - std::sqrt(std::max(0.0, reach * reach - l * l));
  Eigen::Vector3d grip(c.x(), c.y(), 0.0);
  grip += r * h;
  Eigen::Vector3d z_dir = grip - Eigen::Vector3d(w.x(), w.y(), 0.0);
  z_dir.z() = 0.0;
  const double side = lateral >= 0.0 ? 1.0 : -1.0;
  z_dir = Eigen::AngleAxisd(side * style.yaw_offset + k * o.yaw_noise * rng.Normal(),
                            Eigen::Vector3d::UnitZ()) *
          z_dir;
  const Eigen::Matrix3d R_grasp =
      HandFrame(z_dir, pitch) * Eigen::AngleAxisd(style.roll, Eigen::Vector3d::UnitZ()).matrix();
  const Eigen::Quaterniond q_grasp(R_grasp);

  // rest: toward the object from the base, the hand turned like the grasp and pitched 30 deg.
  const Eigen::Vector2d toward = Eigen::Rotation2Dd(o.rest_turn) * c.normalized();
  const Eigen::Vector3d p_rest(o.rest_distance * toward.x(), o.rest_distance * toward.y(),
                               scene.table.top_z + o.rest_height);
  const Eigen::Quaterniond q_rest(R_grasp *
                                  Eigen::AngleAxisd(30.0 * kDeg, Eigen::Vector3d::UnitY()));

  const double eta_pg = plan.pregrasp_eta_deg * kDeg + turn;
  const double travel_z = w.z() + o.travel_height;
  const Eigen::Vector3d p_out = Polar(c, o.entry_out, eta_pg, travel_z);
  const Eigen::Vector3d p_in = Polar(c, o.entry_in, eta_pg, travel_z - 0.01);
  const Eigen::Vector3d p_above = w + o.above_height * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d p_lift = w + o.lift_height * Eigen::Vector3d::UnitZ();

  const HandVector closed = NoisyClosedHand(hand, style, k * o.finger_noise, rng);
  const HandVector& open = style.open_hand;

  auto scaled = [&](double duration) {
    return duration * rng.Uniform(1.0 - o.timing_spread, 1.0 + o.timing_spread);
  };
  Eigen::Vector3d bow(rng.Normal(), rng.Normal(), rng.Normal());
  bow *= k * o.path_noise;

  PlannedTrial t;
  auto add = [&](double duration, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                 const Eigen::Quaterniond& q0, const Eigen::Quaterniond& q1, const HandVector& f0,
                 const HandVector& f1, const Eigen::Vector3d& b = Eigen::Vector3d::Zero()) {
    t.segments.push_back(Segment{duration, p0, p1, q0, q1, f0, f1, b});
  };
  add(scaled(o.rest_duration), p_rest, p_rest, q_rest, q_rest, open, open);
  add(scaled(o.reach_duration), p_rest, p_out, q_rest, q_grasp, open, open, bow);
  add(scaled(o.entry_duration), p_out, p_in, q_grasp, q_grasp, open, open);
  add(scaled(o.approach_duration), p_in, p_above, q_grasp, q_grasp, open, open);
  add(scaled(o.descent_duration), p_above, w, q_grasp, q_grasp, open, open);
  AddClosing(style, scaled(o.close_duration), o.close_duration, w, q_grasp, open, closed, &t);
  add(scaled(o.settle_duration), w, w, q_grasp, q_grasp, closed, closed);
  for (const Segment& s : t.segments) t.grasp_time += s.duration;
  add(scaled(o.lift_duration), w, p_lift, q_grasp, q_grasp, closed, closed);
  add(scaled(o.hold_duration), p_lift, p_lift, q_grasp, q_grasp, closed, closed);
  return t;
}

DemoSample SampleAt(const PlannedTrial& plan, double t) {
  double t0 = 0.0;
  size_t i = 0;
  while (i + 1 < plan.segments.size() && t > t0 + plan.segments[i].duration) {
    t0 += plan.segments[i].duration;
    ++i;
  }
  const Segment& s = plan.segments[i];
  const double u = std::clamp((t - t0) / s.duration, 0.0, 1.0);
  const double m = MinimumJerk(u);
  DemoSample sample;
  sample.t = t;
  sample.p_WH = (1.0 - m) * s.p0 + m * s.p1 + std::sin(M_PI * m) * s.bow;
  sample.q_WH = Canonical(s.q0.slerp(m, s.q1));
  sample.f = (1.0 - m) * s.f0 + m * s.f1;
  return sample;
}

// The log of a planned trial at the sample rate, object columns at rest.
DemoLog SampleTrial(const PlannedTrial& plan, const OperatorOptions& o, const SceneModel& scene,
                    double theta_deg, const std::optional<Eigen::Vector2d>& position, int index) {
  DemoLog log;
  char name[96];
  if (position) {
    std::snprintf(name, sizeof name, "x%+05ld_y%+05ld_theta%03d_trial%02d.csv",
                  std::lround(position->x() * 1000.0), std::lround(position->y() * 1000.0),
                  static_cast<int>(std::lround(theta_deg)), index);
  } else {
    std::snprintf(name, sizeof name, "theta%03d_trial%02d.csv",
                  static_cast<int>(std::lround(theta_deg)), index);
  }
  log.source = name;
  log.metadata.theta_deg = theta_deg;
  const Eigen::Isometry3d X_WO = scene.ObjectPose(Placement{theta_deg * kDeg, position});
  log.metadata.object_position = X_WO.translation();
  log.metadata.trial = std::to_string(index);
  log.metadata.operator_name = "synthetic (graspsynth operator model)";
  log.metadata.sample_rate_hz = o.sample_rate_hz;
  double total = 0.0;
  for (const Segment& s : plan.segments) total += s.duration;
  const double dt = 1.0 / o.sample_rate_hz;
  const int n = static_cast<int>(std::ceil(total / dt - 1e-9));
  bool grasp_marked = false;
  for (int i = 0; i <= n; ++i) {
    DemoSample s = SampleAt(plan, i * dt);
    s.p_WO = X_WO.translation();
    if (!grasp_marked && s.t >= plan.grasp_time - 1e-9) {
      s.event = DemoEvent::kGrasp;
      grasp_marked = true;
    }
    log.samples.push_back(s);
  }
  log.samples.back().event = DemoEvent::kEnd;
  return log;
}

// Runs the log through the IK and the simulation and writes the object's simulated centre
// into its object columns. Returns false when the arm cannot execute it.
bool Simulate(const SimulationModel& model, OperatorTrial* trial) {
  DemoLog& log = trial->log;
  const DemoReplay replay = ReplayDemoLog(model.robot(), log);
  if (!replay.ok) {
    trial->outcome.reset();
    trial->reason = replay.message;
    return false;
  }
  TrialOptions options;
  options.hold = 0.05;  // the log holds the lifted pan itself
  options.record_interval = 0.5 / log.metadata.sample_rate_hz.value_or(60.0);
  // the shipped sets were simulated with the fingers on the one wrist body and ODE's own
  // step: the same physics, and their object columns reproduce byte for byte only on that
  // solve.
  options.finger_mounts = false;
  options.structured_solver = false;
  const TrialResult result = RunTrial(model, replay.trajectory, options);
  trial->outcome = result.outcome;
  trial->reason = result.reason;
  // the object at each sample's (possibly re-timed) trajectory time; past the end of the
  // simulation (a trial stopped early) it stays where it was last.
  const std::vector<TrialState>& states = result.states;
  size_t j = 0;
  for (size_t i = 0; i < log.samples.size(); ++i) {
    const double t = replay.trajectory.samples[i].t;
    while (j + 1 < states.size() && states[j + 1].t <= t) ++j;
    Eigen::Vector3d p = states.empty() ? log.samples[i].p_WO : states[j].X_WO.translation();
    if (j + 1 < states.size() && states[j + 1].t > states[j].t && t > states[j].t) {
      const double u = (t - states[j].t) / (states[j + 1].t - states[j].t);
      p = (1.0 - u) * p + u * states[j + 1].X_WO.translation();
    }
    log.samples[i].p_WO = p;
  }
  trial->success = log.samples.back().p_WO.z() - log.samples.front().p_WO.z() >= 0.05 - 1e-9;
  return true;
}

// The trial's random stream; a position (in mm) adds its own term, so that the trials at the
// scene's centre keep the streams they had before positions existed.
uint64_t StreamIndex(const std::optional<Eigen::Vector2d>& position, double theta_deg, int index,
                     int attempt) {
  uint64_t s = static_cast<uint64_t>(std::llround(theta_deg * 1000.0)) * 1000003ull +
               static_cast<uint64_t>(index) * 101ull + static_cast<uint64_t>(attempt);
  if (position) {
    s += static_cast<uint64_t>(std::llround(position->x() * 1000.0) + 10000) * 0x9E3779B97F4Aull +
         static_cast<uint64_t>(std::llround(position->y() * 1000.0) + 10000) * 0xC2B2AE3Dull;
  }
  return s;
}

OperatorTrial MakeTrial(const SimulationModel& model, const OperatorOptions& o,
                        const OrientationPlan& plan, const std::optional<Eigen::Vector2d>& position,
                        int index) {
  OperatorTrial trial;
  trial.position = position;
  trial.theta_deg = plan.theta_deg;
  trial.index = index;
  const Placement placement{plan.theta_deg * kDeg, position};
  for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
    SplitMix64 rng =
        SplitMix64::ForStream(o.seed, StreamIndex(position, plan.theta_deg, index, attempt));
    double total = 0.0;
    for (const GraspStrategy& s : plan.strategies) total += s.weight;
    double pick = rng.Uniform(0.0, total);
    trial.strategy = 0;
    while (trial.strategy + 1 < static_cast<int>(plan.strategies.size()) &&
           pick >= plan.strategies[trial.strategy].weight) {
      pick -= plan.strategies[trial.strategy].weight;
      ++trial.strategy;
    }
    trial.sloppy = rng.Uniform() < o.sloppy_fraction;
    const PlannedTrial planned = PlanTrial(model.scene(), model.robot().hand, o, plan, placement,
                                           plan.strategies[trial.strategy], trial.sloppy, rng);
    trial.log = SampleTrial(planned, o, model.scene(), plan.theta_deg, position, index);
    trial.attempts = attempt + 1;
    if (Simulate(model, &trial)) break;
  }
  auto& extra = trial.log.metadata.extra;
  extra.emplace_back("generator", "graspsynth demos generate");
  extra.emplace_back("strategy", std::to_string(trial.strategy));
  extra.emplace_back("simulated_outcome", std::string(OutcomeName(trial)));
  extra.emplace_back("simulated_reason", trial.reason);
  return trial;
}

}  // namespace

std::string_view OutcomeName(const OperatorTrial& trial) {
  return trial.outcome ? ToString(*trial.outcome) : std::string_view("not_executable");
}

std::vector<OperatorTrial> GenerateDemonstrations(const SimulationModel& model,
                                                  const OperatorOptions& options, int threads,
                                                  const OperatorProgress& progress,
                                                  JobRunner* runner) {
  RequireValid(options, "invalid operator options");
  std::vector<std::optional<Eigen::Vector2d>> positions(options.positions.begin(),
                                                        options.positions.end());
  if (positions.empty()) positions.emplace_back();  // the scene's centre
  struct Job {
    size_t position, plan;
    int trial;
  };
  std::vector<Job> jobs;
  for (size_t x = 0; x < positions.size(); ++x) {
    for (size_t p = 0; p < options.plans.size(); ++p) {
      const int n =
          options.plans[p].trials > 0 ? options.plans[p].trials : options.trials_per_orientation;
      for (int i = 1; i <= n; ++i) jobs.push_back({x, p, i});
    }
  }
  const int total = static_cast<int>(jobs.size());
  std::mutex mutex;
  int finished = 0;
  JobStage stage;
  stage.name = "demos";
  stage.count = total;
  stage.threads = threads;
  stage.run = [&](int j) {
    const Job& job = jobs[static_cast<size_t>(j)];
    return EncodeOperatorTrial(
        MakeTrial(model, options, options.plans[job.plan], positions[job.position], job.trial));
  };
  stage.payload = kOperatorTrialLayout;
  // job j's trial from its bytes: a kept one is checked with it, and every one read back.
  const auto decode = [](int j, std::string_view bytes) {
    return DecodeOperatorTrial(bytes, "demos job " + std::to_string(j));
  };
  stage.check = decode;
  stage.finished = [&](int, bool) {
    std::lock_guard<std::mutex> lock(mutex);
    ++finished;
    if (progress) progress(finished, total);
  };
  LocalJobRunner local;
  const std::vector<std::string> done = (runner ? *runner : local).Run(stage);
  std::vector<OperatorTrial> trials;
  trials.reserve(done.size());
  for (size_t j = 0; j < done.size(); ++j) {
    trials.push_back(decode(static_cast<int>(j), done[j]));
  }
  return trials;
}

std::string EncodeOperatorTrial(const OperatorTrial& t) { return EncodeFields(t); }

OperatorTrial DecodeOperatorTrial(std::string_view bytes, const std::string& source) {
  return DecodeFields<OperatorTrial>(bytes, source);
}

}  // namespace graspsynth
