#include "solver/placement_cell.hpp"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using DataStructure = CGAL::Triangulation_data_structure_3<VertexBase>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, DataStructure>;

// A weight this small is a point on the opposite face: dropped.
constexpr double kZeroWeight = 1e-12;

std::string Triple(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(x " << p.x() << " m, y " << p.y() << " m, theta " << Degrees(p.z()) << " deg)";
  return s.str();
}

}  // namespace

PlacementTriangulation::PlacementTriangulation(const std::vector<Eigen::Vector3d>& placements,
                                               double theta_length, const std::string& source)
    : placements_(placements), theta_length_(theta_length) {
  if (!(theta_length > 0.0) || !std::isfinite(theta_length)) {
    throw InputError(source + ": the placement space's theta length must be positive, is " +
                     std::to_string(theta_length));
  }
  Delaunay dt;
  // one at a time, in index order: the triangulation (with CGAL's symbolic perturbation of
  // degenerate sets such as a grid) does not depend on a random insertion order.
  for (size_t i = 0; i < placements_.size(); ++i) {
    const Eigen::Vector3d p = Point(placements_[i]);
    const size_t before = dt.number_of_vertices();
    Delaunay::Vertex_handle v = dt.insert(Kernel::Point_3(p.x(), p.y(), p.z()));
    if (dt.number_of_vertices() == before) {
      throw InputError(source + ": the placement " + Triple(placements_[i]) +
                       " is there twice (entries " + std::to_string(v->info()) + " and " +
                       std::to_string(i) + ")");
    }
    v->info() = static_cast<int>(i);
  }
  // flat exactly (CGAL's exact predicates), or up to roundoff: positions on one line but for
  // digits past the 15th make cells of no volume in which no query is found.
  const double thickness = Thickness();
  if (dt.dimension() < 3 || thickness < kMinThickness) {
    std::ostringstream spread;
    if (dt.dimension() == 3) {
      spread << "; they leave it by " << thickness << " m at most, under the " << kMinThickness
             << " m taken as none";
    }
    throw InputError(source + ": the " + std::to_string(placements_.size()) +
                     " placements span no volume in (x, y, theta) (all at one orientation, or "
                     "their positions on one line" +
                     spread.str() +
                     "): interpolation over placements needs at least two orientations at "
                     "positions that are not on one line");
  }
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
    std::array<int, 4> v{};
    for (int k = 0; k < 4; ++k) v[static_cast<size_t>(k)] = c->vertex(k)->info();
    std::sort(v.begin(), v.end());
    cells_.push_back(v);
  }
  std::sort(cells_.begin(), cells_.end());
}

double PlacementTriangulation::Thickness() const {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : placements_) mean += Point(p);
  mean /= static_cast<double>(placements_.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : placements_) {
    const Eigen::Vector3d d = Point(p) - mean;
    scatter += d * d.transpose();
  }
  // the direction in which the points spread least, and how far they leave their mean plane.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  const Eigen::Vector3d normal = eigen.eigenvectors().col(0);
  double most = 0.0;
  for (const Eigen::Vector3d& p : placements_) {
    most = std::max(most, std::abs(normal.dot(Point(p) - mean)));
  }
  return most;
}

Eigen::Vector3d PlacementTriangulation::Point(const Eigen::Vector3d& placement) const {
  return {placement.x(), placement.y(), theta_length_ * placement.z()};
}

double PlacementTriangulation::Distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
  return (Point(a) - Point(b)).norm();
}

int PlacementTriangulation::Nearest(const Eigen::Vector3d& query) const {
  int best = -1;
  double best_d = INFINITY;
  for (size_t i = 0; i < placements_.size(); ++i) {
    const double d = Distance(query, placements_[i]);
    if (d < best_d) {
      best_d = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

PlacementCell PlacementTriangulation::Locate(const Eigen::Vector3d& query) const {
  PlacementCell cell;
  for (size_t i = 0; i < placements_.size(); ++i) {
    if (placements_[i] == query) {
      cell.inside = true;
      cell.vertices = {static_cast<int>(i)};
      cell.weights = {1.0};
      return cell;
    }
  }
  const Eigen::Vector3d q = Point(query);
  for (const std::array<int, 4>& c : cells_) {
    const Eigen::Vector3d p0 = Point(placements_[static_cast<size_t>(c[0])]);
    Eigen::Matrix3d A;
    for (int k = 1; k < 4; ++k) A.col(k - 1) = Point(placements_[static_cast<size_t>(c[k])]) - p0;
    const Eigen::Vector3d l = A.partialPivLu().solve(q - p0);
    const double w[4] = {1.0 - l.sum(), l[0], l[1], l[2]};
    if (*std::min_element(w, w + 4) < -kZeroWeight) continue;
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) {
      if (w[k] > kZeroWeight) sum += w[k];
    }
    for (int k = 0; k < 4; ++k) {
      if (w[k] <= kZeroWeight) continue;
      cell.vertices.push_back(c[static_cast<size_t>(k)]);
      cell.weights.push_back(w[k] / sum);
    }
    if (cell.vertices.size() == 1) cell.weights = {1.0};
    cell.inside = true;
    return cell;
  }
  Eigen::Vector3d lo = placements_.front(), hi = placements_.front();
  for (const Eigen::Vector3d& p : placements_) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  std::ostringstream why;
  why << "the placement " << Triple(query) << " is outside the convex hull of the library's "
      << placements_.size() << " demonstrated placements (x " << lo.x() << " to " << hi.x()
      << " m, y " << lo.y() << " to " << hi.y() << " m, theta " << Degrees(lo.z()) << " to "
      << Degrees(hi.z()) << " deg; the nearest is "
      << Triple(placements_[static_cast<size_t>(Nearest(query))]) << ")";
  cell.reason = why.str();
  return cell;
}

}  // namespace graspsynth
