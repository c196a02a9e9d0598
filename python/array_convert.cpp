// numpy arrays and JSON documents to and from the C++ types (python/bindings.hpp).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "python/bindings.hpp"

namespace graspsynth::python {
namespace {

// Whether all `n` values are finite numbers: x * 0 is 0 for a finite x and NaN for a NaN or an
// infinity, and Eigen sums in SIMD packets (a batch of IK targets is checked in a few
// instructions per target: benchmarks/README.md, "Python: the IK on a batch").
bool AllFinite(const double* values, py::ssize_t n) {
  return (Eigen::Map<const Eigen::ArrayXd>(values, n) * 0.0).sum() == 0.0;
}

std::string ShapeText(const std::vector<py::ssize_t>& shape, bool batch) {
  std::string text = batch ? "(N" : "(";
  for (size_t i = 0; i < shape.size(); ++i) {
    text += (batch || i > 0 ? ", " : "") + std::to_string(shape[i]);
  }
  return text + ")";
}

template <class Json>
py::object JsonToPython(const Json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::null:
    case nlohmann::json::value_t::discarded:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(value.template get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(value.template get<int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(value.template get<uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(value.template get<double>());
    case nlohmann::json::value_t::string:
      return py::str(value.template get_ref<const std::string&>());
    case nlohmann::json::value_t::binary:
      return py::none();
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const Json& item : value) list.append(JsonToPython(item));
      return list;
    }
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (auto it = value.begin(); it != value.end(); ++it) {
        dict[py::str(it.key())] = JsonToPython(it.value());
      }
      return dict;
    }
  }
  return py::none();
}

}  // namespace

py::array_t<double> NewArray(const std::vector<py::ssize_t>& shape) {
  return py::array_t<double>(shape);
}

Batch ReadBatch(const DoubleArray& array, const std::vector<py::ssize_t>& item_shape,
                const char* what) {
  const auto item_ndim = static_cast<py::ssize_t>(item_shape.size());
  const py::ssize_t ndim = array.ndim();
  Batch batch;
  batch.single = ndim == item_ndim;
  bool ok = ndim == item_ndim || ndim == item_ndim + 1;
  for (py::ssize_t i = 0; ok && i < item_ndim; ++i) {
    ok = array.shape(ndim - item_ndim + i) == item_shape[static_cast<size_t>(i)];
  }
  if (!ok) {
    std::string got = "(";
    for (py::ssize_t i = 0; i < ndim; ++i) {
      got += (i > 0 ? ", " : "") + std::to_string(array.shape(i));
    }
    throw InputError(std::string(what) + " must have shape " + ShapeText(item_shape, false) +
                     " or " + ShapeText(item_shape, true) + ", not " + got + ")");
  }
  batch.count = batch.single ? 1 : array.shape(0);
  batch.data = array.data();
  // as the command line's number fields: a value that is not a finite number is refused, with
  // where it is (the row of a batch, then the field of an item, 1-based as the commands count).
  py::ssize_t per_item = 1;
  for (const py::ssize_t n : item_shape) per_item *= n;
  const py::ssize_t values = batch.count * per_item;
  if (AllFinite(batch.data, values)) return batch;
  for (py::ssize_t k = 0; k < values; ++k) {
    if (std::isfinite(batch.data[k])) continue;
    const std::string row = batch.single ? "" : "row " + std::to_string(k / per_item + 1) + ", ";
    std::ostringstream value;
    value << batch.data[k];
    throw InputError(std::string(what) + ": " + row + "field " + std::to_string(k % per_item + 1) +
                     " is not a finite number: '" + value.str() + "'");
  }
  return batch;
}

std::vector<py::ssize_t> BatchShape(const Batch& batch,
                                    const std::vector<py::ssize_t>& item_shape) {
  std::vector<py::ssize_t> shape;
  if (!batch.single) shape.push_back(batch.count);
  shape.insert(shape.end(), item_shape.begin(), item_shape.end());
  return shape;
}

bool PoseFromMatrix(const double* m, Eigen::Isometry3d* X, std::string* why) {
  constexpr double kTolerance = 1e-6;
  for (int k = 0; k < 12; ++k) {
    if (!std::isfinite(m[k])) {
      *why = "has a value that is not finite";
      return false;
    }
  }
  if (m[12] != 0.0 || m[13] != 0.0 || m[14] != 0.0 || m[15] != 1.0) {
    *why = "the last row must be (0, 0, 0, 1)";
    return false;
  }
  const Eigen::Vector3d c0(m[0], m[4], m[8]), c1(m[1], m[5], m[9]), c2(m[2], m[6], m[10]);
  const double error = std::max({std::abs(c0.squaredNorm() - 1.0), std::abs(c1.squaredNorm() - 1.0),
                                 std::abs(c2.squaredNorm() - 1.0), std::abs(c0.dot(c1)),
                                 std::abs(c0.dot(c2)), std::abs(c1.dot(c2))});
  if (error > kTolerance || c0.cross(c1).dot(c2) < 0.0) {
    *why =
        "the rotation is not orthonormal with determinant 1 (error " + std::to_string(error) + ")";
    return false;
  }
  X->linear().col(0) = c0;
  X->linear().col(1) = c1;
  X->linear().col(2) = c2;
  X->translation() = Eigen::Vector3d(m[3], m[7], m[11]);
  X->makeAffine();
  return true;
}

void WriteMatrix(const Eigen::Isometry3d& X, double* rows) {
  const Eigen::Matrix4d& M = X.matrix();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) rows[4 * r + c] = M(r, c);
  }
}

py::array ReadOnlyView(const double* first, py::ssize_t count, py::ssize_t stride,
                       const std::vector<py::ssize_t>& shape,
                       const std::vector<py::ssize_t>& strides, py::handle owner) {
  std::vector<py::ssize_t> full_shape = {count};
  std::vector<py::ssize_t> full_strides = {stride};
  full_shape.insert(full_shape.end(), shape.begin(), shape.end());
  full_strides.insert(full_strides.end(), strides.begin(), strides.end());
  py::array view(py::dtype::of<double>(), full_shape, full_strides, first, owner);
  view.attr("flags").attr("writeable") = false;
  return view;
}

std::optional<Eigen::Vector2d> AtArgument(const py::object& at) {
  if (at.is_none()) return std::nullopt;
  const auto array = DoubleArray::ensure(at);
  if (!array || array.ndim() != 1 || array.shape(0) != 2) {
    throw InputError("at must be (x, y): two numbers of metres, the object centre on the table");
  }
  const Eigen::Vector2d xy(array.data()[0], array.data()[1]);
  if (!xy.allFinite())
    throw InputError("at must be finite, not (" + std::to_string(xy.x()) + ", " +
                     std::to_string(xy.y()) + ")");
  return xy;
}

py::object ToPython(const nlohmann::json& value) { return JsonToPython(value); }
py::object ToPython(const nlohmann::ordered_json& value) { return JsonToPython(value); }

py::object JsonTextToPython(const std::string& text) {
  return ToPython(nlohmann::ordered_json::parse(text));
}

}  // namespace graspsynth::python
