#include "frame_rate.h"

#include <cmath>

namespace throng::detail {

std::optional<double> uniform_frame_rate(const std::vector<double>& times) {
  const std::size_t T = times.size();
  if (T < 2) return std::nullopt;
  const double step = (times.back() - times.front()) / static_cast<double>(T - 1);
  for (std::size_t k = 0; k < T; ++k) {
    if (std::abs(times[k] - (times.front() + static_cast<double>(k) * step)) > 1e-6 * step) return std::nullopt;
  }
  return 1.0 / step;
}

}  // namespace throng::detail
