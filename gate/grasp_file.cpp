#include "gate/grasp_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/field_text.hpp"
#include "common/json_reader.hpp"
#include "kinematics/pose_math.hpp"
#include "simulation/simulation_fields.hpp"
#include "simulation_mujoco/mujoco_fields.hpp"

namespace graspsynth {

namespace {

using nlohmann::json;

json Vec(const Eigen::VectorXd& v) {
  json a = json::array();
  for (int i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

json Quat(const Eigen::Quaterniond& q) {
  const Eigen::Quaterniond c = Canonical(q);
  return json::array({c.w(), c.x(), c.y(), c.z()});
}

json Finite(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json Constraints(const RefinementConstraints& c) {
  return {{"approach_clearance_m", Finite(c.approach_clearance)},
          {"grasp_clearance_m", Finite(c.grasp_clearance)},
          {"closest_pair", c.closest_pair},
          {"contact_error_m", Finite(c.contact_error)},
          {"min_psi_width_deg", c.min_psi_width / kDeg},
          {"reachable", c.reachable},
          {"states", c.states},
          {"feasible", c.feasible},
          {"violation", c.violation}};
}

}  // namespace

namespace {

json MethodJson(const SynthesisResult& s) {
  json m = {{"requested", ToString(s.requested)},
            {"used", ToString(s.used)},
            {"fallback", s.fallback},
            {"reason", s.fallback_reason.Text()}};
  if (s.side != 0) m["side"] = s.side;
  return m;
}

json BracketJson(const Bracket& b) {
  return {{"kind", ToString(b.kind)},
          {"lower", b.lower},
          {"upper", b.upper},
          {"nearest", b.nearest},
          {"t", b.t},
          {"blendable", b.blendable},
          {"reason", b.reason},
          {"orientation_change_deg", b.orientation_change / kDeg},
          {"sides", json::array({b.side_lower, b.side_upper})}};
}

json RefinementJson(const SynthesisResult& s) {
  const RefinementReport& r = s.refinement;
  json ref = {{"refined", s.refined}};
  if (!s.refined) return ref;
  ref["kept"] = ToString(r.kept);
  ref["time_s"] = r.time_s;
  ref["before"] = Constraints(r.before);
  ref["after_ceres"] = Constraints(r.after_ceres);
  ref["after"] = Constraints(r.after);
  ref["ceres"] = {{"run", r.ceres.run},
                  {"initial_cost", r.ceres.initial_cost},
                  {"final_cost", r.ceres.final_cost},
                  {"terms",
                   {{"fidelity", r.ceres.fidelity},
                    {"smoothness", r.ceres.smoothness},
                    {"line", r.ceres.line},
                    {"reach", r.ceres.reach},
                    {"reach_before", r.ceres.initial_reach}}},
                  {"iterations", r.ceres.iterations},
                  {"termination", r.ceres.termination},
                  {"time_s", r.ceres.time_s}};
  ref["nlopt"] = {{"run", r.nlopt.run},
                  {"algorithm", r.nlopt.algorithm},
                  {"fallback_used", r.nlopt.fallback_used},
                  {"termination", r.nlopt.termination},
                  {"evaluations", r.nlopt.evaluations},
                  {"initial_objective", r.nlopt.initial_objective},
                  {"final_objective", r.nlopt.final_objective},
                  {"shift_m", Vec(r.nlopt.shift)},
                  {"yaw_deg", r.nlopt.yaw / kDeg},
                  {"closure", r.nlopt.closure},
                  {"time_s", r.nlopt.time_s}};
  ref["thresholds"] = {{"clearance_margin_m", s.clearance_margin},
                       {"penetration_tolerance_m", s.penetration_tolerance},
                       {"contact_tolerance_m", s.contact_tolerance}};
  if (std::isfinite(s.grip_radius)) {  // the grip slide ran (only when asked for)
    ref["grip_slide"] = {{"grip_radius_m", s.grip_radius}, {"slid_m", s.grip_slide}};
  }
  return ref;
}

json QualityJson(const PhysicsGateResult& gate) {
  const GraspQuality& q = gate.quality;
  return {{"contacts", gate.contacts.size()},
          {"force_closure", q.force_closure},
          {"epsilon", q.epsilon},
          {"volume", q.volume},
          {"wrenches", q.wrenches},
          {"facets", q.facets},
          {"torque_scale_m", q.torque_scale},
          {"message", q.message}};
}

json ValidationJson(const PhysicsGateResult& gate, bool forced) {
  const TrialResult& n = gate.nominal;
  json v = {{"passed", gate.passed},
            {"forced", forced},
            {"reason", gate.reason},
            {"nominal", FieldsJson<json>(n)}};
  v["nominal"]["success"] = n.success();
  if (gate.robustness_run) {
    const RobustnessResult& rb = gate.robustness;
    v["robustness"] = {{"trials", rb.trials.size()},
                       {"successes", rb.successes},
                       {"score", rb.score},
                       {"ci95", json::array({rb.ci95.lo, rb.ci95.hi})}};
  } else {
    v["robustness"] = nullptr;
  }
  // MuJoCo, when it was among the gate's engines and ran (the key is absent otherwise).
  if (gate.mujoco) v["mujoco"] = MujocoSweepJson<json>(*gate.mujoco);
  v["hold_margin"] =
      HoldMarginReportJson<json>(gate.hold_margin, gate.hold_margin_shortfall,
                                 gate.hold_margin_options, [](double x) { return x; });
  return v;
}

}  // namespace

std::string GraspFileToJson(const SynthesisResult& s, const PhysicsGateResult* gate, bool forced) {
  json j;
  j["format"] = kGraspFileFormat;
  j["theta_deg"] = s.theta_deg;
  if (s.placement.xy) j["object_xy"] = {s.placement.xy->x(), s.placement.xy->y()};
  j["method"] = MethodJson(s);
  j["reach"] = {{"used", ToString(s.reach_used)}, {"reason", s.reach_reason}};
  j["bracket"] = BracketJson(s.bracket);
  json sources = json::array();
  for (const SourceDemo& d : s.sources) {
    sources.push_back(
        {{"theta_deg", d.theta_deg}, {"file", d.file}, {"trial", d.trial}, {"weight", d.weight}});
  }
  j["sources"] = sources;
  j["start"] = Vec(s.start);
  json waypoints = json::array();
  for (const MotionWaypoint& w : s.motion.waypoints) {
    waypoints.push_back({{"t", w.t},
                         {"position", Vec(w.p_WH)},
                         {"quaternion", Quat(w.q_WH)},
                         {"fingers", Vec(w.f)}});
  }
  j["waypoints"] = waypoints;
  j["trajectory"] = json::parse(JointTrajectoryToJson(s.trajectory));
  j["refinement"] = RefinementJson(s);
  json timing = {{"generate_s", s.generate_s}, {"refine_s", s.refine_s}, {"joints_s", s.joints_s}};
  if (gate) {
    j["quality"] = QualityJson(*gate);
    j["validation"] = ValidationJson(*gate, forced);
    timing["gate_s"] = gate->time_s;
  } else {
    j["quality"] = nullptr;
    j["validation"] = nullptr;
  }
  j["timing"] = timing;
  return j.dump(1) + "\n";
}

void WriteGraspFile(const std::filesystem::path& path, const SynthesisResult& synthesis,
                    const PhysicsGateResult* gate, bool forced) {
  WriteFileAtomically(path, GraspFileToJson(synthesis, gate, forced));
}

namespace {

JointTrajectory ReadTrajectoryOrGrasp(const JsonReader& doc, const ArmModel& arm,
                                      const HandModel& hand) {
  const bool grasp_file =
      doc.IsObject() && doc.Field("format").IsString() && doc.String("format") == kGraspFileFormat;
  const JsonReader object = grasp_file ? doc.Object("trajectory") : doc;
  const JointTrajectory t = ReadJointTrajectory(object);
  CheckJointLimits(t, arm, hand, doc.source(), 1e-9, grasp_file ? "trajectory." : "");
  return t;
}

}  // namespace

JointTrajectory LoadTrajectoryOrGraspFile(const std::filesystem::path& path, const ArmModel& arm,
                                          const HandModel& hand) {
  return ReadTrajectoryOrGrasp(JsonReader::Load(path, input_kind::kTrajectory), arm, hand);
}

JointTrajectory ParseTrajectoryOrGraspFile(std::string_view json_text, const std::string& source,
                                           const ArmModel& arm, const HandModel& hand) {
  return ReadTrajectoryOrGrasp(JsonReader::Parse(json_text, source), arm, hand);
}

}  // namespace graspsynth
