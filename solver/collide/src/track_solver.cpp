#include "track_solver.h"

#include "band_cholesky.h"

#include <throng/core/errors.h>
#include <throng/graph/features.h>
#include <throng/linalg/least_squares.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>
#include <string>
#include <vector>

namespace throng::collide {
namespace {

using Index = Eigen::Index;
using Triplet = Eigen::Triplet<double>;
using Sparse = linalg::SparseMatrix;
using Displacement = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// Spreads above this count as this: the anchor weight stays ≥ 1e-12 of the temporal weights, so the system
// without pins (whose similarity modes only the anchor holds) stays well conditioned.
constexpr double spread_cap = 1000.0;

// Smoothing times of more frames than this count as this: the anchor weight λ w̄ / n⁴ stays ≥ 1.6e-7 of the
// bending weight, so the system keeps a condition number below ~1e8 and the three track methods agree to 1e-10
// m (at 30 frames per second catch_up_time counts up to 1.7 s; at 5 fps, 10 s).
constexpr double smoothing_cap = 50.0;

// The objective of one track over all 2·length unknowns: A, its row weights, and which unknowns are free.
struct Objective {
  Sparse A;
  Eigen::VectorXd weights;
  std::vector<Index> free_of;     // unknown → free index, −1 when pinned
  std::vector<Index> unknown_of;  // free index → unknown
};

Objective make_objective(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned,
                         const Options& options, double interval_s) {
  const Index length = positions.rows();
  FeatureOptions feature_options;
  feature_options.min_length = options.min_feature_length;
  const Index features = length >= 3 ? length - 2 : 0;
  const Index steps = length - 1;
  const bool smooth = options.smoothing_time > 0;
  const Index bends = smooth ? features : 0;  // acceleration rows d_{k−1} − 2 d_k + d_{k+1}
  const Index rows = 2 * features + 2 * bends + 2 * steps + 2 * length;
  std::vector<Triplet> entries;
  entries.reserve(static_cast<std::size_t>(12 * features + 6 * bends + 4 * steps + 2 * length));
  Objective o;
  o.weights.resize(rows);
  // Temporal features: residual d_v − (1 − c) d_u − c d_w as two real rows (complex coefficients, Eq. 1).
  for (Index k = 1; k + 1 < length; ++k) {
    const Feature f = make_feature(static_cast<int>(k - 1), static_cast<int>(k), static_cast<int>(k + 1),
                                   positions.row(k - 1).transpose(), positions.row(k).transpose(),
                                   positions.row(k + 1).transpose(), feature_options);
    const Index row = 2 * (k - 1);
    const int vertex[3] = {f.v, f.u, f.w};
    const std::complex<double> coefficient[3] = {1.0, -(1.0 - f.c), -f.c};
    for (int j = 0; j < 3; ++j) {
      const Index x = 2 * static_cast<Index>(vertex[j]);
      const std::complex<double> a = coefficient[j];
      entries.emplace_back(row, x, a.real());
      entries.emplace_back(row + 1, x + 1, a.real());
      if (a.imag() != 0.0) {
        entries.emplace_back(row, x + 1, -a.imag());
        entries.emplace_back(row + 1, x, a.imag());
      }
    }
    o.weights[row] = o.weights[row + 1] = f.weight;
  }
  const double mean_weight = features > 0 ? o.weights.head(2 * features).mean() : 1.0;
  // Velocity and anchor weights across (and, with smoothing, along) the agent's path.
  double velocity = 0, anchor = 0, velocity_along = 0, anchor_along = 0;
  if (smooth) {
    // Smoothing in time (collide.h "Deformation of one trajectory"): with n = T / h frames, the rows
    // Δ²d, Δd and d weighted λ w̄ (1, 2/n², 1/n⁴) are the discrete ∫ T⁴|d″|² + 2T²|d′|² + |d|² dt, whose
    // response to a push is (1 + |t|/T) e^{−|t|/T}; along the path the same with n = catch_up_time / h.
    const double n = std::min(options.smoothing_time / interval_s, smoothing_cap);
    const double m = std::min(std::max(options.catch_up_time, options.smoothing_time) / interval_s, smoothing_cap);
    const double bend = options.smoothing_weight * mean_weight;
    velocity = 2 * bend / (n * n);
    anchor = bend / (n * n * n * n);
    velocity_along = 2 * bend / (m * m);
    anchor_along = bend / (m * m * m * m);
    for (Index k = 1; k + 1 < length; ++k) {
      for (Index axis = 0; axis < 2; ++axis) {
        const Index row = 2 * features + 2 * (k - 1) + axis;
        entries.emplace_back(row, 2 * (k - 1) + axis, 1.0);
        entries.emplace_back(row, 2 * k + axis, -2.0);
        entries.emplace_back(row, 2 * (k + 1) + axis, 1.0);
        o.weights[row] = bend;
      }
    }
  } else {
    // Velocity: every step's change d_{k+1} − d_k (the change of the step vector, so of the velocity), weight
    // velocity_weight · (mean temporal weight). Anchor: every unknown, weight (velocity weight) / spread²; the
    // two balance at about `spread` frames, so a push fades as exp(−|k|/spread) (with velocity_weight 0 the
    // anchor is (mean temporal weight) / spread⁴ against the bending term).
    const double spread = std::min(options.spread, spread_cap);
    velocity = options.velocity_weight * mean_weight;
    anchor = velocity > 0 ? velocity / (spread * spread) : mean_weight / std::pow(spread, 4);
    velocity_along = velocity;
    anchor_along = anchor;
  }
  // The rows in the path's own frame: t̂ (along, the direction of the input's motion there) and its left normal.
  // A vertex (or step) where the input does not move has no direction: both rows take the across weights.
  auto direction = [&](Index from, Index to) -> Eigen::Vector2d {
    const Eigen::Vector2d d = positions.row(std::min(to, length - 1)) - positions.row(std::max<Index>(from, 0));
    const double norm = d.norm();
    return norm > 1e-9 ? Eigen::Vector2d(d / norm) : Eigen::Vector2d::Zero();
  };
  auto frame_rows = [&](Index row, const Eigen::Vector2d& along, const std::vector<std::pair<Index, double>>& terms,
                        double weight_along, double weight_across) {
    const bool oriented = along.squaredNorm() > 0;
    const Eigen::Vector2d t = oriented ? along : Eigen::Vector2d(1, 0), n(-t.y(), t.x());
    for (const auto& [vertex, c] : terms) {
      entries.emplace_back(row, 2 * vertex, c * t.x());
      entries.emplace_back(row, 2 * vertex + 1, c * t.y());
      entries.emplace_back(row + 1, 2 * vertex, c * n.x());
      entries.emplace_back(row + 1, 2 * vertex + 1, c * n.y());
    }
    o.weights[row] = oriented ? weight_along : weight_across;
    o.weights[row + 1] = weight_across;
  };
  for (Index k = 0; k < steps; ++k) {
    frame_rows(2 * features + 2 * bends + 2 * k, direction(k, k + 1), {{k, -1.0}, {k + 1, 1.0}}, velocity_along, velocity);
  }
  for (Index k = 0; k < length; ++k) {
    frame_rows(2 * features + 2 * bends + 2 * steps + 2 * k, direction(k - 1, k + 1), {{k, 1.0}}, anchor_along, anchor);
  }
  o.A.resize(rows, 2 * length);
  o.A.setFromTriplets(entries.begin(), entries.end());
  o.free_of.assign(static_cast<std::size_t>(2 * length), -1);
  for (Index k = 0; k < length; ++k) {
    if (pinned[static_cast<std::size_t>(k)] != 0) continue;
    for (Index axis = 0; axis < 2; ++axis) {
      o.free_of[static_cast<std::size_t>(2 * k + axis)] = static_cast<Index>(o.unknown_of.size());
      o.unknown_of.push_back(2 * k + axis);
    }
  }
  return o;
}

// One constraint row on the free unknowns: Σ c[a] x[u[a]] = target (u[1] = −1 when one unknown carries it).
struct Row {
  Index u[2] = {-1, -1};
  double c[2] = {0.0, 0.0};
  double target = 0.0;
  Index unknown[2] = {-1, -1};  // the same entries as unknowns of the whole track (for the linalg path)
};

std::vector<Row> constraint_rows(const std::vector<PointConstraint>& constraints, const std::vector<Index>& free_of) {
  std::vector<Row> rows;
  rows.reserve(2 * constraints.size());
  for (const PointConstraint& c : constraints) {
    for (Index axis = 0; axis < 2; ++axis) {
      Row r;
      r.unknown[0] = 2 * c.v0 + axis;
      r.u[0] = free_of[static_cast<std::size_t>(r.unknown[0])];
      r.c[0] = c.c0;
      if (c.c1 != 0.0) {
        r.unknown[1] = 2 * c.v1 + axis;
        r.u[1] = free_of[static_cast<std::size_t>(r.unknown[1])];
        r.c[1] = c.c1;
      }
      r.target = c.target[axis];
      rows.push_back(r);
    }
  }
  return rows;
}

double row_value(const Row& r, const Eigen::Ref<const Eigen::VectorXd>& x) {
  return r.c[0] * x[r.u[0]] + (r.u[1] >= 0 ? r.c[1] * x[r.u[1]] : 0.0);
}

void check_met(const std::vector<Row>& rows, const Eigen::VectorXd& x) {
  double worst = 0.0, largest = 0.0;
  for (const Row& r : rows) {
    worst = std::max(worst, std::abs(row_value(r, x) - r.target));
    largest = std::max(largest, std::abs(r.target));
  }
  // Rounding: the smoothing in time makes Q's condition number up to ~1e8 (smoothing_cap), so a solve through a
  // Schur complement (schur, linalg) meets its rows to ~1e-8 of the largest push; beyond 1e-7 it went wrong.
  if (!(worst <= 1e-7 * largest + 1e-14)) {
    throw NumericalError("collide: a trajectory's pushes could not be met (residual " + std::to_string(worst) + " m)");
  }
}

Displacement to_displacement(Index length, const std::vector<Index>& unknown_of, const Eigen::VectorXd& x) {
  Displacement d = Displacement::Zero(length, 2);
  for (std::size_t f = 0; f < unknown_of.size(); ++f) d(unknown_of[f] / 2, unknown_of[f] % 2) = x[static_cast<Index>(f)];
  return d;
}

// Q = AᵀWA over the free unknowns as a band (the free numbering keeps the natural order, so the half-bandwidth
// stays ≤ 5: a vertex couples with two neighbours on each side), with the objective's maps.
struct BandedObjective {
  BandCholesky Q;
  std::vector<Index> free_of, unknown_of;
};

BandedObjective banded_objective(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned,
                                 const Options& options, double interval_s) {
  constexpr Index p = 5;
  Objective o = make_objective(positions, pinned, options, interval_s);
  BandedObjective b;
  b.free_of = std::move(o.free_of);
  b.unknown_of = std::move(o.unknown_of);
  const auto n = static_cast<Index>(b.unknown_of.size());
  // Q = Σ_rows w_r a_r a_rᵀ over the free unknowns, accumulated row by row into the band (each row touches at
  // most three neighbouring vertices).
  const Eigen::SparseMatrix<double, Eigen::RowMajor, Index> rows = o.A;
  b.Q.reset(n, p);
  for (Index r = 0; r < rows.outerSize(); ++r) {
    const double w = o.weights[r];
    for (Eigen::SparseMatrix<double, Eigen::RowMajor, Index>::InnerIterator i(rows, r); i; ++i) {
      const Index fi = b.free_of[static_cast<std::size_t>(i.col())];
      if (fi < 0) continue;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor, Index>::InnerIterator j(rows, r); j; ++j) {
        const Index fj = b.free_of[static_cast<std::size_t>(j.col())];
        if (fj < 0 || fj > fi) continue;
        if (fi - fj > p) throw std::logic_error("collide: a trajectory's system is wider than its band");
        b.Q.at(fi, fj) += w * i.value() * j.value();
      }
    }
  }
  return b;
}

void factorize_or_throw(BandCholesky& band, const std::string& what) {
  Index failed_at = 0;
  if (!band.factorize(failed_at)) {
    throw NumericalError("collide: a trajectory's " + what + " (" + std::to_string(band.size()) +
                         " unknowns) is not positive definite at unknown " + std::to_string(failed_at));
  }
}

// --- eliminate: each push row solved for one of its unknowns, the rest solved in a window ---
//
// A row c_e x_e + c_o x_o = t is met by x_e = t/c_e − (c_o/c_e) x_o, where e is the unknown with the larger
// |c| (so |c_o/c_e| ≤ 1: no growth); a row on one unknown fixes it. With every free unknown in at most one row,
// x = Z y + x0, Z identity on the kept unknowns y and one entry −c_o/c_e on an eliminated row; the constrained
// minimiser is y = H⁻¹ g with H = ZᵀQZ, g = −ZᵀQ x0. H is SPD (Z has full column rank) and a band: an
// eliminated unknown's couplings move to its partner, a vertex away (half-bandwidth at most 9).
//
// H differs from Q only in the window W = [lo − 5, hi + 5] around the constrained unknowns lo .. hi, and g is
// zero outside it. So with T the unknowns before W and B those after: Q = L Lᵀ (top-down, once) gives
// Q_WT Q_TT⁻¹ Q_TW = L_WT L_WTᵀ, nonzero on W's first 5 unknowns only; Q = V Vᵀ (V upper triangular: the
// Cholesky factor of Q in reversed order, once) gives the same from B on W's last 5. The window system
// (H_WW − L_WT L_WTᵀ − V_WB V_WBᵀ) y_W = g_W is factorised per solve; then y_T = −L_TT⁻ᵀ L_WTᵀ y_W and
// y_B = −V_BB⁻ᵀ V_WBᵀ y_W, one back substitution each. Exact (block elimination of the same system), at
// O(|W|·9² + n·5) per solve, where the pushes of one trajectory and iteration span 5 % of it in the configs.
class EliminationSolver final : public TrackSolver {
 public:
  EliminationSolver(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned, const Options& options,
                    double interval_s)
      : length_(positions.rows()), objective_(banded_objective(positions, pinned, options, interval_s)) {
    const BandCholesky& Q = objective_.Q;
    const Index n = Q.size(), p = Q.bandwidth();
    top_ = Q;
    factorize_or_throw(top_, "deformation system");
    bottom_.reset(n, p);  // Q in reversed order: R(i, j) = Q(n − 1 − i, n − 1 − j)
    for (Index i = 0; i < n; ++i) {
      for (Index j = std::max<Index>(0, i - p); j <= i; ++j) bottom_.at(i, j) = Q.at(n - 1 - j, n - 1 - i);
    }
    factorize_or_throw(bottom_, "deformation system");
  }

