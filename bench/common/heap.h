// Heap memory for the benchmarks: in use now (heap_mb: a difference of two readings is what the code between
// them holds, whatever earlier cases freed; a resident-set difference is not, freed pages stay resident), the
// process's peak resident set, and the peak heap of the code run while a HeapPeak lives.
//
// glibc's mallinfo2 gives the heap in use (arena and mmapped blocks) but no peak, and a factorisation frees its
// factor before the stitch returns; so a thread reads it every 2 ms and keeps the largest reading. The counter
// is the peak minus the reading at construction: what the measured code held at most, whatever earlier cases
// left (a resident-set figure is not: freed pages stay resident). CHOLMOD, PETSc and Eigen allocate through
// malloc; OpenBLAS's small work buffers do not and are not counted. A peak shorter than 2 ms may be missed.
#pragma once

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>

namespace throng::bench {

/// Heap memory in use, MB (glibc's mallinfo2: arena and mmapped blocks in use).
inline double heap_mb() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

/// The process's peak resident set so far, MB (monotone over the whole run: meaningful for its largest case).
inline double max_rss_mb() {
  struct rusage u {};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;
}

class HeapPeak {
 public:
  HeapPeak() : base_(heap_mb()), peak_(base_), watcher_([this] {
    while (!stop_.load()) {
      peak_.store(std::max(peak_.load(), heap_mb()));
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }) {}
  HeapPeak(const HeapPeak&) = delete;
  HeapPeak& operator=(const HeapPeak&) = delete;
  ~HeapPeak() { (void)stop(); }

  /// Stops watching; the peak above the starting reading, MB.
  double stop() {
    if (!stop_.exchange(true)) watcher_.join();
    peak_.store(std::max(peak_.load(), heap_mb()));
    return peak_.load() - base_;
  }

 private:
  double base_;
  std::atomic<double> peak_;
  std::atomic<bool> stop_{false};
  std::thread watcher_;
};

}  // namespace throng::bench
