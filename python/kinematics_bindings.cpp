// graspsynth._core: the robot and scene models, batched forward and inverse kinematics of the
// arm, and its feasible arm angles.

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/robot_description.hpp"
#include "python/bindings.hpp"
#include "python/repr.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::python {
namespace {

constexpr int kBranches = 8;

py::array_t<double> VectorArray(const double* data, py::ssize_t size) {
  py::array_t<double> out = NewArray({size});
  std::copy(data, data + size, out.mutable_data());
  return out;
}

// The psi of target i: one value for every target, or one each.
struct ArmAngles {
  DoubleArray values;
  bool scalar = true;
  double operator[](py::ssize_t i) const { return values.data()[scalar ? 0 : i]; }
};

ArmAngles ReadArmAngles(const py::object& psi, const Batch& targets) {
  ArmAngles angles{DoubleArray::ensure(psi), true};
  if (!angles.values) throw InputError("psi must be a number or an array of numbers (rad)");
  if (angles.values.ndim() == 1 && !targets.single) {
    if (angles.values.shape(0) != targets.count) {
      throw InputError("psi has " + std::to_string(angles.values.shape(0)) + " values for " +
                       std::to_string(targets.count) + " targets");
    }
    angles.scalar = false;
  } else if (angles.values.ndim() != 0) {
    throw InputError("psi must be a number, or one value per target (shape (N,))");
  }
  const py::ssize_t n = angles.scalar ? 1 : targets.count;
  for (py::ssize_t i = 0; i < n; ++i) {
    const double v = angles.values.data()[i];
    if (!(v >= -M_PI - 1e-12 && v <= M_PI + 1e-12)) {
      throw InputError("psi[" + std::to_string(i) + "] = " + std::to_string(v) +
                       " is outside [-pi, pi]");
    }
  }
  return angles;
}

// The branch of target i: none (every branch), one for every target, or one each.
struct Branches {
  std::optional<DoubleArray> values;
  Batch batch;
  std::optional<ArmBranch> operator()(py::ssize_t i) const {
    if (!values) return std::nullopt;
    const double* s = batch.data + 3 * (batch.single ? 0 : i);
    return ArmBranch{static_cast<int>(s[0]), static_cast<int>(s[1]), static_cast<int>(s[2])};
  }
};

Branches ReadBranches(const py::object& branch, const Batch& targets) {
  Branches b;
  if (branch.is_none()) return b;
  b.values = DoubleArray::ensure(branch);
  if (!*b.values) throw InputError("branch must be three signs (GC2, GC4, GC6), each 1 or -1");
  b.batch = ReadBatch(*b.values, {3}, "branch");
  if (!b.batch.single && b.batch.count != targets.count) {
    throw InputError("branch has " + std::to_string(b.batch.count) + " rows for " +
                     std::to_string(targets.count) + " targets");
  }
  for (py::ssize_t k = 0; k < 3 * b.batch.count; ++k) {
    if (b.batch.data[k] != 1.0 && b.batch.data[k] != -1.0) {
      throw InputError("branch signs must be 1 or -1, got " + std::to_string(b.batch.data[k]));
    }
  }
  return b;
}

std::vector<Eigen::Isometry3d> ReadTargets(const Batch& batch) {
  std::vector<Eigen::Isometry3d> targets(static_cast<size_t>(batch.count));
  std::string why;
  for (py::ssize_t i = 0; i < batch.count; ++i) {
    if (!PoseFromMatrix(batch.data + 16 * i, &targets[static_cast<size_t>(i)], &why)) {
      throw InputError("target " + std::to_string(i) + " (a 4 x 4 pose): " + why);
    }
  }
  return targets;
}

py::array_t<double> Fk(const RobotModel& robot, const DoubleArray& q) {
  const Batch batch = ReadBatch(q, {kArmDof}, "q");
  py::array_t<double> out = NewArray(BatchShape(batch, {4, 4}));
  double* rows = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < batch.count; ++i) {
      WriteMatrix(ArmFlangePose(robot.arm, Eigen::Map<const Vector7d>(batch.data + kArmDof * i)),
                  rows + 16 * i);
    }
  }
  return out;
}

