#include "gate/grasp_quality.hpp"

#include <CGAL/Epick_d.h>
#include <CGAL/Triangulation.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>

#include "common/demand.hpp"
#include "common/valid_options.hpp"

namespace graspsynth {
namespace {

using Kernel = CGAL::Epick_d<CGAL::Dimension_tag<6>>;
using Hull = CGAL::Triangulation<Kernel>;
using Wrench = Eigen::Matrix<double, 6, 1>;

// Two unit vectors spanning the plane normal to n.
std::pair<Eigen::Vector3d, Eigen::Vector3d> TangentBasis(const Eigen::Vector3d& n) {
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = n.cross(helper).normalized();
  return {t1, n.cross(t1)};
}

Wrench ToEigen(const Kernel::Point_d& p) {
  Wrench w;
  for (int i = 0; i < 6; ++i) w[i] = p[i];
  return w;
}

}  // namespace

bool GraspQualityOptions::IsValid(std::string* why) const {
  if (cone_edges < 3) {
    if (why) *why = "GraspQualityOptions::cone_edges must be at least 3";
    return false;
  }
  if (!(torque_scale >= 0.0)) {
    if (why) *why = "GraspQualityOptions::torque_scale must be >= 0";
    return false;
  }
  return true;
}

GraspQuality EvaluateGraspQuality(const std::vector<GraspContact>& contacts,
                                  const Eigen::Vector3d& p_WR, const GraspQualityOptions& options) {
  RequireValid(options, "invalid GraspQualityOptions");
  GraspQuality q;
  double rho = options.torque_scale;
  if (rho == 0.0) {
    for (const GraspContact& c : contacts) rho = std::max(rho, (c.p_WC - p_WR).norm());
    if (rho == 0.0) rho = 1.0;
  }
  q.torque_scale = rho;

  // primitive wrenches: the cone edges with unit normal force, torques about p_WR over rho.
  std::vector<Kernel::Point_d> points;
  std::vector<Wrench> wrenches;
  for (const GraspContact& c : contacts) {
    const Eigen::Vector3d n = c.n_W.normalized();
    const auto [t1, t2] = TangentBasis(n);
    for (int j = 0; j < options.cone_edges; ++j) {
      const double phi = 2.0 * M_PI * j / options.cone_edges;
      const Eigen::Vector3d f =
          c.normal_force * (n + c.mu * (std::cos(phi) * t1 + std::sin(phi) * t2));
      Wrench w;
      w << f, (c.p_WC - p_WR).cross(f) / rho;
      wrenches.push_back(w);
      points.emplace_back(w.data(), w.data() + 6);
    }
  }
  q.wrenches = static_cast<int>(points.size());

  Hull hull(6);
  hull.insert(points.begin(), points.end());
  if (hull.current_dimension() < 6) {
    q.message = "the wrenches span only " + std::to_string(std::max(0, hull.current_dimension())) +
                " of 6 dimensions";
    return q;
  }
  Wrench centroid = Wrench::Zero();
  for (const Wrench& w : wrenches) centroid += w;
  centroid /= static_cast<double>(wrenches.size());

  double epsilon = INFINITY;
  double volume = 0.0;
  for (auto cell = hull.full_cells_begin(); cell != hull.full_cells_end(); ++cell) {
    if (!hull.is_infinite(cell)) {
      Eigen::Matrix<double, 6, 6> edges;
      const Wrench v0 = ToEigen(cell->vertex(0)->point());
      for (int i = 1; i <= 6; ++i) edges.col(i - 1) = ToEigen(cell->vertex(i)->point()) - v0;
      volume += std::abs(edges.determinant()) / 720.0;  // 6!
      continue;
    }
    // an infinite cell's finite vertices form one hull facet.
    Eigen::Matrix<double, 6, 6> facet;
    int k = 0;
    for (int i = 0; i <= 6; ++i) {
      if (!hull.is_infinite(cell->vertex(i))) facet.col(k++) = ToEigen(cell->vertex(i)->point());
    }
    Eigen::Matrix<double, 5, 6> span;
    for (int i = 1; i < 6; ++i) span.row(i - 1) = (facet.col(i) - facet.col(0)).transpose();
    // the facet's normal spans the null space of its edge vectors: the eigenvector of the
    // smallest eigenvalue of span^T span.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(span.transpose() * span);
    // with coplanar wrenches (symmetric contacts) the triangulation has flat boundary
    // simplices; they cover no area of the hull's boundary and have no plane of their own.
    if (eig.eigenvalues()[1] < 1e-12 * eig.eigenvalues()[5]) continue;
    Wrench normal = eig.eigenvectors().col(0);
    double offset = normal.dot(facet.col(0));
    if (normal.dot(centroid) > offset) {  // make the normal point out of the hull
      normal = -normal;
      offset = -offset;
    }
    // signed distance of the origin from this facet's plane, positive on the hull's side.
    epsilon = std::min(epsilon, offset);
    ++q.facets;
  }
  q.epsilon = epsilon;
  q.volume = volume;
  q.force_closure = epsilon > 1e-12;
  return q;
}

}  // namespace graspsynth
