// Thread control and deterministic parallel helpers.
//
// The product's own loops use TBB; Eigen's dense kernels use OpenMP. `ThreadLimit` sets both once, for the
// lifetime of the object (the --threads flag). Determinism comes from the algorithms (two-buffer steps, fixed
// reduction order), never from the scheduler: see `parallel_for` and `deterministic_sum`.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>

namespace throng {

/// Limits TBB and OpenMP (Eigen) to `threads` threads while alive; 0 means all hardware threads.
class ThreadLimit {
 public:
  explicit ThreadLimit(std::size_t threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

  /// The effective thread count.
  [[nodiscard]] std::size_t threads() const noexcept { return threads_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::size_t threads_;
};

/// Hardware threads available to this process.
[[nodiscard]] std::size_t hardware_threads() noexcept;

/// Calls body(begin, end) on disjoint ranges covering [0, n) in parallel (TBB). `grain` is the smallest range.
/// The body must only write state owned by its range: then the result does not depend on the thread count.
void parallel_for(std::size_t n, std::size_t grain, const std::function<void(std::size_t, std::size_t)>& body);

/// Σ term(i) for i in [0, n), summed in fixed blocks of `block` and then in block order, so the floating-point
/// result is the same bits whatever the thread count.
[[nodiscard]] double deterministic_sum(std::size_t n, std::size_t block, const std::function<double(std::size_t)>& term);

}  // namespace throng
