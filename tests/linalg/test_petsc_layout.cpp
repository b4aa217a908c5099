// The petsc backend's layout (solver/linalg/src/petsc_layout.h, built with PETSc only): unknowns ordered by
// METIS part, parts dealt to ranks, each rank's rows contiguous.
#include "petsc_layout.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <set>
#include <vector>

using throng::linalg::SparseMatrix;

namespace {

// The 5-point Laplacian-like pattern of a side × side grid with `bs` interleaved unknowns per node.
SparseMatrix grid_matrix(int side, int bs) {
  const int nodes = side * side;
  std::vector<Eigen::Triplet<double>> t;
  auto couple = [&](int a, int b) {
    for (int i = 0; i < bs; ++i)
      for (int j = 0; j < bs; ++j) t.emplace_back(a * bs + i, b * bs + j, a == b ? 4.0 : -0.5);
  };
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const int v = y * side + x;
      couple(v, v);
      if (x + 1 < side) couple(v, v + 1), couple(v + 1, v);
      if (y + 1 < side) couple(v, v + side), couple(v + side, v);
    }
  SparseMatrix m(nodes * bs, nodes * bs);
  m.setFromTriplets(t.begin(), t.end());
  return m;
}

}  // namespace

TEST_CASE("one rank and one part is the identity ordering") {
  const auto layout = throng::linalg::petsc::part_layout(grid_matrix(6, 2), 2, 1, 1);
  for (std::size_t i = 0; i < layout.new_of.size(); ++i) CHECK(layout.new_of[i] == static_cast<int>(i));
  CHECK(layout.rank_begin == std::vector<int>{0, 72});
  CHECK(layout.part_rank == std::vector<int>{0});
}

TEST_CASE("parts are dealt to ranks as contiguous rows, whole nodes, balanced and connected") {
  const int side = 20, bs = 2, ranks = 3, per_rank = 4;
  const SparseMatrix m = grid_matrix(side, bs);
  const auto layout = throng::linalg::petsc::part_layout(m, bs, ranks, per_rank);
  const int n = side * side * bs;
  // A permutation and its inverse.
  REQUIRE(static_cast<int>(layout.new_of.size()) == n);
  for (int i = 0; i < n; ++i) CHECK(layout.old_of[static_cast<std::size_t>(layout.new_of[static_cast<std::size_t>(i)])] == i);
  // Ranks: contiguous, covering everything, within METIS's 3% imbalance (plus a node of rounding).
  REQUIRE(static_cast<int>(layout.rank_begin.size()) == ranks + 1);
  CHECK(layout.rank_begin.front() == 0);
  CHECK(layout.rank_begin.back() == n);
  for (int r = 0; r < ranks; ++r) {
    const int rows = layout.rank_begin[static_cast<std::size_t>(r) + 1] - layout.rank_begin[static_cast<std::size_t>(r)];
    CHECK(rows <= 1.03 * n / ranks + bs);
  }
  // Parts: each inside one rank's range, ranks in order, per_rank parts each; a node's unknowns stay together.
  REQUIRE(static_cast<int>(layout.part_rank.size()) == ranks * per_rank);
  for (std::size_t p = 0; p < layout.part_rank.size(); ++p) {
    const int r = layout.part_rank[p];
    CHECK(layout.part_begin[p] >= layout.rank_begin[static_cast<std::size_t>(r)]);
    CHECK(layout.part_begin[p + 1] <= layout.rank_begin[static_cast<std::size_t>(r) + 1]);
    CHECK(r == static_cast<int>(p) / per_rank);
  }
  for (int node = 0; node < side * side; ++node) {
    CHECK(layout.new_of[static_cast<std::size_t>(node * bs + 1)] == layout.new_of[static_cast<std::size_t>(node * bs)] + 1);
  }
  // METIS parts of a grid are connected: every part is one component of the grid graph.
  for (std::size_t p = 0; p < layout.part_rank.size(); ++p) {
    std::set<int> nodes;
    for (int row = layout.part_begin[p]; row < layout.part_begin[p + 1]; row += bs) nodes.insert(layout.old_of[static_cast<std::size_t>(row)] / bs);
    std::vector<int> stack{*nodes.begin()};
    std::set<int> seen{*nodes.begin()};
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      for (SparseMatrix::InnerIterator it(m, v * bs); it; ++it) {
        const int w = static_cast<int>(it.row()) / bs;
        if (nodes.count(w) && seen.insert(w).second) stack.push_back(w);
      }
    }
    CAPTURE(p);
    CHECK(seen.size() == nodes.size());
  }
}
