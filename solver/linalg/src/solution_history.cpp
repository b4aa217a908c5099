#include <throng/core/parallel.h>
#include <throng/linalg/solution_history.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace throng::linalg {
namespace {

constexpr std::size_t sum_block = 4096;  // rows per partial sum (fixed: the sums' bits must not depend on threads)
// A new direction whose A-norm after projection is below this fraction of the solution's lies in the span.
constexpr double in_span = 1e-10;

}  // namespace

SolutionHistory::SolutionHistory(int capacity) : capacity_(std::max(1, capacity)) {}

void SolutionHistory::clear() {
  size_ = 0;
  next_ = 0;
  V_.resize(0, 0);
  W_.resize(0, 0);
}

Eigen::VectorXcd SolutionHistory::adjoint_times(const ComplexBlock& M, const ComplexBlock& y) const {
  const auto n = static_cast<std::size_t>(y.rows());
  const auto k = static_cast<std::size_t>(size_);
  const std::size_t blocks = (n + sum_block - 1) / sum_block;
  std::vector<Complex> partial(blocks * k, Complex(0));
  parallel_for(blocks, 1, [&](std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) {
      Complex* sum = partial.data() + b * k;
      const std::size_t end = std::min(n, (b + 1) * sum_block);
      for (std::size_t i = b * sum_block; i < end; ++i) {
        const Complex yi = y(static_cast<Eigen::Index>(i), 0);
        for (std::size_t c = 0; c < k; ++c) sum[c] += conj_times(M(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)), yi);
      }
    }
  });
  Eigen::VectorXcd total = Eigen::VectorXcd::Zero(static_cast<Eigen::Index>(k));
  for (std::size_t b = 0; b < blocks; ++b)
    for (std::size_t c = 0; c < k; ++c) total[static_cast<Eigen::Index>(c)] += partial[b * k + c];
  return total;
}

void SolutionHistory::start(const ComplexBlock& b, ComplexBlock& x, ComplexBlock& r) const {
  if (b.cols() != 1) throw std::invalid_argument("SolutionHistory::start: one right-hand side at a time");
  x.setZero(b.rows(), 1);
  r = b;
  if (size_ == 0) return;
  const Eigen::VectorXcd c = adjoint_times(V_, b);  // Vᴴ b (V A-orthonormal: the Galerkin coefficients)
  const Eigen::Index k = size_;
  parallel_for(static_cast<std::size_t>(b.rows()), sum_block, [&](std::size_t begin, std::size_t end) {
    for (auto i = static_cast<Eigen::Index>(begin); i < static_cast<Eigen::Index>(end); ++i) {
      Complex xi = 0, ai = 0;
      for (Eigen::Index j = 0; j < k; ++j) {
        xi += times(V_(i, j), c[j]);
        ai += times(W_(i, j), c[j]);
      }
      x(i, 0) = xi;
      r(i, 0) = b(i, 0) - ai;
    }
  });
}

void SolutionHistory::start(const ComplexBlock& b, const ComplexBlock& g, const ComplexBlock& Ag, ComplexBlock& x,
                            ComplexBlock& r) const {
  if (b.cols() != 1 || g.cols() != 1 || g.rows() != b.rows() || Ag.rows() != b.rows() || Ag.cols() != 1) {
    throw std::invalid_argument("SolutionHistory::start: shapes (one right-hand side and one guess)");
  }
  // The Galerkin start in span{V, g}: x = V y + η g with
  //     [ I     Wᴴg ] [y]   [Vᴴb]
  //     [ gᴴW   gᴴAg] [η] = [gᴴb]      (VᴴAV = I, VᴴAg = Wᴴg),
  // solved by eliminating y; every inner product in fixed blocks of rows (the same bits for any thread count).
  const auto n = static_cast<std::size_t>(b.rows());
  const auto k = static_cast<std::size_t>(size_);
  const Eigen::VectorXcd vb = adjoint_times(V_, b), wg = adjoint_times(W_, g);
  const Complex gb = column_dots(g, b)[0];
  const double energy = column_dots(g, Ag)[0].real();  // gᴴAg
  // η from the Schur complement gᴴAg − |Wᴴg|² (g's energy outside the span); none when g lies in the span.
  Complex numerator = gb;
  double outside = energy;
  for (std::size_t c = 0; c < k; ++c) {
    const auto i = static_cast<Eigen::Index>(c);
    numerator -= conj_times(wg[i], vb[i]);
    outside -= std::norm(wg[i]);
  }
  const Complex eta = energy > 0 && outside > in_span * energy ? numerator / outside : Complex(0);
  std::vector<Complex> y(k);
  for (std::size_t c = 0; c < k; ++c) y[c] = vb[static_cast<Eigen::Index>(c)] - times(wg[static_cast<Eigen::Index>(c)], eta);
  x.resize(b.rows(), 1);
  r.resize(b.rows(), 1);
  parallel_for(n, sum_block, [&](std::size_t begin, std::size_t end) {
    for (auto i = static_cast<Eigen::Index>(begin); i < static_cast<Eigen::Index>(end); ++i) {
      Complex xi = times(g(i, 0), eta), ai = times(Ag(i, 0), eta);
      for (std::size_t c = 0; c < k; ++c) {
        xi += times(V_(i, static_cast<Eigen::Index>(c)), y[c]);
        ai += times(W_(i, static_cast<Eigen::Index>(c)), y[c]);
      }
      x(i, 0) = xi;
      r(i, 0) = b(i, 0) - ai;
    }
  });
}

void SolutionHistory::add(const ComplexBlock& x, const ComplexBlock& Ax) {
  if (x.cols() != 1 || Ax.rows() != x.rows() || Ax.cols() != 1) throw std::invalid_argument("SolutionHistory::add: shapes");
  const Eigen::Index n = x.rows();
  if (V_.rows() != n) {
    V_ = ComplexBlock::Zero(n, capacity_);
    W_ = ComplexBlock::Zero(n, capacity_);
    size_ = next_ = 0;
  }
  // A-orthogonalise against the kept directions (twice: classical Gram–Schmidt loses orthogonality once).
  ComplexBlock v = x, w = Ax;
  const double energy = std::max(0.0, column_dots(x, Ax)[0].real());
  if (!(energy > 0)) return;
  // The slot about to be overwritten drops out of the span first.
  if (size_ == capacity_) {
    V_.col(next_).setZero();
    W_.col(next_).setZero();
  }
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::VectorXcd c = adjoint_times(W_, v);  // v_jᴴ A v = w_jᴴ v
    // Rows in parallel: each row's update is the same sequence of operations whatever the thread count.
    const auto k = static_cast<Eigen::Index>(size_);
    parallel_for(static_cast<std::size_t>(n), sum_block, [&](std::size_t begin, std::size_t end) {
      for (auto i = static_cast<Eigen::Index>(begin); i < static_cast<Eigen::Index>(end); ++i) {
        for (Eigen::Index j = 0; j < k; ++j) {
          v(i, 0) -= times(V_(i, j), c[j]);
          w(i, 0) -= times(W_(i, j), c[j]);
        }
      }
    });
  }
  const double left = column_dots(v, w)[0].real();
  if (!(left > in_span * energy)) return;
  const double scale = 1.0 / std::sqrt(left);
  V_.col(next_) = v.col(0) * scale;
  W_.col(next_) = w.col(0) * scale;
  next_ = (next_ + 1) % capacity_;
  size_ = std::min(size_ + 1, capacity_);
}

}  // namespace throng::linalg
