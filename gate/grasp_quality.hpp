#pragma once

/// @file
/// Grasp quality from contacts (Ferrari and Canny, "Planning optimal grasps", 1992): each
/// contact's friction cone is linearized into a few edge forces of unit normal component; their
/// wrenches about a reference point span a convex hull in R^6. The grasp is force closure when
/// the origin lies strictly inside the hull; the epsilon quality is the distance from the origin
/// to the nearest hull facet (the smallest disturbance wrench the grasp resists in every
/// direction, per unit of summed normal force), and the hull volume is a second, global figure.
/// The hull is computed with CGAL's d-dimensional triangulation.

#include <string>
#include <vector>

#include "kinematics/types.hpp"

namespace graspsynth {

/// One contact between the hand and the object, in world.
struct GraspContact {
  Eigen::Vector3d p_WC = Eigen::Vector3d::Zero();  ///< contact point, m
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();  ///< unit normal, pointing into the object
  double mu = 1.0;                                 ///< Coulomb friction coefficient
  /// Normal force that scales the contact's cone edges, N (1: Ferrari and Canny's unit force).
  double normal_force = 1.0;
};

/// Options of EvaluateGraspQuality.
struct GraspQualityOptions {
  int cone_edges = 8;  ///< edges of each linearized friction cone (>= 3)
  /// Length that turns torques into forces (m): torque / torque_scale. 0 = the largest distance
  /// of a contact from the reference point, which makes the measure independent of the
  /// object's size.
  double torque_scale = 0.0;

  bool IsValid(std::string* why) const;
};

/// The figures of a grasp.
struct GraspQuality {
  bool force_closure = false;  ///< the origin is strictly inside the wrench hull
  /// Signed distance from the origin to the nearest hull facet (positive inside); <= 0 means no
  /// force closure. 0 when the hull has no interior (fewer than 7 affinely independent
  /// wrenches, e.g. fewer than 2 contacts).
  double epsilon = 0.0;
  double volume = 0.0;      ///< 6-volume of the hull (same normalized units)
  int wrenches = 0;         ///< primitive wrenches used
  int facets = 0;           ///< hull facets
  double torque_scale = 0;  ///< the length used, m
  std::string message;      ///< why the hull is degenerate, when it is
};

/// Evaluates the contacts about the reference point p_WR (usually the object's centre of mass,
/// world, m).
GraspQuality EvaluateGraspQuality(const std::vector<GraspContact>& contacts,
                                  const Eigen::Vector3d& p_WR,
                                  const GraspQualityOptions& options = {});

}  // namespace graspsynth
