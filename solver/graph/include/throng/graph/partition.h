// Partitioning the space-time graph into parts (METIS k-way on the whole graph, or time blocks × agent groups:
// partition_time_blocks), as plain data other code builds on: local edits solve only the parts an edit reaches
// (throng/edit/local_edit.h), distributed solves give parts to ranks.
//
// The graph is undirected and given in CSR form (METIS's xadj/adjncy). For a motion graph its vertices are the
// graph's vertices (agent j at sample i = row i·#agents + j) and its edges the formation edges of every sample
// plus the motion edges (i, j)–(i + 1, j) (space_time_adjacency).
//
// Decisions:
//  * METIS_PartGraphKway with a fixed seed (PartitionOptions::seed) and 1 thread: the same graph and options give
//    the same parts on every run and thread count. One part, or a graph with no vertex, needs no METIS call.
//  * METIS may leave a part empty (a disconnected graph, more parts than the graph can balance); empty parts
//    are dropped and the rest renumbered in order of their smallest vertex, so every part has a vertex and
//    part numbers do not depend on METIS's labels. part_count() can therefore be below the requested count.
//  * Boundary of a part: its vertices with a neighbour in another part. Adjacent parts: parts joined by an edge.
#pragma once

#include <throng/graph/motion_graph.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace throng {

/// An undirected graph in compressed sparse rows: the neighbours of v are neighbours[offsets[v] ..
/// offsets[v + 1]), increasing, no self loops, every edge listed from both ends.
///   offsets     #vertices + 1;   neighbours  2·#edges
struct AdjacencyGraph {
  std::vector<int> offsets{0};
  std::vector<int> neighbours;

  [[nodiscard]] std::size_t vertex_count() const noexcept { return offsets.size() - 1; }
  [[nodiscard]] std::size_t edge_count() const noexcept { return neighbours.size() / 2; }
  [[nodiscard]] std::span<const int> neighbours_of(std::size_t v) const noexcept {
    return {neighbours.data() + offsets[v], neighbours.data() + offsets[v + 1]};
  }
};

/// The graph of `vertex_count` vertices with the given edges (either order; duplicates and self loops are
/// dropped). Throws std::invalid_argument for a vertex index outside [0, vertex_count).
[[nodiscard]] AdjacencyGraph adjacency_from_edges(std::size_t vertex_count, std::span<const std::array<int, 2>> edges);

/// The space-time graph of a motion graph: formation edges within each sample and motion edges between
/// consecutive samples of each agent.
[[nodiscard]] AdjacencyGraph space_time_adjacency(const MotionGraph& graph);

struct PartitionOptions {
  int parts = 8;                 ///< parts asked for, ≥ 1 (fewer come back when METIS leaves some empty)
  double imbalance = 1.03;       ///< largest part ≤ imbalance · average size (METIS ufactor), in (1, 10]
  std::uint64_t seed = 1;        ///< METIS's random seed: same seed, same parts
};

/// Parts of a graph, their boundaries and their adjacency.
///   part_of   #vertices: the part of each vertex, in [0, part_count())
///   parts     #parts: the vertices of each part, increasing
///   boundary  #parts: the vertices of each part with a neighbour in another part, increasing
///   adjacent  #parts: the other parts joined to each part by an edge, increasing
struct Partition {
  std::vector<int> part_of;
  std::vector<std::vector<int>> parts;
  std::vector<std::vector<int>> boundary;
  std::vector<std::vector<int>> adjacent;
  std::size_t edge_cut = 0;  ///< edges whose ends lie in different parts

  [[nodiscard]] int part_count() const noexcept { return static_cast<int>(parts.size()); }
};

/// Splits `graph` with METIS (see the decisions above). Throws ConfigError for parts < 1, parts above the
/// vertex count, or an imbalance outside (1, 10]; NumericalError when METIS fails.
[[nodiscard]] Partition partition_graph(const AdjacencyGraph& graph, const PartitionOptions& options);

