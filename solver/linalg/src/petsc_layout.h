// How the petsc backend lays a system out over ranks: the unknowns ordered by part, parts dealt to ranks, so
// each rank owns one contiguous range of rows holding whole parts (built only with PETSc; no PETSc type here).
//
// The parts are METIS k-way parts of the matrix's node graph (nodes of `block_size` consecutive unknowns, so a
// node's x and y stay together; an edge joins two nodes when their block of the matrix has an entry). For a
// least-squares system built on a space-time graph that node graph is the space-time graph of the free vertices,
// so these are the parts of solver/graph's partition.h of the unknowns the ranks solve for. Two levels:
//   * rank parts: the graph split into #ranks parts (fewer edges cut = fewer off-rank entries in MatMult);
//   * sub-parts: each rank part split again into `parts_per_rank` parts, the subdomains of additive Schwarz.
// Within a part the original order is kept, so one rank and one part per rank is the identity ordering.
// METIS runs with a fixed seed on 1 thread: the same pattern gives the same layout on every run.
#pragma once

#include <throng/linalg/solver_options.h>

#include <vector>

namespace throng::linalg::petsc {

struct Layout {
  /// new_of[old]: the unknown's row in the distributed (part-ordered) system; old_of is its inverse. #n each.
  std::vector<int> new_of;
  std::vector<int> old_of;
  /// First new row of each rank, #ranks + 1 (rank r owns [rank_begin[r], rank_begin[r + 1])).
  std::vector<int> rank_begin;
  /// First new row of each sub-part, in rank order, #parts + 1; part_rank[p] is the rank holding part p.
  std::vector<int> part_begin;
  std::vector<int> part_rank;
};

/// The layout of `matrix` (#n by #n, symmetric pattern, both triangles) over `ranks` ranks with
/// `parts_per_rank` ≥ 1 sub-parts each. block_size must divide #n. Parts are capped at the number of nodes
/// (a tiny system gives some ranks no rows). Throws NumericalError when METIS fails.
[[nodiscard]] Layout part_layout(const SparseMatrix& matrix, int block_size, int ranks, int parts_per_rank);

}  // namespace throng::linalg::petsc
