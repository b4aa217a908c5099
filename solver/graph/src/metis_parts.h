// METIS labels of a graph, shared by partition_graph (the whole space-time graph, k-way) and
// partition_time_blocks (each block's agents, recursive bisection).
#pragma once

#include <throng/graph/partition.h>

#include <span>
#include <vector>

namespace throng::detail {

/// METIS_PartGraphKway, or METIS_PartGraphRecursive: on a block's agents (about 31 a part) recursive bisection
/// ran 4x faster for about the same cut on large blocks and a far better one on small ones (10,000 agents into
/// 320 parts: 35 against 143 ms, 6,796 against 6,544 cut edges; 48 agents into 5 parts: 40 against 92 of 130
/// edges cut).
enum class MetisMethod { kway, recursive };

/// A label in [0, options.parts) for every vertex of `graph` (all 0 for one part), by `method` with
/// options.seed and options.imbalance, one thread. `edge_weights` is empty (every edge 1) or one positive weight
/// per entry of graph.neighbours, the same for both ends of an edge. Options are not checked here (the callers
/// do: check_imbalance). Safe to call from several threads: the calls take turns (METIS's random generator is one
/// per process; METIS calls made by other libraries, such as CHOLMOD's orderings, are not covered). A graph with
/// no edge must not be given with more than one part (METIS may read its empty edge arrays): callers group those
/// vertices themselves. NumericalError when METIS fails; std::invalid_argument for weights of the wrong length.
[[nodiscard]] std::vector<int> metis_parts(const AdjacencyGraph& graph, std::span<const int> edge_weights,
                                           const PartitionOptions& options, MetisMethod method);

/// ConfigError unless imbalance is in (1, 10] (PartitionOptions::imbalance): both partitioners check it so.
void check_imbalance(double imbalance);

}  // namespace throng::detail
