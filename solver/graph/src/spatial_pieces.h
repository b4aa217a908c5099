// Cutting a large block of agents into pieces by place before METIS groups each piece (partition_time_blocks,
// throng/graph/partition.h).
//
// Why: METIS's recursive bisection of one block into g groups costs about n·log g, so with groups of a fixed size
// (n/31 of them) partitioning grew as N^1.1. Cutting the block first at the median of its agents' places, along
// the wider side, until each piece holds at most a fixed number of groups, leaves METIS pieces of a bounded size,
// so METIS's share grows linearly; the cuts are selections, log2(g/16) passes over the agents (N log N, but a few
// milliseconds at 20,000 agents). Below that number of groups nothing is cut.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace throng::detail {

/// Agents that METIS groups together, and into how many groups.
///   agents  increasing agent indices (rows of the places given to spatial_pieces)
struct AgentPiece {
  std::vector<int> agents;
  int groups = 1;
};

/// Agents 0 .. places.rows() − 1 cut into pieces of at most `max_groups` groups (groups ≥ 1, max_groups ≥ 1):
/// a set of g > max_groups groups is cut into ⌊g/2⌋ and g − ⌊g/2⌋ groups, its agents in the same proportion (rounded)
/// at the order statistic of their coordinate along the wider side of their bounding box (x on a tie), ties broken
/// by agent index, so the pieces do not depend on how the selection is implemented. Pieces are listed depth first,
/// the lower side first. A piece never has fewer agents than groups when there are at least as many agents as
/// groups; a side left without agents (fewer agents than groups) gives no piece. One piece of every agent when
/// groups ≤ max_groups; none for no agent. std::invalid_argument for groups or max_groups below 1.
///   places  #agents × 2: one finite place per agent (metres)
[[nodiscard]] std::vector<AgentPiece> spatial_pieces(const Eigen::Matrix<double, Eigen::Dynamic, 2>& places, int groups,
                                                     int max_groups);

/// Shares `groups` among `pieces` (their agents kept) in proportion to their agents, by largest remainder (ties
/// to the earlier piece), each piece at least 1 group and at most its agents and `max_groups`. False, pieces
/// unchanged, when that cannot be done (a piece without agents, fewer groups than pieces, more than the pieces can
/// hold).
[[nodiscard]] bool share_groups(std::vector<AgentPiece>& pieces, int groups, int max_groups);

}  // namespace throng::detail
