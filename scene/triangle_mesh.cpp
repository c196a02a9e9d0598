#include "scene/triangle_mesh.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <sstream>

#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/text_input.hpp"

namespace graspsynth {
namespace {

// Merges coincident vertices (exactly equal coordinates), as STL repeats them per triangle.
class VertexWelder {
 public:
  explicit VertexWelder(TriangleMesh* mesh) : mesh_(mesh) {}
  int Add(const Eigen::Vector3d& v) {
    const auto key = std::array<double, 3>{v.x(), v.y(), v.z()};
    const auto [it, inserted] = index_.emplace(key, static_cast<int>(mesh_->vertices.size()));
    if (inserted) mesh_->vertices.push_back(v);
    return it->second;
  }

 private:
  TriangleMesh* mesh_;
  std::map<std::array<double, 3>, int> index_;
};

void CheckScale(double scale, const std::string& source) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    std::ostringstream s;
    s << source << ": mesh scale must be a finite number > 0 (got " << scale << ")";
    throw InputError(s.str());
  }
}

[[noreturn]] void FailAt(const std::string& source, size_t line, const std::string& what) {
  throw InputError(source + ":" + std::to_string(line) + ": " + what);
}

// The blank-separated words of one line.
std::vector<std::string_view> Words(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// Calls `f(line_number, line)` for each line of `text`.
template <typename F>
void ForEachLine(std::string_view text, F&& f) {
  size_t line_number = 0, start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    ++line_number;
    f(line_number, text.substr(start, end - start));
    if (end == text.size()) break;
    start = end + 1;
  }
}

Eigen::Vector3d ParseVertex(const std::vector<std::string_view>& w, size_t first,
                            const std::string& source, size_t line) {
  if (w.size() < first + 3)
    FailAt(source, line, "expected 3 coordinates after '" + std::string(w[0]) + "'");
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) {
    const std::optional<double> x = ParseFiniteDouble(w[first + k]);
    if (!x) {
      FailAt(source, line,
             "coordinate " + std::to_string(k + 1) + " is not a finite number: '" +
                 std::string(w[first + k]) + "'");
    }
    v[k] = *x;
  }
  return v;
}

TriangleMesh ParseAsciiStl(std::string_view text, double scale, const std::string& source) {
  TriangleMesh mesh;
  mesh.source = source;
  VertexWelder welder(&mesh);
  std::array<int, 3> tri{};
  int in_loop = -1;  // vertices seen in the current loop, -1 outside a loop
  size_t loop_line = 0;
  bool ended = false;
  ForEachLine(text, [&](size_t line, std::string_view l) {
    const std::vector<std::string_view> w = Words(l);
    if (w.empty() || ended) return;
    const std::string_view key = w[0];
    if (key == "vertex") {
      if (in_loop < 0) FailAt(source, line, "'vertex' outside an 'outer loop'");
      if (in_loop == 3) FailAt(source, line, "a loop with more than 3 vertices");
      tri[static_cast<size_t>(in_loop++)] = welder.Add(scale * ParseVertex(w, 1, source, line));
    } else if (key == "outer") {
      if (in_loop >= 0) FailAt(source, line, "'outer loop' inside a loop");
      in_loop = 0;
      loop_line = line;
    } else if (key == "endloop") {
      if (in_loop != 3) {
        FailAt(
            source, loop_line,
            "a loop with " + std::to_string(std::max(in_loop, 0)) + " vertices (a facet needs 3)");
      }
      mesh.triangles.push_back(tri);
      in_loop = -1;
    } else if (key == "endsolid") {
      ended = true;
    } else if (key != "solid" && key != "facet" && key != "endfacet") {
      FailAt(source, line, "unexpected '" + std::string(key) + "' in an ASCII STL file");
    }
  });
  if (in_loop >= 0) FailAt(source, loop_line, "the file ends inside this loop");
  return mesh;
}

