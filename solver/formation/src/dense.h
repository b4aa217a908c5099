// Dense kernels of the spectral method (products, symmetric and Hermitian eigenproblems, determinant signs),
// through BLAS/LAPACK (OpenBLAS on Debian: run-time CPU dispatch, several times Eigen's speed at the project's
// portable -march=x86-64 flags).
//
// Repeatable bits whatever the thread count: a multi-threaded BLAS splits its work by thread count, so its
// results differ in the last bits from one thread count to another (measured: OpenBLAS and Eigen both do). Here
// every BLAS/LAPACK call runs single-threaded, and parallelism comes from splitting the work into pieces whose
// boundaries do not depend on the thread count (fixed column blocks of a product, independent problems),
// spread over TBB's threads (the --threads limit, core/parallel.h). OpenBLAS's OpenMP build sizes a call by the
// calling thread's omp_get_max_threads(), so each call is made with that set to 1 on its thread.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <functional>

namespace throng::formation::dense {

/// c = op(a) · b, op(a) = aᵀ when `transpose_a`. Shapes must agree (asserted). Deterministic (see above).
void multiply(const Eigen::Ref<const Eigen::MatrixXd>& a, bool transpose_a, const Eigen::Ref<const Eigen::MatrixXd>& b,
              Eigen::Ref<Eigen::MatrixXd> c);
[[nodiscard]] Eigen::MatrixXd multiply(const Eigen::Ref<const Eigen::MatrixXd>& a, bool transpose_a,
                                       const Eigen::Ref<const Eigen::MatrixXd>& b);

/// Eigen-decomposition of the symmetric matrix `a` (its lower triangle is read): on return `a` holds the
/// orthonormal eigenvectors (columns) and `values` the eigenvalues in ascending order. LAPACK dsyevd.
/// Throws NumericalError if LAPACK reports a failure.
void symmetric_eigen(Eigen::MatrixXd& a, Eigen::VectorXd& values);

/// The same for a complex Hermitian matrix (LAPACK zheevd).
void hermitian_eigen(Eigen::MatrixXcd& a, Eigen::VectorXd& values);

/// Sign of det(a) for a square, non-singular matrix: +1 or −1 (LU with partial pivoting, LAPACK dgetrf);
/// 0 if LU finds an exactly zero pivot.
[[nodiscard]] int determinant_sign(const Eigen::Ref<const Eigen::MatrixXd>& a);

/// Calls body(i) for every i in [0, n) on TBB's threads (one task per i); loops whose total work
/// n · work_per_item (about floating-point operations) is too small to pay for waking threads run sequentially.
/// Nested calls share the same threads. The body must only write state owned by i; BLAS/LAPACK calls inside run
/// single-threaded. If bodies throw, the exception of the lowest i is rethrown after every body has run.
void for_each(std::size_t n, double work_per_item, const std::function<void(std::size_t)>& body);

}  // namespace throng::formation::dense
