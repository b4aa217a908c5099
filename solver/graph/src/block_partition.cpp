// partition_time_blocks (throng/graph/partition.h): blocks of consecutive samples, each block's agents cut by place
// into pieces of at most max_groups_per_metis groups, each piece grouped by METIS over the block's formation edges.
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/graph/partition.h>

#include "metis_parts.h"
#include "spatial_pieces.h"

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace throng {
namespace {

// The most groups one METIS call makes (16: about 500 agents at 500 vertices a part). Chosen by measurement
// against 32 and 64 (bench_partition, bench_scale's local drag, regions of random drags): bench/scale/README.md.
constexpr int max_groups_per_metis = 16;

// The agents' graph of samples [first, last): an edge for every pair that is a formation edge at some sample
// of the block, weighted by how many samples hold it. weights: one per entry of neighbours. Linear in the block's
// edges: each agent's entries are gathered by counting, then merged with a mark per neighbour (no global sort;
// a sort of keys was a fifth of partitioning at 10,000 agents), each row sorted (a handful of neighbours).
struct WeightedGraph {
  AdjacencyGraph graph;
  std::vector<int> weights;
};

WeightedGraph block_graph(const MotionGraph& graph, std::size_t first, std::size_t last) {
  const std::size_t n = graph.agent_count();
  // Every sample's edge listed from both ends, by agent (repeats across samples kept for now).
  std::vector<int> start(n + 1, 0);
  for (std::size_t i = first; i < last; ++i) {
    for (const auto& e : graph.edges[i]) {
      ++start[static_cast<std::size_t>(e[0]) + 1];
      ++start[static_cast<std::size_t>(e[1]) + 1];
    }
  }
  for (std::size_t v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<int> entries(static_cast<std::size_t>(start.back()));
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (std::size_t i = first; i < last; ++i) {
      for (const auto& e : graph.edges[i]) {
        entries[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[0])]++)] = e[1];
        entries[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[1])]++)] = e[0];
      }
    }
  }
  // Each row's distinct neighbours with their counts, increasing.
  WeightedGraph out;
  std::vector<int>& offsets = out.graph.offsets;
  offsets.assign(n + 1, 0);
  out.graph.neighbours.reserve(entries.size() / std::max<std::size_t>(1, last - first) + n);
  out.weights.reserve(out.graph.neighbours.capacity());
  std::vector<int> seen_by(n, -1), slot(n, 0);
  std::vector<std::pair<int, int>> row;
  for (std::size_t v = 0; v < n; ++v) {
    row.clear();
    for (int k = start[v]; k < start[v + 1]; ++k) {
      const auto b = static_cast<std::size_t>(entries[static_cast<std::size_t>(k)]);
      if (seen_by[b] != static_cast<int>(v)) {
        seen_by[b] = static_cast<int>(v);
        slot[b] = static_cast<int>(row.size());
        row.emplace_back(static_cast<int>(b), 0);
      }
      ++row[static_cast<std::size_t>(slot[b])].second;
    }
    std::sort(row.begin(), row.end());
    for (const auto& [b, weight] : row) {
      out.graph.neighbours.push_back(b);
      out.weights.push_back(weight);
    }
    offsets[v + 1] = static_cast<int>(out.graph.neighbours.size());
  }
  return out;
}

// The subgraph of `g` on `agents` (increasing), renumbered 0 .. #agents − 1 in their order. local: scratch of
// g's size, −1 outside the piece on entry and on return.
WeightedGraph induced(const WeightedGraph& g, std::span<const int> agents, std::vector<int>& local) {
  for (std::size_t k = 0; k < agents.size(); ++k) local[static_cast<std::size_t>(agents[k])] = static_cast<int>(k);
  WeightedGraph out;
  out.graph.offsets.assign(agents.size() + 1, 0);
  for (std::size_t k = 0; k < agents.size(); ++k) {
    const auto v = static_cast<std::size_t>(agents[k]);
    for (int e = g.graph.offsets[v]; e < g.graph.offsets[v + 1]; ++e) {
      const int b = local[static_cast<std::size_t>(g.graph.neighbours[static_cast<std::size_t>(e)])];
      if (b < 0) continue;
      out.graph.neighbours.push_back(b);
      out.weights.push_back(g.weights[static_cast<std::size_t>(e)]);
    }
    out.graph.offsets[k + 1] = static_cast<int>(out.graph.neighbours.size());
  }
  for (const int a : agents) local[static_cast<std::size_t>(a)] = -1;
  return out;
}

