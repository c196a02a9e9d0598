#pragma once

/// @file
/// A velocity-level constraint solve for rigid bodies, in the formulation of ODE's direct
/// stepper (`dWorldStep`), that uses the structure of a hand grasping an object.
///
/// The problem, for the rows r of the Jacobian J (each row acts on at most two bodies):
///   A = J M^-1 J^T + diag(cfm_r) / h,   b = c / h - J (v / h + M^-1 f),
///   find lambda with A lambda = b + w, lo <= lambda <= hi and, per row, lambda = lo and
///   w >= 0, or lambda = hi and w <= 0, or lo < lambda < hi and w = 0;
/// a row with findex >= 0 is a friction row whose bounds become +-|hi * lambda[findex]| when it
/// is reached, as in ODE's Dantzig solver (the normal force at that point of the solve).
/// Then v += h M^-1 (f + J^T lambda), so that J v = c - cfm lambda after the step.
///
/// ODE factors the whole matrix of an island, whose rows are mostly the hinges' equality rows
/// (five per hinge, unbounded). Here the equality rows of each chain of bodies that they join
/// (a finger's four links) are eliminated first, block by block (a Schur complement), and only
/// the bounded rows (motors, stops, contacts) are left to the box solve. That solve first tries
/// the states its rows ended at in the last call (ConstraintRow::key names a row from call to
/// call): the free rows' forces with the others at their bounds, kept when every row meets its
/// condition; a row that fails its condition changes its state and the solve tries again (three
/// tries at most), and then it pivots as ODE's Dantzig solver does. Every row's cfm > 0 makes
/// the matrix positive definite, so the answer is unique and ODE's, to roundoff, however found.

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

namespace graspsynth {

/// One body's state in the solve. A body with inv_mass == 0 is not moved by the solve
/// (kinematic or static) and is best left out: rows refer to moving bodies only.
struct SolverBody {
  double inv_mass = 0.0;                                    ///< 1/kg
  Eigen::Matrix3d inv_inertia_W = Eigen::Matrix3d::Zero();  ///< world frame, 1/(kg m^2)
  Eigen::Vector3d v = Eigen::Vector3d::Zero();              ///< linear velocity, m/s
  Eigen::Vector3d w = Eigen::Vector3d::Zero();              ///< angular velocity, rad/s
  Eigen::Vector3d force = Eigen::Vector3d::Zero();          ///< external force, N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();         ///< external torque, N m
};

/// One constraint row: J_r = [lin[0] ang[0]] on body[0] and [lin[1] ang[1]] on body[1].
struct ConstraintRow {
  std::array<int, 2> body{-1, -1};  ///< SolverBody index, -1: none (a kinematic or static body)
  std::array<Eigen::Vector3d, 2> lin{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<Eigen::Vector3d, 2> ang{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  double c = 0.0;    ///< desired J v after the step (velocity units)
  double cfm = 0.0;  ///< constraint force mixing, > 0 (the matrix must be positive definite)
  /// Bounds on the row's force, lo <= 0 <= hi (a friction row's are -mu and mu).
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  int findex = -1;  ///< friction row: index of its normal row (a bounded row), else -1
  /// Names the row from step to step (0: none): the solver first tries the bounds that the
  /// rows of the same keys ended at in the last solve (the answer does not depend on it).
  std::uint64_t key = 0;
};

/// What the solves of a ConstraintSolverData have needed so far.
struct ConstraintSolverStatistics {
  int max_bounded_rows = 0;  ///< most bounded rows in one island
  long pivots = 0;           ///< pivots of the bounded solves
  long guessed = 0;          ///< islands solved at the first guess of their rows' states
  long amended = 0;          ///< of those, solved only after the guess was amended
  long pivoted = 0;          ///< islands that needed the pivoting (Dantzig) solve
  long unsolved = 0;         ///< pivoting solves stopped at their pivot limit (never seen)
};

/// Work memory of SolveConstraints, reused between calls (one per thread): the forces of the
/// last solve, the states its keyed rows ended at (the next solve's first guess), statistics,
/// and the solver's own buffers, which no other code can reach.
class ConstraintSolverData {
 public:
  ConstraintSolverData();
  ~ConstraintSolverData();
  ConstraintSolverData(ConstraintSolverData&&) noexcept;
  ConstraintSolverData& operator=(ConstraintSolverData&&) noexcept;
  ConstraintSolverData(const ConstraintSolverData&) = delete;
  ConstraintSolverData& operator=(const ConstraintSolverData&) = delete;

  /// The rows' forces after the last solve (N or N m), in the rows' order.
  const std::vector<double>& lambda() const;
  /// What the solves so far have needed.
  const ConstraintSolverStatistics& statistics() const;

  struct Work;  ///< the buffers (constraint_solver.cpp)

 private:
  friend void SolveConstraints(double h, const std::vector<ConstraintRow>& rows,
                               std::vector<SolverBody>* bodies, ConstraintSolverData* data);
  std::unique_ptr<Work> work_;
};

/// Solves the rows' forces for one step of h seconds and adds their impulse and the external
/// forces' to the bodies' velocities. Rows of different islands (bodies that no row joins)
/// are solved apart. data->lambda() holds the forces afterwards, in the rows' order.
void SolveConstraints(double h, const std::vector<ConstraintRow>& rows,
                      std::vector<SolverBody>* bodies, ConstraintSolverData* data);

}  // namespace graspsynth
