// Complex Hermitian sparse systems and the dense blocks of vectors they act on, with parallel kernels whose
// results do not depend on the thread count.
//
// The editing energies act on 2-D points as complex numbers (a feature is v − u − c (w − u) with complex c), so
// their normal matrices are complex Hermitian: half the unknowns and a quarter of the entries of the real form.
// The iterative solvers of this layer (two_level.h, conjugate_gradients.h) work on them directly.
//
// Shapes: a ComplexSparse stores both triangles of a Hermitian matrix, rows compressed (a row times a block of
// vectors then reads the block's rows, which are contiguous). A ComplexBlock is #unknowns by #vectors, row-major.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <complex>
#include <vector>

namespace throng::linalg {

using Complex = std::complex<double>;
/// A complex sparse matrix, rows compressed. Hermitian matrices store both triangles.
using ComplexSparse = Eigen::SparseMatrix<Complex, Eigen::RowMajor, int>;
/// #unknowns by #vectors, row-major.
using ComplexBlock = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// a b and conj(a) b in plain real arithmetic. std::complex's operator* guards against infinities and NaNs
/// through a library call (C99 Annex G) that costs more than the memory traffic of these kernels; their values
/// are finite.
[[nodiscard]] inline Complex times(Complex a, Complex b) noexcept {
  return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}
[[nodiscard]] inline Complex conj_times(Complex a, Complex b) noexcept {
  return {a.real() * b.real() + a.imag() * b.imag(), a.real() * b.imag() - a.imag() * b.real()};
}

/// Y = A X, rows in parallel (each row summed by one thread in storage order: the same bits for any thread
/// count). Y is resized. A is #rows by #n, X is #n by #k.
void multiply(const ComplexSparse& A, const ComplexBlock& X, ComplexBlock& Y);

/// Y = B − A X (same rules as multiply).
void residual(const ComplexSparse& A, const ComplexBlock& X, const ComplexBlock& B, ComplexBlock& Y);

/// xᴴ y for every column pair (X, Y of one shape), summed in fixed blocks of rows and then in block order: the
/// same bits for any thread count.
[[nodiscard]] std::vector<Complex> column_dots(const ComplexBlock& X, const ComplexBlock& Y);

/// The largest modulus in each column.
[[nodiscard]] std::vector<double> column_max_abs(const ComplexBlock& X);

}  // namespace throng::linalg