/// Parts of a motion graph's space-time graph cut along time and space separately, about `vertices_per_part`
/// vertices each (local edits' `parts: auto`, throng/edit/local_edit.h). The samples are split into blocks of
/// about samples_per_block(vertices_per_part) consecutive samples (as even as whole samples allow); each block's
/// agents into about #agents × block length / vertices_per_part groups over the union of the block's formation
/// edges, each weighted by the samples that hold it; a part is one group of one block. A block of at most 16
/// groups is grouped by one METIS call (recursive bisection; options.seed, options.imbalance). A larger block is
/// first cut into pieces by median cuts of its agents' mean places along the wider side (as many pieces as the
/// largest block's groups need at 16 a piece; its own groups shared among them, at most 16 each), and METIS groups
/// each piece; a block keeps the previous block's pieces (its groups shared among them) while they cut at most
/// 10 % more of its formation edges (counted at every fourth sample) than its own pieces would.
///
/// Why: METIS on the whole space-time graph grew as N^1.3 (17 s of partitioning at 10,000 agents × 300 samples)
/// and the shapes of its parts drifted with the crowd's size, so a local drag's region (the reached parts and
/// their neighbours) did too. Here each METIS call sees one block's agents, and a part's extent in time does not
/// depend on the crowd. One METIS call per block still grew as N^1.1 (recursive bisection into N/31 groups costs
/// N log(N/31)); pieces of at most 16 groups make it linear (bench_partition: 0.045 s at 1,000 agents, 0.94 s at
/// 20,000). Pieces cut afresh in each block shift as a crowd turns, and the groups with them: a part then touched
/// 6.5–7.0 parts of the blocks beside it instead of 3.2–3.7, and halo-1 regions grew by a fifth; kept pieces touch
/// 2.7–3.4. A crowd whose agents change places outgrows its pieces' cut, and gets new ones. A block with no
/// formation edge (or a piece with none inside it) has its agents grouped by index (nothing to follow). Same graph
/// and options, same parts, whatever the thread count. Throws ConfigError for vertices_per_part < 1 or an
/// imbalance outside (1, 10]; NumericalError when METIS fails.
[[nodiscard]] Partition partition_time_blocks(const MotionGraph& graph, int vertices_per_part, const PartitionOptions& options);

/// Samples per block of partition_time_blocks: 2∛vertices_per_part, rounded, at least 1 (16 for 500: groups of
/// about 31 agents). Chosen by measurement (bench_scale's local drag, 20 agents dragged over 21 frames, halo 1, 500
/// vertices a part, 1,000 to 10,000 agents × 300 samples): blocks of 3, 5 and 8 samples gave regions of 21,000 to
/// 47,000 vertices that changed with the crowd's size; 12 and 16 gave 19,000 to 28,000 at every size, and with 16
/// 0.05–0.10 m added at the region's edge (a jump, by BoundaryStep's rule, at one size of four), against 0.7–1.7 m
/// with METIS on the whole graph; 24 gave smaller regions with jumps at the edge again. (Minimising a part's cut edges alone would give 5 to 8.)
[[nodiscard]] std::size_t samples_per_block(int vertices_per_part);

/// Builds the partition data for a given assignment (any labels ≥ 0; renumbered like partition_graph).
///   part_of  #vertices
/// Throws std::invalid_argument for a size mismatch or a negative label.
[[nodiscard]] Partition make_partition(const AdjacencyGraph& graph, std::span<const int> part_of);

/// The same for the space-time graph of `graph` (formation edges within a sample, each agent to itself at the
/// next sample): make_partition(space_time_adjacency(graph), part_of), without building that adjacency (at
/// 10,000 agents × 300 samples it took 287 ms on one core of a 900 ms partition_time_blocks; bench_partition).
/// `graph.edges` as build_motion_graph makes them: each sample's pairs a < b of the clip's agents, sorted
/// (checked by assertions in debug builds). Also throws std::invalid_argument for INT_MAX or more vertices.
[[nodiscard]] Partition make_partition(const MotionGraph& graph, std::span<const int> part_of);

/// The parts within `hops` steps of `seeds` in the part adjacency (seeds included), increasing. hops < 0
/// means every part connected to a seed.
[[nodiscard]] std::vector<int> parts_within(const Partition& partition, std::span<const int> seeds, int hops);

}  // namespace throng