py::tuple Ik(const RobotModel& robot, const DoubleArray& X, const py::object& psi,
             const py::object& branch, const std::optional<DoubleArray>& q_near) {
  const Batch batch = ReadBatch(X, {4, 4}, "X");
  const std::vector<Eigen::Isometry3d> targets = ReadTargets(batch);
  const ArmAngles angles = ReadArmAngles(psi, batch);
  const Branches branches = ReadBranches(branch, batch);
  Batch near;
  if (q_near) {
    near = ReadBatch(*q_near, {kArmDof}, "q_near");
    if (!near.single && near.count != batch.count) {
      throw InputError("q_near has " + std::to_string(near.count) + " rows for " +
                       std::to_string(batch.count) + " targets");
    }
  }
  const bool one_branch = branches.values.has_value();
  const py::ssize_t per_target = one_branch ? 1 : kBranches;
  std::vector<py::ssize_t> q_shape = BatchShape(batch, {kArmDof});
  std::vector<py::ssize_t> status_shape = BatchShape(batch, {});
  if (!one_branch) {
    q_shape.insert(q_shape.end() - 1, kBranches);
    status_shape.push_back(kBranches);
  }
  py::array_t<double> q_out = NewArray(q_shape);
  py::array_t<int8_t> status_out(status_shape);
  double* q = q_out.mutable_data();
  int8_t* status = status_out.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < batch.count; ++i) {
      Vector7d near_q;
      const Vector7d* near_ptr = nullptr;
      if (q_near) {
        // finite: ReadBatch checked every value.
        near_q = Eigen::Map<const Vector7d>(near.data + kArmDof * (near.single ? 0 : i));
        near_ptr = &near_q;
      }
      for (py::ssize_t k = 0; k < per_target; ++k) {
        const ArmBranch b = one_branch ? *branches(i) : ArmBranch::FromIndex(static_cast<int>(k));
        const ArmIkSolution s =
            SolveArmIk(robot.arm, targets[static_cast<size_t>(i)], angles[i], b, near_ptr);
        const py::ssize_t slot = i * per_target + k;
        status[slot] = static_cast<int8_t>(s.status);
        double* row = q + kArmDof * slot;
        for (int j = 0; j < kArmDof; ++j) {
          row[j] = s.status == IkStatus::kOk ? s.q[j] : std::numeric_limits<double>::quiet_NaN();
        }
      }
    }
  }
  return py::make_tuple(q_out, status_out);
}

py::object FeasibleAngles(const RobotModel& robot, const DoubleArray& X, const py::object& branch) {
  const Batch batch = ReadBatch(X, {4, 4}, "X");
  const std::vector<Eigen::Isometry3d> targets = ReadTargets(batch);
  const Branches branches = ReadBranches(branch, batch);
  std::vector<std::vector<Interval>> all(static_cast<size_t>(batch.count));
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < batch.count; ++i) {
      std::vector<Interval> intervals;
      for (int k = 0; k < kBranches; ++k) {
        const ArmBranch b = ArmBranch::FromIndex(k);
        if (branches.values && !(b == *branches(i))) continue;
        const ArmTargetForm form =
            PrepareArmTarget(robot.arm, targets[static_cast<size_t>(i)], b.gc4);
        const std::vector<Interval> feasible = FeasibleArmAngles(robot.arm, form, b.gc2, b.gc6);
        intervals.insert(intervals.end(), feasible.begin(), feasible.end());
      }
      all[static_cast<size_t>(i)] = MergeIntervals(std::move(intervals));
    }
  }
  py::list out;
  for (const std::vector<Interval>& intervals : all) {
    py::array_t<double> a = NewArray({static_cast<py::ssize_t>(intervals.size()), 2});
    for (size_t k = 0; k < intervals.size(); ++k) {
      a.mutable_data()[2 * k] = intervals[k].lo;
      a.mutable_data()[2 * k + 1] = intervals[k].hi;
    }
    out.append(a);
  }
  if (batch.single) return out[0];
  return out;
}

