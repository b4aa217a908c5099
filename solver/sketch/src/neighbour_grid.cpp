#include "neighbour_grid.h"

#include <throng/core/parallel.h>

#include <cassert>
#include <limits>

namespace throng::sketch::detail {

void NeighbourGrid::build(const std::vector<double>& x, const std::vector<double>& y,
                          const std::vector<std::uint8_t>& in_grid, std::size_t count,
                          const Eigen::AlignedBox2d& bounds, double min_cell) {
  const std::size_t n = x.size();
  assert(y.size() == n && in_grid.size() == n && count <= n && n < std::numeric_limits<std::uint32_t>::max());
  in_grid_ = count;
  double x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  if (count > 0) {
    x_min = bounds.min().x();
    y_min = bounds.min().y();
    x_max = bounds.max().x();
    y_max = bounds.max().y();
  }

  // Cell side: at least min_cell, larger when the cell count would exceed ~2 per agent.
  const double cap = std::max(64.0, 2.0 * static_cast<double>(count));
  h_ = std::max(min_cell, 1e-9);
  const double wx = x_max - x_min, wy = y_max - y_min;
  if ((std::floor(wx / h_) + 1) * (std::floor(wy / h_) + 1) > cap) {
    // Smallest h with (wx/h + 1)(wy/h + 1) ≤ cap: positive root of (cap − 1)h² − (wx + wy)h − wx·wy = 0.
    const double a = cap - 1, b = wx + wy, c = wx * wy;
    h_ = std::max(h_, (b + std::sqrt(b * b + 4 * a * c)) / (2 * a));
  }
  inv_h_ = 1.0 / h_;
  x0_ = x_min;
  y0_ = y_min;
  nx_ = static_cast<std::size_t>(std::floor(wx * inv_h_)) + 1;
  ny_ = static_cast<std::size_t>(std::floor(wy * inv_h_)) + 1;

  // Counting sort: count, prefix sum, scatter (agent index order within a cell).
  const std::size_t cells = nx_ * ny_;
  start_.assign(cells + 1, 0);
  cell_of_.resize(n);
  parallel_for(n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) cell_of_[i] = static_cast<std::uint32_t>(cell(x[i], y[i]));
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (in_grid[i]) ++start_[cell_of_[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  order_.resize(n);
  sorted_x_.resize(n);
  sorted_y_.resize(n);
  // Scatter with a moving cursor per cell; start_ is restored afterwards by shifting.
  std::uint32_t outside = static_cast<std::uint32_t>(count);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t slot = in_grid[i] ? start_[cell_of_[i]]++ : outside++;
    order_[slot] = static_cast<std::uint32_t>(i);
    sorted_x_[slot] = x[i];
    sorted_y_[slot] = y[i];
  }
  for (std::size_t c = cells; c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
}

}  // namespace throng::sketch::detail
