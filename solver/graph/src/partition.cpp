#include <throng/core/errors.h>
#include <throng/graph/partition.h>

#include "metis_parts.h"
#include "numbered_parts.h"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>

namespace throng {
namespace {

static_assert(sizeof(idx_t) == sizeof(int), "throng passes int arrays to METIS: a 32-bit idx_t build is needed");

std::string metis_status(int status) {
  switch (status) {
    case METIS_ERROR_INPUT: return "input error";
    case METIS_ERROR_MEMORY: return "out of memory";
    default: return "error " + std::to_string(status);
  }
}

}  // namespace

AdjacencyGraph adjacency_from_edges(std::size_t vertex_count, std::span<const std::array<int, 2>> edges) {
  if (vertex_count >= static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument("adjacency_from_edges: " + std::to_string(vertex_count) + " vertices exceed int indices");
  }
  // Count both ends, fill, then sort and deduplicate each row.
  std::vector<int> degree(vertex_count + 1, 0);
  for (const auto& e : edges) {
    for (int v : e) {
      if (v < 0 || static_cast<std::size_t>(v) >= vertex_count) {
        throw std::invalid_argument("adjacency_from_edges: vertex " + std::to_string(v) + " outside [0, " +
                                    std::to_string(vertex_count) + ")");
      }
    }
    if (e[0] == e[1]) continue;
    ++degree[static_cast<std::size_t>(e[0]) + 1];
    ++degree[static_cast<std::size_t>(e[1]) + 1];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) degree[v + 1] += degree[v];
  std::vector<int> fill(degree.begin(), degree.end() - 1);
  std::vector<int> all(static_cast<std::size_t>(degree.back()));
  for (const auto& e : edges) {
    if (e[0] == e[1]) continue;
    all[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[0])]++)] = e[1];
    all[static_cast<std::size_t>(fill[static_cast<std::size_t>(e[1])]++)] = e[0];
  }
  AdjacencyGraph g;
  g.offsets.assign(vertex_count + 1, 0);
  g.neighbours.reserve(all.size());
  for (std::size_t v = 0; v < vertex_count; ++v) {
    const auto begin = all.begin() + degree[v], end = all.begin() + degree[v + 1];
    std::sort(begin, end);
    g.neighbours.insert(g.neighbours.end(), begin, std::unique(begin, end));
    g.offsets[v + 1] = static_cast<int>(g.neighbours.size());
  }
  return g;
}

AdjacencyGraph space_time_adjacency(const MotionGraph& graph) {
  const std::size_t n = graph.agent_count(), samples = graph.sample_count();
  std::vector<std::array<int, 2>> edges;
  edges.reserve(graph.formation_edge_count() + (samples > 0 ? (samples - 1) * n : 0));
  for (std::size_t i = 0; i < samples; ++i) {
    const int base = static_cast<int>(i * n);
    for (const auto& e : graph.edges[i]) edges.push_back({base + e[0], base + e[1]});
    if (i + 1 < samples) {
      for (std::size_t j = 0; j < n; ++j) edges.push_back({base + static_cast<int>(j), base + static_cast<int>(n + j)});
    }
  }
  return adjacency_from_edges(graph.vertex_count(), edges);
}

Partition make_partition(const AdjacencyGraph& graph, std::span<const int> part_of) {
  const std::size_t vertices = graph.vertex_count();
  Partition p = detail::numbered_parts(vertices, part_of);
  const std::size_t count = p.parts.size();
  p.boundary.resize(count);
  p.adjacent.resize(count);
  std::size_t cut_ends = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    const int part = p.part_of[v];
    bool on_boundary = false;
    for (int u : graph.neighbours_of(v)) {
      const int other = p.part_of[static_cast<std::size_t>(u)];
      if (other == part) continue;
      on_boundary = true;
      ++cut_ends;
      p.adjacent[static_cast<std::size_t>(part)].push_back(other);
    }
    if (on_boundary) p.boundary[static_cast<std::size_t>(part)].push_back(static_cast<int>(v));
  }
  for (auto& list : p.adjacent) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  p.edge_cut = cut_ends / 2;
  return p;
}

Partition partition_graph(const AdjacencyGraph& graph, const PartitionOptions& options) {
  const std::size_t vertices = graph.vertex_count();
  if (options.parts < 1) throw ConfigError("partition parts " + std::to_string(options.parts) + ": expected ≥ 1");
  if (vertices > 0 && static_cast<std::size_t>(options.parts) > vertices) {
    throw ConfigError("partition parts " + std::to_string(options.parts) + ": the graph has only " +
                      std::to_string(vertices) + " vertices");
  }
  detail::check_imbalance(options.imbalance);
  return make_partition(graph, detail::metis_parts(graph, {}, options, detail::MetisMethod::kway));
}

