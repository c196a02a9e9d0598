#include "scene/object_model.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "common/errors.hpp"
#include "scene/scene_model.hpp"
#include "scene/triangle_mesh.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;

fs::path ShippedObject(const std::string& name) {
  return fs::path(::testing::SourceDir()) / "models" / "objects" / (name + ".json");
}

// A scratch folder for object files and meshes, removed at the end of the test.
class ObjectFiles : public ::testing::Test {
 protected:
  fs::path Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // A one-part object: `part` is the JSON of that part.
  fs::path WriteObject(const nlohmann::json& part, const nlohmann::json& handle = nullptr) {
    nlohmann::json j = {{"format", "graspsynth-object/1"}, {"name", "thing"}, {"parts", {part}}};
    if (!handle.is_null()) j["handle"] = handle;
    return Write("thing.json", j.dump());
  }

  const testing::TestFolder folder_;
  const fs::path& dir_ = folder_.path();
};

// The object's grip axis runs from `start` to `end` m from its centre, `height` m up.
void ExpectGripAxis(const ObjectModel& o, double start, double end, double height) {
  ASSERT_TRUE(o.handle) << o.name;
  EXPECT_DOUBLE_EQ(o.handle->start_radius, start) << o.name;
  EXPECT_DOUBLE_EQ(o.handle->end_radius, end) << o.name;
  EXPECT_DOUBLE_EQ(o.handle->axis_height, height) << o.name;
}

// A closed unit tetrahedron scaled by `s`, outward, as OBJ.
std::string Tetrahedron(double s) {
  const std::string a = std::to_string(s);
  return "v 0 0 0\nv " + a + " 0 0\nv 0 " + a + " 0\nv 0 0 " + a +
         "\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
}

TEST(ObjectModel, ShippedPanHasTheHandComputedMassInertiaAndRestHeight) {
  const ObjectModel pan = LoadObjectModel(ShippedObject("pan"));
  EXPECT_EQ(pan.name, "pan");
  ASSERT_EQ(pan.parts.size(), 4u);
  EXPECT_EQ(pan.parts[0].touches, PartContact::kRobot);
  EXPECT_EQ(pan.parts[1].touches, PartContact::kRobotAndTable);
  EXPECT_EQ(pan.parts[2].touches, PartContact::kTable);
  EXPECT_EQ(pan.parts[2].mass, 0.0);
  // it rests on its foot, 0.05 m high, centred on O.
  EXPECT_DOUBLE_EQ(pan.rest_height, 0.025);
  ExpectGripAxis(pan, 0.08, 0.38, 0.045);
  // body 0.20 kg at O; handle 0.07 kg at (0.23, 0, 0.02): centre of mass 0.07 / 0.27 of the
  // way to the handle's centre.
  const ObjectInertia in = pan.Inertia();
  EXPECT_DOUBLE_EQ(in.mass, 0.27);
  EXPECT_TRUE(
      testing::MatricesNear(in.p_OC, Eigen::Vector3d(0.23, 0.0, 0.02) * 0.07 / 0.27, 1e-12));
  // cylinder: m (3 r^2 + h^2) / 12 = 3.6167e-4 (x, y), m r^2 / 2 = 6.4e-4 (z); bar
  // 0.3 x 0.024 x 0.024: 6.72e-6, 5.2836e-4, 5.2836e-4; plus both parallel-axis terms
  // m (|d|^2 1 - d d^T) about the centre of mass.
  Eigen::Matrix3d expected;
  expected << 3.89127407407e-4, 0.0, -2.38518518519e-4,  //
      0.0, 3.65373037037e-3, 0.0,                        //
      -2.38518518519e-4, 0.0, 3.91132296296e-3;
  EXPECT_TRUE(testing::MatricesNear(in.I_C, expected, 1e-14));
}