  Displacement solve(const std::vector<PointConstraint>& constraints) override {
    const std::vector<Row> rows = constraint_rows(constraints, objective_.free_of);
    const BandCholesky& Q = objective_.Q;
    const Index n = Q.size(), p = Q.bandwidth();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    if (rows.empty() || n == 0) {
      check_met(rows, x);
      return to_displacement(length_, objective_.unknown_of, x);
    }
    Index lo = n, hi = -1;
    for (const Row& r : rows) {
      for (int a = 0; a < 2; ++a) {
        if (r.u[a] >= 0) {
          lo = std::min(lo, r.u[a]);
          hi = std::max(hi, r.u[a]);
        }
      }
    }
    const Index w0 = std::max<Index>(0, lo - p), w1 = std::min(n, hi + p + 1), w = w1 - w0;
    // Roles in the window (local index u − w0): kept_[u] the local reduced index of a kept unknown, −1 when
    // eliminated; an eliminated unknown is base_[u] + coef_[u] · x[via_[u]] (via_ −1: fixed at base_).
    kept_.assign(static_cast<std::size_t>(w), 0);
    via_.assign(static_cast<std::size_t>(w), -1);
    coef_.assign(static_cast<std::size_t>(w), 1.0);
    base_.setZero(w);
    for (const Row& r : rows) {
      const int e = r.u[1] >= 0 && std::abs(r.c[1]) > std::abs(r.c[0]) ? 1 : 0;
      const Index ue = r.u[e] - w0, uo = r.u[1 - e] >= 0 ? r.u[1 - e] - w0 : -1;
      for (Index u : {ue, uo}) {
        if (u >= 0 && kept_[static_cast<std::size_t>(u)] != 0) {
          throw std::logic_error("collide: two pushes of one iteration share a trajectory vertex");
        }
      }
      kept_[static_cast<std::size_t>(ue)] = -1;
      if (uo >= 0) kept_[static_cast<std::size_t>(uo)] = 1;  // used; kept
      base_[ue] = r.target / r.c[e];
      if (uo >= 0) {
        via_[static_cast<std::size_t>(ue)] = uo;
        coef_[static_cast<std::size_t>(ue)] = -r.c[1 - e] / r.c[e];
      }
    }
    Index reduced = 0;
    for (Index& k : kept_) k = k < 0 ? -1 : reduced++;
    // Where each window unknown lands in the window's reduced system, with which factor (−1: a constant).
    target_.resize(static_cast<std::size_t>(w));
    factor_.resize(static_cast<std::size_t>(w));
    for (Index u = 0; u < w; ++u) {
      const auto s = static_cast<std::size_t>(u);
      if (kept_[s] >= 0) {
        target_[s] = kept_[s];
        factor_[s] = 1.0;
      } else if (via_[s] >= 0) {
        target_[s] = kept_[static_cast<std::size_t>(via_[s])];
        factor_[s] = coef_[s];
      } else {
        target_[s] = -1;
        factor_[s] = 0.0;
      }
    }
    auto q_at = [&](Index i, Index j) { return Q.at(w0 + i, w0 + j); };  // window-local, i ≥ j
    Eigen::VectorXd y = Eigen::VectorXd::Zero(reduced);
    if (reduced > 0) {
      Index q = 0;
      for (Index i = 0; i < w; ++i) {
        const Index ki = target_[static_cast<std::size_t>(i)];
        if (ki < 0) continue;
        for (Index j = std::max<Index>(0, i - p); j < i; ++j) {
          const Index kj = target_[static_cast<std::size_t>(j)];
          if (kj >= 0 && q_at(i, j) != 0.0) q = std::max(q, std::abs(ki - kj));
        }
      }
      H_.reset(reduced, std::max(q, p));  // ≥ p: the corrections below fill W's first and last p × p blocks
      for (Index i = 0; i < w; ++i) {
        const Index ki = target_[static_cast<std::size_t>(i)];
        if (ki < 0) continue;
        const double zi = factor_[static_cast<std::size_t>(i)];
        H_.at(ki, ki) += zi * zi * q_at(i, i);
        for (Index j = std::max<Index>(0, i - p); j < i; ++j) {
          const Index kj = target_[static_cast<std::size_t>(j)];
          if (kj < 0) continue;
          const double v = zi * q_at(i, j) * factor_[static_cast<std::size_t>(j)];
          if (ki == kj) {
            H_.at(ki, ki) += 2.0 * v;
          } else {
            H_.at(std::max(ki, kj), std::min(ki, kj)) += v;
          }
        }
      }
      // The unknowns before and after the window, eliminated through the stored factors. W's first p and last
      // p unknowns are kept (they are outside lo .. hi), with local reduced indices 0 .. p − 1 and
      // reduced − p .. reduced − 1.
      if (w0 > 0) {
        for (Index i = 0; i < p; ++i) {
          for (Index j = 0; j <= i; ++j) {
            double s = 0.0;
            for (Index k = std::max<Index>(0, w0 + i - p); k < w0; ++k) s += top_.at(w0 + i, k) * top_.at(w0 + j, k);
            H_.at(i, j) -= s;
          }
        }
      }
      if (w1 < n) {
        // In reversed order B is the leading block [0, n − w1) and W's last p unknowns are n − w1 .. n − w1 + p − 1.
        const Index b = n - w1;
        for (Index i = 0; i < p; ++i) {
          for (Index j = 0; j <= i; ++j) {
            double s = 0.0;
            for (Index k = std::max<Index>(0, b + i - p); k < b; ++k) s += bottom_.at(b + i, k) * bottom_.at(b + j, k);
            H_.at(reduced - 1 - j, reduced - 1 - i) -= s;
          }
        }
      }
      // g = −Zᵀ Q x0 (x0 = base_ in the window, zero elsewhere: Q x0 is zero outside the window).
      for (Index i = 0; i < w; ++i) {
        double qx = 0.0;
        for (Index j = std::max<Index>(0, i - p); j <= std::min(w - 1, i + p); ++j) qx += (j <= i ? q_at(i, j) : q_at(j, i)) * base_[j];
        const Index k = target_[static_cast<std::size_t>(i)];
        if (k >= 0) y[k] -= factor_[static_cast<std::size_t>(i)] * qx;
      }
      factorize_or_throw(H_, "deformation system with its pushes eliminated");
      H_.solve(y);
    }
    for (Index u = 0; u < w; ++u) {
      const Index k = target_[static_cast<std::size_t>(u)];
      x[w0 + u] = base_[u] + (k >= 0 ? factor_[static_cast<std::size_t>(u)] * y[k] : 0.0);
    }
    // y_T = −L_TT⁻ᵀ L_WTᵀ y_W, y_B likewise through the reversed factor.
    if (w0 > 0) {
      for (Index i = 0; i < p; ++i) {
        for (Index k = std::max<Index>(0, w0 + i - p); k < w0; ++k) x[k] -= top_.at(w0 + i, k) * x[w0 + i];
      }
      top_.backward(x, w0);
    }
    if (w1 < n) {
      const Index b = n - w1;
      reversed_.setZero(b);
      for (Index i = 0; i < p; ++i) {
        for (Index k = std::max<Index>(0, b + i - p); k < b; ++k) reversed_[k] -= bottom_.at(b + i, k) * x[w1 - 1 - i];
      }
      bottom_.backward(reversed_, b);
      for (Index k = 0; k < b; ++k) x[n - 1 - k] = reversed_[k];
    }
    check_met(rows, x);
    return to_displacement(length_, objective_.unknown_of, x);
  }

