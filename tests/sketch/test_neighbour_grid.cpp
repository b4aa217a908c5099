// The neighbour grid (solver/sketch/src/neighbour_grid.h): its counting sort, made in two parts of the agents on
// two cores from 8,192 agents on, gives the order of a serial stable counting sort (cell by cell, agent index order
// within a cell, the agents left out last in index order), whatever the number of threads; the positions follow
// the order, each agent's slot is given back by slot_of, and the padding after the positions is zeros.
#include "neighbour_grid.h"

#include <throng/core/parallel.h>
#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

using throng::Rng;
using throng::sketch::detail::NeighbourGrid;

TEST_CASE("the neighbour grid sorts agents by cell as a serial stable counting sort does") {
  Rng rng(11);
  for (const std::size_t n : {0, 1, 5, 8191, 8192, 20001}) {
    for (const double left_out_share : {0.0, 0.3}) {
      // A crowd at about 1 per m², some agents left out of the grid (removed agents), a few at one place.
      std::vector<double> x(n), y(n);
      std::vector<std::uint8_t> in_grid(n, 1);
      std::size_t count = 0;
      Eigen::AlignedBox2d bounds;
      const double side = std::sqrt(static_cast<double>(n)) + 1.0;
      for (std::size_t i = 0; i < n; ++i) {
        x[i] = rng.uniform(-side, side);
        y[i] = rng.uniform(0, side);
        if (i > 0 && rng.uniform() < 0.02) {
          x[i] = x[i - 1];
          y[i] = y[i - 1];
        }
        in_grid[i] = rng.uniform() >= left_out_share;
        if (in_grid[i]) {
          ++count;
          bounds.extend(Eigen::Vector2d(x[i], y[i]));
        }
      }
      for (const std::size_t threads : {1, 2}) {
        INFO("agents " << n << ", left out " << left_out_share << ", threads " << threads);
        const throng::ThreadLimit limit(threads);
        NeighbourGrid grid;
        grid.build(x, y, in_grid, count, bounds, 1.0);
        REQUIRE(grid.in_grid_count() == count);
        // The serial counting sort, straight: cells in order, agents in index order within each.
        std::vector<std::vector<std::uint32_t>> by_cell(grid.cell_count());
        std::vector<std::uint32_t> expected, left_out;
        for (std::size_t i = 0; i < n; ++i) {
          if (in_grid[i]) {
            by_cell[grid.cell(x[i], y[i])].push_back(static_cast<std::uint32_t>(i));
          } else {
            left_out.push_back(static_cast<std::uint32_t>(i));
          }
        }
        std::size_t mismatched_starts = 0;
        for (std::size_t c = 0; c < grid.cell_count(); ++c) {
          mismatched_starts += grid.cell_start(c) != expected.size();
          expected.insert(expected.end(), by_cell[c].begin(), by_cell[c].end());
        }
        CHECK(mismatched_starts == 0);
        CHECK(grid.cell_start(grid.cell_count()) == count);
        expected.insert(expected.end(), left_out.begin(), left_out.end());
        CHECK(grid.order() == expected);
        // slot_of is order's inverse: every agent's slot, the left-out ones' included.
        REQUIRE(grid.slot_of().size() == n);
        std::size_t not_inverse = 0;
        for (std::size_t slot = 0; slot < n; ++slot) not_inverse += grid.slot_of()[expected[slot]] != slot;
        CHECK(not_inverse == 0);
        REQUIRE(grid.sorted_x().size() == count + NeighbourGrid::padding);
        REQUIRE(grid.sorted_y().size() == count + NeighbourGrid::padding);
        std::size_t misplaced = 0;
        for (std::size_t slot = 0; slot < count; ++slot) {
          misplaced += grid.sorted_x()[slot] != x[expected[slot]] || grid.sorted_y()[slot] != y[expected[slot]];
        }
        CHECK(misplaced == 0);
        for (std::size_t slot = count; slot < count + NeighbourGrid::padding; ++slot) {
          CHECK(grid.sorted_x()[slot] == 0.0);
          CHECK(grid.sorted_y()[slot] == 0.0);
        }
      }
    }
  }
}
