#pragma once

/// @file
/// Triangle meshes of objects: reading STL (binary and ASCII) and OBJ files, the checks a mesh
/// must pass before a simulator or a collision checker may use it, and the mass properties of
/// the solid it bounds.
///
/// A mesh is used as the boundary of a solid, so it must be closed and consistently oriented
/// (every edge shared by exactly two triangles, in opposite directions), without degenerate
/// triangles, with its normals outward (positive volume). Coordinates are metres in the mesh's
/// own frame once scaled.

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace graspsynth {

/// A triangle mesh: vertices and counter-clockwise (seen from outside) index triples.
struct TriangleMesh {
  std::vector<Eigen::Vector3d> vertices;      ///< m
  std::vector<std::array<int, 3>> triangles;  ///< indices into vertices
  std::string source;                         ///< file it was read from, for messages

  /// The corners of the axis-aligned bounding box (zero for an empty mesh).
  Eigen::Vector3d BoxMin() const;
  Eigen::Vector3d BoxMax() const;
};

/// Mass properties of the solid a closed mesh bounds, at uniform density.
struct MeshMassProperties {
  double volume = 0.0;                                 ///< m^3 (> 0 for outward normals)
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< m, mesh frame
  /// Inertia of the solid of unit density (1 kg/m^3) about the centroid, mesh axes, kg m^2;
  /// multiply by the density for the part's inertia.
  Eigen::Matrix3d unit_inertia = Eigen::Matrix3d::Zero();
};

/// Limits of a mesh that an object may use.
struct MeshLimits {
  size_t max_triangles = 200000;
  double max_extent = 2.0;           ///< m, the longest side of the bounding box (after scaling)
  double min_triangle_area = 1e-12;  ///< m^2; smaller triangles are degenerate
};

/// Parses the text or bytes of an STL file (binary or ASCII, told apart by the size a binary
/// file of its triangle count must have) and scales it by `scale`. Coincident vertices are
/// merged. Throws InputError naming `source` (and the line, for ASCII) for anything that is not
/// STL.
TriangleMesh ParseStl(std::string_view bytes, double scale, const std::string& source);

/// Parses the text of a Wavefront OBJ file: `v` and `f` lines (faces of 3 or more vertices are
/// split into triangles as fans; `f a/b/c` forms and negative indices are accepted); every
/// other statement is ignored. Throws InputError naming `source` and the line.
TriangleMesh ParseObj(std::string_view text, double scale, const std::string& source);

/// Reads an .stl or .obj file (by its extension, any case). Throws InputError naming the file.
TriangleMesh LoadTriangleMesh(const std::filesystem::path& path, double scale);

/// Checks that `mesh` is usable as a solid's boundary within `limits`: not empty, no more
/// triangles than allowed, no degenerate triangle, closed and consistently oriented, outward
/// (positive volume), not larger than allowed. Throws InputError naming the mesh's source and
/// the first fault (with the triangle or edge).
void CheckSolidMesh(const TriangleMesh& mesh, const MeshLimits& limits = {});

/// Volume, centroid and unit-density inertia of the solid bounded by a closed mesh (signed
/// tetrahedra from the origin; exact for a closed mesh).
MeshMassProperties ComputeMeshMassProperties(const TriangleMesh& mesh);

}  // namespace graspsynth
