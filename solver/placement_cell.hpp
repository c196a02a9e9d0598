#pragma once

/// @file
/// Where a query placement falls among the demonstrated placements (issue: the object anywhere
/// on the table): a Delaunay triangulation (CGAL) of the library's placements, each a point
/// (x, y, theta_length * theta) in metres, and the barycentric weights of the query in the
/// tetrahedron that holds it. The weights are >= 0 and sum to 1 inside the convex hull; a query
/// on a vertex has the weight 1 there, on an edge two weights, on a face three.
///
/// The orientation is scaled to a length so that the triangulation's shapes mean something:
/// by default 0.41 m per rad, the pre-grasp distance (GraspRegionModel::radius), so that a turn
/// of the object by d theta counts as much as a move of the wrist at the pre-grasp by about
/// 0.41 d theta. Demonstrations every 10 deg and 0.05-0.08 m apart then make cells of similar
/// extent in every direction (10 deg = 0.072 m).

#include <array>
#include <string>
#include <vector>

#include "scene/scene_model.hpp"

namespace graspsynth {

/// The metres per radian of orientation in the placement space.
inline constexpr double kDefaultThetaLength = 0.41;
/// Placements that leave their mean plane in the placement space by less than this (m) at most
/// span no volume (the shipped ones: several centimetres).
inline constexpr double kMinThickness = 1e-6;

/// The cell of a query: the demonstrated placements (vertex indices) with nonzero weight.
struct PlacementCell {
  bool inside = false;          ///< inside the convex hull of the placements (border included)
  std::vector<int> vertices;    ///< indices into the placements given, increasing, weight > 0
  std::vector<double> weights;  ///< barycentric, > 0, sum 1 (weights below 1e-12 are dropped)
  std::string reason;           ///< why not inside: the hull and the query in words
};

/// The Delaunay triangulation of a set of placements, each given as (x, y, theta): the object
/// centre on the table (m) and its orientation (rad).
class PlacementTriangulation {
 public:
  /// Triangulates `placements` in the placement space (x, y, theta_length * theta). Throws
  /// InputError naming `source` when two placements coincide or when they span less than a
  /// volume (all at one orientation, or at positions on one line, exactly or up to
  /// kMinThickness: roundoff would leave cells of no volume that hold no query), or
  /// theta_length is not positive and finite.
  PlacementTriangulation(const std::vector<Eigen::Vector3d>& placements, double theta_length,
                         const std::string& source);

  /// The cell of `query` (x, y, theta) and its weights, or why it is outside the hull. A query
  /// on a demonstrated placement has that vertex alone, with weight 1. Cells are searched in a
  /// fixed order (by their sorted vertex indices), so that a query on a shared face or edge
  /// always gets the same cell and weights.
  PlacementCell Locate(const Eigen::Vector3d& query) const;
  /// The index of the placement nearest `query` in the placement space (ties: the lower one).
  int Nearest(const Eigen::Vector3d& query) const;
  /// The placement space's distance between two placements (x, y, theta), m.
  double Distance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  /// Number of tetrahedra.
  int cells() const { return static_cast<int>(cells_.size()); }
  double theta_length() const { return theta_length_; }
  const std::vector<Eigen::Vector3d>& placements() const { return placements_; }

 private:
  Eigen::Vector3d Point(const Eigen::Vector3d& placement) const;
  // The most any placement leaves the plane the placements spread least from (m).
  double Thickness() const;

  std::vector<Eigen::Vector3d> placements_;  // (x, y, theta)
  double theta_length_ = kDefaultThetaLength;
  std::vector<std::array<int, 4>> cells_;  // sorted vertex indices, cells in sorted order
};

}  // namespace graspsynth
