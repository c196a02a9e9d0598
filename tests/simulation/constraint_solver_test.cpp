#include "simulation/constraint_solver.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>

namespace graspsynth {
namespace {

constexpr double kH = 0.004;
constexpr double kInf = std::numeric_limits<double>::infinity();

// w = A lambda - b for every row, with the whole matrix formed directly (no elimination).
std::vector<double> Residual(const std::vector<ConstraintRow>& rows,
                             const std::vector<SolverBody>& before,
                             const std::vector<double>& lambda) {
  const size_t n = rows.size();
  auto im = [&](const ConstraintRow& r, int k) {
    Eigen::Matrix<double, 6, 1> v;
    const SolverBody& b = before[r.body[k]];
    v << b.inv_mass * r.lin[k], b.inv_inertia_W * r.ang[k];
    return v;
  };
  std::vector<double> w(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const ConstraintRow& r = rows[i];
    double b = r.c / kH;
    for (int k = 0; k < 2; ++k) {
      if (r.body[k] < 0) continue;
      const SolverBody& body = before[r.body[k]];
      b -= r.lin[k].dot(body.v / kH + body.inv_mass * body.force) +
           r.ang[k].dot(body.w / kH + body.inv_inertia_W * body.torque);
    }
    double a = r.cfm / kH * lambda[i];
    for (size_t j = 0; j < n; ++j) {
      const ConstraintRow& s = rows[j];
      for (int k = 0; k < 2; ++k) {
        for (int l = 0; l < 2; ++l) {
          if (r.body[k] < 0 || r.body[k] != s.body[l]) continue;
          const Eigen::Matrix<double, 6, 1> m = im(s, l);
          a += (r.lin[k].dot(m.head<3>()) + r.ang[k].dot(m.tail<3>())) * lambda[j];
        }
      }
    }
    w[i] = a - b;
  }
  return w;
}

SolverBody RandomBody(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), m(0.02, 0.5);
  SolverBody b;
  b.inv_mass = 1.0 / m(rng);
  const Eigen::Matrix3d R = Eigen::Quaterniond::UnitRandom().toRotationMatrix();
  const Eigen::Vector3d I(m(rng) * 1e-4, m(rng) * 1e-4, m(rng) * 1e-4);
  b.inv_inertia_W = R * I.cwiseInverse().asDiagonal() * R.transpose();
  b.v = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.1;
  b.w = Eigen::Vector3d(u(rng), u(rng), u(rng));
  b.force = Eigen::Vector3d(0.0, 0.0, -9.81 / b.inv_mass);
  return b;
}

Eigen::Vector3d RandomUnit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

// Random grasp-like problems: chains of bodies joined by equality rows (five per joint, the
// first joint on a fixed base), each joint with a bounded motor row, and contacts (a normal
// row and two friction rows) between the chains' bodies and one free body or the ground.
struct Problem {
  std::vector<SolverBody> bodies;
  std::vector<ConstraintRow> rows;
};

Problem RandomProblem(std::mt19937& rng, int chains, int links, int contacts) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Problem p;
  for (int i = 0; i < chains * links + 1; ++i) p.bodies.push_back(RandomBody(rng));
  const int object = chains * links;
  auto row = [&](int b0, int b1) {
    ConstraintRow r;
    r.body = {b0, b1};
    r.lin[0] = RandomUnit(rng);
    r.ang[0] = 0.03 * RandomUnit(rng);
    if (b1 >= 0) {
      r.lin[1] = -r.lin[0];
      r.ang[1] = 0.03 * RandomUnit(rng);
    }
    r.c = 0.01 * u(rng);
    r.cfm = 1e-9;
    return r;
  };
  for (int c = 0; c < chains; ++c) {
    for (int k = 0; k < links; ++k) {
      const int child = c * links + k, parent = k == 0 ? -1 : child - 1;
      for (int e = 0; e < 5; ++e) p.rows.push_back(row(child, parent));
      ConstraintRow motor = row(child, parent);
      motor.lin = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
      motor.c = 2.0 * u(rng);
      motor.lo = -0.05;
      motor.hi = 0.05;
      p.rows.push_back(motor);
    }
  }
  std::uniform_int_distribution<int> link(0, chains * links - 1);
  for (int i = 0; i < contacts; ++i) {
    const bool ground = i % 3 == 2;
    ConstraintRow normal = row(object, ground ? -1 : link(rng));
    normal.lo = 0.0;
    normal.hi = kInf;
    normal.c = 0.05 * (u(rng) + 1.0);
    normal.cfm = 1e-5;
    const int ni = static_cast<int>(p.rows.size());
    p.rows.push_back(normal);
    for (int t = 0; t < 2; ++t) {
      ConstraintRow f = row(normal.body[0], normal.body[1]);
      f.c = 0.0;
      f.lo = -0.8;
      f.hi = 0.8;
      f.findex = ni;
      p.rows.push_back(f);
    }
  }
  return p;
}

