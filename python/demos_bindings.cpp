// graspsynth._core: demonstration logs and folders, segmentation, the Table I analysis and the
// wrist-line fit.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analysis_report.hpp"
#include "analysis/wrist_line.hpp"
#include "common/errors.hpp"
#include "learning_data/demo_directory.hpp"
#include "learning_data/demo_log.hpp"
#include "learning_data/segmentation.hpp"
#include "python/bindings.hpp"
#include "python/repr.hpp"
#include "python/request_bindings.hpp"
#include "request/analyze_request.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::python {
namespace {

// Copies one field of every sample into an (N, width) array (or (N,) with width 0).
template <class Sample, class Field>
py::array_t<double> Column(const std::vector<Sample>& samples, int width, Field field) {
  const auto n = static_cast<py::ssize_t>(samples.size());
  py::array_t<double> out =
      width == 0 ? NewArray({n}) : NewArray({n, static_cast<py::ssize_t>(width)});
  double* data = out.mutable_data();
  const int stride = std::max(width, 1);
  for (size_t i = 0; i < samples.size(); ++i) field(samples[i], data + stride * i);
  return out;
}

void WriteQuaternion(const Eigen::Quaterniond& q, double* out) {
  out[0] = q.w();
  out[1] = q.x();
  out[2] = q.y();
  out[3] = q.z();
}

py::dict SegmentDict(const DemoLog& log, const SegmentationOptions& options) {
  const SegmentedTrial s = Segment(log, options);
  py::dict d;
  d["source"] = s.source;
  d["theta_deg"] = s.theta_deg;
  d["success"] = s.success;
  d["lift"] = s.lift;
  d["status"] = ToString(s.status);
  d["message"] = s.message;
  if (s.ok()) {
    d["pregrasp"] = s.pregrasp;
    d["grasp"] = s.grasp;
    d["end"] = s.end;
    d["motion"] = MotionArrays(s.motion);
  } else {
    d["pregrasp"] = py::none();
    d["grasp"] = py::none();
    d["end"] = py::none();
    d["motion"] = py::none();
  }
  return d;
}

py::dict LineDict(const Line2d& line, const FitResiduals& residuals) {
  py::dict d;
  d["point"] = py::make_tuple(line.point.x(), line.point.y());
  d["direction"] = py::make_tuple(line.direction.x(), line.direction.y());
  d["angle_deg"] = line.angle() / kDeg;
  d["residuals"] = residuals.per_point;
  d["rms"] = residuals.rms;
  d["max"] = residuals.max;
  return d;
}

py::dict FitLine(const DoubleArray& points, const py::dict& given) {
  const WristLineOptions options =
      request::ToWristLineOptions(RequestFromPython(request::WristLineRequestOptions(), given));
  const Batch batch = ReadBatch(points, {2}, "points");
  std::vector<Eigen::Vector2d> p;
  for (py::ssize_t i = 0; i < batch.count; ++i) {
    p.emplace_back(batch.data[2 * i], batch.data[2 * i + 1]);
    if (!p.back().allFinite()) {
      throw InputError("points[" + std::to_string(i) + "] is not finite");
    }
  }
  WristLineResult r;
  {
    py::gil_scoped_release release;
    r = FitWristLine(p, options);
  }
  py::dict d;
  d["termination"] = ToString(r.termination);
  d["message"] = r.message;
  d["usable"] = r.usable();
  d["loss"] = ToString(r.loss);
  d["loss_scale"] = r.loss_scale;
  d["line"] = r.usable() ? py::object(LineDict(r.line, r.residuals)) : py::none();
  d["plain_line"] = r.usable() ? py::object(LineDict(r.plain_line, r.plain_residuals)) : py::none();
  d["cgal_line"] = r.usable() ? py::object(LineDict(r.cgal_line, r.cgal_residuals)) : py::none();
  d["cgal_agrees"] = r.cgal_agrees;
  d["iterations"] = r.iterations;
  return d;
}

py::object Analyze(const std::optional<std::filesystem::path>& directory,
                   const std::shared_ptr<SceneModel>& scene_arg, const py::dict& given) {
  const std::shared_ptr<const SceneModel> scene = SceneOrDefault(scene_arg);
  const AnalysisOptions options = request::ToAnalysisOptions(
      RequestFromPython(request::AnalyzeOptions(), given), scene->grasp_region);
  PaperComparisonOptions comparison;
  std::string text;
  {
    py::gil_scoped_release release;
    const DemonstrationAnalysis analysis = AnalyzeDemonstrations(
        directory ? ReadDemoDirectory(*directory) : ReadDefaultDemoDirectory(scene->object.name),
        options);
    text = AnalysisReportJson(analysis, scene->object.paper_object ? &comparison : nullptr);
  }
  return JsonTextToPython(text);
}

}  // namespace

