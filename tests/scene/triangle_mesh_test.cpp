#include "scene/triangle_mesh.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

// A closed box with outward (counter-clockwise seen from outside) triangles, as OBJ text.
std::string BoxObj(const Eigen::Vector3d& size) {
  std::string text = "# a box\no box\n";
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector3d v(((i & 1) ? 0.5 : -0.5) * size.x(), ((i & 2) ? 0.5 : -0.5) * size.y(),
                            ((i & 4) ? 0.5 : -0.5) * size.z());
    text += "v " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
            std::to_string(v.z()) + "\n";
  }
  // quads of the six faces, 1-based, counter-clockwise from outside.
  text += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return text;
}

// The same box as ASCII STL text.
std::string BoxAsciiStl(const TriangleMesh& box) {
  std::string text = "solid box\n";
  for (const std::array<int, 3>& t : box.triangles) {
    text += "  facet normal 0 0 0\n    outer loop\n";
    for (int k : t) {
      const Eigen::Vector3d& v = box.vertices[static_cast<size_t>(k)];
      text += "      vertex " + std::to_string(v.x()) + " " + std::to_string(v.y()) + " " +
              std::to_string(v.z()) + "\n";
    }
    text += "    endloop\n  endfacet\n";
  }
  return text + "endsolid box\n";
}

// The same box as binary STL bytes.
std::string BoxBinaryStl(const TriangleMesh& box) {
  std::string bytes(80, ' ');
  const uint32_t n = static_cast<uint32_t>(box.triangles.size());
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for (const std::array<int, 3>& t : box.triangles) {
    float record[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      for (int c = 0; c < 3; ++c) {
        record[3 + 3 * k + c] = static_cast<float>(box.vertices[static_cast<size_t>(t[k])][c]);
      }
    }
    bytes.append(reinterpret_cast<const char*>(record), sizeof record);
    bytes.append(2, '\0');
  }
  return bytes;
}

TEST(TriangleMesh, ObjBoxHasTheBoxsVolumeCentroidAndInertia) {
  const Eigen::Vector3d size(0.1, 0.2, 0.3);
  const TriangleMesh box = ParseObj(BoxObj(size), 1.0, "box.obj");
  ASSERT_EQ(box.vertices.size(), 8u);
  ASSERT_EQ(box.triangles.size(), 12u);
  CheckSolidMesh(box);
  const MeshMassProperties mp = ComputeMeshMassProperties(box);
  EXPECT_NEAR(mp.volume, 0.006, 1e-15);
  EXPECT_TRUE(testing::MatricesNear(mp.centroid, Eigen::Vector3d::Zero(), 1e-15));
  // a solid box of unit density: m = V, I = m / 12 (b^2 + c^2, ...).
  const double m = 0.006;
  const Eigen::Vector3d expected(m * (0.04 + 0.09) / 12, m * (0.01 + 0.09) / 12,
                                 m * (0.01 + 0.04) / 12);
  EXPECT_TRUE(testing::MatricesNear(mp.unit_inertia, expected.asDiagonal().toDenseMatrix(), 1e-15));
}

TEST(TriangleMesh, StlAsciiAndBinaryGiveTheObjMesh) {
  const TriangleMesh box = ParseObj(BoxObj(Eigen::Vector3d(0.1, 0.2, 0.3)), 1.0, "box.obj");
  for (const std::string& bytes : {BoxAsciiStl(box), BoxBinaryStl(box)}) {
    const TriangleMesh stl = ParseStl(bytes, 1.0, "box.stl");
    EXPECT_EQ(stl.vertices.size(), 8u) << "coincident vertices are merged";
    EXPECT_EQ(stl.triangles.size(), 12u);
    CheckSolidMesh(stl);
    EXPECT_NEAR(ComputeMeshMassProperties(stl).volume, 0.006, 1e-8);
  }
}

TEST(TriangleMesh, ScaleAppliesToEveryVertex) {
  const TriangleMesh mm = ParseObj(BoxObj(Eigen::Vector3d(100, 200, 300)), 0.001, "box.obj");
  EXPECT_NEAR(ComputeMeshMassProperties(mm).volume, 0.006, 1e-12);
  GS_EXPECT_THROW_WITH(ParseObj(BoxObj(Eigen::Vector3d::Ones()), -1.0, "box.obj"), InputError,
                       "box.obj: mesh scale must be a finite number > 0 (got -1)");
}

TEST(TriangleMesh, ObjAcceptsSlashFormsAndNegativeIndices) {
  const TriangleMesh m = ParseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nf 1/1/1 3//1 2\nf -4 -3 -1\n"
      "f 1 4 3\nf 2 3 4\n",
      1.0, "t.obj");
  ASSERT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.triangles[1], (std::array<int, 3>{0, 1, 3}));
  CheckSolidMesh(m);
  EXPECT_NEAR(ComputeMeshMassProperties(m).volume, 1.0 / 6.0, 1e-15);
}

