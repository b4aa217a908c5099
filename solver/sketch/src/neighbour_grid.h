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
/// the agents left out. sorted_x/sorted_y are the positions of the agents in the grid in slot order, followed by
/// `padding` zeros, so that a search may read up to that many slots past the end of its cells (vector lanes) and
/// mask them out.
///
/// Cells are squares of side ≥ `min_cell`, so every agent within min_cell of a point lies in the 3×3 cells around
/// the point's cell. The cell count is capped at about twice the agent count (cells grow when agents are spread
/// far apart), so memory and the prefix sum stay O(agents).
class NeighbourGrid {
 public:
  /// Entries (zeros) after the last agent's position in sorted_x and sorted_y.
  static constexpr std::size_t padding = 3;

  /// x, y: #agents positions; in_grid: #agents flags (0: left out, e.g. removed agents); count: the number of
  /// flags set; bounds: the box holding the agents in the grid (the caller gathers both while writing the state).
  void build(const std::vector<double>& x, const std::vector<double>& y, const std::vector<std::uint8_t>& in_grid,
             std::size_t count, const Eigen::AlignedBox2d& bounds, double min_cell);

  [[nodiscard]] std::size_t in_grid_count() const noexcept { return in_grid_; }
  [[nodiscard]] const std::vector<std::uint32_t>& order() const noexcept { return order_; }
  /// agent → slot, the inverse of order().
  [[nodiscard]] const std::vector<std::uint32_t>& slot_of() const noexcept { return slot_of_; }
  [[nodiscard]] const std::vector<double>& sorted_x() const noexcept { return sorted_x_; }
  [[nodiscard]] const std::vector<double>& sorted_y() const noexcept { return sorted_y_; }

  [[nodiscard]] std::size_t columns() const noexcept { return nx_; }
  [[nodiscard]] std::size_t rows() const noexcept { return ny_; }
  [[nodiscard]] std::size_t cell_count() const noexcept { return nx_ * ny_; }
  [[nodiscard]] double cell_size() const noexcept { return h_; }

  /// Column and row of a point, clamped to the grid (points outside map to border cells).
  [[nodiscard]] std::size_t column(double x) const noexcept { return clamp_index((x - x0_) * inv_h_, last_column_); }
  [[nodiscard]] std::size_t row(double y) const noexcept { return clamp_index((y - y0_) * inv_h_, last_row_); }
  [[nodiscard]] std::size_t cell(double x, double y) const noexcept { return row(y) * nx_ + column(x); }

  /// First slot of cell c; cells c..c2 (same row) occupy slots [cell_start(c), cell_start(c2 + 1)).
  [[nodiscard]] std::uint32_t cell_start(std::size_t c) const noexcept { return start_[c]; }

  /// Lower-left corner of cell (column, row); cells are [corner, corner + cell_size()).
  [[nodiscard]] double cell_x0(std::size_t column) const noexcept { return x0_ + static_cast<double>(column) * h_; }
  [[nodiscard]] double cell_y0(std::size_t row) const noexcept { return y0_ + static_cast<double>(row) * h_; }

 private:
  // v's integer part clamped to [0, top]: 0 for v ≤ 0 or NaN (max keeps its first argument when the comparison is
  // false), top for v ≥ top. Without branches (it runs for every agent and step, and for every neighbour search);
  // top is below 2^53, so the conversion is exact.
  static std::size_t clamp_index(double v, double top) noexcept {
    return static_cast<std::size_t>(static_cast<std::int64_t>(std::min(std::max(0.0, v), top)));
  }

  double x0_ = 0, y0_ = 0, h_ = 1, inv_h_ = 1;
  double last_column_ = 0, last_row_ = 0;  // nx − 1, ny − 1
  std::size_t nx_ = 1, ny_ = 1, in_grid_ = 0;
  std::vector<std::uint32_t> start_;    // #cells + 1
  std::vector<std::uint32_t> cell_of_;  // #agents, cell of each agent
  std::vector<std::uint32_t> counts_;   // #parts by #cells: a part's agents in each cell, then its first slot there
  std::vector<std::uint32_t> outside_;  // #parts + 1: each part's first slot for its agents left out
  std::vector<std::uint32_t> order_;    // #agents, slot → agent
  std::vector<std::uint32_t> slot_of_;  // #agents, agent → slot
  std::vector<double> sorted_x_, sorted_y_;
};

}  // namespace throng::sketch::detail
