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

/// Work memory of SolveConstraints, reused between calls (one per thread).
struct ConstraintSolverData {
  std::vector<double> lambda;  ///< the rows' forces after the last solve (N or N m)
  int max_bounded_rows = 0;    ///< most bounded rows in one island so far (statistics)
  long pivots = 0;             ///< pivots of the bounded solves so far (statistics)
  long guessed = 0;            ///< islands solved at the first guess (statistics)
  long amended = 0;            ///< of those, solved only after the guess was amended (statistics)
  long pivoted = 0;            ///< islands that needed the pivoting solve (statistics)
  long unsolved = 0;  ///< pivoting solves stopped at their pivot limit (never seen; statistics)

  /// Where each keyed row ended in a solve, without the friction rows and with them (0 free,
  /// 1 at its lower bound, 2 at its upper bound): an open-addressing table of its keys (key 0
  /// marks an empty slot), kept from call to call so that a step allocates nothing.
  class RowStates {
   public:
    struct Slot {
      std::uint64_t key = 0;
      std::uint8_t frictionless = 0, final = 0;
    };
    void Clear();
    void Set(const Slot& slot);                 ///< replaces the slot of the same key
    const Slot* Find(std::uint64_t key) const;  ///< nullptr when absent

   private:
    size_t Home(std::uint64_t key) const;
    std::vector<Slot> slots_;
    size_t size_ = 0;
  };
  RowStates last_states, next_states;  ///< the last solve's, the one being solved

  // buffers (the solver's own)
  struct Block {         // an eliminated equality block of the island being solved
    int e0 = 0, ne = 0;  // its rows: e_rows[e0, e0 + ne)
    int c0 = 0, nc = 0;  // the bounded rows it touches: cols[c0, c0 + nc)
    size_t g0 = 0;       // its [W z] = L^-1 [A_eu b_e] from G[g0], ne rows of nc + 1
    size_t l0 = 0;       // its A_ee = L L^T from Aee[l0], ne x ne (envelope[e0...])
  };
  std::vector<Block> blocks;
  std::vector<int> island, block, row_root, order, local, cols, C, state, count, grouped;
  std::vector<Eigen::Matrix<double, 6, 1>> im0, im1, tmp, f;
  // update: a block's row of W^T [W z] while it is eliminated, its equality forces after
  std::vector<double> S, b, x, w, dx, dw, L, y, lo, hi, mu, Aee, G, update;
  std::vector<int> findex, u_rows, e_rows, first, envelope, span;
  std::vector<std::uint8_t> guess0, guess1;
};

/// Solves the rows' forces for one step of h seconds and adds their impulse and the external
/// forces' to the bodies' velocities. Rows of different islands (bodies that no row joins)
/// are solved apart. data->lambda holds the forces afterwards, in the rows' order.
void SolveConstraints(double h, const std::vector<ConstraintRow>& rows,
                      std::vector<SolverBody>* bodies, ConstraintSolverData* data);

}  // namespace graspsynth
