// Wall time of a phase, for reports and benchmarks (never for results: no output depends on it).
#pragma once

#include <chrono>

namespace throng {

/// Seconds since `start` (steady clock).
[[nodiscard]] inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace throng