// Every row meets its condition: equality rows w = 0; a bounded row at its lower bound with
// w >= 0, at its upper bound with w <= 0, or strictly inside with w = 0; friction rows within
// +-mu times their normal's force without friction (the bounds ODE fixes).
TEST(SolveConstraints, EveryRowMeetsItsConditionOnRandomGraspLikeProblems) {
  std::mt19937 rng(7);
  ConstraintSolverData data, frictionless_data;
  int at_bound = 0, free_rows = 0, friction_at_bound = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Problem p = RandomProblem(rng, 1 + trial % 5, 4, trial % 9);
    const std::vector<SolverBody> before = p.bodies;
    SolveConstraints(kH, p.rows, &p.bodies, &data);
    // the forces without the friction rows fix the friction bounds.
    std::vector<ConstraintRow> frictionless;
    std::vector<int> index(p.rows.size(), -1);
    for (size_t i = 0; i < p.rows.size(); ++i) {
      if (p.rows[i].findex >= 0) continue;
      index[i] = static_cast<int>(frictionless.size());
      frictionless.push_back(p.rows[i]);
    }
    std::vector<SolverBody> scratch = before;
    SolveConstraints(kH, frictionless, &scratch, &frictionless_data);

    const std::vector<double>& x = data.lambda();
    const std::vector<double> w = Residual(p.rows, before, x);
    for (size_t i = 0; i < p.rows.size(); ++i) {
      const ConstraintRow& r = p.rows[i];
      double lo = r.lo, hi = r.hi;
      if (r.findex >= 0) {
        hi = std::fabs(r.hi * frictionless_data.lambda()[index[r.findex]]);
        lo = -hi;
      }
      const double scale = 1e-6 * (1.0 + std::fabs(x[i]));
      const double wtol = 1e-6 * (1.0 + std::fabs(w[i]) + 1e3);
      ASSERT_GE(x[i], lo - scale) << "trial " << trial << " row " << i;
      ASSERT_LE(x[i], hi + scale) << "trial " << trial << " row " << i;
      if (lo == hi) {
        EXPECT_EQ(x[i], 0.0);  // friction on a normal that carries nothing: any w
        continue;
      }
      if (x[i] <= lo + scale && lo > -kInf) {
        EXPECT_GE(w[i], -wtol) << "trial " << trial << " row " << i;
        ++at_bound;
        friction_at_bound += r.findex >= 0;
      } else if (x[i] >= hi - scale && hi < kInf) {
        EXPECT_LE(w[i], wtol) << "trial " << trial << " row " << i;
        ++at_bound;
        friction_at_bound += r.findex >= 0;
      } else {
        EXPECT_NEAR(w[i], 0.0, wtol) << "trial " << trial << " row " << i;
        ++free_rows;
      }
    }
    // and the velocities moved by h M^-1 (f + J^T lambda).
    for (size_t b = 0; b < p.bodies.size(); ++b) {
      Eigen::Vector3d f = before[b].force, t = before[b].torque;
      for (size_t i = 0; i < p.rows.size(); ++i) {
        for (int k = 0; k < 2; ++k) {
          if (p.rows[i].body[k] != static_cast<int>(b)) continue;
          f += p.rows[i].lin[k] * x[i];
          t += p.rows[i].ang[k] * x[i];
        }
      }
      const Eigen::Vector3d v = before[b].v + kH * before[b].inv_mass * f;
      const Eigen::Vector3d om = before[b].w + kH * before[b].inv_inertia_W * t;
      EXPECT_LT((p.bodies[b].v - v).norm(), 1e-9 * (1.0 + v.norm()));
      EXPECT_LT((p.bodies[b].w - om).norm(), 1e-9 * (1.0 + om.norm()));
    }
  }
  // the problems exercise both kinds of rows, friction at its bound included.
  EXPECT_GT(at_bound, 100);
  EXPECT_GT(free_rows, 100);
  EXPECT_GT(friction_at_bound, 10);
}