// The mean place of every agent over samples [first, last): where spatial_pieces cuts the block.
Eigen::Matrix<double, Eigen::Dynamic, 2> mean_places(const Clip& clip, std::size_t first, std::size_t last) {
  const auto n = static_cast<Eigen::Index>(clip.agent_count());
  Eigen::Matrix<double, Eigen::Dynamic, 2> places = Eigen::Matrix<double, Eigen::Dynamic, 2>::Zero(n, 2);
  for (std::size_t i = first; i < last; ++i) places += clip.positions.middleRows(clip.vertex(i, 0), n);
  return places / static_cast<double>(last - first);
}

// Groups of `agents` (increasing, rows of `g`), `groups` of them, labelled from `first_group`, written into
// group (indexed by agent). Consecutive agents where there is nothing for METIS to do: one group, an agent a group
// (METIS would leave some empty), or no edge among them (METIS is not given empty edge arrays, which it may read).
void group_piece(const WeightedGraph& g, const detail::AgentPiece& piece, int first_group, const PartitionOptions& options,
                 std::vector<int>& local, std::vector<int>& group) {
  const std::size_t m = piece.agents.size();
  const auto count = static_cast<std::size_t>(piece.groups);
  std::vector<int> labels(m);
  for (std::size_t k = 0; k < m; ++k) labels[k] = static_cast<int>(k * count / m);
  if (count > 1 && count < m) {
    // A piece of every agent is agents 0 .. n − 1 in order: g itself.
    const WeightedGraph sub = m == g.graph.vertex_count() ? WeightedGraph{} : induced(g, piece.agents, local);
    const WeightedGraph& used = m == g.graph.vertex_count() ? g : sub;
    if (!used.graph.neighbours.empty()) {
      PartitionOptions call = options;
      call.parts = piece.groups;
      labels = detail::metis_parts(used.graph, used.weights, call, detail::MetisMethod::recursive);
    }
  }
  for (std::size_t k = 0; k < m; ++k) group[static_cast<std::size_t>(piece.agents[k])] = first_group + labels[k];
}

// Formation edges of every fourth sample of [first, last) whose agents lie in different pieces (a sample's edges
// change little from one to the next; all of them cost as much as the rest of the choice). piece_of: scratch of
// #agents.
std::size_t pieces_cut(const MotionGraph& graph, const std::vector<detail::AgentPiece>& pieces, std::size_t first,
                       std::size_t last, std::vector<int>& piece_of) {
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    for (const int a : pieces[k].agents) piece_of[static_cast<std::size_t>(a)] = static_cast<int>(k);
  }
  std::size_t cut = 0;
  for (std::size_t i = first; i < last; i += 4) {
    for (const auto& e : graph.edges[i]) {
      cut += piece_of[static_cast<std::size_t>(e[0])] != piece_of[static_cast<std::size_t>(e[1])] ? 1 : 0;
    }
  }
  return cut;
}

