// graspsynth._core: the study's, the selection's and the simulation's results as typed classes and
// its outcomes, methods and statuses as enums, all made from the field lists
// (common/field_list.hpp, studies/study_fields.hpp) by python/field_class.hpp.

#include "learning_data/learning_data_fields.hpp"
#include "python/bindings.hpp"
#include "python/field_class.hpp"
#include "simulation/simulation_fields.hpp"
#include "studies/study_fields.hpp"

namespace graspsynth::python {

void BindResults(py::module_& m) {
  BindEnum<TrialOutcome>(m, "TrialOutcome", "How a grasp-and-lift trial ended.");
  BindEnum<SynthesisMethod>(m, "SynthesisMethod", "How a grasp is made from the library.");
  BindEnum<SynthesisStatus>(m, "SynthesisStatus", "How a synthesis ended.");
  BindEnum<FallbackKind>(m, "FallbackKind", "Which fallback replaced the requested method.");
  BindEnum<PhysicsFactor>(m, "PhysicsFactor", "A factor of the physics perturbation.");

  BindFieldClass<HoldQuality>(
      m, "HoldQuality",
      "How the object sat in the hand at the end of a trial: tilts (rad), slip (m, rad), "
      "contacts, load_share (the fingers, then the palm).");
  BindFieldClass<PhysicsVariation>(m, "PhysicsVariation",
                                   "A replay's physics: factors on the modelled values, the "
                                   "centre of mass offset (object frame, m).");
  BindFieldClass<PhysicsDraw>(m, "PhysicsDraw", "A replay's physics and its step (s; 0: own).");
  BindFieldClass<SensitivityCell>(m, "SensitivityCell",
                                  "Replays at one end of a physics factor's range.");
  BindFieldClass<SensitivityRow>(m, "SensitivityRow",
                                 "One factor of a sensitivity table: its low and high end.");
  BindFieldClass<SensitivityResult>(m, "SensitivityResult",
                                    "What a grasp depends on: one row per physics factor.");
  BindFieldClass<Interval>(m, "Interval", "A closed interval lo..hi.");
  BindFieldClass<WorldCounts>(m, "WorldCounts", "The bodies, joints and geoms of a trial's world.");
  BindFieldClass<StepStatistics>(m, "StepStatistics",
                                 "A trial's steps and where their wall time went (s).");
  BindFieldClass<RobustnessTrial>(
      m, "RobustnessTrial",
      "One perturbed replay: its index, time scaling and drawn physics, and what happened (m, "
      "s; final_object_pose 4 x 4, world).")
      .def_property_readonly("success", &RobustnessTrial::success);
  BindFieldClass<RobustnessResult>(
      m, "RobustnessResult",
      "Perturbed replays of a trajectory: each replay (trials), the successes, the score "
      "(successes / replays) and its Wilson 95% interval (ci95), and the time they took (s).")
      .def("failure_summary", &FailureSummary,
           "the failures' outcomes and counts, e.g. \"dropped 3, not_lifted 1\"");
  BindFieldClass<FallbackReason>(m, "FallbackReason",
                                 "Why a method other than the requested one was used.")
      .def("text", &FallbackReason::Text, "the reason in words, as synthesis.json writes it");
  BindFieldClass<StudyRow>(
      m, "StudyRow",
      "One row of a synthesis table: one orientation (deg), one method, its physics gate. "
      "to_dict() gives every field; synthesis.json's rows are the files' form.");
  BindFieldClass<StudyMethodSummary>(m, "StudyMethodSummary",
                                     "Per-method totals of a synthesis table.");
  BindFieldClass<DemoScore>(
      m, "DemoScore",
      "A successful demonstration's robustness in the selection: its perturbed replays (trials, "
      "successes, score, the Wilson 95% interval ci_low..ci_high), the nominal replay, whether it "
      "was selected, and why its replays stopped early (stopped; empty when all ran). xy: the "
      "object centre on the table in its log, m.");
}

}  // namespace graspsynth::python
