// The first half of both make_partition versions (throng/graph/partition.h): labels checked and renumbered.
#pragma once

#include <throng/graph/partition.h>

#include <span>

namespace throng::detail {

/// A Partition with part_of and parts filled from `part_of` (`vertices` labels ≥ 0), parts numbered in order of
/// their smallest vertex; boundary, adjacent and edge_cut left for the caller (they need the graph's edges).
/// std::invalid_argument for a size mismatch or a negative label.
[[nodiscard]] Partition numbered_parts(std::size_t vertices, std::span<const int> part_of);

}  // namespace throng::detail