TriangleMesh ParseBinaryStl(std::string_view bytes, double scale, const std::string& source) {
  uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  TriangleMesh mesh;
  mesh.source = source;
  VertexWelder welder(&mesh);
  mesh.triangles.reserve(count);
  for (uint32_t t = 0; t < count; ++t) {
    const char* record = bytes.data() + 84 + 50 * static_cast<size_t>(t);
    std::array<int, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      float xyz[3];
      std::memcpy(xyz, record + 12 * (k + 1), sizeof xyz);
      const Eigen::Vector3d v(xyz[0], xyz[1], xyz[2]);
      if (!v.allFinite()) {
        throw InputError(source + ": triangle " + std::to_string(t) +
                         " has a vertex that is not "
                         "a finite number");
      }
      tri[static_cast<size_t>(k)] = welder.Add(scale * v);
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

// Index of OBJ face vertex `word` ("7", "7/1", "7//3", "-2") among `count` vertices.
int ObjIndex(std::string_view word, size_t count, const std::string& source, size_t line) {
  const std::string_view head = word.substr(0, word.find('/'));
  const std::optional<double> x = ParseFiniteDouble(head);
  const long long n = static_cast<long long>(count);
  if (!x || *x != std::floor(*x) || *x == 0.0 || std::abs(*x) > static_cast<double>(n)) {
    FailAt(source, line,
           "face vertex '" + std::string(word) + "' is not a vertex index in 1.." +
               std::to_string(n) + " (or -1..-" + std::to_string(n) + ")");
  }
  const long long i = static_cast<long long>(*x);
  return static_cast<int>(i > 0 ? i - 1 : n + i);
}

double Area(const TriangleMesh& m, const std::array<int, 3>& t) {
  const Eigen::Vector3d& a = m.vertices[static_cast<size_t>(t[0])];
  return 0.5 * (m.vertices[static_cast<size_t>(t[1])] - a)
                   .cross(m.vertices[static_cast<size_t>(t[2])] - a)
                   .norm();
}

std::string Describe(const TriangleMesh& m, size_t t) {
  std::ostringstream s;
  s << "triangle " << t << " (vertices";
  for (int k : m.triangles[t]) s << " " << k;
  s << ")";
  return s.str();
}

}  // namespace

Eigen::Vector3d TriangleMesh::BoxMin() const {
  if (vertices.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d lo = vertices.front();
  for (const Eigen::Vector3d& v : vertices) lo = lo.cwiseMin(v);
  return lo;
}

Eigen::Vector3d TriangleMesh::BoxMax() const {
  if (vertices.empty()) return Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = vertices.front();
  for (const Eigen::Vector3d& v : vertices) hi = hi.cwiseMax(v);
  return hi;
}

TriangleMesh ParseStl(std::string_view bytes, double scale, const std::string& source) {
  CheckScale(scale, source);
  if (bytes.size() >= 84) {
    uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    if (bytes.size() == 84 + 50 * static_cast<uint64_t>(count)) {
      return ParseBinaryStl(bytes, scale, source);
    }
  }
  const std::string_view start = bytes.substr(0, std::min<size_t>(bytes.size(), 512));
  const std::vector<std::string_view> w = Words(start.substr(0, start.find('\n')));
  if (w.empty() || w[0] != "solid") {
    throw InputError(source +
                     ": not an STL file (neither a binary STL of the size its triangle "
                     "count gives nor text starting with 'solid')");
  }
  return ParseAsciiStl(bytes, scale, source);
}

TriangleMesh ParseObj(std::string_view text, double scale, const std::string& source) {
  CheckScale(scale, source);
  TriangleMesh mesh;
  mesh.source = source;
  ForEachLine(text, [&](size_t line, std::string_view l) {
    const std::vector<std::string_view> w = Words(l.substr(0, l.find('#')));
    if (w.empty()) return;
    if (w[0] == "v") {
      mesh.vertices.push_back(scale * ParseVertex(w, 1, source, line));
    } else if (w[0] == "f") {
      if (w.size() < 4) FailAt(source, line, "a face needs at least 3 vertices");
      std::vector<int> face;
      for (size_t k = 1; k < w.size(); ++k) {
        face.push_back(ObjIndex(w[k], mesh.vertices.size(), source, line));
      }
      for (size_t k = 1; k + 1 < face.size(); ++k) {
        mesh.triangles.push_back({face[0], face[k], face[k + 1]});
      }
    }
  });
  return mesh;
}

TriangleMesh LoadTriangleMesh(const std::filesystem::path& path, double scale) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".stl" && ext != ".obj") {
    throw InputError(path.string() + ": unknown mesh format '" + ext + "' (expected .stl or .obj)");
  }
  const std::string data = ReadInputFile(path, input_kind::kMesh);
  return ext == ".stl" ? ParseStl(data, scale, path.string())
                       : ParseObj(data, scale, path.string());
}

