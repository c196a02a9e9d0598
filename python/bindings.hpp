#pragma once

/// @file
/// Pieces shared by the bindings of the Python module graspsynth._core: numpy arrays in and
/// out, JSON documents as Python objects, and the registration function of each part.
///
/// Arrays: float64, C order on the way in (anything else is converted once); poses are 4 x 4
/// homogeneous matrices, row-major as numpy shows them. Large results (trajectories, trial
/// records) are read-only views into the C++ object that owns them, not copies.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/robot_description.hpp"
#include "learning_data/grasp_library.hpp"
#include "motion/grasping_motion.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::python {

namespace py = pybind11;

/// A float64 array argument, converted to C order when it is not already.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// The object position of an `at` argument: None, or (x, y) in metres (any sequence or array
/// of two finite numbers). Throws InputError otherwise; whether it is on the table is the
/// scene's check (SceneModel::CheckOnTable).
std::optional<Eigen::Vector2d> AtArgument(const py::object& at);

/// A new, uninitialized float64 array of `shape`.
py::array_t<double> NewArray(const std::vector<py::ssize_t>& shape);

/// A batch of fixed-size items in an array: `count` items of `item_size` doubles, starting at
/// `data`. `single` when the array had only the item's own dimensions (no batch axis).
struct Batch {
  const double* data = nullptr;
  py::ssize_t count = 0;
  bool single = false;
};

/// The batch in `array` whose items have shape `item_shape` (e.g. {7} or {4, 4}): the array's
/// shape is item_shape, or (N, *item_shape). Throws InputError naming `what` otherwise.
Batch ReadBatch(const DoubleArray& array, const std::vector<py::ssize_t>& item_shape,
                const char* what);

/// The shape of a result for a batch: (N, *item_shape), or item_shape when the batch was single.
std::vector<py::ssize_t> BatchShape(const Batch& batch, const std::vector<py::ssize_t>& item_shape);

/// Reads a row-major 4 x 4 matrix into the rigid transform *X. False, with the reason in `why`,
/// when a value is not finite, the last row is not (0, 0, 0, 1) or the rotation is not
/// orthonormal with determinant 1 within 1e-6. Cheap (no allocation unless it fails): batches
/// of poses are read in a loop.
bool PoseFromMatrix(const double* rows, Eigen::Isometry3d* X, std::string* why);

/// Writes X as a row-major 4 x 4 matrix into `rows` (16 doubles).
void WriteMatrix(const Eigen::Isometry3d& X, double* rows);

/// A read-only view of `count` records of `stride` bytes, the field at `first` in the first
/// record, with the field's own `shape` and byte `strides` appended to the record axis. `owner`
/// (the Python object that holds the records) stays alive as long as the view.
py::array ReadOnlyView(const double* first, py::ssize_t count, py::ssize_t stride,
                       const std::vector<py::ssize_t>& shape,
                       const std::vector<py::ssize_t>& strides, py::handle owner);

/// The Python value of a JSON document: dict, list, str, int, float, bool or None.
py::object ToPython(const nlohmann::json& value);
py::object ToPython(const nlohmann::ordered_json& value);
/// The Python value of a JSON text (the report builders' output).
py::object JsonTextToPython(const std::string& text);

/// A grasping motion as a dict: theta_deg, object_position, source, and the waypoints' arrays
/// t (N,) s, position (N, 3) m, quaternion (N, 4) (w, x, y, z), fingers (N, 16) rad.
py::dict MotionArrays(const GraspingMotion& motion);

/// The robot a function was given, or the shipped one (read once, then shared: the URDF is not
/// read again at every call).
std::shared_ptr<const RobotModel> RobotOrDefault(const std::shared_ptr<RobotModel>& robot);
/// The scene a function was given, or the shipped one (read once, then shared).
std::shared_ptr<const SceneModel> SceneOrDefault(const std::shared_ptr<SceneModel>& scene);

/// SceneOrDefault(scene), after checking that its object has the handle the synthesis aims at
/// (InputError naming the object otherwise).
std::shared_ptr<const SceneModel> SynthesisScene(const std::shared_ptr<SceneModel>& scene);

/// The grasp library a function was given: None (the object's shipped library), a path (str or
/// os.PathLike) or a GraspLibrary. Throws InputError for a file that cannot be read, and
/// TypeError (pybind11's type_error) for anything else.
std::shared_ptr<const GraspLibrary> LibraryArgument(const py::object& library,
                                                    const std::string& object_name);

/// The registration of each part of the module (one source file each).
/// The result classes and enums made from the field lists (python/result_bindings.cpp).
void BindResults(py::module_& m);
void BindKinematics(py::module_& m);
void BindDemos(py::module_& m);
void BindLibrary(py::module_& m);
void BindSimulation(py::module_& m);
void BindStudy(py::module_& m);
void BindRequests(py::module_& m);

}  // namespace graspsynth::python
