// graspsynth._core: the end-to-end study (`graspsynth run`) and the generalization table
// (`graspsynth generalize`), returned as data.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "analysis/analysis_report.hpp"
#include "common/errors.hpp"
#include "common/orientation_list.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/demo_directory.hpp"
#include "learning_data/grasp_library.hpp"
#include "python/bindings.hpp"
#include "python/request_bindings.hpp"
#include "request/generalize_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "solver/synthesis_model.hpp"
#include "studies/study.hpp"
#include "studies/study_method.hpp"
#include "studies/study_report.hpp"

namespace graspsynth::python {
namespace {

// Orientations as a list of numbers, or as the command line's text ("20:100:5,33").
using Orientations = std::variant<std::string, std::vector<double>>;

std::vector<double> OrientationsOf(const Orientations& given) {
  if (const auto* text = std::get_if<std::string>(&given)) {
    return ParseOrientationList(*text, "orientations");
  }
  const auto& values = std::get<std::vector<double>>(given);
  for (double v : values) {
    if (!std::isfinite(v)) throw InputError("orientations: every value must be finite (deg)");
  }
  if (values.empty()) throw InputError("orientations: no orientation given");
  return values;
}

py::dict Run(const std::optional<std::filesystem::path>& demos, bool quick,
             const std::optional<Orientations>& orientations, uint64_t seed, int threads,
             std::optional<int> perturb, std::optional<int> select_perturb,
             std::optional<int> sensitivity, bool physics, bool physics_fallback, bool all_replays,
             const std::shared_ptr<RobotModel>& robot,
             const std::shared_ptr<SceneModel>& scene_arg) {
  const SceneModel& scene = *SynthesisScene(scene_arg);
  StudyOptions options;
  options.demos = demos ? std::filesystem::path(*demos) : DefaultDemoDirectory(scene.object.name);
  options.seed = seed;
  options.threads = threads;
  options.analysis.segmentation.region = scene.grasp_region;
  options.paper_object = scene.object.paper_object;
  options.perturbation.physics.enabled = physics;
  options.physics_fallback = physics_fallback;
  options.selection_early_stop = !all_replays;
  if (quick) options.UseQuickStudy();
  if (sensitivity) options.sensitivity_trials = *sensitivity;
  if (perturb) options.gate_perturbations = *perturb;
  if (select_perturb) options.selection_perturbations = *select_perturb;
  if (orientations) options.orientations = OrientationsOf(*orientations);
  CheckThreads(threads);
  std::string why;
  if (!options.IsValid(&why)) throw InputError("run: " + why);
  if (!std::filesystem::is_directory(options.demos)) {
    throw InputError("run: demos '" + options.demos.string() + "' is not a folder");
  }
  StudyResult result;
  std::string analysis, synthesis, timing;
  {
    py::gil_scoped_release release;
    const SimulationModel model(*RobotOrDefault(robot), scene);
    result = RunStudy(model, options);
    analysis = AnalysisReportJson(result.analysis, result.options.PaperComparison());
    synthesis = StudySynthesisJson(result);
    timing = StudyTimingJson(result);
  }
  py::dict d;
  d["analysis"] = JsonTextToPython(analysis);
  d["library"] = std::make_shared<GraspLibrary>(result.selection.library);
  d["synthesis"] = JsonTextToPython(synthesis);
  d["timing"] = JsonTextToPython(timing);
  d["rows"] = py::cast(result.rows);
  d["summary"] = py::cast(SummarizeStudy(result.rows));
  return d;
}

py::object Generalize(const py::object& library_arg, const py::dict& options,
                      const std::shared_ptr<RobotModel>& robot,
                      const std::shared_ptr<SceneModel>& scene_arg) {
  const request::GeneralizeRequest r = RequestFromPython(request::GeneralizeOptions(), options);
  const SynthesisTableOptions table = request::ToSynthesisTableOptions(r);
  const bool leave_one_out = r.leave_one_out;
  const SceneModel& scene = *SynthesisScene(scene_arg);
  const std::shared_ptr<const GraspLibrary> shared =
      LibraryArgument(library_arg, scene.object.name);
  const GraspLibrary& library = *shared;
  std::vector<StudyRow> rows;
  {
    py::gil_scoped_release release;
    const SimulationModel model(*RobotOrDefault(robot), scene);
    rows = leave_one_out ? LeaveOneOutTable(model, library, table)
                         : SynthesisTable(model, library, table);
  }
  return py::make_tuple(rows, SummarizeStudy(rows));
}

}  // namespace

void BindStudy(py::module_& m) {
  m.def("run", &Run, py::arg("demos") = py::none(), py::arg("quick") = false,
        py::arg("orientations") = py::none(), py::arg("seed") = StudyOptions{}.seed,
        py::arg("threads") = 0, py::arg("perturb") = py::none(),
        py::arg("select_perturb") = py::none(), py::arg("sensitivity") = py::none(),
        py::arg("physics") = true, py::arg("physics_fallback") = true,
        py::arg("all_replays") = false, py::arg("robot") = py::none(),
        py::arg("scene") = py::none(), R"doc(
The end-to-end study of `graspsynth run`: Table I, the representative selection, and a grasp
for every orientation by each method, validated in physics. The same options give the same
analysis, library and synthesis as the command line, whatever `threads` is.
Returns a dict: analysis (analysis.json), library (a GraspLibrary), synthesis
(synthesis.json: summary and rows), timing (timing.json), rows (StudyRow objects) and summary
(StudyMethodSummary objects).)doc");

  m.def("_generalize", &Generalize, py::arg("library"), py::arg("options"), py::arg("robot"),
        py::arg("scene"), R"doc(
generalize's work (graspsynth/__init__.py gives it its signature): the options of
request_options("generalize") as a dict. Returns (rows, summary): StudyRow objects (per
orientation and method) and StudyMethodSummary objects (per method).)doc");
}

}  // namespace graspsynth::python