// With keys, the solver first tries the states the same rows ended at in the last solve: the
// same problem solved again is answered at that guess, with the same forces as without one;
// a wrong guess (the keys of another problem's rows) is amended or, failing that, left for the
// pivoting solve, with the same forces too.
TEST(SolveConstraints, AKeyedRowsGuessGivesTheSameAnswer) {
  std::mt19937 rng(11);
  int guessed = 0;
  ConstraintSolverData stale;  // keeps the keys of every earlier problem
  for (int trial = 0; trial < 50; ++trial) {
    Problem p = RandomProblem(rng, 1 + trial % 5, 4, trial % 9);
    for (size_t i = 0; i < p.rows.size(); ++i) p.rows[i].key = 100 + i;
    const std::vector<SolverBody> before = p.bodies;
    ConstraintSolverData cold, warm;
    std::vector<SolverBody> a = before, b = before;
    SolveConstraints(kH, p.rows, &a, &cold);
    SolveConstraints(kH, p.rows, &b, &warm);  // learns the states
    const long before_guessed = warm.statistics().guessed;
    b = before;
    SolveConstraints(kH, p.rows, &b, &warm);  // starts from them
    guessed += warm.statistics().guessed > before_guessed;
    std::vector<SolverBody> c = before;
    SolveConstraints(kH, p.rows, &c, &stale);
    for (size_t i = 0; i < p.rows.size(); ++i) {
      EXPECT_NEAR(stale.lambda()[i], cold.lambda()[i], 1e-6 * (1.0 + std::fabs(cold.lambda()[i])))
          << "trial " << trial << " row " << i << " (stale guess)";
    }
    for (size_t i = 0; i < p.rows.size(); ++i) {
      EXPECT_NEAR(warm.lambda()[i], cold.lambda()[i], 1e-6 * (1.0 + std::fabs(cold.lambda()[i])))
          << "trial " << trial << " row " << i;
    }
    for (size_t k = 0; k < a.size(); ++k) {
      EXPECT_LT((a[k].v - b[k].v).norm(), 1e-9 * (1.0 + a[k].v.norm()));
    }
  }
  EXPECT_EQ(guessed, 50);
  EXPECT_GT(stale.statistics().amended, 0);  // stale guesses were amended
  EXPECT_GT(stale.statistics().pivoted, 0);  // or rejected
}

// A body resting on the ground through one contact: the normal force carries its weight and
// the body does not move (the contact's correction aside).
TEST(SolveConstraints, AContactCarriesTheWeightOfABodyAtRest) {
  std::vector<SolverBody> bodies(1);
  bodies[0].inv_mass = 1.0 / 0.3;
  bodies[0].inv_inertia_W = Eigen::Matrix3d::Identity() * 1e3;
  bodies[0].force = Eigen::Vector3d(0.0, 0.0, -9.81 * 0.3);
  std::vector<ConstraintRow> rows(3);
  rows[0].body = {0, -1};
  rows[0].lin[0] = Eigen::Vector3d::UnitZ();
  rows[0].lo = 0.0;
  rows[0].cfm = 1e-9;
  for (int t = 1; t <= 2; ++t) {
    rows[t].body = {0, -1};
    rows[t].lin[0] = Eigen::Vector3d::Unit(t - 1);
    rows[t].lo = -0.5;
    rows[t].hi = 0.5;
    rows[t].findex = 0;
    rows[t].cfm = 1e-9;
  }
  ConstraintSolverData data;
  SolveConstraints(kH, rows, &bodies, &data);
  EXPECT_NEAR(data.lambda()[0], 9.81 * 0.3, 1e-6);
  EXPECT_NEAR(data.lambda()[1], 0.0, 1e-9);
  EXPECT_LT(bodies[0].v.norm(), 1e-8);
}

// A body pushed sideways on the ground slides once the push exceeds mu times its weight:
// friction stops at its bound.
TEST(SolveConstraints, FrictionStopsAtMuTimesTheNormalForce) {
  for (double push : {1.0, 2.0}) {
    std::vector<SolverBody> bodies(1);
    bodies[0].inv_mass = 1.0;
    bodies[0].inv_inertia_W = Eigen::Matrix3d::Identity();
    bodies[0].force = Eigen::Vector3d(push, 0.0, -10.0);
    std::vector<ConstraintRow> rows(2);
    rows[0].body = {0, -1};
    rows[0].lin[0] = Eigen::Vector3d::UnitZ();
    rows[0].lo = 0.0;
    rows[1].body = {0, -1};
    rows[1].lin[0] = Eigen::Vector3d::UnitX();
    rows[1].lo = -0.15;
    rows[1].hi = 0.15;
    rows[1].findex = 0;
    ConstraintSolverData data;
    SolveConstraints(kH, rows, &bodies, &data);
    EXPECT_NEAR(data.lambda()[0], 10.0, 1e-9);
    if (push < 1.5) {
      EXPECT_NEAR(data.lambda()[1], -push, 1e-9);  // sticks
      EXPECT_NEAR(bodies[0].v.x(), 0.0, 1e-12);
    } else {
      EXPECT_NEAR(data.lambda()[1], -1.5, 1e-9);  // slides
      EXPECT_NEAR(bodies[0].v.x(), kH * 0.5, 1e-12);
    }
  }
}

}  // namespace
}  // namespace graspsynth
