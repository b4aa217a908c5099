// Uniform grid over agent positions, rebuilt each step by a counting sort (cache-friendly neighbour search).
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace throng::sketch::detail {

/// Agents sorted by cell. After build(): slots [0, in_grid_count()) hold the agents in the grid, cell by cell
/// (row-major cells, agent index order within a cell: a stable, thread-independent order); slots after that hold
/// the agents left out. sorted_x/sorted_y are the positions in slot order.
///
/// Cells are squares of side ≥ `min_cell`, so every agent within min_cell of a point lies in the 3×3 cells around
/// the point's cell. The cell count is capped at about twice the agent count (cells grow when agents are spread
/// far apart), so memory and the prefix sum stay O(agents).
class NeighbourGrid {
 public:
  /// x, y: #agents positions; in_grid: #agents flags (0: left out, e.g. removed agents); count: the number of
  /// flags set; bounds: the box holding the agents in the grid (the caller gathers both while writing the state).
  void build(const std::vector<double>& x, const std::vector<double>& y, const std::vector<std::uint8_t>& in_grid,
             std::size_t count, const Eigen::AlignedBox2d& bounds, double min_cell);

  [[nodiscard]] std::size_t in_grid_count() const noexcept { return in_grid_; }
  [[nodiscard]] const std::vector<std::uint32_t>& order() const noexcept { return order_; }
  [[nodiscard]] const std::vector<double>& sorted_x() const noexcept { return sorted_x_; }
  [[nodiscard]] const std::vector<double>& sorted_y() const noexcept { return sorted_y_; }

  [[nodiscard]] std::size_t columns() const noexcept { return nx_; }
  [[nodiscard]] std::size_t rows() const noexcept { return ny_; }
  [[nodiscard]] std::size_t cell_count() const noexcept { return nx_ * ny_; }
  [[nodiscard]] double cell_size() const noexcept { return h_; }

  /// Column and row of a point, clamped to the grid (points outside map to border cells).
  [[nodiscard]] std::size_t column(double x) const noexcept { return clamp_index((x - x0_) * inv_h_, nx_); }
  [[nodiscard]] std::size_t row(double y) const noexcept { return clamp_index((y - y0_) * inv_h_, ny_); }
  [[nodiscard]] std::size_t cell(double x, double y) const noexcept { return row(y) * nx_ + column(x); }

  /// First slot of cell c; cells c..c2 (same row) occupy slots [cell_start(c), cell_start(c2 + 1)).
  [[nodiscard]] std::uint32_t cell_start(std::size_t c) const noexcept { return start_[c]; }

  /// Lower-left corner of cell (column, row); cells are [corner, corner + cell_size()).
  [[nodiscard]] double cell_x0(std::size_t column) const noexcept { return x0_ + static_cast<double>(column) * h_; }
  [[nodiscard]] double cell_y0(std::size_t row) const noexcept { return y0_ + static_cast<double>(row) * h_; }

 private:
  static std::size_t clamp_index(double v, std::size_t n) noexcept {
    if (!(v > 0)) return 0;  // also NaN
    const double top = static_cast<double>(n - 1);
    return v >= top ? n - 1 : static_cast<std::size_t>(v);
  }

  double x0_ = 0, y0_ = 0, h_ = 1, inv_h_ = 1;
  std::size_t nx_ = 1, ny_ = 1, in_grid_ = 0;
  std::vector<std::uint32_t> start_;    // #cells + 1
  std::vector<std::uint32_t> cell_of_;  // #agents, cell of each agent in the grid
  std::vector<std::uint32_t> order_;    // #agents, slot → agent
  std::vector<double> sorted_x_, sorted_y_;
};

}  // namespace throng::sketch::detail
