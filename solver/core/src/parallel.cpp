#include <throng/core/parallel.h>

#include <Eigen/Core>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace throng {

struct ThreadLimit::Impl {
  explicit Impl(std::size_t threads) : control(tbb::global_control::max_allowed_parallelism, threads) {}
  tbb::global_control control;
};

std::size_t hardware_threads() noexcept {
  return static_cast<std::size_t>(std::max(1, tbb::info::default_concurrency()));
}

ThreadLimit::ThreadLimit(std::size_t threads) : threads_(threads == 0 ? hardware_threads() : threads) {
  impl_ = std::make_unique<Impl>(threads_);
  Eigen::setNbThreads(static_cast<int>(threads_));
#ifdef _OPENMP
  omp_set_num_threads(static_cast<int>(threads_));
#endif
}

ThreadLimit::~ThreadLimit() = default;

void parallel_for(std::size_t n, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body) {
  if (n == 0) return;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, std::max<std::size_t>(1, grain)),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

double deterministic_sum(std::size_t n, std::size_t block, const std::function<double(std::size_t)>& term) {
  block = std::max<std::size_t>(1, block);
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<double> partial(blocks, 0.0);
  parallel_for(blocks, 1, [&](std::size_t b0, std::size_t b1) {
    for (std::size_t b = b0; b < b1; ++b) {
      double s = 0.0;
      const std::size_t end = std::min(n, (b + 1) * block);
      for (std::size_t i = b * block; i < end; ++i) s += term(i);
      partial[b] = s;
    }
  });
  double total = 0.0;
  for (double p : partial) total += p;
  return total;
}

}  // namespace throng
