// Cholesky factorisation of a symmetric positive definite band matrix (private to solver/collide).
//
// Shape: n × n, half-bandwidth p (entry (i, j) is zero when |i − j| > p). Storage: the lower band, row by row,
// (p + 1) values per row; L(i, j) for i − p ≤ j ≤ i. Factorising overwrites the stored matrix with its factor
// (A = L Lᵀ, no pivoting, no fill outside the band): O(n p²) work, then O(n p) per solve. Used for a
// trajectory's deformation system (p = 5 in interleaved x, y unknowns: a vertex couples with two neighbours on
// each side) and for the same system with the pushed unknowns eliminated (p up to 9).
#pragma once

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace throng::collide {

class BandCholesky {
 public:
  using Index = Eigen::Index;

  BandCholesky() = default;
  /// An all-zero n × n matrix of half-bandwidth p, to be filled through at() then factorised.
  void reset(Index n, Index p) {
    n_ = n;
    p_ = p;
    data_.assign(static_cast<std::size_t>(n * (p + 1)), 0.0);
  }

  [[nodiscard]] Index size() const noexcept { return n_; }
  [[nodiscard]] Index bandwidth() const noexcept { return p_; }

  /// Entry (i, j) of the matrix before factorising, i ≥ j, i − j ≤ p.
  double& at(Index i, Index j) { return data_[static_cast<std::size_t>(i * (p_ + 1) + (j - i + p_))]; }
  [[nodiscard]] double at(Index i, Index j) const { return data_[static_cast<std::size_t>(i * (p_ + 1) + (j - i + p_))]; }

  /// Factorises in place; false (the matrix not positive definite) with `failed_at` the pivot's index.
  [[nodiscard]] bool factorize(Index& failed_at) {
    for (Index i = 0; i < n_; ++i) {
      const Index first = std::max<Index>(0, i - p_);
      for (Index j = first; j <= i; ++j) {
        double s = at(i, j);
        for (Index k = first; k < j; ++k) s -= at(i, k) * at(j, k);
        if (i == j) {
          if (!(s > 0.0)) {
            failed_at = i;
            return false;
          }
          at(i, i) = std::sqrt(s);
        } else {
          at(i, j) = s / at(j, j);
        }
      }
    }
    return true;
  }

  /// y ← L⁻¹ y, where y is zero before `start`.
  void forward(Eigen::Ref<Eigen::VectorXd> y, Index start = 0) const {
    for (Index i = start; i < n_; ++i) {
      double s = y[i];
      for (Index k = std::max(start, i - p_); k < i; ++k) s -= at(i, k) * y[k];
      y[i] = s / at(i, i);
    }
  }
  /// y ← L⁻ᵀ y over the leading block [0, end) (the factor of the leading principal block is L's leading block);
  /// y.size() ≥ end, entries from `end` on are not touched.
  void backward(Eigen::Ref<Eigen::VectorXd> y, Index end) const {
    for (Index i = end - 1; i >= 0; --i) {
      double s = y[i];
      for (Index k = i + 1; k <= std::min(end - 1, i + p_); ++k) s -= at(k, i) * y[k];
      y[i] = s / at(i, i);
    }
  }
  void backward(Eigen::Ref<Eigen::VectorXd> y) const { backward(y, n_); }
  /// y ← A⁻¹ y (after factorize()).
  void solve(Eigen::Ref<Eigen::VectorXd> y) const {
    forward(y);
    backward(y);
  }

 private:
  Index n_ = 0, p_ = 0;
  std::vector<double> data_;
};

}  // namespace throng::collide