py::dict MotionArrays(const GraspingMotion& motion) {
  py::dict d;
  d["theta_deg"] = motion.theta / kDeg;
  d["object_position"] = py::make_tuple(motion.p_WO.x(), motion.p_WO.y(), motion.p_WO.z());
  d["source"] = motion.source;
  const std::vector<MotionWaypoint>& w = motion.waypoints;
  d["t"] = Column(w, 0, [](const MotionWaypoint& s, double* o) { *o = s.t; });
  d["position"] = Column(w, 3, [](const MotionWaypoint& s, double* o) {
    std::copy(s.p_WH.data(), s.p_WH.data() + 3, o);
  });
  d["quaternion"] =
      Column(w, 4, [](const MotionWaypoint& s, double* o) { WriteQuaternion(s.q_WH, o); });
  d["fingers"] = Column(w, kHandDof, [](const MotionWaypoint& s, double* o) {
    std::copy(s.f.data(), s.f.data() + kHandDof, o);
  });
  return d;
}

namespace {

std::string DemoLogRepr(const DemoLog& l) {
  std::string text =
      "DemoLog(source=" + ReprText(l.source) + ", theta_deg=" + ReprNumber(l.metadata.theta_deg);
  if (l.metadata.trial) text += ", trial=" + ReprText(*l.metadata.trial);
  return text + ", samples=" + std::to_string(l.samples.size()) + ")";
}

void BindDemoLog(py::module_& m) {
  py::class_<DemoLog, std::shared_ptr<DemoLog>>(m, "DemoLog", R"doc(
A demonstration log (format graspsynth-demo/1): one teleoperated trial, sampled.

Arrays are copies, one row per sample: t (N,) s; wrist_position (N, 3) m and wrist_quaternion
(N, 4) (w, x, y, z), world; fingers (N, 16) rad; events (N,) (0 none, 1 grasp button, 2 end);
object_position (N, 3) m.)doc")
      .def("__repr__", &DemoLogRepr, "one line: the file, orientation, trial and samples")
      .def_readonly("source", &DemoLog::source, "The log file it was read from")
      .def_property_readonly(
          "theta_deg", [](const DemoLog& l) { return l.metadata.theta_deg; },
          "The object orientation, deg")
      .def_property_readonly(
          "trial", [](const DemoLog& l) { return l.metadata.trial; },
          "The trial's name in the log's metadata, or None")
      .def_property_readonly(
          "operator_name", [](const DemoLog& l) { return l.metadata.operator_name; },
          "The operator's name in the log's metadata, or None")
      .def_property_readonly(
          "sample_rate_hz", [](const DemoLog& l) { return l.metadata.sample_rate_hz; },
          "The nominal sample rate in the log's metadata, Hz, or None")
      .def_property_readonly(
          "metadata_extra",
          [](const DemoLog& l) {
            py::dict d;
            for (const auto& [k, v] : l.metadata.extra) d[py::str(k)] = v;
            return d;
          },
          "The log's other metadata, {key: text}")
      .def(
          "__len__", [](const DemoLog& l) { return l.samples.size(); }, "the number of samples")
      .def_property_readonly(
          "t",
          [](const DemoLog& l) {
            return Column(l.samples, 0, [](const DemoSample& s, double* o) { *o = s.t; });
          },
          "The samples' times (N,), s")
      .def_property_readonly(
          "wrist_position",
          [](const DemoLog& l) {
            return Column(l.samples, 3, [](const DemoSample& s, double* o) {
              std::copy(s.p_WH.data(), s.p_WH.data() + 3, o);
            });
          },
          "The wrist (hand mount) position (N, 3), m, world")
      .def_property_readonly(
          "wrist_quaternion",
          [](const DemoLog& l) {
            return Column(l.samples, 4,
                          [](const DemoSample& s, double* o) { WriteQuaternion(s.q_WH, o); });
          },
          "The wrist orientation (N, 4), unit quaternions (w, x, y, z), world")
      .def_property_readonly(
          "fingers",
          [](const DemoLog& l) {
            return Column(l.samples, kHandDof, [](const DemoSample& s, double* o) {
              std::copy(s.f.data(), s.f.data() + kHandDof, o);
            });
          },
          "The finger joint angles (N, 16), rad")
      .def_property_readonly(
          "events",
          [](const DemoLog& l) {
            py::array_t<int8_t> out(static_cast<py::ssize_t>(l.samples.size()));
            for (size_t i = 0; i < l.samples.size(); ++i) {
              out.mutable_data()[i] = static_cast<int8_t>(l.samples[i].event);
            }
            return out;
          },
          "The events (N,), int8: 0 none, 1 grasp button, 2 end")
      .def_property_readonly(
          "object_position",
          [](const DemoLog& l) {
            return Column(l.samples, 3, [](const DemoSample& s, double* o) {
              std::copy(s.p_WO.data(), s.p_WO.data() + 3, o);
            });
          },
          "The object centre (N, 3), m, world");
}

void BindDemoAnalysis(py::module_& m) {
  m.def(
      "read_demo_log",
      [](const std::filesystem::path& path) {
        return std::make_shared<DemoLog>(ReadDemoLog(path));
      },
      py::arg("path"),
      "Reads a demonstration log. Raises InputError naming the file, line and column at fault.");

  m.def(
      "read_demo_directory",
      [](const std::optional<std::filesystem::path>& directory) {
        DemoDirectory d = directory ? ReadDemoDirectory(*directory) : ReadDefaultDemoDirectory();
        py::list logs;
        for (DemoLog& log : d.logs) logs.append(std::make_shared<DemoLog>(std::move(log)));
        py::list rejected;
        for (const RejectedDemoFile& r : d.rejected) {
          py::dict item;
          item["file"] = r.file;
          item["reason"] = r.reason;
          rejected.append(item);
        }
        return py::make_tuple(logs, rejected);
      },
      py::arg("directory") = py::none(), R"doc(
Reads every *.csv log of a folder (the shipped pan demonstrations by default).

Returns (logs, rejected): the good logs sorted by file name, and a list of
{"file", "reason"} for each file the reader refused (the others are still read). Raises
InputError when the folder cannot be read.)doc");

  m.def(
      "_segment",
      [](const DemoLog& log, const std::shared_ptr<SceneModel>& scene, const py::dict& given) {
        return SegmentDict(
            log, request::ToSegmentationOptions(RequestFromPython(request::SegmentOptions(), given),
                                                SceneOrDefault(scene)->grasp_region));
      },
      py::arg("log"), py::arg("scene"), py::arg("options"), R"doc(
Segments a log into reach, grasping motion (pre-grasp to grasp) and lift.

The pre-grasp pose is the first sample with the wrist inside the scene's grasp region around
the object centre; the grasp is the button press. Returns a dict: status ("ok" or why not),
message, success (the object rose >= success_lift m), lift, the sample indices pregrasp, grasp
and end, and motion: the grasping motion as arrays (t, position, quaternion, fingers), None
when the log could not be segmented.)doc");

  m.def("_analyze_demonstrations", &Analyze, py::arg("directory"), py::arg("scene"),
        py::arg("options"),
        "analyze_demonstrations's work, with its options (request_options(\"analyze\")) as a "
        "dict");

  m.def("_fit_wrist_line", &FitLine, py::arg("points"), py::arg("options"), R"doc(
Fits a line to 2-D points (shape (N, 2), m) by total least squares (Ceres), with an optional
robust loss (robust_loss "none", "huber", "cauchy"; loss_scale in m), cross-checked with CGAL's
fit.
Returns a dict with the termination, the line (point, direction, angle_deg, residuals, rms,
max), the plain and CGAL lines and whether they agree.)doc");
}

}  // namespace

void BindDemos(py::module_& m) {
  BindDemoLog(m);
  BindDemoAnalysis(m);
}

}  // namespace graspsynth::python
