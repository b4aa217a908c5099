#include "synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/core/random.h>
#include <throng/graph/motion_graph.h>
#include <throng/graph/partition.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

MotionGraph grid_graph(int rows, int cols, std::size_t frames) {
  return build_motion_graph(make_clip(test::marching_grid(rows, cols, frames, 1.0, 1.2, 0.1, 0.3), {}), {});
}

// Checks every stated property of a partition against the graph by brute force.
void check_partition(const AdjacencyGraph& g, const Partition& p) {
  const std::size_t n = g.vertex_count();
  REQUIRE(p.part_of.size() == n);
  // Every vertex in exactly one part, and parts list exactly their vertices, increasing and non-empty.
  std::vector<int> seen(n, 0);
  for (int part = 0; part < p.part_count(); ++part) {
    const auto& list = p.parts[static_cast<std::size_t>(part)];
    REQUIRE_FALSE(list.empty());
    CHECK(std::is_sorted(list.begin(), list.end()));
    for (int v : list) {
      ++seen[static_cast<std::size_t>(v)];
      CHECK(p.part_of[static_cast<std::size_t>(v)] == part);
    }
  }
  CHECK(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
  // Boundary = vertices with a neighbour elsewhere; adjacency = parts joined by an edge; cut = such edges.
  std::vector<std::set<int>> boundary(static_cast<std::size_t>(p.part_count())), adjacent(boundary.size());
  std::size_t cut = 0;
  for (std::size_t v = 0; v < n; ++v) {
    const int a = p.part_of[v];
    for (int u : g.neighbours_of(v)) {
      const int b = p.part_of[static_cast<std::size_t>(u)];
      if (a == b) continue;
      boundary[static_cast<std::size_t>(a)].insert(static_cast<int>(v));
      adjacent[static_cast<std::size_t>(a)].insert(b);
      if (static_cast<std::size_t>(u) > v) ++cut;
    }
  }
  for (std::size_t part = 0; part < boundary.size(); ++part) {
    CHECK(p.boundary[part] == std::vector<int>(boundary[part].begin(), boundary[part].end()));
    CHECK(p.adjacent[part] == std::vector<int>(adjacent[part].begin(), adjacent[part].end()));
  }
  CHECK(p.edge_cut == cut);
}

}  // namespace

TEST_CASE("space-time adjacency holds the formation edges of each sample and the motion edges") {
  const MotionGraph mg = grid_graph(3, 4, 5);
  const AdjacencyGraph g = space_time_adjacency(mg);
  const std::size_t n = mg.agent_count();
  REQUIRE(g.vertex_count() == mg.vertex_count());
  CHECK(g.edge_count() == mg.formation_edge_count() + (mg.sample_count() - 1) * n);
  auto linked = [&](int a, int b) {
    const auto list = g.neighbours_of(static_cast<std::size_t>(a));
    return std::binary_search(list.begin(), list.end(), b);
  };
  for (std::size_t i = 0; i < mg.sample_count(); ++i) {
    for (const auto& e : mg.edges[i]) {
      CHECK(linked(static_cast<int>(i * n) + e[0], static_cast<int>(i * n) + e[1]));
      CHECK(linked(static_cast<int>(i * n) + e[1], static_cast<int>(i * n) + e[0]));
    }
  }
  CHECK(linked(static_cast<int>(n + 2), 2));
  CHECK(linked(2, static_cast<int>(n + 2)));
  CHECK_FALSE(linked(2, static_cast<int>(2 * n + 2)));  // no edge skips a sample
}

TEST_CASE("adjacency_from_edges drops duplicates and self loops and rejects bad indices") {
  const std::vector<std::array<int, 2>> edges{{0, 1}, {1, 0}, {2, 2}, {1, 2}};
  const AdjacencyGraph g = adjacency_from_edges(4, edges);
  CHECK(g.offsets == std::vector<int>{0, 1, 3, 4, 4});
  CHECK(g.neighbours == std::vector<int>{1, 0, 2, 1});
  const std::vector<std::array<int, 2>> bad{{0, 4}};
  CHECK_THROWS_AS(adjacency_from_edges(4, bad), std::invalid_argument);
}

TEST_CASE("METIS parts cover every vertex once, with correct boundaries and adjacency") {
  const MotionGraph mg = grid_graph(6, 8, 40);
  const AdjacencyGraph g = space_time_adjacency(mg);
  for (int parts : {1, 2, 5, 16}) {
    INFO("parts " << parts);
    const Partition p = partition_graph(g, {.parts = parts});
    check_partition(g, p);
    CHECK(p.part_count() <= parts);
    CHECK(p.part_count() >= 1);
    if (parts == 1) {
      CHECK(p.boundary[0].empty());
      CHECK(p.edge_cut == 0);
    } else {
      CHECK(p.part_count() == parts);  // a connected graph of 1,920 vertices: METIS fills every part
      // Balanced within the allowed imbalance (plus a vertex of slack for rounding).
      const double average = static_cast<double>(g.vertex_count()) / parts;
      for (const auto& list : p.parts) CHECK(static_cast<double>(list.size()) <= 1.03 * average + 1.0);
      // A sensible cut: far below the edges a random split would cut (about half of them).
      CHECK(p.edge_cut < g.edge_count() / 4);
    }
  }
}

