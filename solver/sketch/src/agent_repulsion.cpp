#include "agent_repulsion.h"

#include "neighbour_sum.h"

#include <throng/core/random.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace throng::sketch::detail {
namespace {

// A unit direction for two agents at the same place: fixed by the pair, opposite for the two of them.
Eigen::Vector2d coincident_direction(std::uint32_t self, std::uint32_t other) {
  const std::uint64_t lo = std::min(self, other), hi = std::max(self, other);
  const double angle = 2 * std::numbers::pi * static_cast<double>(derive_seed(lo, hi) >> 11) * 0x1.0p-53;
  const Eigen::Vector2d d(std::cos(angle), std::sin(angle));
  return self < other ? d : Eigen::Vector2d(-d);
}

// The neighbour loop for this processor, chosen once at start rather than asked for every agent of every step.
using NeighbourLoop = NeighbourSum (*)(const NeighbourQuery&) noexcept;
const NeighbourLoop neighbour_loop = has_avx2() ? neighbour_sum_avx2 : neighbour_sum_sse2;

}  // namespace

Eigen::Vector2d agent_repulsion(const NeighbourGrid& grid, std::size_t slot, const Eigen::Vector2d& p, double r) {
  const std::uint32_t* order = grid.order().data();
  const double* sx = grid.sorted_x().data();
  const double* sy = grid.sorted_y().data();
  const std::size_t nx = grid.columns(), ny = grid.rows();
  const double px = p.x(), py = p.y();
  // The agent at p is counted among the candidates at p below: p must be its place in the grid.
  assert(slot < grid.in_grid_count() && sx[slot] == px && sy[slot] == py);
  const std::size_t cx = grid.column(px), cy = grid.row(py);
  const std::size_t c0 = cx > 0 ? cx - 1 : 0, c1 = std::min(cx + 1, nx - 1);
  const std::size_t r0 = cy > 0 ? cy - 1 : 0, r1 = std::min(cy + 1, ny - 1);
  NeighbourQuery query{sx, sy, {}, {}, 0, px, py, r};
  for (std::size_t row = r0; row <= r1; ++row, ++query.ranges) {
    // The three cells of a row are consecutive slots.
    query.from[query.ranges] = grid.cell_start(row * nx + c0);
    query.to[query.ranges] = grid.cell_start(row * nx + c1 + 1);
  }
  const NeighbourSum sum = neighbour_loop(query);
  double ax = sum.x, ay = sum.y;
  // Candidates at p: the agent itself (its own cell is searched, and p is its place there) and any other.
  if (sum.at_p > 1) {
    // Same place: (p_j − p_l)(r/d − 1) has length r − d → r, in a direction fixed by the pair.
    for (std::size_t range = 0; range < query.ranges; ++range) {
      for (std::uint32_t l = query.from[range]; l < query.to[range]; ++l) {
        if (l == slot || sx[l] != px || sy[l] != py) continue;
        const Eigen::Vector2d u = coincident_direction(order[slot], order[l]);
        ax += r * u.x();
        ay += r * u.y();
      }
    }
  }
  return {ax, ay};
}

}  // namespace throng::sketch::detail
