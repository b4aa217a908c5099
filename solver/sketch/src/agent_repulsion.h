// The agents' repulsion of paper Eq. 16–17 (as read in sketch.h): the neighbour sum of one agent over the grid.
#pragma once

#include <Eigen/Core>
#include <cstddef>

#include "neighbour_grid.h"

namespace throng::sketch::detail {

/// Σ over the agents l closer than r to p of (p − p_l)(r/d − 1), d = |p − p_l|, over the grid's 3×3 cells around
/// p (their side is at least r). `slot` is the agent's own grid slot: it is skipped, and any other agent exactly
/// at p adds r in a direction fixed by the pair (opposite for the two of them), so agents at one place part.
/// The terms are added in a fixed order: row by row, a row's slots in pairs into two lane sums and its odd last
/// slot into a scalar sum; then the lane sums, then the terms of agents exactly at p. The same bits whatever the
/// thread count.
[[nodiscard]] Eigen::Vector2d agent_repulsion(const NeighbourGrid& grid, std::size_t slot, const Eigen::Vector2d& p,
                                              double r);

}  // namespace throng::sketch::detail