TEST_CASE("partitioning is deterministic: the same graph and seed give the same parts") {
  const AdjacencyGraph g = space_time_adjacency(grid_graph(5, 6, 30));
  const Partition a = partition_graph(g, {.parts = 6, .seed = 3});
  const Partition b = partition_graph(g, {.parts = 6, .seed = 3});
  CHECK(a.part_of == b.part_of);
  CHECK(a.boundary == b.boundary);
  CHECK(a.adjacent == b.adjacent);
}

TEST_CASE("labels are renumbered by smallest vertex, and empty labels are dropped") {
  // Path 0-1-2-3-4 labelled 7 7 3 3 9: parts {0,1} {2,3} {4}.
  const std::vector<std::array<int, 2>> edges{{0, 1}, {1, 2}, {2, 3}, {3, 4}};
  const AdjacencyGraph g = adjacency_from_edges(5, edges);
  const std::vector<int> labels{7, 7, 3, 3, 9};
  const Partition p = make_partition(g, labels);
  check_partition(g, p);
  CHECK(p.part_of == std::vector<int>{0, 0, 1, 1, 2});
  CHECK(p.boundary == std::vector<std::vector<int>>{{1}, {2, 3}, {4}});
  CHECK(p.adjacent == std::vector<std::vector<int>>{{1}, {0, 2}, {1}});
  CHECK(p.edge_cut == 2);
  // Hops through the part adjacency.
  const std::vector<int> seed{0};
  CHECK(parts_within(p, seed, 0) == std::vector<int>{0});
  CHECK(parts_within(p, seed, 1) == std::vector<int>{0, 1});
  CHECK(parts_within(p, seed, 2) == std::vector<int>{0, 1, 2});
  CHECK(parts_within(p, seed, -1) == std::vector<int>{0, 1, 2});
}

TEST_CASE("a motion graph's partition data, built without its adjacency, equals the adjacency's") {
  const MotionGraph graph = grid_graph(6, 9, 25);
  const AdjacencyGraph g = space_time_adjacency(graph);
  const std::size_t n = graph.vertex_count();
  Rng rng(3);
  std::vector<std::vector<int>> labelings;
  labelings.push_back(partition_time_blocks(graph, 40, {}).part_of);   // blocks of samples × groups
  labelings.push_back(partition_graph(g, {.parts = 17, .seed = 1}).part_of);  // METIS on the whole graph
  labelings.emplace_back(n, 4);                                        // one part
  std::vector<int> scattered(n);                                       // labels at random, some unused
  for (int& label : scattered) label = static_cast<int>(rng.below(50)) * 2;
  labelings.push_back(scattered);
  for (const std::vector<int>& labels : labelings) {
    const Partition direct = make_partition(graph, labels);
    const Partition from_adjacency = make_partition(g, labels);
    check_partition(g, direct);
    CHECK(direct.part_of == from_adjacency.part_of);
    CHECK(direct.parts == from_adjacency.parts);
    CHECK(direct.boundary == from_adjacency.boundary);
    CHECK(direct.adjacent == from_adjacency.adjacent);
    CHECK(direct.edge_cut == from_adjacency.edge_cut);
  }
  CHECK_THROWS_AS(make_partition(graph, std::vector<int>(n - 1, 0)), std::invalid_argument);
  std::vector<int> negative(n, 0);
  negative[7] = -1;
  CHECK_THROWS_AS(make_partition(graph, negative), std::invalid_argument);
}

TEST_CASE("a disconnected graph: parts_within stays in the seed's component") {
  const std::vector<std::array<int, 2>> edges{{0, 1}, {2, 3}};
  const AdjacencyGraph g = adjacency_from_edges(4, edges);
  const std::vector<int> labels{0, 1, 2, 3};
  const Partition p = make_partition(g, labels);
  check_partition(g, p);
  const std::vector<int> seed{2};
  CHECK(parts_within(p, seed, -1) == std::vector<int>{2, 3});
}

TEST_CASE("bad partition options are ConfigErrors naming the option") {
  const AdjacencyGraph g = space_time_adjacency(grid_graph(2, 3, 4));
  CHECK_THROWS_WITH(partition_graph(g, {.parts = 0}), Contains("partition parts 0"));
  CHECK_THROWS_AS(partition_graph(g, {.parts = 1000}), ConfigError);
  CHECK_THROWS_WITH(partition_graph(g, {.parts = 2, .imbalance = 1.0}), Contains("imbalance"));
}