// The saucepan: a 0.64 kg cylinder (r 0.07, h 0.08) at O and a 0.12 kg bar 0.22 x 0.022 x
// 0.022 m centred at (0.18, 0, 0.025); the inertia written out part by part.
TEST(ObjectModel, ShippedSaucepanHasTheHandComputedMassInertiaAndRestHeight) {
  const ObjectModel saucepan = LoadObjectModel(ShippedObject("saucepan"));
  EXPECT_FALSE(saucepan.paper_object);
  EXPECT_TRUE(LoadObjectModel(ShippedObject("pan")).paper_object);
  EXPECT_DOUBLE_EQ(saucepan.rest_height, 0.04);  // its foot, 0.08 m high, centred on O
  ExpectGripAxis(saucepan, 0.07, 0.29, 0.065);
  const ObjectInertia in = saucepan.Inertia();
  const double m1 = 0.64, r = 0.07, h = 0.08, m2 = 0.12, a = 0.22, b = 0.022;
  const Eigen::Vector3d D(0.18, 0.0, 0.025);  // the bar's centre from the body's
  EXPECT_DOUBLE_EQ(in.mass, 0.76);
  EXPECT_TRUE(testing::MatricesNear(in.p_OC, D * m2 / (m1 + m2), 1e-12));
  // each part about its own centre, plus the two-body parallel-axis term with the reduced
  // mass m1 m2 / (m1 + m2) and the offset D between the centres.
  Eigen::Matrix3d expected = Eigen::Vector3d((m1 * (3 * r * r + h * h) + m2 * 2 * b * b) / 12,
                                             (m1 * (3 * r * r + h * h) + m2 * (a * a + b * b)) / 12,
                                             m1 * r * r / 2 + m2 * (a * a + b * b) / 12)
                                 .asDiagonal();
  const double mu = m1 * m2 / (m1 + m2);
  expected += mu * (D.squaredNorm() * Eigen::Matrix3d::Identity() - D * D.transpose());
  EXPECT_TRUE(testing::MatricesNear(in.I_C, expected, 1e-14));
  EXPECT_NEAR(in.I_C(0, 0), 1.19817e-3, 1e-8);  // the figures of models/README.md
  EXPECT_NEAR(in.I_C(2, 2), 5.33095e-3, 1e-8);
}

// The sugar box (YCB 004): one 0.514 kg box 0.038 x 0.089 x 0.175 m at O, standing on its
// end; its grip axis runs along y through the body, 30 mm below the top.
TEST(ObjectModel, ShippedSugarBoxHasTheHandComputedMassInertiaAndRestHeight) {
  const ObjectModel box = LoadObjectModel(ShippedObject("sugar_box"));
  EXPECT_FALSE(box.paper_object);
  EXPECT_DOUBLE_EQ(box.rest_height, 0.0875);
  ExpectGripAxis(box, -0.03, 0.03, 0.145);
  EXPECT_TRUE(testing::MatricesNear(box.handle->Along(), Eigen::Vector3d::UnitY(), 1e-15));
  // turned 30 deg about z, the axis is turned with it.
  const Eigen::Isometry3d X_WO(Eigen::AngleAxisd(30.0 * kDeg, Eigen::Vector3d::UnitZ()));
  EXPECT_TRUE(testing::MatricesNear(box.HandleDirection(X_WO),
                                    Eigen::Vector3d(-0.5, std::sqrt(3.0) / 2.0, 0.0), 1e-15));
  const ObjectInertia in = box.Inertia();
  const double m = 0.514, a = 0.038, b = 0.089, c = 0.175;
  EXPECT_DOUBLE_EQ(in.mass, m);
  EXPECT_TRUE(testing::MatricesNear(in.p_OC, Eigen::Vector3d::Zero(), 1e-15));
  const Eigen::Matrix3d expected =
      Eigen::Vector3d(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)
          .asDiagonal();
  EXPECT_TRUE(testing::MatricesNear(in.I_C, expected, 1e-15));
  EXPECT_NEAR(in.I_C(0, 0), 1.65105e-3, 1e-8);  // the figures of models/README.md
  EXPECT_NEAR(in.I_C(2, 2), 4.01134e-4, 1e-9);
}

