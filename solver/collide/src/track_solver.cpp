#include "track_solver.h"

#include <throng/core/errors.h>
#include <throng/graph/features.h>
#include <throng/linalg/least_squares.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <complex>
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

// The objective of one track over all 2·length unknowns: A, its row weights, and which unknowns are free.
struct Objective {
  Sparse A;
  Eigen::VectorXd weights;
  std::vector<Index> free_of;     // unknown → free index, −1 when pinned
  std::vector<Index> unknown_of;  // free index → unknown
};

Objective make_objective(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned,
                         const Options& options) {
  const Index length = positions.rows();
  FeatureOptions feature_options;
  feature_options.min_length = options.min_feature_length;
  const Index features = length >= 3 ? length - 2 : 0;
  const Index steps = length - 1;
  const Index rows = 2 * features + 2 * steps + 2 * length;
  std::vector<Triplet> entries;
  entries.reserve(static_cast<std::size_t>(12 * features + 4 * steps + 2 * length));
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
  // Velocity: every step's change d_{k+1} − d_k (the change of the step vector, so of the velocity), weight
  // velocity_weight · (mean temporal weight). Anchor: every unknown, weight (velocity weight) / spread²; the two
  // balance at about `spread` frames, so a push fades as exp(−|k|/spread) (with velocity_weight 0 the anchor is
  // (mean temporal weight) / spread⁴ against the bending term).
  const double mean_weight = features > 0 ? o.weights.head(2 * features).mean() : 1.0;
  const double spread = std::min(options.spread, spread_cap);
  const double velocity = options.velocity_weight * mean_weight;
  const double anchor = velocity > 0 ? velocity / (spread * spread) : mean_weight / std::pow(spread, 4);
  for (Index k = 0; k < steps; ++k) {
    for (Index axis = 0; axis < 2; ++axis) {
      const Index row = 2 * features + 2 * k + axis;
      entries.emplace_back(row, 2 * k + axis, -1.0);
      entries.emplace_back(row, 2 * (k + 1) + axis, 1.0);
      o.weights[row] = velocity;
    }
  }
  for (Index u = 0; u < 2 * length; ++u) {
    entries.emplace_back(2 * features + 2 * steps + u, u, 1.0);
    o.weights[2 * features + 2 * steps + u] = anchor;
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
  if (!(worst <= 1e-9 * largest + 1e-14)) {
    throw NumericalError("collide: a trajectory's pushes could not be met (residual " + std::to_string(worst) + " m)");
  }
}

Displacement to_displacement(Index length, const std::vector<Index>& unknown_of, const Eigen::VectorXd& x) {
  Displacement d = Displacement::Zero(length, 2);
  for (std::size_t f = 0; f < unknown_of.size(); ++f) d(unknown_of[f] / 2, unknown_of[f] % 2) = x[static_cast<Index>(f)];
  return d;
}

// --- banded: LLᵀ of the band, exact Schur complement over the constraint rows ---
class BandedSolver final : public TrackSolver {
 public:
  BandedSolver(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned, const Options& options)
      : length_(positions.rows()) {
    Objective o = make_objective(positions, pinned, options);
    free_of_ = std::move(o.free_of);
    unknown_of_ = std::move(o.unknown_of);
    n_ = static_cast<Index>(unknown_of_.size());
    // Q = AᵀWA over the free unknowns, copied into the band (free numbering keeps the natural order, so the
    // half-bandwidth stays ≤ 5).
    Sparse selection(2 * length_, n_);
    std::vector<Triplet> pick;
    for (Index f = 0; f < n_; ++f) pick.emplace_back(unknown_of_[static_cast<std::size_t>(f)], f, 1.0);
    selection.setFromTriplets(pick.begin(), pick.end());
    const Sparse AF = o.A * selection;
    const Sparse Q = AF.transpose() * o.weights.asDiagonal() * AF;
    band_.assign(static_cast<std::size_t>(n_ * (p + 1)), 0.0);
    for (Index j = 0; j < Q.outerSize(); ++j) {
      for (Sparse::InnerIterator it(Q, j); it; ++it) {
        if (it.row() >= j && it.row() - j <= p) L(it.row(), j) = it.value();
      }
    }
    factorize();
  }

  Displacement solve(const std::vector<PointConstraint>& constraints) override {
    const std::vector<Row> rows = constraint_rows(constraints, free_of_);
    const auto m = static_cast<Index>(rows.size());
    // G = Q⁻¹Cᵀ, a column per row; the forward substitution starts at the row's first unknown.
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n_, m);
    for (Index j = 0; j < m; ++j) {
      const Row& r = rows[static_cast<std::size_t>(j)];
      auto g = G.col(j);
      g[r.u[0]] = r.c[0];
      Index start = r.u[0];
      if (r.u[1] >= 0) {
        g[r.u[1]] = r.c[1];
        start = std::min(start, r.u[1]);
      }
      forward(g, start);
      backward(g);
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
    return to_displacement(length_, unknown_of_, x);
  }

 private:
  static constexpr Index p = 5;  // half-bandwidth
  // L(i, j) for i − p ≤ j ≤ i (the lower band, overwritten by the factor).
  double& L(Index i, Index j) { return band_[static_cast<std::size_t>(i * (p + 1) + (j - i + p))]; }
  double L(Index i, Index j) const { return band_[static_cast<std::size_t>(i * (p + 1) + (j - i + p))]; }

  void factorize() {
    for (Index i = 0; i < n_; ++i) {
      for (Index j = std::max<Index>(0, i - p); j <= i; ++j) {
        double s = L(i, j);
        for (Index k = std::max<Index>(0, i - p); k < j; ++k) s -= L(i, k) * L(j, k);
        if (i == j) {
          if (!(s > 0.0)) {
            throw NumericalError("collide: a trajectory's deformation system (" + std::to_string(n_) +
                                 " unknowns) is not positive definite at unknown " + std::to_string(i));
          }
          L(i, i) = std::sqrt(s);
        } else {
          L(i, j) = s / L(j, j);
        }
      }
    }
  }
  // y ← L⁻¹ y, y zero before `start`.
  void forward(Eigen::Ref<Eigen::VectorXd> y, Index start) const {
    for (Index i = start; i < n_; ++i) {
      double s = y[i];
      for (Index k = std::max(start, i - p); k < i; ++k) s -= L(i, k) * y[k];
      y[i] = s / L(i, i);
    }
  }
  // y ← L⁻ᵀ y.
  void backward(Eigen::Ref<Eigen::VectorXd> y) const {
    for (Index i = n_ - 1; i >= 0; --i) {
      double s = y[i];
      for (Index k = i + 1; k <= std::min(n_ - 1, i + p); ++k) s -= L(k, i) * y[k];
      y[i] = s / L(i, i);
    }
  }

  Index length_, n_ = 0;
  std::vector<Index> free_of_, unknown_of_;
  std::vector<double> band_;
};

// --- linalg: the solver layer's ConstrainedLeastSquares (eigen backend) ---
class LinalgSolver final : public TrackSolver {
 public:
  LinalgSolver(const Eigen::Ref<const Displacement>& positions, const std::vector<char>& pinned, const Options& options)
      : length_(positions.rows()) {
    Objective o = make_objective(positions, pinned, options);
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
    solver_.set_complex_pairs(true);
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
                                               const std::vector<char>& pinned, const Options& options) {
  if (options.track_method == TrackMethod::linalg) return std::make_unique<LinalgSolver>(positions, pinned, options);
  return std::make_unique<BandedSolver>(positions, pinned, options);
}

}  // namespace throng::collide
