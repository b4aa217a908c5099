#include "track_solver.h"

#include <throng/core/errors.h>
#include <throng/graph/features.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

namespace throng::collide {

using Index = Eigen::Index;
using Triplet = Eigen::Triplet<double>;

TrackSolver::TrackSolver(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& positions,
                         const std::vector<char>& pinned, double spread, double min_feature_length)
    : length_(positions.rows()) {
  FeatureOptions feature_options;
  feature_options.min_length = min_feature_length;
  const Index features = length_ >= 3 ? length_ - 2 : 0;
  const Index rows = 2 * features + 2 * length_;
  std::vector<Triplet> entries;
  entries.reserve(static_cast<std::size_t>(12 * features + 2 * length_));
  Eigen::VectorXd weights(rows);
  // Temporal features: residual d_v − (1 − c) d_u − c d_w as two real rows (complex coefficients, Eq. 1).
  for (Index k = 1; k + 1 < length_; ++k) {
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
    weights[row] = weights[row + 1] = f.weight;
  }
  // Anchor: every unknown, weight (mean temporal weight) / spread⁴ — the bending term (fourth differences of d)
  // and the anchor balance at wavelengths of about `spread` vertices, so a push fades over that many frames.
  const double mean_weight = features > 0 ? weights.head(2 * features).mean() : 1.0;
  const double anchor = mean_weight / std::pow(spread, 4);
  for (Index u = 0; u < 2 * length_; ++u) {
    entries.emplace_back(2 * features + u, u, 1.0);
    weights[2 * features + u] = anchor;
  }
  Sparse A(rows, 2 * length_);
  A.setFromTriplets(entries.begin(), entries.end());
  // Free unknowns in their natural (banded) order.
  free_of_.assign(static_cast<std::size_t>(2 * length_), -1);
  for (Index k = 0; k < length_; ++k) {
    if (pinned[static_cast<std::size_t>(k)] != 0) continue;
    for (Index axis = 0; axis < 2; ++axis) {
      free_of_[static_cast<std::size_t>(2 * k + axis)] = static_cast<Index>(unknown_of_.size());
      unknown_of_.push_back(2 * k + axis);
    }
  }
  Sparse selection(2 * length_, static_cast<Index>(unknown_of_.size()));
  std::vector<Triplet> pick;
  for (std::size_t f = 0; f < unknown_of_.size(); ++f) pick.emplace_back(unknown_of_[f], static_cast<Index>(f), 1.0);
  selection.setFromTriplets(pick.begin(), pick.end());
  const Sparse AF = A * selection;
  // The whole band of free unknowns as explicit zeros, so Q and every penalised Q share one pattern.
  const auto nf = static_cast<Index>(unknown_of_.size());
  std::vector<Triplet> band;
  for (Index i = 0; i < nf; ++i) {
    for (Index j = i; j < nf && unknown_of_[static_cast<std::size_t>(j)] <= unknown_of_[static_cast<std::size_t>(i)] + 5; ++j) {
      band.emplace_back(i, j, 0.0);
      band.emplace_back(j, i, 0.0);
    }
  }
  Sparse pattern(nf, nf);
  pattern.setFromTriplets(band.begin(), band.end());
  Q_ = Sparse(AF.transpose() * weights.asDiagonal() * AF) + pattern;
  Q_.makeCompressed();
  stiffness_ = 1e7 * Q_.diagonal().maxCoeff();
  factor_.analyzePattern(Q_);
}

Eigen::Matrix<double, Eigen::Dynamic, 2> TrackSolver::solve(const std::vector<PointConstraint>& constraints) {
  Sparse K = Q_;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(K.rows());
  // One penalised row per constraint and axis: ρ (c·d − t)².
  struct Row {
    Index u[2];
    double c[2];
    double target;
  };
  std::vector<Row> rows;
  rows.reserve(2 * constraints.size());
  for (const PointConstraint& c : constraints) {
    for (Index axis = 0; axis < 2; ++axis) {
      Row r{{free_of_[static_cast<std::size_t>(2 * c.v0 + axis)], -1}, {c.c0, 0.0}, c.target[axis]};
      if (c.c1 != 0.0) {
        r.u[1] = free_of_[static_cast<std::size_t>(2 * c.v1 + axis)];
        r.c[1] = c.c1;
      }
      const int n = r.u[1] >= 0 ? 2 : 1;
      for (int a = 0; a < n; ++a) {
        rhs[r.u[a]] += stiffness_ * r.c[a] * r.target;
        for (int b = 0; b < n; ++b) K.coeffRef(r.u[a], r.u[b]) += stiffness_ * r.c[a] * r.c[b];
      }
      rows.push_back(r);
    }
  }
  factor_.factorize(K);
  if (factor_.info() != Eigen::Success) {
    throw NumericalError("collide: a trajectory's deformation system (" + std::to_string(K.rows()) +
                         " unknowns) is not positive definite");
  }
  const Eigen::VectorXd x = factor_.solve(rhs);
  double worst = 0.0, largest = 0.0;
  for (const Row& r : rows) {
    const double value = r.c[0] * x[r.u[0]] + (r.u[1] >= 0 ? r.c[1] * x[r.u[1]] : 0.0);
    worst = std::max(worst, std::abs(value - r.target));
    largest = std::max(largest, std::abs(r.target));
  }
  if (worst > 1e-5 * largest + 1e-12) {
    throw NumericalError("collide: a trajectory's pushes could not be met (residual " + std::to_string(worst) + " m)");
  }
  Eigen::Matrix<double, Eigen::Dynamic, 2> d = Eigen::Matrix<double, Eigen::Dynamic, 2>::Zero(length_, 2);
  for (std::size_t f = 0; f < unknown_of_.size(); ++f) d(unknown_of_[f] / 2, unknown_of_[f] % 2) = x[static_cast<Index>(f)];
  return d;
}

}  // namespace throng::collide
