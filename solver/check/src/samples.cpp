#include "samples.h"

#include <algorithm>
#include <cmath>

namespace throng::check::detail {

void Samples::append(const Samples& other) {
  values.insert(values.end(), other.values.begin(), other.values.end());
  agents.insert(agents.end(), other.agents.begin(), other.agents.end());
  times.insert(times.end(), other.times.begin(), other.times.end());
}

namespace {

// Index of the nearest-rank p-th percentile in a sorted sequence of n values: ⌈p·n⌉ − 1.
std::size_t rank_index(std::size_t n, double p) {
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(n) - 1e-9));
  return std::min(n, std::max<std::size_t>(rank, 1)) - 1;
}

}  // namespace

Distribution distribution(const Samples& samples, const std::vector<std::int64_t>& ids) {
  Distribution d;
  d.samples = samples.values.size();
  if (d.samples == 0) return d;
  std::size_t worst = 0;
  for (std::size_t i = 1; i < d.samples; ++i) {
    if (samples.values[i] > samples.values[worst]) worst = i;
  }
  d.max = samples.values[worst];
  d.max_agent = ids[samples.agents[worst]];
  d.max_time = samples.times[worst];
  std::vector<double> sorted = samples.values;
  std::sort(sorted.begin(), sorted.end());
  d.p50 = sorted[rank_index(d.samples, 0.50)];
  d.p95 = sorted[rank_index(d.samples, 0.95)];
  d.p99 = sorted[rank_index(d.samples, 0.99)];
  return d;
}

}  // namespace throng::check::detail