void CheckSolidMesh(const TriangleMesh& mesh, const MeshLimits& limits) {
  const std::string& src = mesh.source;
  if (mesh.triangles.empty()) throw InputError(src + ": the mesh has no triangles");
  if (mesh.triangles.size() > limits.max_triangles) {
    throw InputError(src + ": the mesh has " + std::to_string(mesh.triangles.size()) +
                     " triangles, more than the " + std::to_string(limits.max_triangles) +
                     " allowed");
  }
  const Eigen::Vector3d extent = mesh.BoxMax() - mesh.BoxMin();
  if (extent.maxCoeff() > limits.max_extent) {
    std::ostringstream s;
    s << src << ": the mesh is " << extent.maxCoeff() << " m long, more than the "
      << limits.max_extent << " m allowed (is its scale right? a mesh in millimetres needs "
      << "\"scale\": 0.001)";
    throw InputError(s.str());
  }
  // degenerate triangles, then edges: each directed edge once, with its reverse once.
  std::map<std::pair<int, int>, size_t> directed;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::array<int, 3>& tri = mesh.triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] ||
        Area(mesh, tri) < limits.min_triangle_area) {
      throw InputError(src + ": " + Describe(mesh, t) + " is degenerate (no area)");
    }
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> edge(tri[static_cast<size_t>(k)],
                                     tri[static_cast<size_t>((k + 1) % 3)]);
      if (!directed.emplace(edge, t).second) {
        throw InputError(src + ": edge " + std::to_string(edge.first) + "-" +
                         std::to_string(edge.second) + " of " + Describe(mesh, t) +
                         " is used twice in the same direction (triangles not consistently "
                         "oriented, or more than two triangles on an edge)");
      }
    }
  }
  for (const auto& [edge, t] : directed) {
    if (!directed.contains({edge.second, edge.first})) {
      throw InputError(src + ": the mesh is not closed: edge " + std::to_string(edge.first) + "-" +
                       std::to_string(edge.second) + " of " + Describe(mesh, t) +
                       " has no triangle on its other side");
    }
  }
  const MeshMassProperties mp = ComputeMeshMassProperties(mesh);
  if (!(mp.volume > 0.0)) {
    std::ostringstream s;
    s << src << ": the mesh encloses a volume of " << mp.volume
      << " m^3; its triangles must be counter-clockwise seen from outside (normals outward)";
    throw InputError(s.str());
  }
}

MeshMassProperties ComputeMeshMassProperties(const TriangleMesh& mesh) {
  // Each triangle (a, b, c) with the origin spans a tetrahedron of signed volume
  // det(a, b, c) / 6 whose first moment is volume * (a + b + c) / 4 and whose second moment
  // integral of x x^T is det / 120 * (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
  double volume = 0.0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const std::array<int, 3>& t : mesh.triangles) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<size_t>(t[0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<size_t>(t[1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<size_t>(t[2])];
    const double det = a.dot(b.cross(c));
    const Eigen::Vector3d s = a + b + c;
    volume += det / 6.0;
    first += det / 24.0 * s;
    second += det / 120.0 *
              (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  MeshMassProperties out;
  out.volume = volume;
  if (volume == 0.0) return out;
  out.centroid = first / volume;
  const Eigen::Matrix3d central = second - volume * out.centroid * out.centroid.transpose();
  out.unit_inertia = central.trace() * Eigen::Matrix3d::Identity() - central;
  return out;
}

}  // namespace graspsynth
