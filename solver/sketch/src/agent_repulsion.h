// The agents' repulsion of paper Eq. 16–17 (as read in sketch.h): the neighbour sum of one agent over the grid.
#pragma once

#include <Eigen/Core>
#include <cstddef>

#include "neighbour_grid.h"

namespace throng::sketch::detail {

/// Σ over the agents l closer than r to p of (p − p_l)(r/d − 1), d = |p − p_l|, over the grid's 3×3 cells around
/// p (their side is at least r). `slot` is the agent's own grid slot and p its place there: it is skipped, and any
/// other agent exactly at p adds r in a direction fixed by the pair (opposite for the two of them), so agents at
/// one place part. The terms are added in the fixed order of neighbour_sum.h (the 3×3 cells as three ranges of
/// slots, one per row), then the terms of agents exactly at p: the same bits whatever the thread count, and
/// whichever of its loops runs (AVX2 where the processor has it, SSE2 elsewhere).
[[nodiscard]] Eigen::Vector2d agent_repulsion(const NeighbourGrid& grid, std::size_t slot, const Eigen::Vector2d& p,
                                              double r);

}  // namespace throng::sketch::detail