namespace detail {

Partition numbered_parts(std::size_t vertices, std::span<const int> part_of) {
  if (part_of.size() != vertices) {
    throw std::invalid_argument("make_partition: " + std::to_string(part_of.size()) + " labels for " +
                                std::to_string(vertices) + " vertices");
  }
  // Renumber labels in order of their smallest vertex (a scan in vertex order meets them in that order).
  int max_label = -1;
  for (int label : part_of) {
    if (label < 0) throw std::invalid_argument("make_partition: negative part label " + std::to_string(label));
    max_label = std::max(max_label, label);
  }
  std::vector<int> renumber(static_cast<std::size_t>(max_label + 1), -1);
  Partition p;
  p.part_of.resize(vertices);
  for (std::size_t v = 0; v < vertices; ++v) {
    int& part = renumber[static_cast<std::size_t>(part_of[v])];
    if (part < 0) {
      part = static_cast<int>(p.parts.size());
      p.parts.emplace_back();
    }
    p.part_of[v] = part;
    p.parts[static_cast<std::size_t>(part)].push_back(static_cast<int>(v));
  }
  return p;
}

void check_imbalance(double imbalance) {
  if (!(imbalance > 1.0 && imbalance <= 10.0)) {
    throw ConfigError("partition imbalance " + std::to_string(imbalance) + ": expected (1, 10]");
  }
}

std::vector<int> metis_parts(const AdjacencyGraph& graph, std::span<const int> edge_weights, const PartitionOptions& options,
                             MetisMethod method) {
  const std::size_t vertices = graph.vertex_count();
  if (!edge_weights.empty() && edge_weights.size() != graph.neighbours.size()) {
    throw std::invalid_argument("metis_parts: " + std::to_string(edge_weights.size()) + " edge weights for " +
                                std::to_string(graph.neighbours.size()) + " neighbour entries");
  }
  std::vector<int> labels(vertices, 0);
  if (options.parts > 1) {
    idx_t nvtxs = static_cast<idx_t>(vertices), ncon = 1, nparts = options.parts, objval = 0;
    idx_t metis_options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(metis_options);
    metis_options[METIS_OPTION_SEED] = static_cast<idx_t>(options.seed % 2147483647u);
    metis_options[METIS_OPTION_UFACTOR] = std::max<idx_t>(1, static_cast<idx_t>(std::lround((options.imbalance - 1.0) * 1000.0)));
    metis_options[METIS_OPTION_NUMBERING] = 0;
    // METIS takes non-const pointers but does not write the graph.
    auto* xadj = const_cast<idx_t*>(graph.offsets.data());
    auto* adjncy = const_cast<idx_t*>(graph.neighbours.data());
    auto* adjwgt = edge_weights.empty() ? nullptr : const_cast<idx_t*>(edge_weights.data());
    const auto call = method == MetisMethod::kway ? METIS_PartGraphKway : METIS_PartGraphRecursive;
    // One METIS call at a time: its random number generator (GKlib's) is one per process, reseeded by each
    // call, so calls that overlap would draw from each other's sequence and their parts would depend on timing.
    static std::mutex metis_lock;
    const std::lock_guard<std::mutex> hold(metis_lock);
    const int status = call(&nvtxs, &ncon, xadj, adjncy, nullptr, nullptr, adjwgt, &nparts, nullptr, nullptr,
                            metis_options, &objval, labels.data());
    if (status != METIS_OK) {
      throw NumericalError("METIS could not partition the graph (" + std::to_string(vertices) + " vertices, " +
                           std::to_string(options.parts) + " parts): " + metis_status(status));
    }
  }
  return labels;
}

}  // namespace detail

std::vector<int> parts_within(const Partition& partition, std::span<const int> seeds, int hops) {
  const auto count = static_cast<std::size_t>(partition.part_count());
  std::vector<int> depth(count, -1);
  std::vector<int> frontier;
  for (int s : seeds) {
    if (s < 0 || static_cast<std::size_t>(s) >= count) {
      throw std::invalid_argument("parts_within: part " + std::to_string(s) + " outside [0, " + std::to_string(count) + ")");
    }
    if (depth[static_cast<std::size_t>(s)] < 0) {
      depth[static_cast<std::size_t>(s)] = 0;
      frontier.push_back(s);
    }
  }
  for (int level = 0; !frontier.empty() && (hops < 0 || level < hops); ++level) {
    std::vector<int> next;
    for (int part : frontier) {
      for (int other : partition.adjacent[static_cast<std::size_t>(part)]) {
        if (depth[static_cast<std::size_t>(other)] >= 0) continue;
        depth[static_cast<std::size_t>(other)] = level + 1;
        next.push_back(other);
      }
    }
    frontier = std::move(next);
  }
  std::vector<int> out;
  for (std::size_t p = 0; p < count; ++p) {
    if (depth[p] >= 0) out.push_back(static_cast<int>(p));
  }
  return out;
}

}  // namespace throng