py::object ArmAngle(const RobotModel& robot, const DoubleArray& q) {
  const Batch batch = ReadBatch(q, {kArmDof}, "q");
  if (batch.single) return py::float_(ArmAngleOf(robot.arm, Eigen::Map<const Vector7d>(q.data())));
  py::array_t<double> out = NewArray({batch.count});
  double* psi = out.mutable_data();
  py::gil_scoped_release release;
  for (py::ssize_t i = 0; i < batch.count; ++i) {
    psi[i] = ArmAngleOf(robot.arm, Eigen::Map<const Vector7d>(batch.data + kArmDof * i));
  }
  return out;
}

py::array_t<int8_t> BranchOfArray(const DoubleArray& q) {
  const Batch batch = ReadBatch(q, {kArmDof}, "q");
  py::array_t<int8_t> out(BatchShape(batch, {3}));
  int8_t* signs = out.mutable_data();
  py::gil_scoped_release release;
  for (py::ssize_t i = 0; i < batch.count; ++i) {
    const ArmBranch b = BranchOf(Eigen::Map<const Vector7d>(batch.data + kArmDof * i));
    signs[3 * i] = static_cast<int8_t>(b.gc2);
    signs[3 * i + 1] = static_cast<int8_t>(b.gc4);
    signs[3 * i + 2] = static_cast<int8_t>(b.gc6);
  }
  return out;
}

std::shared_ptr<RobotModel> LoadRobot(const std::optional<std::filesystem::path>& path) {
  return std::make_shared<RobotModel>(
      LoadRobotModel(path ? std::filesystem::path(*path) : DefaultRobotDescriptionPath()));
}

std::shared_ptr<SceneModel> LoadScene(const std::optional<std::filesystem::path>& path,
                                      const std::optional<std::string>& object) {
  return std::make_shared<SceneModel>(LoadSceneModel(
      path ? std::filesystem::path(*path) : DefaultSceneModelPath(), object.value_or("")));
}

}  // namespace

std::shared_ptr<const RobotModel> RobotOrDefault(const std::shared_ptr<RobotModel>& robot) {
  if (robot) return robot;
  // a throwing initializer leaves it unset: the next call reads the file again.
  static const std::shared_ptr<const RobotModel> shipped = LoadRobot(std::nullopt);
  return shipped;
}

std::shared_ptr<const SceneModel> SceneOrDefault(const std::shared_ptr<SceneModel>& scene) {
  if (scene) return scene;
  static const std::shared_ptr<const SceneModel> shipped = LoadScene(std::nullopt, std::nullopt);
  return shipped;
}