// The mug (meshes from make_meshes.py, 900 kg/m^3): its body a 48-sided cup (outer radius
// 0.040 m, height 0.090 m, wall 4.5 mm, bottom 6 mm), whose volume and polar moment are the
// regular polygon's (area N/2 R^2 sin(2 pi/N), polar moment A R^2 (1 + 2 cos^2(pi/N)) / 6) times
// the heights; its loop handle a 10 x 12 mm band along a half ellipse (semi-axes 0.034 and
// 0.028 m), whose volume is the band's section times the path's length.
TEST(ObjectModel, ShippedMugHasTheHandComputedMassInertiaAndRestHeight) {
  const ObjectModel mug = LoadObjectModel(ShippedObject("mug"));
  EXPECT_FALSE(mug.paper_object);
  EXPECT_DOUBLE_EQ(mug.rest_height, 0.045);  // its foot, 0.09 m high, centred on O
  ASSERT_EQ(mug.parts[0].shape.kind, CollisionShape::Kind::kMesh);
  ASSERT_EQ(mug.parts[1].shape.kind, CollisionShape::Kind::kMesh);
  const double rho = 900.0, R = 0.040, Ri = 0.0355, h = 0.090, tb = 0.006;
  const int N = 48;
  auto area = [&](double r) { return N / 2.0 * r * r * std::sin(2.0 * M_PI / N); };
  auto polar = [&](double r) {
    return area(r) * r * r * (1.0 + 2.0 * std::pow(std::cos(M_PI / N), 2)) / 6.0;
  };
  ObjectModel body = mug;
  body.parts.resize(1);
  const ObjectInertia b = body.Inertia();
  // float32 STL vertices: relative errors of about 1e-7.
  EXPECT_NEAR(b.mass, rho * (area(R) * h - area(Ri) * (h - tb)), 1e-6 * b.mass);
  EXPECT_NEAR(b.I_C(2, 2), rho * (polar(R) * h - polar(Ri) * (h - tb)), 1e-5 * b.I_C(2, 2));
  // the cavity (centred 3 mm above O) takes mass from the top: the centre of mass is below O.
  const double cavity = area(Ri) * (h - tb);
  EXPECT_NEAR(b.p_OC.z(), -cavity * 0.5 * tb / (area(R) * h - cavity), 1e-6);
  ObjectModel handle = mug;
  handle.parts = {mug.parts[1]};
  double length = 0.0;  // the half ellipse's length, summed finely
  for (int k = 0; k < 10000; ++k) {
    const double a0 = M_PI * k / 10000, a1 = M_PI * (k + 1) / 10000;
    length +=
        std::hypot(0.034 * (std::sin(a1) - std::sin(a0)), 0.028 * (std::cos(a1) - std::cos(a0)));
  }
  EXPECT_NEAR(handle.Inertia().mass, rho * 0.010 * 0.012 * length, 0.01 * handle.Inertia().mass);
  // the whole: 0.118 kg, the YCB mug's (models/README.md).
  EXPECT_NEAR(mug.Inertia().mass, 0.118, 0.0005);
}

