// Private to solver/check: samples of one measure with where they were taken, and their distribution.
#pragma once

#include <throng/check/motion_check.h>

#include <cstdint>
#include <vector>

namespace throng::check::detail {

/// Values of one measure, and where the largest was taken (agent index and time): the only place a report names.
/// Only the values are kept per sample (8 bytes, not 20 with an agent and a time each: the merged samples of a
/// 10,000-agent × 601-frame crowd are 6 million per measure).
struct Samples {
  std::vector<double> values;
  double max = 0;                 ///< the first largest value (valid when values is not empty)
  std::uint32_t max_agent = 0;    ///< its agent index
  double max_time = 0;            ///< its time

  void add(double value, std::size_t agent, double time) {
    if (values.empty() || value > max) {
      max = value;
      max_agent = static_cast<std::uint32_t>(agent);
      max_time = time;
    }
    values.push_back(value);
  }
  /// Appends `other` (used to merge per-agent collections in agent order: deterministic). The largest stays the
  /// first one in that order: `other`'s only when larger.
  void append(const Samples& other);
  /// Room for `count` values, so that merging a crowd's samples allocates once.
  void reserve(std::size_t count) { values.reserve(count); }
};

/// Percentiles (nearest rank) and the maximum, with the id of its agent (`ids` by agent index). Ties for the
/// maximum go to the first sample in order (Samples::add, append). Takes the samples (their values are reordered: three selections
/// instead of a sort, the same order statistics).
[[nodiscard]] Distribution distribution(Samples samples, const std::vector<std::int64_t>& ids);

}  // namespace throng::check::detail
