#pragma once

/// @file
/// Pose and interpolation math of the paper (section IV-A): slerp of orientations, the
/// "average slerp" (aslerp, eqs. 1-2) of positions, the convex blend of finger vectors (eq. 4),
/// and distances between poses.

#include <vector>

#include "kinematics/types.hpp"

namespace graspsynth {

/// Spherical linear interpolation of unit quaternions: q1 at t = 0, q2 at t = 1, constant
/// angular rate in between. q and -q are the same orientation, so the shorter arc is taken
/// (q2 is negated when q1 . q2 < 0). The result is unit. t outside [0, 1] extrapolates.
Eigen::Quaterniond Slerp(const Eigen::Quaterniond& q1, const Eigen::Quaterniond& q2, double t);

/// The paper's aslerp (eqs. 1-2): positions p1, p2 (metres, relative to the object centre) are
/// read as pure quaternions; the direction follows the great-circle arc from p1/|p1| to
/// p2/|p2| at constant rate and the norm is s = (1 - t)|p1| + t|p2|. Unlike orientations,
/// positions have no sign ambiguity, so no arc flipping is done. When either position is at
/// the origin, or the two directions are opposite (the arc is undefined), the result is the
/// plain linear blend (1 - t) p1 + t p2.
Eigen::Vector3d Aslerp(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double t);

/// The weighted slerp of several orientations: their weighted Riemannian (Karcher) mean on the
/// unit quaternions, the orientation m that minimizes sum_i w_i angle(m, q_i)^2, found by
/// Gauss-Newton steps from the heaviest one (the first on ties), every q_i taken on m's side
/// (shorter arcs). Weights are >= 0 and sum to 1 (1e-9). A weight of 1 returns that
/// quaternion's canonical-sign copy exactly; for two orientations with weights (1 - t, t) it
/// is Slerp(q1, q2, t) (to 1e-12 rad). The result is unit.
Eigen::Quaterniond WeightedSlerp(const std::vector<Eigen::Quaterniond>& q,
                                 const std::vector<double>& w);

/// The weighted aslerp of several positions relative to the object centre: the direction is
/// the weighted Karcher mean of the p_i / |p_i| on the unit sphere (from the heaviest one), the
/// norm the weighted mean of the |p_i|. A weight of 1 returns that position exactly; for two
/// positions with weights (1 - t, t) it is Aslerp(p1, p2, t) (to 1e-12 m). When a position is
/// at the origin, or two directions with weight are nearly opposite (no mean direction), the
/// result is the weighted linear mean, as Aslerp does.
Eigen::Vector3d WeightedAslerp(const std::vector<Eigen::Vector3d>& p, const std::vector<double>& w);

/// The convex blend of eq. 4, f = (1 - t) f1 + t f2, for vectors of any size.
template <typename Derived>
typename Derived::PlainObject ConvexBlend(const Eigen::MatrixBase<Derived>& f1,
                                          const Eigen::MatrixBase<Derived>& f2, double t) {
  return (1.0 - t) * f1 + t * f2;
}

/// Rotation angle between two orientations in [0, pi] (radians), independent of the sign of
/// either quaternion.
double AngleBetween(const Eigen::Quaterniond& q1, const Eigen::Quaterniond& q2);

/// Translation and rotation distance between two poses.
struct PoseDistance {
  double translation = 0.0;  ///< |p_a - p_b|, metres
  double rotation = 0.0;     ///< rotation angle of R_a^T R_b, radians in [0, pi]
};

/// The distance between poses X_a and X_b (their rotations must be orthonormal).
PoseDistance DistanceBetween(const Eigen::Isometry3d& X_a, const Eigen::Isometry3d& X_b);

/// The canonical form of q for files: unit and sign-normalized so that w >= 0.
Eigen::Quaterniond Canonical(const Eigen::Quaterniond& q);

/// Canonical for writing to a file: sign-normalized (w >= 0), and divided by its norm only when
/// that differs from 1 by more than 1e-15, so that a unit quaternion read from a file is
/// written back bit for bit.
Eigen::Quaterniond CanonicalForFile(const Eigen::Quaterniond& q);

/// The pose with position `p` (m) and the rotation of the unit quaternion `q` (normalize a
/// quaternion read from a file or a message first).
Eigen::Isometry3d PoseFrom(const Eigen::Vector3d& p, const Eigen::Quaterniond& q);

}  // namespace graspsynth
