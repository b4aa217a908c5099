#include "dense.h"

#include <throng/core/errors.h>

#include <omp.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cassert>
#include <complex>
#include <exception>
#include <string>
#include <vector>

extern "C" {
// Fortran BLAS/LAPACK (reference interfaces; OpenBLAS provides them). Hidden lengths of character arguments are
// omitted, as is usual for single-character flags.
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc);
void dsyevd_(const char* jobz, const char* uplo, const int* n, double* a, const int* lda, double* w, double* work,
             const int* lwork, int* iwork, const int* liwork, int* info);
void zheevd_(const char* jobz, const char* uplo, const int* n, std::complex<double>* a, const int* lda, double* w,
             std::complex<double>* work, const int* lwork, double* rwork, const int* lrwork, int* iwork,
             const int* liwork, int* info);
void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv, int* info);
}

namespace throng::formation::dense {
namespace {

// Columns per block of a product: large enough for BLAS to run at full speed, fixed so that the result does not
// depend on the thread count.
constexpr Eigen::Index block_columns = 128;
// Below about this many floating-point operations a parallel loop costs more than it saves (thread wake-up and
// barriers, worse when the machine is shared).
constexpr double parallel_work = 4e6;

// While alive, BLAS/LAPACK calls made by this thread run single-threaded. OpenBLAS's OpenMP build (Debian's
// libopenblas0-openmp, which scripts/install-deps selects) sizes each call by the calling thread's
// omp_get_max_threads(); that setting is per thread (a TBB worker gets its own on first use), so setting it
// here touches no other thread. No OpenMP parallel region is opened: OpenMP is only OpenBLAS's thread knob.
class SequentialBlas {
 public:
  SequentialBlas() : saved_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~SequentialBlas() { omp_set_num_threads(saved_); }
  SequentialBlas(const SequentialBlas&) = delete;
  SequentialBlas& operator=(const SequentialBlas&) = delete;

