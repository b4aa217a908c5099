// Private to solver/check: samples of one measure with where they were taken, and their distribution.
#pragma once

#include <throng/check/motion_check.h>

#include <cstdint>
#include <vector>

namespace throng::check::detail {

/// Values of one measure, each with the agent index and time it was taken at.
struct Samples {
  std::vector<double> values;
  std::vector<std::uint32_t> agents;
  std::vector<double> times;

  void add(double value, std::size_t agent, double time) {
    values.push_back(value);
    agents.push_back(static_cast<std::uint32_t>(agent));
    times.push_back(time);
  }
  /// Appends `other` (used to merge per-agent collections in agent order: deterministic).
  void append(const Samples& other);
};

/// Percentiles (nearest rank) and the maximum, with the id of its agent (`ids` by agent index). Ties for the
/// maximum go to the first sample in order.
[[nodiscard]] Distribution distribution(const Samples& samples, const std::vector<std::int64_t>& ids);

}  // namespace throng::check::detail
