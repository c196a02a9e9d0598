#include "simulation/constraint_solver.hpp"

#include <algorithm>
#include <cmath>

namespace graspsynth {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Where each keyed row ended in a solve, without the friction rows and with them (0 free, 1 at
// its lower bound, 2 at its upper bound): an open-addressing table of its keys (key 0 marks an
// empty slot), kept from call to call so that a step allocates nothing.
class RowStates {
 public:
  struct Slot {
    std::uint64_t key = 0;
    std::uint8_t frictionless = 0, final = 0;
  };
  void Clear();
  void Set(const Slot& slot);                 // replaces the slot of the same key
  const Slot* Find(std::uint64_t key) const;  // nullptr when absent

 private:
  size_t Home(std::uint64_t key) const;
  std::vector<Slot> slots_;
  size_t size_ = 0;
};

void RowStates::Clear() {
  std::fill(slots_.begin(), slots_.end(), Slot{});
  size_ = 0;
}

size_t RowStates::Home(std::uint64_t key) const {
  // Fibonacci hashing: the high bits of key times 2^64 / golden ratio.
  return static_cast<size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & (slots_.size() - 1);
}

void RowStates::Set(const Slot& slot) {
  if (2 * (size_ + 1) > slots_.size()) {  // at most half full
    std::vector<Slot> old(std::max<size_t>(64, 2 * slots_.size()));
    old.swap(slots_);
    size_ = 0;
    for (const Slot& s : old) {
      if (s.key != 0) Set(s);
    }
  }
  for (size_t i = Home(slot.key);; i = (i + 1) & (slots_.size() - 1)) {
    if (slots_[i].key == 0) ++size_;
    if (slots_[i].key == 0 || slots_[i].key == slot.key) {
      slots_[i] = slot;
      return;
    }
  }
}

const RowStates::Slot* RowStates::Find(std::uint64_t key) const {
  if (slots_.empty() || key == 0) return nullptr;
  for (size_t i = Home(key);; i = (i + 1) & (slots_.size() - 1)) {
    if (slots_[i].key == key) return &slots_[i];
    if (slots_[i].key == 0) return nullptr;
  }
}

}  // namespace

// The solver's memory: the last forces, statistics, the rows' states and the buffers.
struct ConstraintSolverData::Work {
  std::vector<double> lambda;  // the rows' forces after the last solve (N or N m)
  ConstraintSolverStatistics stats;
  RowStates last_states, next_states;  // the last solve's, the one being solved

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

namespace {

using Work = ConstraintSolverData::Work;

int Find(std::vector<int>& parent, int i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

void Union(std::vector<int>& parent, int a, int b) {
  if (a < 0 || b < 0) return;
  a = Find(parent, a);
  b = Find(parent, b);
  if (a != b) parent[std::max(a, b)] = std::min(a, b);
}

bool IsEquality(const ConstraintRow& r) { return r.findex < 0 && r.lo == -kInf && r.hi == kInf; }

// *a = A_rs = J_r M^-1 J_s^T over the bodies the two rows share (im: M^-1 J_s^T on s's
// bodies); false, *a untouched, when they share none (A_rs = 0).
inline bool Coupling(const ConstraintRow& r, const ConstraintRow& s, const Vector6d& s_im0,
                     const Vector6d& s_im1, double* a) {
  bool shared = false;
  double v = 0.0;
  for (int k = 0; k < 2; ++k) {
    const int body = r.body[k];
    if (body < 0) continue;
    if (s.body[0] == body) {
      v += r.lin[k].dot(s_im0.head<3>()) + r.ang[k].dot(s_im0.tail<3>());
      shared = true;
    }
    if (s.body[1] == body) {
      v += r.lin[k].dot(s_im1.head<3>()) + r.ang[k].dot(s_im1.tail<3>());
      shared = true;
    }
  }
  if (shared) *a = v;
  return shared;
}

// The factors below take the envelope of a symmetric matrix: first[j] is the first column of
// row j's nonzeros in the lower triangle (nullptr: every row dense). A Cholesky factor keeps
// its matrix's envelope, and the loops skip the zeros outside it (a finger's hinge rows
// couple only neighbouring hinges' rows: about a quarter of the dense factor's work). Each
// divides by a pivot through its reciprocal, which is off the chain of dependent operations.
int First(const int* first, int j) { return first ? first[j] : 0; }

// In-place Cholesky factor (lower triangle) of the n x n matrix a, row-major with leading
// dimension ld. A pivot that is not positive (a matrix that is not positive definite, which
// the cfm of every row rules out) is kept tiny rather than failing.
void Cholesky(double* a, int n, int ld, const int* first) {
  // column by column: the rows below a pivot do not wait on each other.
  for (int k = 0; k < n; ++k) {
    double* ak = a + k * ld;
    const int fk = First(first, k);
    double d = ak[k];
    for (int l = fk; l < k; ++l) d -= ak[l] * ak[l];
    ak[k] = std::sqrt(std::max(d, 1e-300));
    const double inv = 1.0 / ak[k];
    for (int j = k + 1; j < n; ++j) {
      double* aj = a + j * ld;
      const int fj = First(first, j);
      if (fj > k) continue;
      double s = aj[k];
      for (int l = std::max(fj, fk); l < k; ++l) s -= aj[l] * ak[l];
      aj[k] = s * inv;
    }
  }
}

// x <- L^-1 x and x <- L^-T x for the lower factor L (n x n, leading dimension ld).
void SolveLower(const double* L, int n, int ld, const int* first, double* x) {
  for (int i = 0; i < n; ++i) {
    const double* li = L + i * ld;
    const double inv = 1.0 / li[i];
    double s = x[i];
    for (int k = First(first, i); k < i; ++k) s -= li[k] * x[k];
    x[i] = s * inv;
  }
}

void SolveLowerTransposed(const double* L, int n, int ld, const int* first, double* x) {
  for (int i = n - 1; i >= 0; --i) {
    const double* li = L + i * ld;
    const double xi = x[i] *= 1.0 / li[i];
    for (int k = First(first, i); k < i; ++k) x[k] -= li[k] * xi;
  }
}

// X <- L^-1 X for the m columns of X (row-major, n x m) side by side. A column's leading zeros
// stay zeros.
void SolveLowerColumns(const double* L, int n, int ld, const int* first, double* X, int m) {
  for (int i = 0; i < n; ++i) {
    const double* li = L + i * ld;
    double* xi = X + static_cast<size_t>(i) * m;
    for (int k = First(first, i); k < i; ++k) {
      const double lik = li[k];
      const double* xk = X + static_cast<size_t>(k) * m;
      for (int c = 0; c < m; ++c) xi[c] -= lik * xk[c];
    }
    const double inv = 1.0 / li[i];
    for (int c = 0; c < m; ++c) xi[c] *= inv;
  }
}

// The pivoting (Dantzig) solve of the bounded rows: S x = b + w with the box conditions, the
// rows taken in order, each driven until it satisfies its condition while the rows before
// it keep theirs. The friction rows come last; when the first is reached, every friction
// row's bounds are fixed from its normal row's force at that point, as in ODE. The Cholesky
// factor of S over the free set C (rows strictly inside their bounds) grows row by row and
// loses a row by Givens rotations when a row leaves C. S is symmetric positive definite (the rows'
// cfm), so the answer is unique: the one ODE's solver finds, to roundoff.
class BoxSolve {
 public:
  BoxSolve(int n, Work* d) : n_(n), d_(*d) { d_.mu = d_.hi; }

  // The answer from a guess of each row's state: the free rows' forces solved with the
  // others at their bounds, over the first `count` rows (the rest at zero); true when every
  // row then meets its condition (kMet), else the guess is amended from the rows that fail
  // (kAmended), or left as it is for a solve that is not a number (kFailed). A try costs one
  // factorisation.
  enum class Try { kMet, kAmended, kFailed };
  Try TryGuess(int count, std::vector<std::uint8_t>& guess) {
    std::vector<double>& x = d_.x;
    std::vector<int>& F = d_.C;
    F.clear();
    for (int i = 0; i < count; ++i) {
      const int g = guess[i];
      if (d_.lo[i] == d_.hi[i]) {
        x[i] = d_.lo[i];  // a row held at zero (friction on a normal that carries nothing)
      } else if (g == kLowGuess && d_.lo[i] > -kInf) {
        x[i] = d_.lo[i];
      } else if (g == kHighGuess && d_.hi[i] < kInf) {
        x[i] = d_.hi[i];
      } else {
        x[i] = 0.0;
        F.push_back(i);
      }
    }
    for (int i = count; i < n_; ++i) x[i] = 0.0;
    const int m = static_cast<int>(F.size());
    double* L = d_.L.data();
    double* y = d_.y.data();
    d_.first.resize(m);
    for (int a = 0; a < m; ++a) {
      const double* sa = &d_.S[static_cast<size_t>(F[a]) * n_];
      double* la = L + static_cast<size_t>(a) * n_;
      int fa = a;
      for (int c = a; c >= 0; --c) {
        la[c] = sa[F[c]];
        if (la[c] != 0.0) fa = c;
      }
      d_.first[a] = fa;
      double r = d_.b[F[a]];
      for (int j = 0; j < count; ++j) r -= sa[j] * x[j];  // the rows at their bounds
      y[a] = r;
    }
    Cholesky(L, m, n_, d_.first.data());
    SolveLower(L, m, n_, d_.first.data(), y);
    SolveLowerTransposed(L, m, n_, d_.first.data(), y);
    // every row's condition; a row that fails it changes its guess (a free row past a bound
    // goes to that bound, a row at a bound pushed the wrong way becomes free).
    bool met = true;
    for (int a = 0; a < m; ++a) {
      const int i = F[a];
      x[i] = y[a];
      if (y[a] < d_.lo[i]) {
        guess[i] = kLowGuess, met = false;
      } else if (y[a] > d_.hi[i]) {
        guess[i] = kHighGuess, met = false;
      } else if (!(y[a] >= d_.lo[i] && y[a] <= d_.hi[i])) {
        return Try::kFailed;  // not a number
      }
    }
    for (int i = 0, a = 0; i < count; ++i) {
      if (a < m && F[a] == i) {
        ++a;
        d_.state[i] = kFree;
        continue;
      }
      const double* si = &d_.S[static_cast<size_t>(i) * n_];
      double w = -d_.b[i];
      for (int j = 0; j < count; ++j) w += si[j] * x[j];
      const bool low = x[i] == d_.lo[i];
      if (d_.lo[i] != d_.hi[i] && (low ? w < 0.0 : w > 0.0)) guess[i] = kFreeGuess, met = false;
      d_.state[i] = low ? kLow : kHigh;
    }
    return met ? Try::kMet : Try::kAmended;
  }

  // Solves with the guesses of the rows' states (d.guess0 without the friction rows, d.guess1
  // with them) and falls back on the pivoting solve; d.guess0/1 hold the states found.
  void Solve() {
    d_.x.assign(n_, 0.0);
    d_.L.resize(static_cast<size_t>(n_) * n_);
    d_.y.resize(n_);
    d_.state.assign(n_, kUnset);
    int nf = n_;  // the rows before the friction rows
    while (nf > 0 && d_.findex[nf - 1] >= 0) --nf;
    if (Guess(nf, d_.guess0)) {
      for (int i = 0; i < nf; ++i) d_.guess0[i] = ToGuess(d_.state[i]);
      FixFrictionBounds(nf);
      if (nf == n_ || Guess(n_, d_.guess1)) {
        for (int i = 0; i < n_; ++i) d_.guess1[i] = ToGuess(d_.state[i]);
        ++d_.stats.guessed;
        if (amended_) ++d_.stats.amended;
        return;
      }
    }
    ++d_.stats.pivoted;
    Run();
  }

  // TryGuess from the guess, then from the guesses it amends, kGuesses times at most (the
  // amendments can cycle; the pivoting solve ends those).
  bool Guess(int count, std::vector<std::uint8_t>& guess) {
    for (int attempt = 0; attempt < kGuesses; ++attempt) {
      const Try t = TryGuess(count, guess);
      if (t == Try::kMet) {
        amended_ = amended_ || attempt > 0;
        return true;
      }
      if (t == Try::kFailed) break;
    }
    return false;
  }

  // the friction rows from `from` on get +-mu |normal force| as their bounds.
  void FixFrictionBounds(int from) {
    for (int k = from; k < n_; ++k) {
      if (d_.findex[k] < 0) continue;
      const double bound = std::fabs(d_.mu[k] * d_.x[d_.findex[k]]);
      d_.lo[k] = -bound;
      d_.hi[k] = bound;
    }
  }

  void Run() {
    std::vector<double>& x = d_.x;
    std::vector<double>& lo = d_.lo;
    std::vector<double>& hi = d_.hi;
    x.assign(n_, 0.0);
    d_.w.assign(n_, 0.0);
    d_.dx.assign(n_, 0.0);
    d_.dw.assign(n_, 0.0);
    d_.L.resize(static_cast<size_t>(n_) * n_);
    d_.y.resize(n_);
    d_.C.clear();
    d_.state.assign(n_, kUnset);
    const long limit = 20L * n_ + 20;
    long pivots = 0;
    bool friction_bounds_set = false;
    for (int i = 0; i < n_; ++i) {
      if (d_.findex[i] >= 0 && !friction_bounds_set) {
        friction_bounds_set = true;
        for (int k = 0; k < i; ++k) d_.guess0[k] = ToGuess(d_.state[k]);
        FixFrictionBounds(i);
      }
      // w_i = (S x)_i - b_i over the rows before it (the later ones are zero).
      const double* si = &d_.S[static_cast<size_t>(i) * n_];
      double wi = -d_.b[i];
      for (int j = 0; j < i; ++j) wi += si[j] * x[j];
      d_.w[i] = wi;
      if (lo[i] == 0.0 && wi >= 0.0) {
        d_.state[i] = kLow;
        continue;
      }
      if (hi[i] == 0.0 && wi <= 0.0) {
        d_.state[i] = kHigh;
        continue;
      }
      if (wi == 0.0) {
        AddToC(i);
        continue;
      }
      while (++pivots <= limit) {  // the limit is never reached on a definite matrix
        const double dir = d_.w[i] < 0.0 ? 1.0 : -1.0;
        Direction(i, dir);
        // the longest step before a row's condition changes.
        double s = -d_.w[i] / d_.dw[i];
        int which = i, kind = kFree;
        const double to_bound = dir > 0 ? hi[i] - x[i] : x[i] - lo[i];
        if (to_bound < s) {
          s = to_bound;
          kind = dir > 0 ? kHigh : kLow;
        }
        for (int j : d_.C) {
          const double dxj = d_.dx[j];
          if (dxj < 0.0 && lo[j] > -kInf) {
            const double t = (lo[j] - x[j]) / dxj;
            if (t < s) s = t, which = j, kind = kLow;
          } else if (dxj > 0.0 && hi[j] < kInf) {
            const double t = (hi[j] - x[j]) / dxj;
            if (t < s) s = t, which = j, kind = kHigh;
          }
        }
        for (int j = 0; j < i; ++j) {
          const int st = d_.state[j];
          if (st == kFree || (lo[j] == 0.0 && hi[j] == 0.0)) continue;
          const double dwj = d_.dw[j];
          if ((st == kLow && dwj < 0.0) || (st == kHigh && dwj > 0.0)) {
            const double t = -d_.w[j] / dwj;
            if (t < s) s = t, which = j, kind = kFree;
          }
        }
        s = std::max(s, 0.0);
        x[i] += s * dir;
        for (int j : d_.C) x[j] += s * d_.dx[j];
        for (int j = 0; j <= i; ++j) {
          if (d_.state[j] != kFree) d_.w[j] += s * d_.dw[j];
        }
        if (which == i) {
          if (kind == kFree) {
            AddToC(i);
          } else {
            x[i] = kind == kHigh ? hi[i] : lo[i];
            d_.state[i] = kind;
          }
          break;
        }
        if (kind == kFree) {
          AddToC(which);
        } else {
          x[which] = kind == kHigh ? hi[which] : lo[which];
          RemoveFromC(which, kind);
        }
      }
    }
    d_.stats.pivots += pivots;
    if (pivots > limit) ++d_.stats.unsolved;
    if (!friction_bounds_set) {
      for (int k = 0; k < n_; ++k) d_.guess0[k] = ToGuess(d_.state[k]);
    }
    for (int k = 0; k < n_; ++k) d_.guess1[k] = ToGuess(d_.state[k]);
  }

 private:
  enum { kUnset = 0, kLow = 1, kHigh = 2, kFree = 3 };
  static constexpr int kGuesses = 3;
  enum : std::uint8_t { kFreeGuess = 0, kLowGuess = 1, kHighGuess = 2 };
  static std::uint8_t ToGuess(int state) {
    return state == kLow ? kLowGuess : state == kHigh ? kHighGuess : kFreeGuess;
  }

  // dx over C for x_i moving by dir, and dw over the rows up to i that are not in C.
  void Direction(int i, double dir) {
    const int m = static_cast<int>(d_.C.size());
    double* y = d_.y.data();
    for (int k = 0; k < m; ++k) y[k] = -d_.S[static_cast<size_t>(d_.C[k]) * n_ + i] * dir;
    SolveLower(d_.L.data(), m, n_, nullptr, y);
    SolveLowerTransposed(d_.L.data(), m, n_, nullptr, y);
    for (int k = 0; k < m; ++k) d_.dx[d_.C[k]] = y[k];
    d_.dx[i] = dir;
    for (int j = 0; j <= i; ++j) {
      if (d_.state[j] == kFree) continue;
      const double* sj = &d_.S[static_cast<size_t>(j) * n_];
      double dw = sj[i] * dir;
      for (int k = 0; k < m; ++k) dw += sj[d_.C[k]] * y[k];
      d_.dw[j] = dw;
    }
  }

  void AddToC(int j) {
    const int m = static_cast<int>(d_.C.size());
    double* row = &d_.L[static_cast<size_t>(m) * n_];
    const double* sj = &d_.S[static_cast<size_t>(j) * n_];
    for (int k = 0; k < m; ++k) row[k] = sj[d_.C[k]];
    SolveLower(d_.L.data(), m, n_, nullptr, row);
    double d = sj[j];
    for (int k = 0; k < m; ++k) d -= row[k] * row[k];
    row[m] = std::sqrt(std::max(d, 1e-300));
    d_.C.push_back(j);
    d_.state[j] = kFree;
    d_.w[j] = 0.0;
  }

  // drops j from C and its row and column from the factor: the rows below it move up, and
  // Givens rotations of neighbouring columns make the factor lower triangular again.
  void RemoveFromC(int j, int kind) {
    std::vector<int>& C = d_.C;
    const int m = static_cast<int>(C.size());
    const int p = static_cast<int>(std::find(C.begin(), C.end(), j) - C.begin());
    C.erase(C.begin() + p);
    d_.state[j] = kind;
    double* L = d_.L.data();
    for (int r = p; r + 1 < m; ++r) {
      std::copy_n(L + static_cast<size_t>(r + 1) * n_, r + 2, L + static_cast<size_t>(r) * n_);
    }
    for (int c = p; c + 1 < m; ++c) {
      double* lc = L + static_cast<size_t>(c) * n_;
      const double a = lc[c], b = lc[c + 1];
      const double norm = std::hypot(a, b);
      const double cs = a / norm, sn = b / norm;
      lc[c] = norm;
      lc[c + 1] = 0.0;
      for (int r = c + 1; r + 1 < m; ++r) {
        double* lr = L + static_cast<size_t>(r) * n_;
        const double x = lr[c], y = lr[c + 1];
        lr[c] = cs * x + sn * y;
        lr[c + 1] = -sn * x + cs * y;
      }
    }
  }

  const int n_;
  Work& d_;
  bool amended_ = false;  // a guess was amended before it held
};

// Sorts `items` stably by group(item), a number in [0, groups) (a counting sort).
template <typename Group>
void GroupBy(std::vector<int>* items, const Group& group, int groups, Work* d) {
  d->count.assign(static_cast<size_t>(groups) + 1, 0);
  for (int i : *items) ++d->count[group(i) + 1];
  for (int g = 0; g < groups; ++g) d->count[g + 1] += d->count[g];
  d->grouped.resize(items->size());
  for (int i : *items) d->grouped[d->count[group(i)]++] = i;
  items->swap(d->grouped);
}

// c / h - J (v / h + M^-1 f) for one row, with tmp = v / h + M^-1 f per body.
double RightHandSide(const ConstraintRow& row, double inv_h, const std::vector<Vector6d>& tmp) {
  double jt = 0.0;
  for (int k = 0; k < 2; ++k) {
    const int body = row.body[k];
    if (body < 0) continue;
    jt += row.lin[k].dot(tmp[body].head<3>()) + row.ang[k].dot(tmp[body].tail<3>());
  }
  return row.c * inv_h - jt;
}

// the set root of a row's first moving body, -1 for a row on no moving body (set: each
// body's root, PrepareRows').
int RootOf(const ConstraintRow& r, const std::vector<int>& set) {
  return r.body[0] < 0 && r.body[1] < 0 ? -1 : set[r.body[r.body[0] >= 0 ? 0 : 1]];
}

// M^-1 J^T of each row on each of its bodies; the islands (bodies joined by any row) and the
// blocks (bodies joined by equality rows); v / h + M^-1 f per body; the rows grouped by
// island, each island's in their given order.
void PrepareRows(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& B,
                 double inv_h, Work* d) {
  const int nb = static_cast<int>(B.size());
  const int nr = static_cast<int>(rows.size());
  d->im0.resize(nr);
  d->im1.resize(nr);
  for (int r = 0; r < nr; ++r) {
    const ConstraintRow& row = rows[r];
    for (int k = 0; k < 2; ++k) {
      Vector6d& im = k == 0 ? d->im0[r] : d->im1[r];
      im.setZero();
      if (row.body[k] < 0) continue;
      const SolverBody& body = B[row.body[k]];
      im.head<3>() = body.inv_mass * row.lin[k];
      im.tail<3>() = body.inv_inertia_W * row.ang[k];
    }
  }
  d->island.resize(nb);
  d->block.resize(nb);
  for (int i = 0; i < nb; ++i) d->island[i] = d->block[i] = i;
  for (const ConstraintRow& r : rows) {
    Union(d->island, r.body[0], r.body[1]);
    if (IsEquality(r)) Union(d->block, r.body[0], r.body[1]);
  }
  for (int i = 0; i < nb; ++i) {  // each body's entry is its set's root from here on
    d->island[i] = Find(d->island, i);
    d->block[i] = Find(d->block, i);
  }
  d->tmp.resize(nb);
  for (int i = 0; i < nb; ++i) {
    d->tmp[i].head<3>() = B[i].v * inv_h + B[i].inv_mass * B[i].force;
    d->tmp[i].tail<3>() = B[i].w * inv_h + B[i].inv_inertia_W * B[i].torque;
  }
  d->row_root.resize(nr);
  d->order.clear();
  for (int r = 0; r < nr; ++r) {
    d->row_root[r] = RootOf(rows[r], d->island);
    if (d->row_root[r] >= 0) d->order.push_back(r);
  }
  GroupBy(
      &d->order, [&](int r) { return d->row_root[r]; }, nb, d);
}

// An island's rows [begin, end) of d->order: its bounded rows (friction rows last, ODE's
// order) and its equality rows by block; S = A_uu and b_u of the bounded rows.
void FormBounded(const std::vector<ConstraintRow>& rows, size_t begin, size_t end, double inv_h,
                 Work* d) {
  d->u_rows.clear();
  d->e_rows.clear();
  for (size_t k = begin; k < end; ++k) {
    const int r = d->order[k];
    if (IsEquality(rows[r])) {
      d->e_rows.push_back(r);
    } else if (rows[r].findex < 0) {
      d->u_rows.push_back(r);
    }
  }
  for (size_t k = begin; k < end; ++k) {
    if (rows[d->order[k]].findex >= 0) d->u_rows.push_back(d->order[k]);
  }
  GroupBy(
      &d->e_rows, [&](int r) { return RootOf(rows[r], d->block); },
      static_cast<int>(d->block.size()), d);
  const int nu = static_cast<int>(d->u_rows.size());
  for (int a = 0; a < nu; ++a) d->local[d->u_rows[a]] = a;
  d->stats.max_bounded_rows = std::max(d->stats.max_bounded_rows, nu);
  d->S.assign(static_cast<size_t>(nu) * nu, 0.0);
  d->b.resize(nu);
  for (int a = 0; a < nu; ++a) {
    const int r = d->u_rows[a];
    d->b[a] = RightHandSide(rows[r], inv_h, d->tmp);
    double* sa = &d->S[static_cast<size_t>(a) * nu];
    for (int c = 0; c <= a; ++c) {
      const int s = d->u_rows[c];
      Coupling(rows[r], rows[s], d->im0[s], d->im1[s], &sa[c]);
    }
    sa[a] += rows[r].cfm * inv_h;
  }
}

// Eliminates the equality block of d->e_rows[e0, e0 + ne) (block root `root`) from the bounded
// rows. With A_ee = L L^T and [W z] = L^-1 [A_eu b_e]: S -= W^T W, b_u -= W^T z (the lower
// triangle of S). Keeps L and [W z] for RecoverEquality.
void EliminateBlock(const std::vector<ConstraintRow>& rows, int e0, int ne, int root, double inv_h,
                    Work* d) {
  const int nu = static_cast<int>(d->u_rows.size());
  const int* er = &d->e_rows[e0];
  Work::Block blk;
  blk.e0 = e0;
  blk.ne = ne;
  blk.c0 = static_cast<int>(d->cols.size());
  blk.g0 = d->G.size();
  blk.l0 = d->Aee.size();
  for (int a = 0; a < nu; ++a) {
    const ConstraintRow& r = rows[d->u_rows[a]];
    if ((r.body[0] >= 0 && d->block[r.body[0]] == root) ||
        (r.body[1] >= 0 && d->block[r.body[1]] == root)) {
      d->cols.push_back(a);
    }
  }
  const int* cols = d->cols.data() + blk.c0;
  const int nc = blk.nc = static_cast<int>(d->cols.size()) - blk.c0;
  const int m = nc + 1;  // [W z]'s columns
  d->blocks.push_back(blk);
  // A_ee (lower, within its envelope, kept after the earlier blocks') and its factor;
  // [A_eu b_e] in X (row-major, ne x m) and the first row of each column's nonzeros (the
  // equality rows that share a body with its row).
  d->Aee.resize(blk.l0 + static_cast<size_t>(ne) * ne);
  double* L = &d->Aee[blk.l0];
  std::fill_n(L, static_cast<size_t>(ne) * ne, 0.0);
  d->envelope.resize(static_cast<size_t>(e0 + ne));
  int* first = &d->envelope[e0];
  d->G.resize(blk.g0 + static_cast<size_t>(ne) * m);
  double* X = &d->G[blk.g0];
  std::fill_n(X, static_cast<size_t>(ne) * m, 0.0);
  d->span.assign(nc, ne);
  for (int a = 0; a < ne; ++a) {
    const ConstraintRow& r = rows[er[a]];
    double* la = L + static_cast<size_t>(a) * ne;
    first[a] = a;
    for (int c = a; c >= 0; --c) {
      if (Coupling(r, rows[er[c]], d->im0[er[c]], d->im1[er[c]], &la[c])) first[a] = c;
    }
    la[a] += r.cfm * inv_h;
    double* xa = X + static_cast<size_t>(a) * m;
    for (int c = 0; c < nc; ++c) {
      const int s = d->u_rows[cols[c]];
      if (Coupling(r, rows[s], d->im0[s], d->im1[s], &xa[c])) {
        d->span[c] = std::min(d->span[c], a);
      }
    }
    xa[nc] = RightHandSide(r, inv_h, d->tmp);
  }
  Cholesky(L, ne, ne, first);
  SolveLowerColumns(L, ne, ne, first, X, m);
  // the update, W's columns side by side (column a is zero above its span).
  d->update.resize(m);
  double* u = d->update.data();
  for (int a = 0; a < nc; ++a) {
    std::fill_n(u, m, 0.0);
    for (int k = d->span[a]; k < ne; ++k) {
      const double* xk = X + static_cast<size_t>(k) * m;
      const double w = xk[a];
      for (int c = 0; c <= a; ++c) u[c] += w * xk[c];
      u[nc] += w * xk[nc];
    }
    d->b[cols[a]] -= u[nc];
    double* sa = &d->S[static_cast<size_t>(cols[a]) * nu];
    // cols ascend, so (cols[a], cols[c]) lies in the lower triangle.
    for (int c = 0; c <= a; ++c) sa[cols[c]] -= u[c];
  }
}

// The bounded rows' forces: bounds, the keyed rows' guesses from the last solve, the box
// solve, and the states kept for the next solve.
void SolveBounded(const std::vector<ConstraintRow>& rows, Work* d) {
  const int nu = static_cast<int>(d->u_rows.size());
  d->lo.resize(nu);
  d->hi.resize(nu);
  d->findex.assign(nu, -1);
  d->guess0.assign(nu, 0);
  d->guess1.assign(nu, 0);
  for (int a = 0; a < nu; ++a) {
    const ConstraintRow& r = rows[d->u_rows[a]];
    d->lo[a] = r.lo;
    d->hi[a] = r.hi;
    if (r.findex >= 0) d->findex[a] = d->local[r.findex];
    if (r.key == 0) continue;
    if (const RowStates::Slot* last = d->last_states.Find(r.key)) {
      d->guess0[a] = last->frictionless;
      d->guess1[a] = last->final;
    }
  }
  BoxSolve(nu, d).Solve();
  for (int a = 0; a < nu; ++a) {
    const ConstraintRow& r = rows[d->u_rows[a]];
    d->lambda[d->u_rows[a]] = d->x[a];
    if (r.key == 0) continue;
    d->next_states.Set({r.key, d->guess0[a], d->guess1[a]});
  }
}

// The equality rows' forces: A_ee^-1 (b_e - A_eu x_u) = L^-T (z - W x_u), block by block.
void RecoverEquality(Work* d) {
  for (const Work::Block& blk : d->blocks) {
    const int m = blk.nc + 1;
    d->update.resize(blk.ne);
    double* le = d->update.data();
    for (int a = 0; a < blk.ne; ++a) {
      const double* xa = &d->G[blk.g0 + static_cast<size_t>(a) * m];
      le[a] = xa[blk.nc];
      for (int c = 0; c < blk.nc; ++c) le[a] -= xa[c] * d->x[d->cols[blk.c0 + c]];
    }
    SolveLowerTransposed(&d->Aee[blk.l0], blk.ne, blk.ne, &d->envelope[blk.e0], le);
    for (int a = 0; a < blk.ne; ++a) d->lambda[d->e_rows[blk.e0 + a]] = le[a];
  }
}

// One island, the rows [begin, end) of d->order.
void SolveIsland(const std::vector<ConstraintRow>& rows, size_t begin, size_t end, double inv_h,
                 Work* d) {
  FormBounded(rows, begin, end, inv_h, d);
  d->blocks.clear();
  d->cols.clear();
  d->G.clear();
  d->Aee.clear();
  const int ne_all = static_cast<int>(d->e_rows.size());
  for (int e0 = 0; e0 < ne_all;) {
    const int root = RootOf(rows[d->e_rows[e0]], d->block);
    int e1 = e0;
    while (e1 < ne_all && RootOf(rows[d->e_rows[e1]], d->block) == root) ++e1;
    EliminateBlock(rows, e0, e1 - e0, root, inv_h, d);
    e0 = e1;
  }
  const int nu = static_cast<int>(d->u_rows.size());
  for (int a = 0; a < nu; ++a) {
    for (int c = 0; c < a; ++c) d->S[static_cast<size_t>(c) * nu + a] = d->S[a * nu + c];
  }
  SolveBounded(rows, d);
  RecoverEquality(d);
}

}  // namespace

ConstraintSolverData::ConstraintSolverData() : work_(std::make_unique<Work>()) {}
ConstraintSolverData::~ConstraintSolverData() = default;
ConstraintSolverData::ConstraintSolverData(ConstraintSolverData&&) noexcept = default;
ConstraintSolverData& ConstraintSolverData::operator=(ConstraintSolverData&&) noexcept = default;

const std::vector<double>& ConstraintSolverData::lambda() const { return work_->lambda; }

const ConstraintSolverStatistics& ConstraintSolverData::statistics() const { return work_->stats; }

void SolveConstraints(double h, const std::vector<ConstraintRow>& rows,
                      std::vector<SolverBody>* bodies, ConstraintSolverData* data) {
  Work* d = data->work_.get();
  const int nb = static_cast<int>(bodies->size());
  const int nr = static_cast<int>(rows.size());
  std::vector<SolverBody>& B = *bodies;
  const double inv_h = 1.0 / h;
  d->lambda.assign(nr, 0.0);
  d->next_states.Clear();
  PrepareRows(rows, B, inv_h, d);
  d->local.assign(nr, -1);
  for (size_t begin = 0; begin < d->order.size();) {
    size_t end = begin;
    while (end < d->order.size() && d->row_root[d->order[end]] == d->row_root[d->order[begin]]) {
      ++end;
    }
    SolveIsland(rows, begin, end, inv_h, d);
    begin = end;
  }
  std::swap(d->last_states, d->next_states);

  // v += h M^-1 (f + J^T lambda).
  d->f.resize(nb);
  for (int i = 0; i < nb; ++i) {
    d->f[i].head<3>() = B[i].force;
    d->f[i].tail<3>() = B[i].torque;
  }
  for (int r = 0; r < nr; ++r) {
    const ConstraintRow& row = rows[r];
    for (int k = 0; k < 2; ++k) {
      if (row.body[k] < 0) continue;
      d->f[row.body[k]].head<3>() += row.lin[k] * d->lambda[r];
      d->f[row.body[k]].tail<3>() += row.ang[k] * d->lambda[r];
    }
  }
  for (int i = 0; i < nb; ++i) {
    B[i].v += h * B[i].inv_mass * d->f[i].head<3>();
    B[i].w += h * (B[i].inv_inertia_W * d->f[i].tail<3>());
  }
}

}  // namespace graspsynth