 private:
  int saved_;
};

int to_int(Eigen::Index i) { return static_cast<int>(i); }

void lapack_check(int info, const char* routine, Eigen::Index n) {
  if (info != 0) {
    throw NumericalError(std::string("spectral formation: LAPACK ") + routine + " failed (info " +
                         std::to_string(info) + ") on a " + std::to_string(n) + " by " + std::to_string(n) +
                         " matrix");
  }
}

}  // namespace

void multiply(const Eigen::Ref<const Eigen::MatrixXd>& a, bool transpose_a, const Eigen::Ref<const Eigen::MatrixXd>& b,
              Eigen::Ref<Eigen::MatrixXd> c) {
  const Eigen::Index m = transpose_a ? a.cols() : a.rows();
  const Eigen::Index k = transpose_a ? a.rows() : a.cols();
  assert(b.rows() == k && c.rows() == m && c.cols() == b.cols());
  if (m == 0 || b.cols() == 0) return;
  if (k == 0) {
    c.setZero();
    return;
  }
  const Eigen::Index blocks = (b.cols() + block_columns - 1) / block_columns;
  const int lda = std::max(1, to_int(a.outerStride()));
  const int ldb = std::max(1, to_int(b.outerStride()));
  const int ldc = std::max(1, to_int(c.outerStride()));
  const char ta = transpose_a ? 'T' : 'N';
  const char tb = 'N';
  const double one = 1.0, zero = 0.0;
  const int mi = to_int(m), ki = to_int(k);
  const double block_work = 2.0 * static_cast<double>(m) * static_cast<double>(k) * static_cast<double>(block_columns);
  for_each(static_cast<std::size_t>(blocks), block_work, [&](std::size_t block) {
    const Eigen::Index first = static_cast<Eigen::Index>(block) * block_columns;
    const int cols = to_int(std::min(block_columns, b.cols() - first));
    SequentialBlas sequential;
    dgemm_(&ta, &tb, &mi, &cols, &ki, &one, a.data(), &lda, b.data() + first * b.outerStride(), &ldb, &zero,
           c.data() + first * c.outerStride(), &ldc);
  });
}

Eigen::MatrixXd multiply(const Eigen::Ref<const Eigen::MatrixXd>& a, bool transpose_a,
                         const Eigen::Ref<const Eigen::MatrixXd>& b) {
  Eigen::MatrixXd c(transpose_a ? a.cols() : a.rows(), b.cols());
  multiply(a, transpose_a, b, c);
  return c;
}

void symmetric_eigen(Eigen::MatrixXd& a, Eigen::VectorXd& values) {
  assert(a.rows() == a.cols());
  const int n = to_int(a.rows());
  values.resize(n);
  if (n == 0) return;
  SequentialBlas sequential;
  int info = 0, lwork = -1, liwork = -1, iwork_query = 0;
  double work_query = 0.0;
  dsyevd_("V", "L", &n, a.data(), &n, values.data(), &work_query, &lwork, &iwork_query, &liwork, &info);
  lapack_check(info, "dsyevd (workspace query)", n);
  lwork = static_cast<int>(work_query);
  liwork = iwork_query;
  std::vector<double> work(static_cast<std::size_t>(lwork));
  std::vector<int> iwork(static_cast<std::size_t>(liwork));
  dsyevd_("V", "L", &n, a.data(), &n, values.data(), work.data(), &lwork, iwork.data(), &liwork, &info);
  lapack_check(info, "dsyevd", n);
}

void hermitian_eigen(Eigen::MatrixXcd& a, Eigen::VectorXd& values) {
  assert(a.rows() == a.cols());
  const int n = to_int(a.rows());
  values.resize(n);
  if (n == 0) return;
  SequentialBlas sequential;
  int info = 0, lwork = -1, lrwork = -1, liwork = -1, iwork_query = 0;
  std::complex<double> work_query = 0.0;
  double rwork_query = 0.0;
  zheevd_("V", "L", &n, a.data(), &n, values.data(), &work_query, &lwork, &rwork_query, &lrwork, &iwork_query,
          &liwork, &info);
  lapack_check(info, "zheevd (workspace query)", n);
  lwork = static_cast<int>(work_query.real());
  lrwork = static_cast<int>(rwork_query);
  liwork = iwork_query;
  std::vector<std::complex<double>> work(static_cast<std::size_t>(lwork));
  std::vector<double> rwork(static_cast<std::size_t>(lrwork));
  std::vector<int> iwork(static_cast<std::size_t>(liwork));
  zheevd_("V", "L", &n, a.data(), &n, values.data(), work.data(), &lwork, rwork.data(), &lrwork, iwork.data(),
          &liwork, &info);
  lapack_check(info, "zheevd", n);
}

int determinant_sign(const Eigen::Ref<const Eigen::MatrixXd>& a) {
  assert(a.rows() == a.cols());
  const int n = to_int(a.rows());
  if (n == 0) return 1;
  Eigen::MatrixXd lu = a;
  std::vector<int> pivots(static_cast<std::size_t>(n));
  int info = 0;
  {
    SequentialBlas sequential;
    dgetrf_(&n, &n, lu.data(), &n, pivots.data(), &info);
  }
  if (info < 0) lapack_check(info, "dgetrf", n);
  if (info > 0) return 0;
  int sign = 1;
  for (int i = 0; i < n; ++i) {
    if (pivots[static_cast<std::size_t>(i)] != i + 1) sign = -sign;
    if (lu(i, i) < 0) sign = -sign;
  }
  return sign;
}

void for_each(std::size_t n, double work_per_item, const std::function<void(std::size_t)>& body) {
  if (n == 0) return;
  if (n == 1 || static_cast<double>(n) * work_per_item < parallel_work) {
    for (std::size_t i = 0; i < n; ++i) body(i);
    return;
  }
  // One task per index (items are few and uneven: a hierarchy's groups, column blocks, keyframes), on TBB's
  // threads like every other loop of the product (nested loops share them). TBB passes on whichever exception
  // reached it first, which depends on the schedule: keep each index's and rethrow the lowest one's, so the
  // error is the same whatever the thread count.
  std::vector<std::exception_ptr> errors(n);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, n, 1),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          try {
            body(i);
          } catch (...) {
            errors[i] = std::current_exception();
          }
        }
      },
      tbb::simple_partitioner());
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace throng::formation::dense