namespace {

void BindRobot(py::module_& m) {
  py::class_<RobotModel, std::shared_ptr<RobotModel>>(m, "Robot", R"doc(
The robot model: the PA-10 arm and the Gifu Hand III, read from a robot description (URDF).

Robot() reads the shipped description (models/pa10_gifu3.urdf, or below $GRASPSYNTH_DATA_DIR);
Robot(path) another one. Raises InputError naming the file and the element at fault.
Joint values are radians, poses 4 x 4 homogeneous matrices in the world frame (the arm's base),
metres.)doc")
      .def(py::init(&LoadRobot), py::arg("path") = py::none(),
           "Reads the robot description at `path` (the shipped one when None)")
      .def(
          "__repr__",
          [](const RobotModel& r) { return "Robot(source=" + ReprText(r.source) + ")"; },
          "one line: the description file")
      .def_readonly("source", &RobotModel::source, "The description file it was read from")
      .def_property_readonly(
          "joint_lower", [](const RobotModel& r) { return VectorArray(r.arm.lower().data(), 7); },
          "Lower limits of the arm joints S1..W2, rad, shape (7,)")
      .def_property_readonly(
          "joint_upper", [](const RobotModel& r) { return VectorArray(r.arm.upper().data(), 7); },
          "Upper limits of the arm joints S1..W2, rad, shape (7,)")
      .def_property_readonly(
          "hand_lower",
          [](const RobotModel& r) { return VectorArray(r.hand.lower().data(), kHandDof); },
          "Lower limits of the finger joints f0..f15, rad, shape (16,)")
      .def_property_readonly(
          "hand_upper",
          [](const RobotModel& r) { return VectorArray(r.hand.upper().data(), kHandDof); },
          "Upper limits of the finger joints f0..f15, rad, shape (16,)")
      .def_property_readonly(
          "X_FH",
          [](const RobotModel& r) {
            py::array_t<double> out = NewArray({4, 4});
            WriteMatrix(r.X_FH, out.mutable_data());
            return out;
          },
          "Pose of the hand mount (the paper's wrist) in the flange frame, 4 x 4")
      .def_property_readonly(
          "lengths",
          [](const RobotModel& r) {
            const SrsLengths& l = r.arm.lengths();
            py::dict d;
            d["d_bs"] = l.d_bs;
            d["d_se"] = l.d_se;
            d["d_ew"] = l.d_ew;
            d["d_wt"] = l.d_wt;
            return d;
          },
          "The SRS lengths of the arm (base-shoulder, shoulder-elbow, elbow-wrist, wrist-flange), "
          "m")
      .def("fk", &Fk, py::arg("q"), R"doc(
Flange poses of arm configurations.

q: shape (7,) or (N, 7), rad (S1 S2 S3 E1 E2 W1 W2). Returns shape (4, 4) or (N, 4, 4): the
flange pose in the world frame, metres. A value that is not a finite number raises InputError
naming its row and field, as `graspsynth fk` refuses it. Releases the GIL.)doc")
      .def("ik", &Ik, py::arg("X"), py::arg("psi"), py::arg("branch") = py::none(),
           py::arg("q_near") = py::none(), R"doc(
Analytic inverse kinematics at a given arm angle.

X: flange targets, shape (4, 4) or (N, 4, 4). psi: the arm angle, rad in [-pi, pi], one
number or shape (N,). branch: None for all eight branches, or the signs (GC2, GC4, GC6) of S2,
E1 and W1, shape (3,) or (N, 3). q_near: joints beyond +-pi take the in-limit value nearest to
it, shape (7,) or (N, 7).
Returns (q, status). With a branch: q shape (N, 7), status shape (N,). Without: q shape
(N, 8, 7) and status (N, 8), branch k being ArmBranch index k (bit 0: GC2 = -1, bit 1:
GC4 = -1, bit 2: GC6 = -1). status holds IkStatus values (0 ok); q is NaN where the status is
not ok. The batch axis is absent when X is one pose. Releases the GIL.)doc")
      .def("feasible_arm_angles", &FeasibleAngles, py::arg("X"), py::arg("branch") = py::none(),
           R"doc(
The arm angles at which flange target X is reachable within every joint limit.

X: shape (4, 4) or (N, 4, 4); branch: None (the union over the eight branches) or three signs.
Returns, per target, sorted disjoint intervals as an array of shape (K, 2), rad; a list of
them for a batch.)doc")
      .def("arm_angle", &ArmAngle, py::arg("q"),
           "The arm angle psi of configurations q (shape (7,) or (N, 7)), rad");

  m.def("branch_of", &BranchOfArray, py::arg("q"),
        "The branch signs (GC2, GC4, GC6) of arm configurations q: shape (3,) or (N, 3), int8 "
        "(a zero joint counts as +1)");

  m.def(
      "default_robot", [] { return std::const_pointer_cast<RobotModel>(RobotOrDefault(nullptr)); },
      "The shipped robot (models/pa10_gifu3.urdf, or below $GRASPSYNTH_DATA_DIR), read once and "
      "shared by every call that is given no robot");

  // the codes of IkStatus, by name: graspsynth.IkStatus (python/graspsynth/__init__.py) is
  // made from them.
  py::dict statuses;
  for (int k = 0; k <= static_cast<int>(EnumRange<IkStatus>::kLast); ++k) {
    statuses[py::str(std::string(ToString(static_cast<IkStatus>(k))))] = k;
  }
  m.attr("IK_STATUS_CODES") = statuses;
}

void BindScene(py::module_& m) {
  py::class_<SceneModel, std::shared_ptr<SceneModel>>(m, "Scene", R"doc(
The scene: the table, the object and where it stands (models/scene.json by default).

Scene(path=None, object=None): object replaces the scene's object with a shipped one by name
(models/objects/NAME.json) or an object file. Raises InputError naming the file at fault.)doc")
      .def(py::init(&LoadScene), py::arg("path") = py::none(), py::arg("object") = py::none(),
           "Reads the scene file at `path` (the shipped one when None); `object` replaces its "
           "object")
      .def(
          "__repr__",
          [](const SceneModel& s) {
            return "Scene(object_name=" + ReprText(s.object.name) + ", object_centre_xy=(" +
                   ReprNumber(s.object_centre_xy.x()) + ", " + ReprNumber(s.object_centre_xy.y()) +
                   "), source=" + ReprText(s.source) + ")";
          },
          "one line: the object, where it stands (m), the scene file")
      .def_readonly("source", &SceneModel::source, "The scene file it was read from")
      .def_property_readonly(
          "object_name", [](const SceneModel& s) { return s.object.name; },
          "The object's name, e.g. \"pan\"")
      .def_property_readonly(
          "object_source", [](const SceneModel& s) { return s.object.source; },
          "The object file it was read from")
      .def_property_readonly(
          "object_mass", [](const SceneModel& s) { return s.object.Inertia().mass; }, "kg")
      .def_property_readonly(
          "object_centre_xy",
          [](const SceneModel& s) { return VectorArray(s.object_centre_xy.data(), 2); },
          "Where the object stands on the table, world, m")
      .def_property_readonly(
          "table",
          [](const SceneModel& s) {
            py::dict d;
            d["top_z"] = s.table.top_z;
            d["centre_xy"] = VectorArray(s.table.centre_xy.data(), 2);
            d["size"] = VectorArray(s.table.size.data(), 3);
            d["friction"] = s.table.friction;
            return d;
          },
          "The table: top height, centre, full size (m) and friction coefficient")
      .def_property_readonly(
          "grasp_region",
          [](const SceneModel& s) {
            py::dict d;
            d["shape"] =
                s.grasp_region.shape == GraspRegionModel::Shape::kCylinder ? "cylinder" : "sphere";
            d["radius"] = s.grasp_region.radius;
            d["height"] = s.grasp_region.height;
            return d;
          },
          "The region whose entry marks the pre-grasp pose (segmentation), m")
      .def(
          "object_pose",
          [](const SceneModel& s, double theta_deg) {
            py::array_t<double> out = NewArray({4, 4});
            WriteMatrix(s.ObjectPose(theta_deg * kDeg), out.mutable_data());
            return out;
          },
          py::arg("theta_deg"), "Pose of the object resting at orientation theta_deg, 4 x 4");

  // after the class, so that its signature names the Python class
  m.def(
      "default_scene", [] { return std::const_pointer_cast<SceneModel>(SceneOrDefault(nullptr)); },
      "The shipped scene (models/scene.json), read once and shared by every call that is given "
      "no scene");
}

}  // namespace

void BindKinematics(py::module_& m) {
  BindRobot(m);
  BindScene(m);
}

}  // namespace graspsynth::python
