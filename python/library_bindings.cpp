// graspsynth._core: the grasp library, the representative selection, and the synthesis of a
// grasp through the physics gate.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "gate/grasp_file.hpp"
#include "gate/physics_gate.hpp"
#include "gate/validated_synthesis.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/demo_directory.hpp"
#include "learning_data/grasp_library.hpp"
#include "learning_data/representative_selection.hpp"
#include "python/bindings.hpp"
#include "python/repr.hpp"
#include "python/request_bindings.hpp"
#include "request/select_request.hpp"
#include "request/synthesize_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "solver/motion_generation.hpp"
#include "solver/reach_planning.hpp"
#include "solver/synthesis.hpp"
#include "solver/synthesis_model.hpp"

namespace graspsynth::python {
namespace {

// The synthesis' models, built once for many grasps: the simulation (the gate) and the
// synthesis model (collision model, line principle, entry constraints) of one library.
struct Synthesizer {
  Synthesizer(const RobotModel& robot, const SceneModel& scene, const GraspLibrary& library)
      : simulation(robot, scene), model(simulation.robot(), simulation.scene(), library) {}
  SimulationModel simulation;
  SynthesisModel model;
};

// A synthesized grasp and its gate.
struct Grasp {
  ValidatedSynthesis validated;
  SynthesisMethod requested = SynthesisMethod::kInterp;
};

std::shared_ptr<GraspLibrary> LoadLibrary(const std::optional<std::filesystem::path>& path,
                                          const std::string& object) {
  return std::make_shared<GraspLibrary>(
      ReadGraspLibrary(path ? std::filesystem::path(*path) : DefaultGraspLibraryPath(object)));
}

std::shared_ptr<Synthesizer> MakeSynthesizer(const py::object& library,
                                             const std::shared_ptr<RobotModel>& robot,
                                             const std::shared_ptr<SceneModel>& scene_arg) {
  const std::shared_ptr<const SceneModel> scene = SynthesisScene(scene_arg);
  const std::shared_ptr<const GraspLibrary> lib = LibraryArgument(library, scene->object.name);
  if (lib->entries.empty()) {
    throw InputError("the grasp library '" + lib->source + "' has no entry to synthesize from");
  }
  py::gil_scoped_release release;
  return std::make_shared<Synthesizer>(*RobotOrDefault(robot), *scene, *lib);
}

std::shared_ptr<Grasp> Synthesize(const Synthesizer& s, const py::dict& options) {
  const request::SynthesizeRequest q = RequestFromPython(request::SynthesizeOptions(), options);
  const ValidatedSynthesisOptions vo = request::ToValidatedSynthesisOptions(q);
  const SynthesisOptions& so = vo.synthesis;
  const SynthesisTask task = MakeSynthesisTask(s.model.scene(), q.theta, q.at);
  auto grasp = std::make_shared<Grasp>();
  grasp->requested = so.generation.method;
  {
    py::gil_scoped_release release;
    SynthesisData data(s.model);
    grasp->validated = SynthesizeAndValidate(s.simulation, s.model, task, vo, &data);
  }
  const SynthesisResult& r = grasp->validated.synthesis;
  switch (r.status) {
    case SynthesisStatus::kOk:
    case SynthesisStatus::kUnreachable:
      return grasp;
    case SynthesisStatus::kOutOfRange:
    case SynthesisStatus::kBadStart:
    case SynthesisStatus::kNoModel:
      break;
  }
  throw InputError(r.message);
}

const SynthesisResult& Synthesized(const Grasp& g) {
  if (!g.validated.synthesis.ok()) {
    throw InputError("no grasp was synthesized: " + g.validated.synthesis.message);
  }
  return g.validated.synthesis;
}

py::tuple Select(const std::optional<std::filesystem::path>& directory, const py::dict& given,
                 const std::shared_ptr<RobotModel>& robot,
                 const std::shared_ptr<SceneModel>& scene_arg) {
  const request::SelectRequest r = RequestFromPython(request::SelectOptions(), given);
  const SceneModel& scene = *SceneOrDefault(scene_arg);
  const SelectionOptions options = request::ToSelectionOptions(r, scene);
  SelectionResult result;
  {
    py::gil_scoped_release release;
    const SimulationModel model(*RobotOrDefault(robot), scene);
    result = SelectRepresentatives(
        model,
        directory ? ReadDemoDirectory(*directory) : ReadDefaultDemoDirectory(scene.object.name),
        options);
  }
  py::list issues;
  for (const SelectionIssue& issue : result.issues) {
    py::dict d;
    d["file"] = issue.file;
    d["kind"] = ToString(issue.kind);
    d["reason"] = issue.reason;
    issues.append(d);
  }
  py::dict report;
  report["logs"] = result.logs;
  report["unsuccessful"] = result.unsuccessful;
  report["issues"] = issues;
  report["unselected_thetas"] = result.unselected_thetas;
  return py::make_tuple(std::make_shared<GraspLibrary>(std::move(result.library)), report);
}

}  // namespace

std::shared_ptr<const SceneModel> SynthesisScene(const std::shared_ptr<SceneModel>& scene_arg) {
  std::shared_ptr<const SceneModel> scene = SceneOrDefault(scene_arg);
  scene->object.Handle(kSynthesisNeedsHandle);
  return scene;
}

std::shared_ptr<const GraspLibrary> LibraryArgument(const py::object& library,
                                                    const std::string& object_name) {
  if (library.is_none()) return LoadLibrary(std::nullopt, object_name);
  if (py::isinstance<GraspLibrary>(library)) return library.cast<std::shared_ptr<GraspLibrary>>();
  if (py::isinstance<py::str>(library) || py::hasattr(library, "__fspath__")) {
    const py::object path = py::module_::import("os").attr("fspath")(library);
    if (py::isinstance<py::str>(path))
      return LoadLibrary(std::filesystem::path(path.cast<std::string>()), object_name);
  }
  throw py::type_error("library must be a GraspLibrary, a path or None, not " +
                       py::repr(library.get_type()).cast<std::string>());
}

namespace {

std::string LibraryRepr(const GraspLibrary& l) {
  std::string text =
      "GraspLibrary(source=" + ReprText(l.source) + ", entries=" + std::to_string(l.entries.size());
  if (!l.entries.empty()) {
    text += ", theta_deg=" + ReprNumber(l.entries.front().theta_deg) + ".." +
            ReprNumber(l.entries.back().theta_deg);
  }
  return text + ", perturbations=" + std::to_string(l.perturbations) + ")";
}

std::string GraspRepr(const Grasp& g) {
  const SynthesisResult& s = g.validated.synthesis;
  std::string text = "Grasp(theta_deg=" + ReprNumber(s.theta_deg);
  if (!s.ok()) {
    return text + ", ok=False, status=" + ReprEnum(py::cast(s.status)) +
           ", message=" + ReprText(s.message) + ")";
  }
  text += ", method_used=" + ReprEnum(py::cast(s.used));
  if (s.fallback) text += ", fallback=True";
  text += std::string(", passed=") +
          (g.validated.gate_run && g.validated.gate.passed ? "True" : "False");
  const RobustnessResult& r = g.validated.gate.robustness;
  text += ", robustness=" + (g.validated.gate.robustness_run ? ReprNumber(r.score) : "None");
  return text + ")";
}

void BindGraspLibrary(py::module_& m) {
  py::class_<GraspLibrary, std::shared_ptr<GraspLibrary>>(m, "GraspLibrary", R"doc(
A grasp library (format graspsynth-library/1): the representative demonstration of each
orientation, chosen by robustness in physics, with every scored demonstration.

GraspLibrary(path=None, object="pan") reads a library file (the object's shipped library by
default). Raises InputError naming the file and the field at fault.)doc")
      .def(py::init(&LoadLibrary), py::arg("path") = py::none(), py::arg("object") = "pan",
           "Reads the library file at `path` (the object's shipped library when None)")
      .def("__repr__", &LibraryRepr, "one line: the file, entries, orientations, replays")
      .def_readonly("source", &GraspLibrary::source, "The library file it was read from")
      .def_readonly("demo_directory", &GraspLibrary::demo_directory,
                    "The folder of the demonstrations it was selected from")
      .def_readonly("seed", &GraspLibrary::seed, "The seed of the selection's perturbations")
      .def_readonly("perturbations", &GraspLibrary::perturbations,
                    "Perturbed replays per demonstration in the selection")
      .def_readonly("tie_rule", &GraspLibrary::tie_rule,
                    "How the selection broke ties between equal scores")
      .def(
          "__len__", [](const GraspLibrary& l) { return l.entries.size(); },
          "the number of entries (orientations)")
      .def_property_readonly(
          "thetas",
          [](const GraspLibrary& l) {
            py::array_t<double> out = NewArray({static_cast<py::ssize_t>(l.entries.size())});
            for (size_t i = 0; i < l.entries.size(); ++i) {
              out.mutable_data()[i] = l.entries[i].theta_deg;
            }
            return out;
          },
          "The orientations of the entries, deg, increasing")
      .def_property_readonly(
          "entries",
          [](const GraspLibrary& l) {
            py::list out;
            for (const LibraryEntry& e : l.entries) {
              py::dict d;
              d["theta_deg"] = e.theta_deg;
              d["file"] = e.file;
              d["trial"] = e.trial;
              d["score"] = e.score;
              d["lift_height"] = e.lift_height;
              d["lift_duration"] = e.lift_duration;
              d["motion"] = MotionArrays(e.motion);
              out.append(d);
            }
            return out;
          },
          "One dict per orientation: theta_deg, file, trial, score, lift_height (m), "
          "lift_duration (s) and motion (the grasping motion's arrays)")
      .def_property_readonly(
          "scores", [](const GraspLibrary& l) { return l.scores; },
          "Every successful demonstration's robustness score (DemoScore), by theta then file")
      .def("to_json", &GraspLibraryToJson, "The graspsynth-library/1 text")
      .def(
          "save",
          [](const GraspLibrary& l, const std::filesystem::path& path) {
            WriteGraspLibrary(l, path);
          },
          py::arg("path"), "Writes the library file atomically");

  m.def("_select_representatives", &Select, py::arg("directory"), py::arg("options"),
        py::arg("robot"), py::arg("scene"), R"doc(
select_representatives' work (graspsynth/__init__.py gives it its signature): the options of
request_options("select") as a dict. Returns (library, report).)doc");
}

void BindSynthesis(py::module_& m) {
  py::class_<Synthesizer, std::shared_ptr<Synthesizer>>(m, "Synthesizer", R"doc(
The synthesis models of one library, built once for many grasps:
Synthesizer(library=None, robot=None, scene=None). library: a GraspLibrary or a file path
(the scene object's shipped library by default). synthesize() is safe to call from several
threads at once, and releases the GIL.)doc")
      .def(py::init(&MakeSynthesizer), py::arg("library") = py::none(),
           py::arg("robot") = py::none(), py::arg("scene") = py::none(),
           "Builds the synthesis models of `library` (a GraspLibrary, a path, or None: the "
           "shipped one) for `robot` and `scene` (the shipped ones when None)")
      .def(
          "__repr__",
          [](const Synthesizer& s) {
            return "Synthesizer(object_name=" + ReprText(s.model.scene().object.name) +
                   ", theta_range=(" + ReprNumber(s.model.theta_min_deg()) + ", " +
                   ReprNumber(s.model.theta_max_deg()) + "))";
          },
          "one line: the object and the library's orientations, deg")
      .def_property_readonly(
          "theta_range",
          [](const Synthesizer& s) {
            return py::make_tuple(s.model.theta_min_deg(), s.model.theta_max_deg());
          },
          "(lowest, highest) orientation of the library, deg: interp's range")
      .def("_synthesize", &Synthesize, py::arg("options"), R"doc(
Synthesizer.synthesize's work (graspsynth/__init__.py gives it its signature): the options of
request_options("synthesize") as a dict, theta among them.)doc");
}

void BindGrasp(py::module_& m) {
  py::class_<Grasp, std::shared_ptr<Grasp>>(m, "Grasp", R"doc(
A synthesized grasp and its physics validation.

ok: a grasp was synthesized (else message says why: no IK solution along the motion).
passed: it passed the physics gate. trajectory: the robot's Trajectory (reach, grasping motion,
lift). motion / unrefined: the grasping motion after / before refinement, as arrays.
report: the grasp file's content as a dict (graspsynth-grasp/1). save(path) writes the grasp
file as `graspsynth synthesize --out` does.)doc")
      .def("__repr__", &GraspRepr, "one line: orientation, method, gate, robustness")
      .def_property_readonly(
          "ok", [](const Grasp& g) { return g.validated.synthesis.ok(); },
          "A grasp was synthesized (status OK); else message says why")
      .def_property_readonly(
          "status", [](const Grasp& g) { return g.validated.synthesis.status; },
          "How the synthesis ended (SynthesisStatus)")
      .def_property_readonly(
          "message", [](const Grasp& g) { return g.validated.synthesis.message; },
          "Why no grasp was synthesized (e.g. no IK solution along the motion); \"\" when ok")
      .def_property_readonly(
          "theta_deg", [](const Grasp& g) { return g.validated.synthesis.theta_deg; },
          "The object orientation asked for, deg")
      .def_property_readonly(
          "method", [](const Grasp& g) { return g.requested; },
          "The method asked for (SynthesisMethod)")
      .def_property_readonly(
          "method_used", [](const Grasp& g) { return Synthesized(g).used; },
          "The method that made the grasp (SynthesisMethod; .label gives \"interp\"); another "
          "than the one asked for when fallback is True. Raises InputError when not ok")
      .def_property_readonly(
          "fallback", [](const Grasp& g) { return Synthesized(g).fallback; },
          "True when a method other than the requested one made the grasp (the requested one "
          "could not: an unblendable bracket, a weak demonstration); the grasp file's report "
          "says why. Raises InputError when not ok")
      .def_property_readonly(
          "passed", [](const Grasp& g) { return g.validated.gate_run && g.validated.gate.passed; },
          "The grasp passed the physics gate: its nominal trial succeeded and its robustness "
          "reached the threshold")
      .def_property_readonly(
          "gate_reason", [](const Grasp& g) { return g.validated.gate.reason; },
          "The physics gate's verdict in words, e.g. \"nominal trial success (lift 0.12 m), "
          "robustness 2/2 = 1 >= 0.8\"; \"\" when the gate did not run")
      .def_property_readonly(
          "robustness",
          [](const Grasp& g) {
            const RobustnessResult& r = g.validated.gate.robustness;
            return g.validated.gate.robustness_run ? py::object(py::float_(r.score))
                                                   : py::object(py::none());
          },
          "The gate's robustness score (successes / perturbed replays), or "
          "None when no replay ran (perturb=0, or no grasp)")
      .def_property_readonly(
          "trajectory",
          [](const Grasp& g) {
            return std::make_shared<JointTrajectory>(Synthesized(g).trajectory);
          },
          "The robot's joint Trajectory: reach, grasping motion, lift")
      .def_property_readonly(
          "motion", [](const Grasp& g) { return MotionArrays(Synthesized(g).motion); },
          "The grasping motion after refinement, as arrays: t (N,) s, "
          "position (N, 3) m, quaternion (N, 4) (w, x, y, z), fingers (N, 16) "
          "rad")
      .def_property_readonly(
          "unrefined", [](const Grasp& g) { return MotionArrays(Synthesized(g).unrefined); },
          "The grasping motion before refinement (the blend), as motion's "
          "arrays")
      .def_property_readonly(
          "report",
          [](const Grasp& g) {
            return JsonTextToPython(GraspFileToJson(Synthesized(g), &g.validated.gate, false));
          },
          "The grasp file's content (graspsynth-grasp/1) as a dict")
      .def(
          "to_json",
          [](const Grasp& g, bool force) {
            return GraspFileToJson(Synthesized(g), &g.validated.gate, force);
          },
          py::arg("force") = false, "The graspsynth-grasp/1 text")
      .def(
          "save",
          [](const Grasp& g, const std::filesystem::path& path, bool force) {
            const SynthesisResult& s = Synthesized(g);
            if (!g.validated.gate.passed && !force) {
              throw InputError("the grasp failed the physics gate: " + g.validated.gate.reason +
                               " (nothing written; force=True writes it with the failed "
                               "validation)");
            }
            WriteGraspFile(path, s, &g.validated.gate, force);
          },
          py::arg("path"), py::arg("force") = false,
          "Writes the grasp file atomically; a grasp that failed the gate only with force=True");
}

}  // namespace

void BindLibrary(py::module_& m) {
  BindGraspLibrary(m);
  BindSynthesis(m);
  BindGrasp(m);
}

}  // namespace graspsynth::python
