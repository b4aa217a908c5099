// Small statistics over crowd frames for the sketch tests: nearest-neighbour distances and their spread.
#pragma once

#include <throng/core/crowd_motion.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>

namespace throng::sketch::test {

/// Distance from each present agent to its nearest present neighbour at `frame` (all pairs: test sizes only).
/// Absent agents get NaN.
inline std::vector<double> nearest_neighbour_distances(const CrowdMotion& m, std::size_t frame) {
  const std::size_t n = m.agent_count();
  std::vector<double> d(n, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t a = 0; a < n; ++a) {
    if (!m.present(frame, a)) continue;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t b = 0; b < n; ++b) {
      if (b != a && m.present(frame, b)) best = std::min(best, (m.position(frame, a) - m.position(frame, b)).norm());
    }
    d[a] = best;
  }
  return d;
}

inline double mean(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

/// Standard deviation over mean.
inline double coefficient_of_variation(const std::vector<double>& v) {
  const double mu = mean(v);
  double var = 0;
  for (double x : v) var += (x - mu) * (x - mu);
  return std::sqrt(var / static_cast<double>(v.size())) / mu;
}

/// The values without the lowest and highest `fraction` of them (stragglers walking alone, agents squeezed at
/// the crowd's edge), sorted.
inline std::vector<double> trimmed(std::vector<double> v, double fraction) {
  std::sort(v.begin(), v.end());
  const auto cut = static_cast<std::size_t>(fraction * static_cast<double>(v.size()));
  return {v.begin() + static_cast<std::ptrdiff_t>(cut), v.end() - static_cast<std::ptrdiff_t>(cut)};
}

/// Pearson correlation of x and y.
inline double correlation(const std::vector<double>& x, const std::vector<double>& y) {
  const double mx = mean(x), my = mean(y);
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

}  // namespace throng::sketch::test
