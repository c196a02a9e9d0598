// graspsynth._core: joint trajectories, the ODE simulation of a grasp-and-lift trial, and the
// robustness evaluation under perturbation.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "gate/grasp_file.hpp"
#include "kinematics/pose_math.hpp"
#include "kinematics/robot_description.hpp"
#include "motion/joint_trajectory.hpp"
#include "python/bindings.hpp"
#include "python/field_class.hpp"
#include "python/repr.hpp"
#include "python/request_bindings.hpp"
#include "request/simulate_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/robustness.hpp"
#include "simulation/simulation_fields.hpp"
#include "simulation/trial.hpp"

namespace graspsynth::python {
namespace {

// A read-only view of one field of every sample of a vector of records: `field` points into
// the first record; `shape` and `strides` are the field's own (empty for a scalar).
template <class Record>
py::array FieldView(const std::vector<Record>& records, const double* field,
                    const std::vector<py::ssize_t>& shape, const std::vector<py::ssize_t>& strides,
                    py::handle owner) {
  return ReadOnlyView(field, static_cast<py::ssize_t>(records.size()),
                      static_cast<py::ssize_t>(sizeof(Record)), shape, strides, owner);
}

// The samples of the Trajectory `self`; every way to make one gives it at least one.
const std::vector<TrajectorySample>& Samples(const py::object& self) {
  const auto& samples = self.cast<const JointTrajectory&>().samples;
  if (samples.empty()) throw InputError("the trajectory has no sample");
  return samples;
}

// The strides of an Eigen fixed matrix of `rows` (column-major) seen as a row-major array.
std::vector<py::ssize_t> MatrixStrides(py::ssize_t rows) {
  return {static_cast<py::ssize_t>(sizeof(double)),
          static_cast<py::ssize_t>(sizeof(double)) * rows};
}

std::shared_ptr<JointTrajectory> MakeTrajectory(const DoubleArray& t, const DoubleArray& arm,
                                                const DoubleArray& hand, double theta_deg,
                                                const std::shared_ptr<RobotModel>& robot_arg,
                                                const py::object& object_xy) {
  if (t.ndim() != 1 || t.shape(0) < 1) {
    throw InputError("t must have shape (N,) with N >= 1 samples");
  }
  const py::ssize_t n = t.shape(0);
  if (arm.ndim() != 2 || arm.shape(0) != n || arm.shape(1) != kArmDof) {
    throw InputError("arm must have shape (N, 7), N = " + std::to_string(n));
  }
  if (hand.ndim() != 2 || hand.shape(0) != n || hand.shape(1) != kHandDof) {
    throw InputError("hand must have shape (N, 16), N = " + std::to_string(n));
  }
  if (!std::isfinite(theta_deg)) throw InputError("theta_deg must be a finite number of degrees");
  auto trajectory = std::make_shared<JointTrajectory>();
  trajectory->theta_deg = theta_deg;
  trajectory->object_xy = AtArgument(object_xy);
  for (py::ssize_t i = 0; i < n; ++i) {
    TrajectorySample s;
    s.t = t.data()[i];
    s.arm = Eigen::Map<const Vector7d>(arm.data() + kArmDof * i);
    s.hand = Eigen::Map<const HandVector>(hand.data() + kHandDof * i);
    if (!std::isfinite(s.t) || !s.arm.allFinite() || !s.hand.allFinite()) {
      throw InputError("sample " + std::to_string(i) + " has a value that is not finite");
    }
    if (i > 0 && !(s.t > trajectory->samples.back().t)) {
      throw InputError("t must increase strictly: t[" + std::to_string(i) +
                       "] = " + std::to_string(s.t) + " after " +
                       std::to_string(trajectory->samples.back().t));
    }
    trajectory->samples.push_back(s);
  }
  const std::shared_ptr<const RobotModel> robot = RobotOrDefault(robot_arg);
  CheckJointLimits(*trajectory, robot->arm, robot->hand, "the trajectory");
  return trajectory;
}

// The states a trial recorded, as read-only views into its result.
py::dict StateArrays(py::object self) {
  const TrialResult& r = self.cast<const TrialResult&>();
  py::dict d;
  if (r.states.empty()) return d;
  const TrialState& first = r.states.front();
  const auto view = [&](const double* field, const std::vector<py::ssize_t>& shape,
                        const std::vector<py::ssize_t>& strides) {
    return FieldView(r.states, field, shape, strides, self);
  };
  d["t"] = view(&first.t, {}, {});
  d["arm"] = view(first.arm.data(), {kArmDof}, {sizeof(double)});
  d["hand"] = view(first.hand.data(), {kHandDof}, {sizeof(double)});
  d["object_pose"] = view(first.X_WO.matrix().data(), {4, 4}, MatrixStrides(4));
  d["wrist_pose"] = view(first.X_WH.matrix().data(), {4, 4}, MatrixStrides(4));
  return d;
}

std::shared_ptr<SimulationModel> MakeSimulation(const std::shared_ptr<RobotModel>& robot,
                                                const std::shared_ptr<SceneModel>& scene) {
  return std::make_shared<SimulationModel>(*RobotOrDefault(robot), *SceneOrDefault(scene));
}

std::string TrajectoryRepr(const JointTrajectory& tr) {
  std::string text = "Trajectory(theta_deg=" + ReprNumber(tr.theta_deg) +
                     ", samples=" + std::to_string(tr.samples.size()) +
                     ", duration=" + ReprNumber(tr.samples.empty() ? 0.0 : tr.duration());
  if (tr.object_xy) {
    text += ", object_xy=(" + ReprNumber(tr.object_xy->x()) + ", " + ReprNumber(tr.object_xy->y()) +
            ")";
  }
  return text + ")";
}

void BindTrajectory(py::module_& m) {
  py::class_<JointTrajectory, std::shared_ptr<JointTrajectory>>(m, "Trajectory", R"doc(
A joint trajectory of the robot (format graspsynth-trajectory/1): what `graspsynth simulate`
plays.

Trajectory(t, arm, hand, theta_deg=0.0, robot=None, object_xy=None) builds one from arrays t
(N,) s strictly increasing, arm (N, 7) rad, hand (N, 16) rad, checked against the robot's joint
limits; object_xy (x, y) m puts the object elsewhere on the table (default: the scene's object
centre), and can be set later (the trials check that it is on the table).
Trajectory.load(path) reads a trajectory file or a grasp file's trajectory. The arrays t, arm
and hand are read-only views into the trajectory (no copy).)doc")
      .def(py::init(&MakeTrajectory), py::arg("t"), py::arg("arm"), py::arg("hand"),
           py::arg("theta_deg") = 0.0, py::arg("robot") = py::none(),
           py::arg("object_xy") = py::none(),
           "Builds a trajectory from arrays, checked against the robot's joint limits")
      .def_static(
          "load",
          [](const std::filesystem::path& path, const std::shared_ptr<RobotModel>& robot_arg) {
            const std::shared_ptr<const RobotModel> robot = RobotOrDefault(robot_arg);
            return std::make_shared<JointTrajectory>(
                LoadTrajectoryOrGraspFile(path, robot->arm, robot->hand));
          },
          py::arg("path"), py::arg("robot") = py::none(),
          "Reads a graspsynth-trajectory/1 file, or the trajectory of a graspsynth-grasp/1 file")
      .def_readonly("theta_deg", &JointTrajectory::theta_deg, "the object orientation, deg")
      .def_property(
          "object_xy",
          [](const JointTrajectory& tr) -> py::object {
            if (!tr.object_xy) return py::none();
            return py::make_tuple(tr.object_xy->x(), tr.object_xy->y());
          },
          [](JointTrajectory& tr, const py::object& xy) { tr.object_xy = AtArgument(xy); },
          "The object centre (x, y) on the table, m, or None: the scene's object centre")
      .def_property_readonly("duration", &JointTrajectory::duration,
                             "the time from the first sample to the last, s")
      .def(
          "__len__", [](const JointTrajectory& tr) { return tr.samples.size(); },
          "the number of samples")
      .def("__repr__", &TrajectoryRepr, "one line: orientation, samples, duration")
      .def_property_readonly(
          "t",
          [](py::object self) {
            const auto& s = Samples(self);
            return FieldView(s, &s.front().t, {}, {}, self);
          },
          "the samples' times (N,), s, strictly increasing (read-only view)")
      .def_property_readonly(
          "arm",
          [](py::object self) {
            const auto& s = Samples(self);
            return FieldView(s, s.front().arm.data(), {kArmDof}, {sizeof(double)}, self);
          },
          "the arm's joint angles (N, 7), rad (read-only view)")
      .def_property_readonly(
          "hand",
          [](py::object self) {
            const auto& s = Samples(self);
            return FieldView(s, s.front().hand.data(), {kHandDof}, {sizeof(double)}, self);
          },
          "the hand's joint angles (N, 16), rad (read-only view)")
      .def_property_readonly(
          "waypoints",
          [](const JointTrajectory& tr) {
            const auto n = static_cast<py::ssize_t>(tr.waypoints.size());
            py::array_t<double> t = NewArray({n}), p = NewArray({n, 3}), q = NewArray({n, 4});
            for (py::ssize_t i = 0; i < n; ++i) {
              const WristWaypoint& w = tr.waypoints[static_cast<size_t>(i)];
              t.mutable_data()[i] = w.t;
              std::copy(w.p_WH.data(), w.p_WH.data() + 3, p.mutable_data() + 3 * i);
              const double wxyz[4] = {w.q_WH.w(), w.q_WH.x(), w.q_WH.y(), w.q_WH.z()};
              std::copy(wxyz, wxyz + 4, q.mutable_data() + 4 * i);
            }
            py::dict d;
            d["t"] = t;
            d["position"] = p;
            d["quaternion"] = q;
            return d;
          },
          "The wrist's Cartesian waypoints (t, position, quaternion w x y z), world")
      .def("to_json", &JointTrajectoryToJson, "The graspsynth-trajectory/1 text")
      .def(
          "save",
          [](const JointTrajectory& tr, const std::filesystem::path& path) {
            WriteJointTrajectory(path, tr);
          },
          py::arg("path"), "Writes the trajectory file atomically");
}

void BindTrial(py::module_& m) {
  BindFieldClass<TrialResult, std::shared_ptr<TrialResult>>(
      m, "TrialResult", R"doc(
The outcome of one grasp-and-lift trial in ODE: a property per field of the C++ TrialResult
(outcome, reason, lift, max_lift, max_penetration (m), simulated_time, planned_time, wall_time,
cpu_time (s), final_object_pose (4 x 4, world), hold (HoldQuality), statistics, counts),
success, to_dict(), and states: when the trial recorded (record_interval > 0), the time series
as read-only arrays: t (N,), arm (N, 7), hand (N, 16), object_pose (N, 4, 4), wrist_pose (N, 4,
4).)doc",
      {{"outcome", "how the trial ended (TrialOutcome)"},
       {"reason", "one sentence, with the figures that decided the outcome"},
       {"lift", "object centre above its rest height at the end, m"},
       {"max_lift", "the highest the object got, m"},
       {"max_penetration", "the deepest contact involving the object, m"},
       {"simulated_time", "s"},
       {"planned_time",
        "the trajectory and the hold, s (more than simulated_time if the trial stopped)"},
       {"wall_time", "s"},
       {"cpu_time", "s of the calling thread's CPU time"},
       {"final_object_pose", "the object's pose at the end, 4 x 4, world"},
       {"hold", "how the object sat in the hand at the end (HoldQuality)"},
       {"statistics", "the steps and where their time went (StepStatistics)"},
       {"counts", "the bodies, joints and geoms of the world (WorldCounts)"}})
      .def_property_readonly("success", &TrialResult::success,
                             "the outcome is success: lifted and held, touching only the hand")
      .def_property_readonly(
          "states", &StateArrays,
          "the recorded time series (record_interval > 0) as a dict of "
          "read-only arrays: t (N,) s, arm (N, 7) rad, hand (N, 16) rad, "
          "object_pose and wrist_pose (N, 4, 4), world; empty when not recorded");

