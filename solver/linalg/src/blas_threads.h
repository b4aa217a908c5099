// The BLAS thread count for one scope. OpenBLAS's OpenMP build (Debian's default here) and CHOLMOD follow
// OpenMP's thread count; on the 2-core reference machine 2 threads are slower than 1 for every BLAS call the
// backends make (spin-waiting threads, small fronts, BLAS-1 in Krylov loops), and 1 thread keeps results
// independent of --threads. SolverOptions::blas_threads sets it; 0 keeps the process's setting.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace throng::linalg {

class BlasThreadScope {
 public:
  explicit BlasThreadScope(int threads) {
#ifdef _OPENMP
    previous_ = omp_get_max_threads();
    if (threads > 0) omp_set_num_threads(threads);
#else
    (void)threads;
#endif
  }
  ~BlasThreadScope() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }
  BlasThreadScope(const BlasThreadScope&) = delete;
  BlasThreadScope& operator=(const BlasThreadScope&) = delete;

 private:
  int previous_ = 1;
};

}  // namespace throng::linalg