 private:
  Index length_;
  BandedObjective objective_;
  BandCholesky top_, bottom_;  // Q = L Lᵀ, and the factor of Q in reversed order
  // Scratch of one solve, kept to avoid reallocating.
  std::vector<Index> kept_, via_, target_;
  std::vector<double> coef_, factor_;
  Eigen::VectorXd base_, reversed_;
  BandCholesky H_;
};

// --- schur: LLᵀ of the band once, exact Schur complement over the constraint rows ---
class SchurSolver final : public TrackSolver {
 public:
  SchurSolver(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned, const Options& options,
              double interval_s)
      : length_(positions.rows()), objective_(banded_objective(positions, pinned, options, interval_s)) {
    factorize_or_throw(objective_.Q, "deformation system");
  }

  Displacement solve(const std::vector<PointConstraint>& constraints) override {
    const std::vector<Row> rows = constraint_rows(constraints, objective_.free_of);
    const BandCholesky& L = objective_.Q;
    const Index n = L.size();
    const auto m = static_cast<Index>(rows.size());
    // G = Q⁻¹Cᵀ, a column per row; the forward substitution starts at the row's first unknown.
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, m);
    for (Index j = 0; j < m; ++j) {
      const Row& r = rows[static_cast<std::size_t>(j)];
      auto g = G.col(j);
      g[r.u[0]] = r.c[0];
      Index start = r.u[0];
      if (r.u[1] >= 0) {
        g[r.u[1]] = r.c[1];
        start = std::min(start, r.u[1]);
      }
      L.forward(g, start);
      L.backward(g);
    }
    Eigen::MatrixXd S(m, m);
    for (Index i = 0; i < m; ++i) {
      for (Index j = 0; j < m; ++j) S(i, j) = row_value(rows[static_cast<std::size_t>(i)], G.col(j));
    }
    const Eigen::LLT<Eigen::MatrixXd> schur(0.5 * (S + S.transpose()));
    if (schur.info() != Eigen::Success) {
      throw NumericalError("collide: a trajectory's pushes are not independent (Schur complement not positive definite)");
    }
    Eigen::VectorXd t(m);
    for (Index i = 0; i < m; ++i) t[i] = rows[static_cast<std::size_t>(i)].target;
    Eigen::VectorXd x = G * schur.solve(t);
    // One refinement step through the same S.
    Eigen::VectorXd residual(m);
    for (Index i = 0; i < m; ++i) residual[i] = t[i] - row_value(rows[static_cast<std::size_t>(i)], x);
    x += G * schur.solve(residual);
    check_met(rows, x);
    return to_displacement(length_, objective_.unknown_of, x);
  }

