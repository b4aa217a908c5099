// make_partition for a motion graph's space-time graph (throng/graph/partition.h) without building its
// adjacency: the same Partition as make_partition(space_time_adjacency(graph), part_of).
#include <throng/core/parallel.h>
#include <throng/graph/partition.h>

#include "numbered_parts.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace throng {

Partition make_partition(const MotionGraph& graph, std::span<const int> part_of) {
  const std::size_t n = graph.agent_count(), samples = graph.sample_count(), vertices = graph.vertex_count();
  if (vertices >= static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument("make_partition: " + std::to_string(vertices) + " vertices exceed int indices");
  }
  Partition p = detail::numbered_parts(vertices, part_of);
  // Per sample, side by side (each writes its own vertices' flags and its own list): the cut formation edges
  // (each pair once: a sample's edges are sorted, so a repeated pair is next to itself), the vertices on a part's
  // boundary (a cut formation edge, or the same agent in another part one sample before or after), and the
  // ordered pairs of adjacent parts. The temporal edge between samples i and i + 1 is counted by sample i.
  const std::vector<int>& label = p.part_of;
  std::vector<char> on_boundary(vertices, 0);
  std::vector<std::vector<std::array<int, 2>>> pairs(samples);
  std::vector<std::size_t> cut(samples, 0);
  parallel_for(samples, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::size_t base = i * n;
      const auto& edges = graph.edges[i];
      for (std::size_t k = 0; k < edges.size(); ++k) {
        const auto [a, b] = edges[k];
        assert(0 <= a && a < b && static_cast<std::size_t>(b) < n && (k == 0 || edges[k - 1] <= edges[k]));
        if (a == b || (k > 0 && edges[k - 1][0] == a && edges[k - 1][1] == b)) continue;
        const std::size_t u = base + static_cast<std::size_t>(a), w = base + static_cast<std::size_t>(b);
        if (label[u] == label[w]) continue;
        ++cut[i];
        on_boundary[u] = on_boundary[w] = 1;
        pairs[i].push_back({label[u], label[w]});
        pairs[i].push_back({label[w], label[u]});
      }
      for (std::size_t j = 0; j < n; ++j) {
        const std::size_t v = base + j;
        if (i > 0 && label[v - n] != label[v]) {
          on_boundary[v] = 1;
          pairs[i].push_back({label[v], label[v - n]});
        }
        if (i + 1 < samples && label[v + n] != label[v]) {
          on_boundary[v] = 1;
          pairs[i].push_back({label[v], label[v + n]});
          ++cut[i];
        }
      }
    }
  });
  const std::size_t count = p.parts.size();
  p.boundary.resize(count);
  p.adjacent.resize(count);
  for (std::size_t v = 0; v < vertices; ++v) {
    if (on_boundary[v]) p.boundary[static_cast<std::size_t>(label[v])].push_back(static_cast<int>(v));
  }
  for (std::size_t i = 0; i < samples; ++i) {
    p.edge_cut += cut[i];
    for (const auto& [part, other] : pairs[i]) {
      auto& list = p.adjacent[static_cast<std::size_t>(part)];
      if (list.empty() || list.back() != other) list.push_back(other);  // runs of one pair are common: fewer to sort
    }
  }
  for (auto& list : p.adjacent) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return p;
}

}  // namespace throng
