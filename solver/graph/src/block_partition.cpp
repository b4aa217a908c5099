// partition_time_blocks (throng/graph/partition.h): blocks of consecutive samples, each block's agents grouped by
// METIS over the block's formation edges.
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/graph/partition.h>

#include "metis_parts.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace throng {
namespace {

// The agents' graph of samples [first, last): an edge for every pair that is a formation edge at some sample
// of the block, weighted by how many samples hold it. weights: one per entry of neighbours.
struct WeightedGraph {
  AdjacencyGraph graph;
  std::vector<int> weights;
};

WeightedGraph block_graph(const MotionGraph& graph, std::size_t first, std::size_t last) {
  const std::size_t n = graph.agent_count();
  // Pairs (a < b) as one key each, sorted: equal keys are the same edge at several samples.
  std::vector<std::uint64_t> keys;
  std::size_t total = 0;
  for (std::size_t i = first; i < last; ++i) total += graph.edges[i].size();
  keys.reserve(total);
  for (std::size_t i = first; i < last; ++i) {
    for (const auto& e : graph.edges[i]) {
      keys.push_back(static_cast<std::uint64_t>(e[0]) << 32 | static_cast<std::uint32_t>(e[1]));
    }
  }
  std::sort(keys.begin(), keys.end());
  // Rows by count then fill: each edge listed from both ends, with its weight.
  WeightedGraph out;
  std::vector<int>& offsets = out.graph.offsets;
  offsets.assign(n + 1, 0);
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (k > 0 && keys[k] == keys[k - 1]) continue;
    ++offsets[(keys[k] >> 32) + 1];
    ++offsets[(keys[k] & 0xffffffffu) + 1];
  }
  for (std::size_t v = 0; v < n; ++v) offsets[v + 1] += offsets[v];
  std::vector<int> fill(offsets.begin(), offsets.end() - 1);
  out.graph.neighbours.resize(static_cast<std::size_t>(offsets.back()));
  out.weights.resize(out.graph.neighbours.size());
  for (std::size_t k = 0; k < keys.size();) {
    std::size_t end = k + 1;
    while (end < keys.size() && keys[end] == keys[k]) ++end;
    const auto a = static_cast<int>(keys[k] >> 32), b = static_cast<int>(keys[k] & 0xffffffffu);
    const int weight = static_cast<int>(end - k);
    const auto at_a = static_cast<std::size_t>(fill[static_cast<std::size_t>(a)]++);
    const auto at_b = static_cast<std::size_t>(fill[static_cast<std::size_t>(b)]++);
    out.graph.neighbours[at_a] = b;
    out.weights[at_a] = weight;
    out.graph.neighbours[at_b] = a;
    out.weights[at_b] = weight;
    k = end;
  }
  return out;
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
  auto first_sample = [&](std::size_t k) { return k * samples / blocks; };
  // Groups per block: about n × its samples / vertices_per_part, between 1 and n.
  std::vector<int> groups(blocks), first_label(blocks + 1, 0);
  for (std::size_t k = 0; k < blocks; ++k) {
    const double vertices = static_cast<double>(n * (first_sample(k + 1) - first_sample(k)));
    groups[k] = static_cast<int>(std::clamp<long>(std::lround(vertices / vertices_per_part), 1, static_cast<long>(n)));
    first_label[k + 1] = first_label[k] + groups[k];
  }
  // Blocks side by side: each writes its own samples' labels, so the labels do not depend on the thread count.
  parallel_for(blocks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t s0 = first_sample(k), s1 = first_sample(k + 1);
      // Consecutive agents where there is nothing for METIS to do: one group, an agent a group (METIS would
      // leave some empty), or a block without formation edges (METIS is not given empty edge arrays, which it
      // may read).
      const auto count = static_cast<std::size_t>(groups[k]);
      std::vector<int> group(n);
      for (std::size_t j = 0; j < n; ++j) group[j] = static_cast<int>(j * count / n);
      if (count > 1 && count < n) {
        const WeightedGraph g = block_graph(graph, s0, s1);
        if (!g.graph.neighbours.empty()) {
          PartitionOptions block = options;
          block.parts = groups[k];
          group = detail::metis_parts(g.graph, g.weights, block, detail::MetisMethod::recursive);
        }
      }
      for (std::size_t i = s0; i < s1; ++i) {
        for (std::size_t j = 0; j < n; ++j) labels[i * n + j] = first_label[k] + group[j];
      }
    }
  });
  return make_partition(graph, labels);
}

}  // namespace throng
