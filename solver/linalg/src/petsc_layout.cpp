#include "petsc_layout.h"

#include <throng/core/errors.h>

#include <metis.h>

#include <algorithm>
#include <numeric>
#include <string>

namespace throng::linalg::petsc {
namespace {

static_assert(sizeof(idx_t) == sizeof(int), "the petsc layout passes int arrays to METIS: a 32-bit idx_t build is needed");

struct Csr {
  std::vector<int> offsets{0};
  std::vector<int> neighbours;
  [[nodiscard]] int nodes() const { return static_cast<int>(offsets.size()) - 1; }
};

// The node graph: node a joined to node b ≠ a when a column of a's block has an entry in a row of b's block.
Csr node_graph(const SparseMatrix& matrix, int bs) {
  const int nodes = static_cast<int>(matrix.cols()) / bs;
  Csr g;
  g.offsets.reserve(static_cast<std::size_t>(nodes) + 1);
  g.neighbours.reserve(static_cast<std::size_t>(matrix.nonZeros() / (bs * bs)));
  std::vector<int> mark(static_cast<std::size_t>(nodes), -1);
  for (int a = 0; a < nodes; ++a) {
    const std::size_t start = g.neighbours.size();
    for (int k = 0; k < bs; ++k) {
      for (SparseMatrix::InnerIterator it(matrix, a * bs + k); it; ++it) {
        const int b = static_cast<int>(it.row()) / bs;
        if (b == a || mark[static_cast<std::size_t>(b)] == a) continue;
        mark[static_cast<std::size_t>(b)] = a;
        g.neighbours.push_back(b);
      }
    }
    std::sort(g.neighbours.begin() + static_cast<std::ptrdiff_t>(start), g.neighbours.end());
    g.offsets.push_back(static_cast<int>(g.neighbours.size()));
  }
  return g;
}

// METIS k-way parts of `g` (k ≥ 2, k ≤ nodes), fixed seed.
std::vector<int> kway(Csr& g, int k) {
  idx_t n = g.nodes();
  idx_t constraints = 1;
  idx_t parts = k;
  idx_t cut = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 1;
  options[METIS_OPTION_NUMBERING] = 0;
  std::vector<idx_t> part(static_cast<std::size_t>(n), 0);
  const int status = METIS_PartGraphKway(&n, &constraints, g.offsets.data(), g.neighbours.data(), nullptr, nullptr,
                                         nullptr, &parts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK) {
    throw NumericalError("petsc backend: METIS could not split the system's " + std::to_string(n) + " nodes into " +
                         std::to_string(k) + " parts (status " + std::to_string(status) + ")");
  }
  return part;
}

// Parts of `g` into min(k, nodes) labels (all 0 when that is 1).
std::vector<int> split(Csr& g, int k) {
  k = std::min(k, g.nodes());
  if (k <= 1) return std::vector<int>(static_cast<std::size_t>(g.nodes()), 0);
  return kway(g, k);
}

// The subgraph induced by `members` (increasing node numbers of g).
Csr induced(const Csr& g, const std::vector<int>& members, std::vector<int>& local_of) {
  for (std::size_t i = 0; i < members.size(); ++i) local_of[static_cast<std::size_t>(members[i])] = static_cast<int>(i);
  Csr sub;
  sub.offsets.reserve(members.size() + 1);
  for (int v : members) {
    for (int e = g.offsets[static_cast<std::size_t>(v)]; e < g.offsets[static_cast<std::size_t>(v) + 1]; ++e) {
      const int w = local_of[static_cast<std::size_t>(g.neighbours[static_cast<std::size_t>(e)])];
      if (w >= 0) sub.neighbours.push_back(w);
    }
    sub.offsets.push_back(static_cast<int>(sub.neighbours.size()));
  }
  for (int v : members) local_of[static_cast<std::size_t>(v)] = -1;
  return sub;
}

}  // namespace

Layout part_layout(const SparseMatrix& matrix, int block_size, int ranks, int parts_per_rank) {
  const int bs = std::max(1, block_size);
  const int n = static_cast<int>(matrix.cols());
  const int nodes = n / bs;
  ranks = std::max(1, ranks);
  parts_per_rank = std::max(1, parts_per_rank);

  Csr g = (ranks > 1 || parts_per_rank > 1) ? node_graph(matrix, bs) : Csr{};
  // Rank of each node, then the sub-part of each node within its rank part.
  std::vector<int> rank_of = ranks > 1 ? split(g, ranks) : std::vector<int>(static_cast<std::size_t>(nodes), 0);
  std::vector<std::vector<int>> members(static_cast<std::size_t>(ranks));
  for (int v = 0; v < nodes; ++v) members[static_cast<std::size_t>(rank_of[static_cast<std::size_t>(v)])].push_back(v);
  std::vector<int> sub_of(static_cast<std::size_t>(nodes), 0);
  if (parts_per_rank > 1) {
    std::vector<int> local_of(static_cast<std::size_t>(nodes), -1);
    for (const auto& m : members) {
      if (m.size() < 2) continue;
      Csr sub = induced(g, m, local_of);
      const std::vector<int> labels = split(sub, parts_per_rank);
      for (std::size_t i = 0; i < m.size(); ++i) sub_of[static_cast<std::size_t>(m[i])] = labels[i];
    }
  }

  // Nodes sorted by (rank, sub-part), original order within: a stable bucket pass per rank.
  Layout layout;
  layout.new_of.assign(static_cast<std::size_t>(n), 0);
  layout.old_of.assign(static_cast<std::size_t>(n), 0);
  layout.rank_begin.assign(1, 0);
  layout.part_begin.assign(1, 0);
  int next = 0;
  for (int r = 0; r < ranks; ++r) {
    const auto& m = members[static_cast<std::size_t>(r)];
    std::vector<std::vector<int>> buckets(static_cast<std::size_t>(parts_per_rank));
    for (int v : m) buckets[static_cast<std::size_t>(sub_of[static_cast<std::size_t>(v)])].push_back(v);
    for (const auto& bucket : buckets) {
      if (bucket.empty()) continue;
      for (int v : bucket) {
        for (int k = 0; k < bs; ++k) {
          layout.new_of[static_cast<std::size_t>(v * bs + k)] = next;
          layout.old_of[static_cast<std::size_t>(next)] = v * bs + k;
          ++next;
        }
      }
      layout.part_begin.push_back(next);
      layout.part_rank.push_back(r);
    }
    layout.rank_begin.push_back(next);
  }
  return layout;
}

}  // namespace throng::linalg::petsc