TEST(TriangleMesh, BadFilesNameTheLineAndTheFault) {
  GS_EXPECT_THROW_WITH(ParseObj("v 0 0 0\nv 1 zero 0\n", 1.0, "m.obj"), InputError,
                       "m.obj:2: coordinate 2 is not a finite number: 'zero'");
  GS_EXPECT_THROW_WITH(ParseObj("v 0 0 0\nf 1 2 3\n", 1.0, "m.obj"), InputError,
                       "m.obj:2: face vertex '2' is not a vertex index in 1..1");
  GS_EXPECT_THROW_WITH(ParseObj("v 0 0 0\nf 1 1\n", 1.0, "m.obj"), InputError,
                       "m.obj:2: a face needs at least 3 vertices");
  GS_EXPECT_THROW_WITH(
      ParseStl("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nendloop\n", 1.0, "m.stl"),
      InputError, "m.stl:3: a loop with 1 vertices (a facet needs 3)");
  GS_EXPECT_THROW_WITH(ParseStl("solid x\nfacet normal 0 0 1\nbanana\n", 1.0, "m.stl"), InputError,
                       "m.stl:3: unexpected 'banana' in an ASCII STL file");
  GS_EXPECT_THROW_WITH(ParseStl("PK\x03\x04 not a mesh", 1.0, "m.stl"), InputError,
                       "m.stl: not an STL file");
  GS_EXPECT_THROW_WITH(LoadTriangleMesh("/nonexistent/m.stl", 1.0), InputError,
                       "cannot read mesh '/nonexistent/m.stl'");
  GS_EXPECT_THROW_WITH(LoadTriangleMesh("m.ply", 1.0), InputError,
                       "m.ply: unknown mesh format '.ply' (expected .stl or .obj)");
}

TEST(TriangleMesh, SolidCheckRejectsOpenDegenerateInsideOutAndHugeMeshes) {
  const std::string box = BoxObj(Eigen::Vector3d(0.1, 0.1, 0.1));
  // one face left out: open.
  const std::string open = box.substr(0, box.rfind("f "));
  GS_EXPECT_THROW_WITH(CheckSolidMesh(ParseObj(open, 1.0, "open.obj")), InputError,
                       "open.obj: the mesh is not closed: edge",
                       "has no triangle on its other side");
  // every face reversed: closed, but the volume is negative.
  TriangleMesh inside_out = ParseObj(box, 1.0, "inv.obj");
  for (std::array<int, 3>& t : inside_out.triangles) std::swap(t[1], t[2]);
  GS_EXPECT_THROW_WITH(CheckSolidMesh(inside_out), InputError,
                       "inv.obj: the mesh encloses a volume of -0.001",
                       "counter-clockwise seen from outside");
  // a triangle with a repeated vertex.
  TriangleMesh degenerate = ParseObj(box, 1.0, "deg.obj");
  degenerate.triangles[3][2] = degenerate.triangles[3][1];
  GS_EXPECT_THROW_WITH(CheckSolidMesh(degenerate), InputError, "deg.obj: triangle 3 (vertices",
                       "is degenerate");
  // one face flipped: an edge used twice in the same direction.
  TriangleMesh flipped = ParseObj(box, 1.0, "flip.obj");
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  GS_EXPECT_THROW_WITH(CheckSolidMesh(flipped), InputError, "flip.obj: edge",
                       "used twice in the same direction");
  // 3 m long: far too large (a mesh in millimetres read as metres).
  GS_EXPECT_THROW_WITH(
      CheckSolidMesh(ParseObj(BoxObj(Eigen::Vector3d(3, 0.1, 0.1)), 1.0, "big.obj")), InputError,
      "big.obj: the mesh is 3 m long, more than the 2 m allowed", "\"scale\": 0.001");
  GS_EXPECT_THROW_WITH(CheckSolidMesh(TriangleMesh{{}, {}, "empty.obj"}), InputError,
                       "empty.obj: the mesh has no triangles");
}

TEST(TriangleMesh, LoadReadsFilesByExtension) {
  const testing::TestFolder folder;
  const std::filesystem::path& dir = folder.path();
  const TriangleMesh box = ParseObj(BoxObj(Eigen::Vector3d(0.1, 0.2, 0.3)), 1.0, "box.obj");
  std::ofstream(dir / "box.OBJ") << BoxObj(Eigen::Vector3d(0.1, 0.2, 0.3));
  std::ofstream(dir / "box.stl", std::ios::binary) << BoxBinaryStl(box);
  EXPECT_EQ(LoadTriangleMesh(dir / "box.OBJ", 1.0).triangles.size(), 12u);
  const TriangleMesh stl = LoadTriangleMesh(dir / "box.stl", 1.0);
  EXPECT_EQ(stl.source, (dir / "box.stl").string());
  EXPECT_EQ(stl.triangles.size(), 12u);
}

// Mangled files - bytes changed, dropped, repeated or cut short - give a mesh or an InputError,
// never another exception or a crash (the sanitizer build runs this too).
TEST(TriangleMesh, MangledFilesGiveAMeshOrAnInputError) {
  const TriangleMesh box = ParseObj(BoxObj(Eigen::Vector3d(0.1, 0.2, 0.3)), 1.0, "box.obj");
  const std::string inputs[] = {BoxObj(Eigen::Vector3d(0.1, 0.2, 0.3)), BoxAsciiStl(box),
                                BoxBinaryStl(box)};
  std::mt19937_64 rng(17);
  int meshes = 0, errors = 0;
  for (int i = 0; i < 3000; ++i) {
    const int which = i % 3;
    std::string bytes = inputs[which];
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !bytes.empty(); ++e) {
      const size_t at = rng() % bytes.size();
      switch (rng() % 4) {
        case 0:  // a byte changed
          bytes[at] = static_cast<char>(rng() % 256);
          break;
        case 1:  // bytes dropped
          bytes.erase(at, 1 + rng() % 8);
          break;
        case 2:  // bytes repeated
          bytes.insert(at, bytes.substr(at, 1 + rng() % 16));
          break;
        default:  // cut short
          bytes.resize(at);
      }
    }
    try {
      const TriangleMesh m =
          which == 0 ? ParseObj(bytes, 1.0, "m.obj") : ParseStl(bytes, 1.0, "m.stl");
      CheckSolidMesh(m);
      ComputeMeshMassProperties(m);
      ++meshes;
    } catch (const InputError&) {
      ++errors;
    }
  }
  EXPECT_EQ(meshes + errors, 3000);
  EXPECT_GT(errors, 0);
}

}  // namespace
}  // namespace graspsynth
