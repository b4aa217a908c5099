// Measures of a partition of a motion graph shared by the tests and bench/graph/bench_partition: how its parts in
// consecutive time blocks line up.
#pragma once

#include <throng/graph/motion_graph.h>
#include <throng/graph/partition.h>

#include <cstddef>

namespace throng::test {

/// Per part, the parts of other blocks it touches (adjacent parts whose first vertex lies at another sample), on
/// average. For partition_time_blocks' parts: about 2 when consecutive blocks group their agents alike.
inline double other_block_neighbours(const MotionGraph& graph, const Partition& p) {
  const std::size_t n = graph.agent_count();
  std::size_t count = 0;
  for (std::size_t part = 0; part < p.parts.size(); ++part) {
    const auto block = static_cast<std::size_t>(p.parts[part].front()) / n;
    for (const int other : p.adjacent[part]) {
      count += static_cast<std::size_t>(p.parts[static_cast<std::size_t>(other)].front()) / n != block ? 1 : 0;
    }
  }
  return static_cast<double>(count) / static_cast<double>(p.parts.size());
}

}  // namespace throng::test
