// Per-agent work spread over threads with a result that does not depend on their number: agents are cut into
// fixed contiguous ranges, each range fills its own part, and the parts are joined in range order.
#pragma once

#include <throng/core/parallel.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace throng::detail {

/// Calls fill(n, part) for every agent n in [0, agents), agents of one range in increasing order into that
/// range's part (default-constructed Part), ranges in parallel; then join(part) for each part in range order.
/// fill must touch only state of agent n (AgentPoses keeps its state per agent).
template <class Part, class Fill, class Join>
void for_agent_ranges(std::size_t agents, Fill fill, Join join) {
  constexpr std::size_t ranges = 16;
  const std::size_t step = (agents + ranges - 1) / ranges;
  std::vector<Part> parts(ranges);
  parallel_for(ranges, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t r = begin; r < end; ++r) {
      for (std::size_t n = r * step; n < std::min(agents, (r + 1) * step); ++n) fill(n, parts[r]);
    }
  });
  for (auto& part : parts) join(part);
}

}  // namespace throng::detail
