#include "agent_repulsion.h"

#include <throng/core/random.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
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

}  // namespace

Eigen::Vector2d agent_repulsion(const NeighbourGrid& grid, std::size_t slot, const Eigen::Vector2d& p, double r) {
  const std::uint32_t* order = grid.order().data();
  const double* sx = grid.sorted_x().data();
  const double* sy = grid.sorted_y().data();
  const std::size_t nx = grid.columns(), ny = grid.rows();
  const double px = p.x(), py = p.y(), r2 = r * r;
  const std::size_t cx = grid.column(px), cy = grid.row(py);
  const std::size_t c0 = cx > 0 ? cx - 1 : 0, c1 = std::min(cx + 1, nx - 1);
  const std::size_t r0 = cy > 0 ? cy - 1 : 0, r1 = std::min(cy + 1, ny - 1);
  double ax = 0, ay = 0;
  bool coincident = false;
  // Two candidates at a time in SSE2 lanes (GCC/Clang vector extensions), branch-free: every candidate computes
  // r/d − 1 (on d = r when out of reach) and is masked by `near`. Lane sums are added in a fixed order, so the
  // result does not depend on the thread count.
  using Pair = double __attribute__((vector_size(16)));
  using Mask = std::int64_t __attribute__((vector_size(16)));
  const Pair vpx = {px, px}, vpy = {py, py}, vr = {r, r}, vr2 = {r2, r2}, zero = {0, 0}, one = {1, 1};
  Pair vax = zero, vay = zero;
  for (std::size_t row = r0; row <= r1; ++row) {
    // The three cells of a row are consecutive slots.
    const std::uint32_t from = grid.cell_start(row * nx + c0), to = grid.cell_start(row * nx + c1 + 1);
    std::uint32_t l = from;
    for (; l + 2 <= to; l += 2) {
      Pair qx, qy;
      std::memcpy(&qx, sx + l, sizeof qx);
      std::memcpy(&qy, sy + l, sizeof qy);
      const Pair dx = vpx - qx, dy = vpy - qy;
      const Pair d2 = dx * dx + dy * dy;
      const Mask near = (d2 < vr2) & (d2 > zero);
      const Pair safe = near ? d2 : vr2;
      const Pair root = {std::sqrt(safe[0]), std::sqrt(safe[1])};
      const Pair c = near ? vr / root - one : zero;
      vax += c * dx;
      vay += c * dy;
      coincident |= (d2[0] == 0 && l != slot) || (d2[1] == 0 && l + 1 != slot);
    }
    for (; l < to; ++l) {
      const double dx = px - sx[l], dy = py - sy[l];
      const double d2 = dx * dx + dy * dy;
      if (d2 < r2 && d2 > 0) {
        const double c = r / std::sqrt(d2) - 1.0;
        ax += c * dx;
        ay += c * dy;
      }
      coincident |= d2 == 0 && l != slot;
    }
  }
  ax += vax[0] + vax[1];
  ay += vay[0] + vay[1];
  if (coincident) {
    // Same place: (p_j − p_l)(r/d − 1) has length r − d → r, in a direction fixed by the pair.
    for (std::size_t row = r0; row <= r1; ++row) {
      const std::uint32_t from = grid.cell_start(row * nx + c0), to = grid.cell_start(row * nx + c1 + 1);
      for (std::uint32_t l = from; l < to; ++l) {
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