  py::class_<SimulationModel, std::shared_ptr<SimulationModel>>(m, "Simulation", R"doc(
The ODE world of the robot, the table and the object: Simulation(robot=None, scene=None)
(the shipped ones by default). Only friction holds the object.

trial() plays a trajectory once; robustness() replays it under perturbation (time scaling,
pose and finger noise, and the physics: friction, contact stiffness and damping, mass, centre
of mass, servo force, step). Both release the GIL, so Python threads run trials in parallel.)doc")
      .def(py::init(&MakeSimulation), py::arg("robot") = py::none(), py::arg("scene") = py::none(),
           "The world of `robot` and `scene` (Robot, Scene; the shipped ones when None)")
      .def(
          "__repr__",
          [](const SimulationModel& model) {
            return "Simulation(robot=" + ReprText(model.robot().source) +
                   ", scene=" + ReprText(model.scene().source) +
                   ", object=" + ReprText(model.scene().object.name) + ")";
          },
          "one line: the robot's and the scene's files, the object")
      .def(
          "_trial",
          [](const SimulationModel& model, const JointTrajectory& trajectory,
             const py::dict& options) {
            const TrialOptions trial =
                request::ToTrialOptions(RequestFromPython(request::TrialRequestOptions(), options));
            if (trajectory.object_xy) model.scene().CheckOnTable(*trajectory.object_xy);
            auto result = std::make_shared<TrialResult>();
            {
              py::gil_scoped_release release;
              *result = RunTrial(model, trajectory, trial);
            }
            return result;
          },
          py::arg("trajectory"), py::arg("options"),
          "Simulation.trial's work, with its options (request_options(\"simulate\")) as a dict")
      .def(
          "_robustness",
          [](const SimulationModel& model, const JointTrajectory& trajectory,
             const py::dict& options) {
            const RobustnessOptions ro = request::ToRobustnessOptions(
                RequestFromPython(request::RobustnessRequestOptions(), options));
            if (trajectory.object_xy) model.scene().CheckOnTable(*trajectory.object_xy);
            RobustnessResult r;
            {
              py::gil_scoped_release release;
              r = EvaluateRobustness(model, trajectory, ro);
            }
            return r;
          },
          py::arg("trajectory"), py::arg("options"),
          "Simulation.robustness's work, with its options (request_options(\"robustness\")) as "
          "a dict");
}

}  // namespace

void BindSimulation(py::module_& m) {
  BindTrajectory(m);
  BindTrial(m);
}

}  // namespace graspsynth::python