 private:
  Index length_;
  BandedObjective objective_;  // Q overwritten by its factor
};

// --- linalg: the solver layer's ConstrainedLeastSquares (eigen backend) ---
class LinalgSolver final : public TrackSolver {
 public:
  LinalgSolver(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned, const Options& options,
               double interval_s)
      : length_(positions.rows()) {
    Objective o = make_objective(positions, pinned, options, interval_s);
    free_of_ = std::move(o.free_of);
    unknown_of_ = std::move(o.unknown_of);
    rows_ = o.A.rows();
    std::vector<Index> pins;
    for (Index u = 0; u < 2 * length_; ++u) {
      if (free_of_[static_cast<std::size_t>(u)] < 0) pins.push_back(u);
    }
    pinned_count_ = static_cast<Index>(pins.size());
    solver_.set_objective(o.A, o.weights);
    solver_.set_pinned(std::move(pins));
    solver_.set_complex_pairs(options.catch_up_time <= options.smoothing_time || options.smoothing_time <= 0);  // isotropic rows
    try {
      solver_.precompute();
    } catch (const NumericalError& e) {
      throw NumericalError(std::string("collide: a trajectory's deformation system is not positive definite: ") + e.what());
    }
  }

  Displacement solve(const std::vector<PointConstraint>& constraints) override {
    const std::vector<Row> rows = constraint_rows(constraints, free_of_);
    std::vector<Triplet> entries;
    Eigen::MatrixXd d(static_cast<Index>(rows.size()), 1);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      for (int a = 0; a < 2; ++a) {
        if (rows[i].u[a] >= 0) entries.emplace_back(static_cast<Index>(i), rows[i].unknown[a], rows[i].c[a]);
      }
      d(static_cast<Index>(i), 0) = rows[i].target;
    }
    Sparse C(static_cast<Index>(rows.size()), 2 * length_);
    C.setFromTriplets(entries.begin(), entries.end());
    solver_.clear_constraints();
    solver_.add_constraints(C);
    const Eigen::MatrixXd x = solver_.solve(Eigen::MatrixXd::Zero(rows_, 1), Eigen::MatrixXd::Zero(pinned_count_, 1), d);
    Displacement out(length_, 2);
    for (Index k = 0; k < length_; ++k) out.row(k) << x(2 * k, 0), x(2 * k + 1, 0);
    Eigen::VectorXd free(static_cast<Index>(unknown_of_.size()));
    for (std::size_t f = 0; f < unknown_of_.size(); ++f) free[static_cast<Index>(f)] = x(unknown_of_[f], 0);
    check_met(rows, free);
    return out;
  }

 private:
  Index length_, rows_ = 0, pinned_count_ = 0;
  std::vector<Index> free_of_, unknown_of_;
  linalg::ConstrainedLeastSquares solver_;
};

}  // namespace

std::unique_ptr<TrackSolver> make_track_solver(const Eigen::Ref<const Displacement>& positions,
                                               const std::vector<char>& pinned, const Options& options,
                                               double interval_s) {
  switch (options.track_method) {
    case TrackMethod::linalg:
      return std::make_unique<LinalgSolver>(positions, pinned, options, interval_s);
    case TrackMethod::schur:
      return std::make_unique<SchurSolver>(positions, pinned, options, interval_s);
    case TrackMethod::eliminate:
      break;
  }
  return std::make_unique<EliminationSolver>(positions, pinned, options, interval_s);
}

}  // namespace throng::collide
