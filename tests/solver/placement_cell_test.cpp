#include "solver/placement_cell.hpp"

#include <gtest/gtest.h>

#include <random>

#include "common/errors.hpp"
#include "kinematics/types.hpp"

namespace graspsynth {
namespace {

// a 3 x 3 grid of positions 0.05 m apart at orientations 20..100 deg every 10 deg, the shape
// of the shipped placements' library.
std::vector<Eigen::Vector3d> Grid() {
  std::vector<Eigen::Vector3d> p;
  for (double x : {-0.30, -0.25, -0.20}) {
    for (double y : {0.80, 0.85, 0.90}) {
      for (int theta = 20; theta <= 100; theta += 10) p.emplace_back(x, y, theta * kDeg);
    }
  }
  return p;
}

TEST(PlacementTriangulation, WeightsAreNonNegativeSumToOneAndReproduceTheQuery) {
  const std::vector<Eigen::Vector3d> grid = Grid();
  const PlacementTriangulation t(grid, kDefaultThetaLength, "grid");
  EXPECT_GT(t.cells(), 0);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> x(-0.30, -0.20), y(0.80, 0.90), th(20.0, 100.0);
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d q(x(rng), y(rng), th(rng) * kDeg);
    const PlacementCell cell = t.Locate(q);
    ASSERT_TRUE(cell.inside) << cell.reason;
    ASSERT_EQ(cell.vertices.size(), cell.weights.size());
    double sum = 0.0;
    Eigen::Vector3d reproduced = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < cell.vertices.size(); ++i) {
      EXPECT_GT(cell.weights[i], 0.0);
      sum += cell.weights[i];
      reproduced += cell.weights[i] * grid[static_cast<size_t>(cell.vertices[i])];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    // barycentric weights reproduce the point (linear precision).
    EXPECT_LT((reproduced - q).norm(), 1e-12);
  }
}

TEST(PlacementTriangulation, ADemonstratedPlacementIsThatVertexAlone) {
  const std::vector<Eigen::Vector3d> grid = Grid();
  const PlacementTriangulation t(grid, kDefaultThetaLength, "grid");
  for (size_t i = 0; i < grid.size(); ++i) {
    const PlacementCell cell = t.Locate(grid[i]);
    ASSERT_TRUE(cell.inside);
    ASSERT_EQ(cell.vertices, std::vector<int>{static_cast<int>(i)});
    EXPECT_EQ(cell.weights, std::vector<double>{1.0});
  }
}

TEST(PlacementTriangulation, OnAConstantPositionItIsThePapersBracket) {
  // between two orientations at one demonstrated position: the two ends, with the paper's t.
  const std::vector<Eigen::Vector3d> grid = Grid();
  const PlacementTriangulation t(grid, kDefaultThetaLength, "grid");
  for (double theta : {23.0, 45.0, 61.5, 99.0}) {
    const PlacementCell cell = t.Locate({-0.25, 0.85, theta * kDeg});
    ASSERT_TRUE(cell.inside);
    ASSERT_EQ(cell.vertices.size(), 2u) << theta;
    const Eigen::Vector3d& a = grid[static_cast<size_t>(cell.vertices[0])];
    const Eigen::Vector3d& b = grid[static_cast<size_t>(cell.vertices[1])];
    EXPECT_EQ(a.head<2>(), Eigen::Vector2d(-0.25, 0.85));
    EXPECT_EQ(b.head<2>(), Eigen::Vector2d(-0.25, 0.85));
    const double t_paper = (theta * kDeg - a.z()) / (b.z() - a.z());
    EXPECT_NEAR(cell.weights[1], t_paper, 1e-12);
    EXPECT_NEAR(cell.weights[0], 1.0 - t_paper, 1e-12);
  }
}

TEST(PlacementTriangulation, OutsideTheHullIsRefusedWithTheHull) {
  const PlacementTriangulation t(Grid(), kDefaultThetaLength, "grid");
  for (const Eigen::Vector3d& q :
       {Eigen::Vector3d(-0.35, 0.85, 60 * kDeg), Eigen::Vector3d(-0.25, 0.85, 105 * kDeg),
        Eigen::Vector3d(-0.25, 0.95, 60 * kDeg)}) {
    const PlacementCell cell = t.Locate(q);
    EXPECT_FALSE(cell.inside);
    EXPECT_TRUE(cell.vertices.empty());
    EXPECT_NE(cell.reason.find("outside the convex hull"), std::string::npos) << cell.reason;
    EXPECT_NE(cell.reason.find("x -0.3 to -0.2 m"), std::string::npos) << cell.reason;
    EXPECT_NE(cell.reason.find("theta 20 to 100 deg"), std::string::npos) << cell.reason;
  }
}

TEST(PlacementTriangulation, TheSameQueryGetsTheSameCellEveryTime) {
  const PlacementTriangulation a(Grid(), kDefaultThetaLength, "grid");
  const PlacementTriangulation b(Grid(), kDefaultThetaLength, "grid");
  // a point on a face shared by two cells.
  const Eigen::Vector3d q(-0.275, 0.85, 50 * kDeg);
  const PlacementCell ca = a.Locate(q);
  const PlacementCell cb = b.Locate(q);
  EXPECT_EQ(ca.vertices, cb.vertices);
  EXPECT_EQ(ca.weights, cb.weights);
}

TEST(PlacementTriangulation, NearestUsesTheScaledOrientation) {
  const PlacementTriangulation t(Grid(), kDefaultThetaLength, "grid");
  // 4 deg of turn = 0.029 m: nearer than the neighbouring position 0.05 m away.
  const int i = t.Nearest({-0.25, 0.85, 64 * kDeg});
  EXPECT_EQ(t.placements()[static_cast<size_t>(i)], Eigen::Vector3d(-0.25, 0.85, 60 * kDeg));
}

TEST(PlacementTriangulation, DegenerateSetsAreRefused) {
  std::vector<Eigen::Vector3d> one_theta;
  for (const Eigen::Vector3d& p : Grid()) {
    if (p.z() == 60 * kDeg) one_theta.push_back(p);
  }
  EXPECT_THROW(PlacementTriangulation(one_theta, kDefaultThetaLength, "flat"), InputError);
  std::vector<Eigen::Vector3d> twice = Grid();
  twice.push_back(twice[5]);
  try {
    PlacementTriangulation(twice, kDefaultThetaLength, "dup.json");
    FAIL() << "a duplicate placement was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dup.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("there twice"), std::string::npos);
  }
  EXPECT_THROW(PlacementTriangulation(Grid(), 0.0, "zero"), InputError);
}

// Positions on one line but for roundoff (x = -0.25 + 1e-16 noise) used to make cells of no
// volume, whose queries all came out "outside the convex hull": refused as a line is.
TEST(PlacementTriangulation, PositionsOnOneLineUpToRoundoffAreRefusedAsALine) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> roundoff(-4e-16, 4e-16);
  std::vector<Eigen::Vector3d> line;
  for (double y : {0.80, 0.83, 0.85, 0.88, 0.90}) {
    for (int theta = 20; theta <= 100; theta += 20) {
      line.emplace_back(-0.25 + roundoff(random), y, theta * kDeg);
    }
  }
  try {
    PlacementTriangulation(line, kDefaultThetaLength, "line.json");
    FAIL() << "placements on one line up to roundoff were accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line.json: the 25 placements span no volume"),
              std::string::npos)
        << e.what();
  }
  // a millimetre off the line is a volume: taken, and a query between them is inside.
  line[7].x() += 1e-3;
  const PlacementTriangulation thin(line, kDefaultThetaLength, "thin.json");
  EXPECT_TRUE(thin.Locate({-0.2499, 0.84, 50 * kDeg}).inside);
}

}  // namespace
}  // namespace graspsynth
