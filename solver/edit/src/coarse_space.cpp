#include "coarse_space.h"

#include <throng/graph/partition.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace throng::edit {
namespace {

using linalg::Complex;

// Agent groups: METIS over the agents joined by a formation edge at any sample; at most `max_groups`.
std::vector<int> agent_groups(const MotionGraph& graph, int agents_per_group, std::size_t max_groups, std::uint64_t seed, int& count) {
  const std::size_t n = graph.agent_count();
  const std::size_t wanted = (n + static_cast<std::size_t>(agents_per_group) / 2) / static_cast<std::size_t>(agents_per_group);
  const int parts = static_cast<int>(std::clamp<std::size_t>(std::min(wanted, max_groups), 1, n));
  if (parts <= 1) {
    count = 1;
    return std::vector<int>(n, 0);
  }
  std::vector<std::array<int, 2>> edges;
  for (const auto& sample : graph.edges) edges.insert(edges.end(), sample.begin(), sample.end());
  const AdjacencyGraph agents = adjacency_from_edges(n, edges);
  const Partition partition = partition_graph(agents, {.parts = parts, .seed = seed});
  count = partition.part_count();
  return partition.part_of;
}

}  // namespace

SpaceTimeCoarsening make_coarsening(const MotionGraph& graph, const VertexSplit& split, int agents_per_group,
                                    int samples_per_node, std::size_t max_functions, std::uint64_t seed) {
  const Clip& clip = graph.clip;
  const auto n = static_cast<int>(graph.agent_count());
  const auto samples = static_cast<int>(graph.sample_count());
  SpaceTimeCoarsening out;
  // Chains.
  std::vector<int> chain_of(static_cast<std::size_t>(n), -1);
  for (int f : split.free) {
    const int agent = f % n;
    if (chain_of[static_cast<std::size_t>(agent)] < 0) {
      chain_of[static_cast<std::size_t>(agent)] = static_cast<int>(out.chains.size());
      out.chains.emplace_back();
    }
  }
  // Free vertices come agent by agent, each in sample order (VertexSplit): every chain is a contiguous range.
  for (std::size_t i = 0; i < split.free.size(); ++i) {
    out.chains[static_cast<std::size_t>(chain_of[static_cast<std::size_t>(split.free[i] % n)])].push_back(static_cast<int>(i));
  }
  // Time nodes: samples 0, τ, 2τ, ... and the last sample.
  std::vector<int> nodes;
  for (int s = 0; s < samples - 1; s += samples_per_node) nodes.push_back(s);
  nodes.push_back(std::max(0, samples - 1));
  if (nodes.size() >= 2 && nodes[nodes.size() - 2] == nodes.back()) nodes.pop_back();
  out.time_nodes = static_cast<int>(nodes.size());
  constexpr int modes = 4;
  // Groups, and their centre and radius at every sample (over all their agents, pinned or not).
  const std::size_t max_groups = std::max<std::size_t>(1, max_functions / (modes * nodes.size()));
  const std::vector<int> group = agent_groups(graph, agents_per_group, max_groups, seed, out.groups);
  const auto G = static_cast<std::size_t>(out.groups);
  std::vector<Complex> centre(G * static_cast<std::size_t>(samples), Complex(0));
  std::vector<double> radius(G * static_cast<std::size_t>(samples), 0.0);
  std::vector<int> size(G, 0);
  for (int j = 0; j < n; ++j) ++size[static_cast<std::size_t>(group[static_cast<std::size_t>(j)])];
  auto z = [&](Eigen::Index v) { return Complex(clip.positions(v, 0), clip.positions(v, 1)); };
  for (int s = 0; s < samples; ++s) {
    for (int j = 0; j < n; ++j) {
      const auto g = static_cast<std::size_t>(group[static_cast<std::size_t>(j)]);
      centre[g * static_cast<std::size_t>(samples) + static_cast<std::size_t>(s)] += z(clip.vertex(static_cast<std::size_t>(s), static_cast<std::size_t>(j)));
    }
  }
  for (std::size_t g = 0; g < G; ++g)
    for (int s = 0; s < samples; ++s) centre[g * static_cast<std::size_t>(samples) + static_cast<std::size_t>(s)] /= static_cast<double>(std::max(1, size[g]));
  for (int s = 0; s < samples; ++s) {
    for (int j = 0; j < n; ++j) {
      const std::size_t k = static_cast<std::size_t>(group[static_cast<std::size_t>(j)]) * static_cast<std::size_t>(samples) + static_cast<std::size_t>(s);
      radius[k] = std::max(radius[k], std::abs(z(clip.vertex(static_cast<std::size_t>(s), static_cast<std::size_t>(j))) - centre[k]));
    }
  }
  std::vector<Eigen::Triplet<Complex>> entries;
  entries.reserve(split.free.size() * 2 * modes);
  for (std::size_t i = 0; i < split.free.size(); ++i) {
    const int v = split.free[i];
    const int s = v / n, j = v % n;
    const auto g = static_cast<std::size_t>(group[static_cast<std::size_t>(j)]);
    const std::size_t k = g * static_cast<std::size_t>(samples) + static_cast<std::size_t>(s);
    const Complex d = radius[k] > 0 ? (z(v) - centre[k]) / radius[k] : Complex(0);
    const Complex value[modes] = {1.0, d, std::conj(d), d * d};
    // The hat functions of the nodes around s.
    const auto upper = static_cast<std::size_t>(std::upper_bound(nodes.begin(), nodes.end(), s) - nodes.begin());
    const std::size_t right = std::min(upper, nodes.size() - 1), left = upper - 1;
    const double span = static_cast<double>(nodes[right] - nodes[left]);
    const double to_right = span > 0 ? static_cast<double>(s - nodes[left]) / span : 0.0;
    for (const auto& [node, weight] : {std::pair{left, 1.0 - to_right}, std::pair{right, to_right}}) {
      if (weight <= 0 || (node == right && right == left)) continue;
      const auto column = static_cast<Eigen::Index>((g * nodes.size() + node) * modes);
      for (int m = 0; m < modes; ++m) entries.emplace_back(static_cast<Eigen::Index>(i), column + m, weight * value[m]);
    }
  }
  out.basis.resize(static_cast<Eigen::Index>(split.free.size()), static_cast<Eigen::Index>(G * nodes.size() * modes));
  out.basis.setFromTriplets(entries.begin(), entries.end());
  out.basis.makeCompressed();
  return out;
}

}  // namespace throng::edit
