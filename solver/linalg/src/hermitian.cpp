#include <throng/core/parallel.h>
#include <throng/linalg/hermitian.h>

#include <algorithm>
#include <cassert>
#include <cmath>

namespace throng::linalg {
namespace {

// Rows per task of the matrix kernels, and per partial sum of the reductions (fixed: the reductions' bits must
// not depend on the scheduler).
constexpr std::size_t row_grain = 2048;
constexpr std::size_t sum_block = 4096;

// y_i = Σ_j a_ij x_j for the rows [begin, end), written through `store(i, sums)` (sums: k complex values as
// 2k doubles, re and im). The products are written out in real arithmetic: std::complex's operator* guards
// against infinities and NaNs through a library call (C99 Annex G) that costs more than the memory traffic.
template <typename Store>
void rows_times(const ComplexSparse& A, const ComplexBlock& X, std::size_t begin, std::size_t end, Store&& store) {
  const Eigen::Index k = X.cols();
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  const double* value = reinterpret_cast<const double*>(A.valuePtr());
  const double* x = reinterpret_cast<const double*>(X.data());
  if (k == 1) {
    for (std::size_t i = begin; i < end; ++i) {
      double re = 0, im = 0;
      for (int e = outer[i]; e < outer[i + 1]; ++e) {
        const double ar = value[2 * e], ai = value[2 * e + 1];
        const double xr = x[2 * inner[e]], xi = x[2 * inner[e] + 1];
        re += ar * xr - ai * xi;
        im += ar * xi + ai * xr;
      }
      const double sum[2] = {re, im};
      store(static_cast<Eigen::Index>(i), sum);
    }
    return;
  }
  std::vector<double> sum(2 * static_cast<std::size_t>(k));
  for (std::size_t i = begin; i < end; ++i) {
    std::fill(sum.begin(), sum.end(), 0.0);
    for (int e = outer[i]; e < outer[i + 1]; ++e) {
      const double ar = value[2 * e], ai = value[2 * e + 1];
      const double* row = x + 2 * static_cast<std::size_t>(inner[e]) * static_cast<std::size_t>(k);
      for (Eigen::Index c = 0; c < k; ++c) {
        const double xr = row[2 * c], xi = row[2 * c + 1];
        sum[2 * static_cast<std::size_t>(c)] += ar * xr - ai * xi;
        sum[2 * static_cast<std::size_t>(c) + 1] += ar * xi + ai * xr;
      }
    }
    store(static_cast<Eigen::Index>(i), sum.data());
  }
}

}  // namespace

void multiply(const ComplexSparse& A, const ComplexBlock& X, ComplexBlock& Y) {
  assert(A.isCompressed() && A.cols() == X.rows());
  Y.resize(A.rows(), X.cols());
  const Eigen::Index k = X.cols();
  parallel_for(static_cast<std::size_t>(A.rows()), row_grain, [&](std::size_t begin, std::size_t end) {
    rows_times(A, X, begin, end, [&](Eigen::Index i, const double* sum) {
      for (Eigen::Index c = 0; c < k; ++c) Y(i, c) = Complex(sum[2 * c], sum[2 * c + 1]);
    });
  });
}

void residual(const ComplexSparse& A, const ComplexBlock& X, const ComplexBlock& B, ComplexBlock& Y) {
  assert(A.isCompressed() && A.cols() == X.rows() && B.rows() == A.rows() && B.cols() == X.cols());
  Y.resize(A.rows(), X.cols());
  const Eigen::Index k = X.cols();
  parallel_for(static_cast<std::size_t>(A.rows()), row_grain, [&](std::size_t begin, std::size_t end) {
    rows_times(A, X, begin, end, [&](Eigen::Index i, const double* sum) {
      for (Eigen::Index c = 0; c < k; ++c) Y(i, c) = B(i, c) - Complex(sum[2 * c], sum[2 * c + 1]);
    });
  });
}

std::vector<Complex> column_dots(const ComplexBlock& X, const ComplexBlock& Y) {
  assert(X.rows() == Y.rows() && X.cols() == Y.cols());
  const auto n = static_cast<std::size_t>(X.rows());
  const auto k = static_cast<std::size_t>(X.cols());
  const std::size_t blocks = (n + sum_block - 1) / sum_block;
  std::vector<Complex> partial(blocks * k, Complex(0));
  parallel_for(blocks, 1, [&](std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) {
      Complex* sum = partial.data() + b * k;
      const std::size_t end = std::min(n, (b + 1) * sum_block);
      for (std::size_t i = b * sum_block; i < end; ++i) {
        const double* x = reinterpret_cast<const double*>(X.data() + i * k);
        const double* y = reinterpret_cast<const double*>(Y.data() + i * k);
        for (std::size_t c = 0; c < k; ++c) {  // conj(x) y in real arithmetic (see rows_times)
          sum[c] += Complex(x[2 * c] * y[2 * c] + x[2 * c + 1] * y[2 * c + 1], x[2 * c] * y[2 * c + 1] - x[2 * c + 1] * y[2 * c]);
        }
      }
    }
  });
  std::vector<Complex> total(k, Complex(0));
  for (std::size_t b = 0; b < blocks; ++b)
    for (std::size_t c = 0; c < k; ++c) total[c] += partial[b * k + c];
  return total;
}

std::vector<double> column_max_abs(const ComplexBlock& X) {
  std::vector<double> out(static_cast<std::size_t>(X.cols()), 0.0);  // squared moduli first
  for (Eigen::Index i = 0; i < X.rows(); ++i)
    for (Eigen::Index c = 0; c < X.cols(); ++c) out[static_cast<std::size_t>(c)] = std::max(out[static_cast<std::size_t>(c)], std::norm(X(i, c)));
  for (double& v : out) v = std::sqrt(v);
  return out;
}

}  // namespace throng::linalg
