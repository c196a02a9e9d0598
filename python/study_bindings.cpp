// graspsynth._core: the end-to-end study (`graspsynth run`) and the generalization table
// (`graspsynth generalize`), returned as data.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analysis_report.hpp"
#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/grasp_library.hpp"
#include "python/bindings.hpp"
#include "python/request_bindings.hpp"
#include "request/generalize_request.hpp"
#include "request/run_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "solver/synthesis_model.hpp"
#include "studies/study.hpp"
#include "studies/study_method.hpp"
#include "studies/study_report.hpp"

namespace graspsynth::python {
namespace {

py::dict Run(const std::optional<std::filesystem::path>& demos, const py::dict& options,
             const std::shared_ptr<RobotModel>& robot,
             const std::shared_ptr<SceneModel>& scene_arg) {
  const request::RunRequest r = RequestFromPython(request::RunOptions(), options);
  const SceneModel& scene = *SynthesisScene(scene_arg);
  const StudyOptions study = request::ToStudyOptions(r, scene, demos.value_or(""));
  StudyResult result;
  std::string analysis, synthesis, timing;
  {
    py::gil_scoped_release release;
    const SimulationModel model(*RobotOrDefault(robot), scene);
    result = RunStudy(model, study);
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
  m.def("_run", &Run, py::arg("demos"), py::arg("options"), py::arg("robot"), py::arg("scene"),
        R"doc(
run's work (graspsynth/__init__.py gives it its signature): the options of
request_options("run") as a dict. Returns a dict: analysis (analysis.json), library (a
GraspLibrary), synthesis (synthesis.json: summary and rows), timing (timing.json), rows
(StudyRow objects) and summary (StudyMethodSummary objects).)doc");

  m.def("_generalize", &Generalize, py::arg("library"), py::arg("options"), py::arg("robot"),
        py::arg("scene"), R"doc(
generalize's work (graspsynth/__init__.py gives it its signature): the options of
request_options("generalize") as a dict. Returns (rows, summary): StudyRow objects (per
orientation and method) and StudyMethodSummary objects (per method).)doc");
}

}  // namespace graspsynth::python
