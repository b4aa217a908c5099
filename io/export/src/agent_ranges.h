// The exporters' split of a crowd's agents into a fixed number of ranges, made in parallel. Fixed, not the
// scheduler's: each range's output lands in its own slot and the slots are joined in range order, so the bytes
// do not depend on the thread count (tests/io/test_export_repeatable.cpp).
#pragma once

#include <throng/core/parallel.h>

#include <algorithm>
#include <cstddef>

namespace throng::detail {

/// How many ranges: enough to balance a few cores, few enough that a range's share of a frame stays contiguous.
inline constexpr std::size_t agent_ranges = 16;

/// Calls body(r, n0, n1) for r in [0, agent_ranges), in parallel: agents [n0, n1) of [0, agents), consecutive
/// equal ranges (the last ones shorter or empty).
template <class Body>
void for_agent_ranges(std::size_t agents, Body body) {
  const std::size_t step = (agents + agent_ranges - 1) / agent_ranges;
  parallel_for(agent_ranges, 1, [&](std::size_t r0, std::size_t r1) {
    for (std::size_t r = r0; r < r1; ++r) body(r, std::min(agents, r * step), std::min(agents, (r + 1) * step));
  });
}

}  // namespace throng::detail