// An object without a grip axis turns its x axis; the pan's axis is its x axis exactly, so
// that every module that follows the axis computes the pan's numbers as before it had one.
TEST(ObjectModel, HandleDirectionIsTheObjectsXAxisForThePan) {
  const ObjectModel pan = LoadObjectModel(ShippedObject("pan"));
  const Eigen::Isometry3d X_WO(Eigen::AngleAxisd(-1.234, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d h = pan.HandleDirection(X_WO);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(h[i], X_WO.linear()(i, 0)) << i;
  ObjectModel bare = pan;
  bare.handle.reset();
  EXPECT_EQ(bare.HandleDirection(X_WO), h);
}

// The pan built from meshes: its prism body (64 sides) and mesh handle give the pan's mass,
// rest height and centre of mass, and its inertia within the prism's 0.2% area deficit.
TEST(ObjectModel, ShippedMeshPanHasThePansMassProperties) {
  const ObjectModel pan = LoadObjectModel(ShippedObject("pan"));
  const ObjectModel mesh = LoadObjectModel(ShippedObject("pan_mesh"));
  ASSERT_EQ(mesh.parts[0].shape.kind, CollisionShape::Kind::kMesh);
  ASSERT_EQ(mesh.parts[1].shape.kind, CollisionShape::Kind::kMesh);
  EXPECT_EQ(mesh.parts[0].shape.mesh->triangles.size(), 4u * 64u);
  EXPECT_EQ(mesh.rest_height, pan.rest_height);
  const ObjectInertia a = pan.Inertia(), b = mesh.Inertia();
  EXPECT_DOUBLE_EQ(b.mass, a.mass);
  EXPECT_TRUE(testing::MatricesNear(b.p_OC, a.p_OC, 1e-7));  // float32 STL vertices
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(b.I_C(i, i), a.I_C(i, i), 0.005 * a.I_C(i, i)) << i;
}

// Every shipped object loads, has a mass, rests above the table and names itself by its file.
TEST(ObjectModel, EveryShippedObjectLoads) {
  int count = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(ShippedObject("pan").parent_path())) {
    if (e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().string());
    const ObjectModel o = LoadObjectModel(e.path());
    EXPECT_EQ(o.name, e.path().stem().string());
    EXPECT_GT(o.Inertia().mass, 0.0);
    EXPECT_GT(o.rest_height, 0.0);
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(ObjectModel, ShippedPanIsTheInlinePanOfSceneFormat1) {
  const ObjectModel file = LoadObjectModel(ShippedObject("pan"));
  LegacyPanParameters p;
  p.body_radius = 0.08;
  p.body_height = 0.05;
  p.handle_start_radius = 0.08;
  p.handle_end_radius = 0.38;
  p.handle_width = 0.024;
  p.handle_thickness = 0.024;
  p.handle_axis_height = 0.045;
  p.body_mass = 0.2;
  p.handle_mass = 0.07;
  const ObjectModel legacy = LegacyPanObject("pan", p, "scene.json");
  ASSERT_EQ(file.parts.size(), legacy.parts.size());
  for (size_t i = 0; i < file.parts.size(); ++i) {
    const ObjectPart& a = file.parts[i];
    const ObjectPart& b = legacy.parts[i];
    EXPECT_EQ(a.name, b.name);
    EXPECT_EQ(a.shape.kind, b.shape.kind) << a.name;
    EXPECT_EQ(a.shape.size, b.shape.size) << a.name;
    EXPECT_EQ(a.shape.X_LG.linear(), b.shape.X_LG.linear()) << a.name;
    // bit for bit: the handle's height is written as the double the study computes.
    EXPECT_EQ(a.shape.X_LG.translation(), b.shape.X_LG.translation()) << a.name;
    EXPECT_EQ(a.mass, b.mass) << a.name;
    EXPECT_EQ(a.friction, b.friction) << a.name;
    EXPECT_EQ(a.touches, b.touches) << a.name;
  }
  EXPECT_EQ(file.rest_height, legacy.rest_height);
  EXPECT_EQ(file.handle->start_radius, legacy.handle->start_radius);
  EXPECT_EQ(file.handle->end_radius, legacy.handle->end_radius);
  EXPECT_EQ(file.handle->axis_height, legacy.handle->axis_height);
}

TEST_F(ObjectFiles, MeshPartHasTheMeshsMassPropertiesAtItsPose) {
  Write("tet.obj", Tetrahedron(0.1));
  const fs::path file = WriteObject({{"name", "tet"},
                                     {"type", "mesh"},
                                     {"file", "tet.obj"},
                                     {"density", 1000.0},
                                     {"position", {0.0, 0.0, -0.05}},
                                     {"rpy_deg", {0.0, 0.0, 90.0}}});
  const ObjectModel o = LoadObjectModel(file);
  // volume 0.1^3 / 6, centroid at a quarter of each edge, turned 90 deg about z.
  const ObjectInertia in = o.Inertia();
  EXPECT_NEAR(in.mass, 1000.0 * 1e-3 / 6.0, 1e-12);
  EXPECT_TRUE(testing::MatricesNear(in.p_OC, Eigen::Vector3d(-0.025, 0.025, -0.025), 1e-12));
  // it rests on its base triangle, 0.05 m below O.
  EXPECT_NEAR(o.rest_height, 0.05, 1e-15);
  EXPECT_FALSE(o.handle);
  GS_EXPECT_THROW_WITH(o.Handle("the line principle"), InputError, "object 'thing' (",
                       "has no handle, and the line principle needs one");
}

TEST_F(ObjectFiles, PrimitiveDensityGivesTheVolumesMass) {
  const ObjectModel o = LoadObjectModel(
      WriteObject({{"name", "ball"}, {"type", "sphere"}, {"radius", 0.1}, {"density", 1000.0}}));
  EXPECT_NEAR(o.Inertia().mass, 1000.0 * 4.0 / 3.0 * M_PI * 1e-3, 1e-12);
  EXPECT_NEAR(o.Inertia().I_C(0, 0), 0.4 * o.Inertia().mass * 0.01, 1e-15);
  EXPECT_DOUBLE_EQ(o.rest_height, 0.1);
}

TEST_F(ObjectFiles, BadObjectFilesNameTheFileAndTheField) {
  const std::string where = (dir_ / "thing.json").string();
  GS_EXPECT_THROW_WITH(
      LoadObjectModel(
          WriteObject({{"name", "m"}, {"type", "mesh"}, {"file", "gone.stl"}, {"mass", 1}})),
      InputError,
      where + ": field 'parts[0].file': cannot read mesh '" + (dir_ / "gone.stl").string() + "'");
  const std::string tet = Tetrahedron(0.1);
  Write("open.obj", tet.substr(0, tet.rfind("f ")));
  GS_EXPECT_THROW_WITH(LoadObjectModel(WriteObject(
                           {{"name", "m"}, {"type", "mesh"}, {"file", "open.obj"}, {"mass", 1}})),
                       InputError,
                       where + ": field 'parts[0].file': " + (dir_ / "open.obj").string() +
                           ": the mesh is not closed");
  GS_EXPECT_THROW_WITH(
      LoadObjectModel(
          WriteObject({{"name", "b"}, {"type", "box"}, {"size", {1, 1, 1}}, {"mass", -2}})),
      InputError, where + ": field 'parts[0].mass': expected a number in", "found -2");
  GS_EXPECT_THROW_WITH(
      LoadObjectModel(WriteObject({{"name", "c"}, {"type", "cone"}, {"mass", 1}})), InputError,
      where +
          ": field 'parts[0].type': expected a part type: \"box\", \"cylinder\", \"capsule\", "
          "\"sphere\" or \"mesh\", found \"cone\"");
  GS_EXPECT_THROW_WITH(
      LoadObjectModel(WriteObject({{"name", "b"}, {"type", "box"}, {"size", {1, 1, 1}}})),
      InputError, where + ": field 'parts[0].mass': expected a mass in kg (or a density");
  GS_EXPECT_THROW_WITH(LoadObjectModel(WriteObject({{"name", "b"},
                                                    {"type", "box"},
                                                    {"size", {1, 1, 1}},
                                                    {"mass", 1},
                                                    {"touches", "robot"}})),
                       InputError,
                       where +
                           ": field 'parts': expected at least one part that "
                           "touches the table");
  GS_EXPECT_THROW_WITH(
      LoadObjectModel(WriteObject(
          {{"name", "b"}, {"type", "box"}, {"size", {1, 1, 1}}, {"mass", 1}, {"colour", "red"}})),
      InputError, where + ": field 'parts[0].colour'");
  GS_EXPECT_THROW_WITH(
      LoadObjectModel(WriteObject({{"name", "b"}, {"type", "box"}, {"radius", 1}, {"mass", 1}})),
      InputError,
      where + ": field 'parts[0].radius': expected no 'radius' on a part of type \"box\"");
  const nlohmann::json box = {{"name", "b"}, {"type", "box"}, {"size", {1, 1, 1}}, {"mass", 1}};
  GS_EXPECT_THROW_WITH(
      LoadObjectModel(
          WriteObject(box, {{"start_radius", 0.1}, {"end_radius", -0.1}, {"axis_height", 0.5}})),
      InputError, where + ": field 'handle.end_radius': expected a radius above start_radius");
  GS_EXPECT_THROW_WITH(LoadObjectModel(WriteObject(box, {{"start_radius", -0.1},
                                                         {"end_radius", 0.1},
                                                         {"axis_height", 0.5},
                                                         {"direction_deg", 400}})),
                       InputError, where + ": field 'handle.direction_deg': expected a number in",
                       "found 400");
  GS_EXPECT_THROW_WITH(LoadObjectModel(dir_ / "none.json"), InputError,
                       "cannot read object description '" + (dir_ / "none.json").string() + "'");
}

TEST(ObjectModel, ResolvesShippedNamesAndFiles) {
  EXPECT_EQ(ResolveObjectPath("pan").filename(), "pan.json");
  EXPECT_EQ(ResolveObjectPath("my/own.json"), fs::path("my/own.json"));
  GS_EXPECT_THROW_WITH(ResolveObjectPath("teapot"), InputError,
                       "unknown object 'teapot': not a file, and not a shipped object (", "pan");
}

TEST(ObjectModel, SceneObjectOverrideReplacesTheScenesObject) {
  const fs::path scene_file = fs::path(::testing::SourceDir()) / "models" / "scene.json";
  const SceneModel scene = LoadSceneModel(scene_file, "pan");
  EXPECT_EQ(scene.object.name, "pan");
  EXPECT_EQ(scene.object.source, ShippedObject("pan").string());
  GS_EXPECT_THROW_WITH(LoadSceneModel(scene_file, "teapot"), InputError, "unknown object 'teapot'");
}

// A mangled pan.json - bytes changed, dropped, repeated or cut short - gives an object or an
// InputError, never another exception or a crash (the sanitizer build runs this too).
TEST(ObjectModel, MangledFilesGiveAnObjectOrAnInputError) {
  const std::string pan = testing::ReadFileText(ShippedObject("pan"));
  std::mt19937_64 rng(23);
  int objects = 0, errors = 0;
  for (int i = 0; i < 2000; ++i) {
    std::string text = pan;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0:
          text[at] = "0123456789.-e,:[]{}\" tx"[rng() % 20];
          break;
        case 1:
          text.erase(at, 1 + rng() % 6);
          break;
        default:
          text.insert(at, text.substr(at, 1 + rng() % 12));
      }
    }
    try {
      const ObjectModel o = ParseObjectModel(text, "pan.json", ShippedObject("pan").parent_path());
      o.Inertia();
      ++objects;
    } catch (const InputError&) {
      ++errors;
    }
  }
  EXPECT_EQ(objects + errors, 2000);
  EXPECT_GT(objects, 0);
  EXPECT_GT(errors, 0);
}

}  // namespace
}  // namespace graspsynth