// The pieces METIS groups in each block (block k: samples [first_sample(k), first_sample(k + 1)), groups[k]
// groups). A block of at most max_groups_per_metis groups is one piece. A larger one is cut by place
// (spatial_pieces.h) into as many pieces as the largest block's groups need, its own groups then shared among them
// (blocks differ by a sample, so their group counts by a few: a common count of pieces keeps the comparison below
// fair, and every piece within max_groups_per_metis); unless the previous block's pieces, its groups shared among
// them instead, cut no more than 10 % more of its formation edges than its own pieces: then those are kept. Why:
// METIS groups the same agents of consecutive blocks alike, so a group of one block meets about one group of the
// next (3.2–3.7 adjacent parts in other blocks per part); cut afresh in every block, the pieces of a turning crowd
// shift (a median along x of a rotated grid takes other agents) and so do the groups (6.5–7.0 adjacent parts in
// other blocks, halo-1 regions 18 % larger). The cuts are made side by side; the choice is sequential (it follows
// the blocks).
template <typename FirstSample>
std::vector<std::vector<detail::AgentPiece>> plan_pieces(const MotionGraph& graph, const std::vector<int>& groups,
                                                          std::size_t blocks, const FirstSample& first_sample) {
  const std::size_t n = graph.agent_count();
  const int most = *std::max_element(groups.begin(), groups.end());
  std::vector<std::vector<detail::AgentPiece>> plan(blocks);
  std::vector<std::size_t> fresh_cut(blocks, 0);
  parallel_for(blocks, 1, [&](std::size_t begin, std::size_t end) {
    std::vector<int> piece_of(n);
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t s0 = first_sample(k), s1 = first_sample(k + 1);
      if (groups[k] <= max_groups_per_metis) {
        plan[k].push_back({std::vector<int>(n), groups[k]});
        for (std::size_t j = 0; j < n; ++j) plan[k].front().agents[j] = static_cast<int>(j);
        continue;
      }
      const Eigen::Matrix<double, Eigen::Dynamic, 2> places = mean_places(graph.clip, s0, s1);
      plan[k] = detail::spatial_pieces(places, most, max_groups_per_metis);
      // Always possible: each piece cut for `most` (≤ n) groups has at least as many agents and at most
      // max_groups_per_metis of them, so the pieces hold groups[k] ≤ most; and each holds at least half of
      // max_groups_per_metis, so there are at most most / 8 ≤ groups[k] / 4 of them (blocks differ by one sample,
      // so most ≤ 2 groups[k]).
      if (!detail::share_groups(plan[k], groups[k], max_groups_per_metis)) {
        throw std::logic_error("partition_time_blocks: " + std::to_string(groups[k]) + " groups do not fit " +
                               std::to_string(plan[k].size()) + " pieces cut for " + std::to_string(most));
      }
      fresh_cut[k] = pieces_cut(graph, plan[k], s0, s1, piece_of);
    }
  });
  std::vector<int> piece_of(n);
  for (std::size_t k = 1; k < blocks; ++k) {
    if (plan[k].size() < 2 || plan[k - 1].size() != plan[k].size()) continue;
    std::vector<detail::AgentPiece> kept = plan[k - 1];
    if (!detail::share_groups(kept, groups[k], max_groups_per_metis)) continue;
    const std::size_t cut = pieces_cut(graph, kept, first_sample(k), first_sample(k + 1), piece_of);
    if (10 * cut <= 11 * fresh_cut[k]) plan[k] = std::move(kept);
  }
  return plan;
}

}  // namespace

std::size_t samples_per_block(int vertices_per_part) {
  if (vertices_per_part < 1) {
    throw ConfigError("vertices per part " + std::to_string(vertices_per_part) + ": expected ≥ 1");
  }
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(2.0 * std::cbrt(static_cast<double>(vertices_per_part)))));
}

Partition partition_time_blocks(const MotionGraph& graph, int vertices_per_part, const PartitionOptions& options) {
  const std::size_t length = samples_per_block(vertices_per_part);
  detail::check_imbalance(options.imbalance);
  const std::size_t samples = graph.sample_count(), n = graph.agent_count();
  std::vector<int> labels(graph.vertex_count(), 0);
  if (samples == 0 || n == 0) return make_partition(graph, labels);
  // Blocks as even as whole samples allow: block k holds samples [k·S/B, (k+1)·S/B).
  const std::size_t blocks = std::max<std::size_t>(1, (samples + length / 2) / length);
  const auto first_sample = [samples, blocks](std::size_t k) { return k * samples / blocks; };
  // Groups per block: about n × its samples / vertices_per_part, between 1 and n.
  std::vector<int> groups(blocks), first_label(blocks + 1, 0);
  for (std::size_t k = 0; k < blocks; ++k) {
    const double vertices = static_cast<double>(n * (first_sample(k + 1) - first_sample(k)));
    groups[k] = static_cast<int>(std::clamp<long>(std::lround(vertices / vertices_per_part), 1, static_cast<long>(n)));
    first_label[k + 1] = first_label[k] + groups[k];
  }
  const std::vector<std::vector<detail::AgentPiece>> plan = plan_pieces(graph, groups, blocks, first_sample);
  // Blocks side by side: each writes its own samples' labels, so the labels do not depend on the thread count.
  parallel_for(blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t s0 = first_sample(k), s1 = first_sample(k + 1);
      const std::vector<detail::AgentPiece>& pieces = plan[k];
      const WeightedGraph g = block_graph(graph, s0, s1);
      std::vector<int> group(n), local(n, -1);
      int first_group = 0;
      for (const auto& piece : pieces) {
        group_piece(g, piece, first_group, options, local, group);
        first_group += piece.groups;
      }
      for (std::size_t i = s0; i < s1; ++i) {
        for (std::size_t j = 0; j < n; ++j) labels[i * n + j] = first_label[k] + group[j];
      }
    }
  });
  return make_partition(graph, labels);
}

}  // namespace throng
