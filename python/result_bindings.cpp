// graspsynth._core: the study's, the selection's and the simulation's results as typed classes and
// its outcomes, methods and statuses as enums, all made from the field lists
// (common/field_list.hpp, studies/study_fields.hpp) by python/field_class.hpp.

#include "learning_data/learning_data_fields.hpp"
#include "python/bindings.hpp"
#include "python/field_class.hpp"
#include "simulation/simulation_fields.hpp"
#include "studies/study_fields.hpp"

namespace graspsynth::python {

namespace {

// The outcomes, methods, statuses and factors, each member documented.
void BindResultEnums(py::module_& m) {
  BindEnum<TrialOutcome>(
      m, "TrialOutcome", "How a grasp-and-lift trial ended.",
      {"lifted, held and touching only the hand", "the object never left the table (no grasp)",
       "the object had been lifted, then slipped or dropped",
       "the object was knocked over or pushed away without being lifted",
       "lifted, but resting on something other than the hand (the arm)",
       "lifted and held by the hand alone, but hanging tilted beyond the limit",
       "the arm, the hand mount or the palm hit the table",
       "an arm command outside the joint limits (the controller stops there)",
       "numerical instability: a non-finite state or runaway energy"});
  BindEnum<SynthesisMethod>(
      m, "SynthesisMethod",
      "How a grasp is made from the library; method= takes a member or its label (\"interp\").",
      {"the paper's: blend of the two demonstrations that bracket the orientation",
       "the line principle: the grasp on the fitted wrist line, also outside the library's range",
       "the nearest demonstration, turned with the object"});
  BindEnum<SynthesisStatus>(
      m, "SynthesisStatus", "How a synthesis ended.",
      {"a grasp was synthesized", "interp asked for outside the library's range",
       "the start configuration is outside the joint limits or in collision",
       "the line principle cannot be fitted on this library",
       "the joint conversion failed (a pose without IK solution, or a jump)"});
  BindEnum<FallbackKind>(
      m, "FallbackKind", "Which fallback replaced the requested method.",
      {"no fallback: the requested method was used",
       "a weak demonstrated orientation: its robust neighbour turned with the object",
       "an unblendable bracket: its nearer (or robust) end turned with the object",
       "an unblendable bracket whose turned end is unreachable: the line principle",
       "an unblendable bracket, nothing else reachable: the plain blend",
       "an unblendable cell (a library over placements): the blend of the vertices that blend"});
  BindEnum<PhysicsFactor>(
      m, "PhysicsFactor", "A factor of the physics perturbation.",
      {"object-hand friction", "object-table friction", "contact stiffness", "contact damping",
       "object mass", "centre of mass offset", "finger servo force caps",
       "the step (low end: the trial's own; high end: the fine step)"});
}

// What a trial and its perturbed replays found.
void BindTrialResults(py::module_& m) {
  BindFieldClass<HoldQuality>(
      m, "HoldQuality",
      "How the object sat in the hand at the end of a trial: tilts (rad), slip (m, rad), "
      "contacts, load_share (the fingers, then the palm).",
      {{"end_tilt", "angle of the object's up axis from vertical at the end, rad"},
       {"max_tilt", "the largest such angle during the trial, rad"},
       {"slip",
        "displacement of the object in the hand from when it last left the table to the end, m "
        "(hand-mount frame; 0 when it is not off the table at the end)"},
       {"slip_angle", "rotation of the object in the hand over the same span, rad"},
       {"contacts", "object-hand contact points at the end"},
       {"load_share",
        "share of the object-hand contact force at the end per finger (thumb, index, middle, "
        "ring), then the palm; sums to 1, all 0 without contact force"}});
  BindFieldClass<HoldMargin>(
      m, "HoldMargin",
      "How securely the object sat in the hand at the end of a trial (gate/hold_margin.hpp): "
      "slip (mm, deg), end tilt (deg), contacts and load share per finger and the palm, "
      "load-bearing links, epsilon at the measured normal forces (object weights), friction use.",
      {{"measured", "the trial ended with contact force on the object"},
       {"slip_mm", "displacement of the object in the hand from lift-off to the end, mm"},
       {"slip_deg", "rotation of the object in the hand over the same span, deg"},
       {"end_tilt_deg", "angle of the object's up axis from vertical at the end, deg"},
       {"contacts", "object-hand contact points at the end per finger, then the palm"},
       {"load_share", "share of the contact force per finger, then the palm"},
       {"load_bearing_links", "hand links carrying at least 10% of the contact force"},
       {"fingertips_only", "every load-bearing link is a fingertip (a pinch)"},
       {"epsilon_weight",
        "Ferrari-Canny epsilon of the cones scaled by the measured normal forces, in object "
        "weights (about the centre of mass, torques over torque_scale_m)"},
       {"torque_scale_m", "the length that turns torques into forces, m"},
       {"friction_use_max", "largest |f_t| / (mu f_n) of a load-bearing contact"},
       {"friction_use_mean", "the same, mean weighted by each contact's force"},
       {"normal_force_weight", "summed normal force over the object's weight"}});
  BindFieldClass<PhysicsVariation>(
      m, "PhysicsVariation",
      "A replay's physics: factors on the modelled values, the "
      "centre of mass offset (object frame, m).",
      {{"object_hand_friction", "factor on the object-hand friction"},
       {"object_table_friction", "factor on the object-table friction"},
       {"contact_stiffness", "factor on every contact's stiffness"},
       {"contact_damping", "factor on every contact's damping"},
       {"object_mass", "factor on the object's mass and inertia"},
       {"object_com_offset",
        "shift of the object's centre of mass, (x, y, z) m, object "
        "frame"},
       {"hand_effort", "factor on every finger servo's force cap"}});
  BindFieldClass<PhysicsDraw>(
      m, "PhysicsDraw", "A replay's physics and its step (s; 0: own).",
      {{"variation", "the factors on the modelled physics (PhysicsVariation)"},
       {"time_step", "the replay's step, s; 0: the trial's own"}});
  BindFieldClass<SensitivityCell>(m, "SensitivityCell",
                                  "Replays at one end of a physics factor's range.",
                                  {{"physics", "the replays' physics (PhysicsDraw)"},
                                   {"trials", "replays run"},
                                   {"successes", "of which succeeded"},
                                   {"failures",
                                    "the failures' outcomes and counts, e.g. "
                                    "\"dropped 2\""}});
  BindFieldClass<SensitivityRow>(m, "SensitivityRow",
                                 "One factor of a sensitivity table: its low and high end.",
                                 {{"factor", "the physics factor (PhysicsFactor)"},
                                  {"low", "the replays at the low end (SensitivityCell)"},
                                  {"high", "the replays at the high end (SensitivityCell)"}});
  BindFieldClass<SensitivityResult>(m, "SensitivityResult",
                                    "What a grasp depends on: one row per physics factor.",
                                    {{"trials_per_cell", "replays at each end of each factor"},
                                     {"rows", "one SensitivityRow per physics factor"},
                                     {"wall_time", "the time the table took, s"}});
  BindFieldClass<Interval>(m, "Interval", "A closed interval lo..hi.",
                           {{"lo", "the lower end"}, {"hi", "the upper end"}});
  BindFieldClass<WorldCounts>(m, "WorldCounts", "The bodies, joints and geoms of a trial's world.",
                              {{"bodies", "dynamic and kinematic bodies"},
                               {"joints", "hinge joints (contacts not counted)"},
                               {"geoms", "collision primitives, the table included"},
                               {"dynamic_bodies", "bodies that the physics moves"}});
  BindFieldClass<StepStatistics>(
      m, "StepStatistics", "A trial's steps and where their wall time went (s).",
      {{"dynamic_steps", "physics steps"},
       {"kinematic_steps", "steps with the object at rest, moved kinematically"},
       {"collision_s", "wall time in collision detection, s"},
       {"solver_s", "wall time in ODE's step, s"},
       {"control_s", "wall time in the controller, kinematics and body placement, s"},
       {"max_contacts", "most contact joints in one step"}});
}

// The perturbed replays.
void BindReplayResults(py::module_& m) {
  BindFieldClass<RobustnessTrial>(
      m, "RobustnessTrial",
      "One perturbed replay: its index, time scaling and drawn physics, and what happened (m, "
      "s; final_object_pose 4 x 4, world).",
      {{"index", "the replay's index (its draws depend on the seed and the index only)"},
       {"time_scale", "the factor on the trajectory's duration"},
       {"physics", "the replay's drawn physics (PhysicsDraw)"},
       {"outcome", "how the replay ended (TrialOutcome)"},
       {"reason", "one sentence, with the figures that decided the outcome"},
       {"lift", "object centre above its rest height at the end, m"},
       {"final_object_pose", "the object's pose at the end, 4 x 4, world"},
       {"hold", "how the object sat in the hand at the end (HoldQuality)"},
       {"simulated_time", "s"},
       {"wall_time", "s"},
       {"cpu_time", "s of CPU time"},
       {"dynamic_steps", "physics steps"},
       {"kinematic_steps", "steps with the object at rest, moved kinematically"}})
      .def_property_readonly("success", &RobustnessTrial::success,
                             "the outcome is success: lifted and held, touching only the hand");
  BindFieldClass<RobustnessResult>(
      m, "RobustnessResult",
      "Perturbed replays of a trajectory: each replay (trials), the successes, the score "
      "(successes / replays) and its Wilson 95% interval (ci95), and the time they took (s).",
      {{"trials", "every replay (RobustnessTrial), in index order"},
       {"successes", "replays that succeeded"},
       {"score", "successes / replays"},
       {"ci95", "Wilson 95% interval of the success probability (Interval)"},
       {"threads", "worker threads used"},
       {"wall_time", "s"},
       {"simulated_time", "s, summed over the replays"},
       {"cpu_time", "s, summed over the replays"}})
      .def("failure_summary", &FailureSummary,
           "the failures' outcomes and counts, e.g. \"dropped 3, not_lifted 1\"");
}

// How the study and the selection judged the grasps and the demonstrations.
void BindStudyResults(py::module_& m) {
  BindFieldClass<FallbackReason>(
      m, "FallbackReason", "Why a method other than the requested one was used.",
      {{"kind", "which fallback (FallbackKind)"},
       {"bracket_reason",
        "why the bracket could not be used as it is; \"\" when it "
        "could"},
       {"lower_deg", "the bracket's lower end, deg"},
       {"upper_deg", "the bracket's upper end, deg"},
       {"used_deg", "the demonstration turned with the object, deg"},
       {"robust",
        "TURNED_DEMO: exactly one end was weak (the robust "
        "one was used)"},
       {"min_psi_width",
        "the arm-angle spare the turned end lacked, "
        "rad"},
       {"line_unreachable", "PLAIN_BLEND: the line principle's grasp was tried too"},
       {"side", "LINE_PRINCIPLE: the side of the handle"},
       {"blend_failed",
        "the bracket was blendable, but its blend failed its nominal "
        "trial in physics"},
       {"cell",
        "a library over placements: the query's cell, its vertices "
        "and weights in words"},
       {"used_placement",
        "a library over placements: the vertex used, or the vertices "
        "blended with their weights"}})
      .def("text", &FallbackReason::Text, "the reason in words, as synthesis.json writes it");
  BindFieldClass<MujocoSweepSummary>(
      m, "MujocoSweepSummary",
      "A grasp in MuJoCo under its contact settings and servo mappings (engines ode,mujoco).",
      {{"runs", "contact settings x servo mappings"},
       {"successes", "runs that held"},
       {"success_fraction", "successes / runs"},
       {"slip_median", "median slip in the hand of the runs that held, m"},
       {"slip_worst", "largest such slip, m"},
       {"slip_angle_median", "median rotation in the hand of the runs that held, rad"},
       {"slip_angle_worst", "largest such rotation, rad"},
       {"failing", "the failed runs, \"setting/servo\" comma-separated"}});
  BindFieldClass<StudyRow>(
      m, "StudyRow",
      "One row of a synthesis table: one orientation (deg), one method, its physics gate. "
      "to_dict() gives every field; synthesis.json's rows are the files' form.",
      {{"theta_deg", "the object orientation, deg"},
       {"at", "the object centre (x, y) on the table, m, world; None: the scene's"},
       {"method", "the method asked for, by its label (\"interp\", \"line\", \"nearest\")"},
       {"message", "the synthesis' message when status is not OK"},
       {"used", "the method used (SynthesisMethod); None when the synthesis did not succeed"},
       {"fallback", "a method other than the requested one was used"},
       {"fallback_reason", "why (FallbackReason)"},
       {"refined", "the refinement ran"},
       {"gate_run", "the physics gate ran (status OK)"},
       {"status", "how the synthesis ended (SynthesisStatus); None without a library"},
       {"nominal_success", "the nominal trial succeeded"},
       {"nominal_outcome", "how the nominal trial ended (TrialOutcome); None without a gate"},
       {"nominal_reason", "the nominal trial's reason sentence"},
       {"trials", "perturbed replays"},
       {"successes", "of which succeeded"},
       {"robustness", "successes / trials (0 without replays)"},
       {"ci_low", "lower end of the Wilson 95% interval of the success probability"},
       {"ci_high", "upper end of the Wilson 95% interval"},
       {"passed", "the physics gate passed"},
       {"gate_reason", "the gate's sentence"},
       {"epsilon", "Ferrari-Canny epsilon of the nominal hold"},
       {"force_closure", "the nominal hold is force closure"},
       {"failures", "perturbed failures by outcome, e.g. \"dropped 2, not_lifted 1\""},
       {"nominal_hold", "how the object sat in the hand after the nominal trial (HoldQuality)"},
       {"hold_margin", "the nominal hold's margin (HoldMargin)"},
       {"hold_margin_shortfall", "the hold-margin thresholds it misses; \"\" when none"},
       {"sensitivity", "the gate's sensitivity table (SensitivityResult), or None"},
       {"mujoco", "the gate's MuJoCo sweep (MujocoSweepSummary), or None (engines ode)"},
       {"seed", "seed of the gate's perturbations"},
       {"synthesis_s", "wall time of the synthesis, s"},
       {"gate_s", "wall time of the gate, s"},
       {"source_thetas_deg", "orientations of the demonstrations the grasp was made from, deg"}});
  BindFieldClass<StudyMethodSummary>(
      m, "StudyMethodSummary", "Per-method totals of a synthesis table.",
      {{"method", "the method, by its label (\"interp\")"},
       {"rows", "orientations tried"},
       {"synthesized", "rows with status OK"},
       {"nominal_successes", "rows whose nominal trial succeeded"},
       {"passed", "rows that passed the physics gate"},
       {"fallbacks", "rows that used another method"},
       {"mean_robustness", "over the synthesized rows (0 if none)"},
       {"mean_robustness_all", "over every row, a row not synthesized counting 0"}});
  BindFieldClass<DemoScore>(
      m, "DemoScore",
      "A successful demonstration's robustness in the selection: its perturbed replays (trials, "
      "successes, score, the Wilson 95% interval ci_low..ci_high), the nominal replay, whether it "
      "was selected, and why its replays stopped early (stopped; empty when all ran). xy: the "
      "object centre on the table in its log, m.",
      {{"file", "the log's file name, relative to the library's demo directory"},
       {"trial", "the log's trial name"},
       {"theta_deg", "the object orientation, deg"},
       {"xy", "the object centre (x, y) on the table in its log, m, world"},
       {"trials", "perturbed replays"},
       {"successes", "of which succeeded"},
       {"score", "successes / trials"},
       {"ci_low", "lower end of the Wilson 95% interval of the success probability"},
       {"ci_high", "upper end of the Wilson 95% interval"},
       {"nominal_success", "the unperturbed replay succeeded"},
       {"seed", "seed of this demonstration's perturbation stream"},
       {"failures", "failure outcomes and counts, e.g. \"dropped 3, not_lifted 1\""},
       {"selected", "the representative of its orientation"},
       {"stopped", "\"\" when every replay ran; otherwise why the replays stopped early"}});
}

}  // namespace

void BindResults(py::module_& m) {
  BindResultEnums(m);
  BindTrialResults(m);
  BindReplayResults(m);
  BindStudyResults(m);
}

}  // namespace graspsynth::python
