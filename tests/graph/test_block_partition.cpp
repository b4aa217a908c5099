// partition_time_blocks (throng/graph/partition.h): parts that are a block of consecutive samples × a group of
// agents, about vertices_per_part vertices each, the groups cut along the block's formation edges.
#include "synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/graph/motion_graph.h>
#include <throng/graph/partition.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <set>
#include <vector>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

MotionGraph grid_graph(int rows, int cols, std::size_t frames) {
  return build_motion_graph(make_clip(test::marching_grid(rows, cols, frames, 1.0, 1.2, 0.1, 0.3), {}), {});
}

// The samples and the agents of each part, from part_of (vertex = sample × agents + agent).
struct PartShape {
  std::set<std::size_t> samples;
  std::vector<std::set<std::size_t>> agents_at;  // per sample of the part, in increasing sample order
};

std::vector<PartShape> shapes(const MotionGraph& g, const Partition& p) {
  const std::size_t n = g.agent_count();
  std::vector<std::vector<std::set<std::size_t>>> by_sample(static_cast<std::size_t>(p.part_count()),
                                                            std::vector<std::set<std::size_t>>(g.sample_count()));
  for (std::size_t v = 0; v < p.part_of.size(); ++v) by_sample[static_cast<std::size_t>(p.part_of[v])][v / n].insert(v % n);
  std::vector<PartShape> out(by_sample.size());
  for (std::size_t part = 0; part < by_sample.size(); ++part) {
    for (std::size_t i = 0; i < g.sample_count(); ++i) {
      if (by_sample[part][i].empty()) continue;
      out[part].samples.insert(i);
      out[part].agents_at.push_back(by_sample[part][i]);
    }
  }
  return out;
}

// 8 agents over 6 samples (the grid's two rows of 4: agents 0..3 and 4..7) with `edges` at every sample; 24
// vertices a part make one block (2∛24 ≈ 6 samples) of 8 × 6 / 24 = 2 groups.
MotionGraph eight_agents(const std::vector<std::array<int, 2>>& edges) {
  MotionGraph g = grid_graph(2, 4, 6);
  REQUIRE(g.agent_count() == 8);
  for (auto& sample : g.edges) sample = edges;
  return g;
}

// The two groups of a one-block partition of eight_agents as the sets of their agents, in part order.
std::vector<std::set<std::size_t>> two_groups(const MotionGraph& g, const Partition& p) {
  REQUIRE(p.part_count() == 2);
  const auto s = shapes(g, p);
  return {s[0].agents_at.front(), s[1].agents_at.front()};
}

// True when the groups are the even and the odd agents (in either order).
bool even_and_odd(const std::vector<std::set<std::size_t>>& groups) {
  const std::set<std::size_t> even{0, 2, 4, 6}, odd{1, 3, 5, 7};
  return (groups[0] == even && groups[1] == odd) || (groups[0] == odd && groups[1] == even);
}

// Rails 0-2-4-6 and 1-3-5-7: the even and the odd agents, each a chain.
const std::vector<std::array<int, 2>> rails{{0, 2}, {2, 4}, {4, 6}, {1, 3}, {3, 5}, {5, 7}};

}  // namespace

TEST_CASE("block parts are consecutive samples of one block times the same agents, about vertices_per_part each") {
  // 48 agents × 40 samples; 96 vertices a part: blocks of 2∛96 ≈ 9 samples, so 4 blocks of 10, and 48 × 10 / 96 = 5
  // groups in each.
  const MotionGraph g = grid_graph(6, 8, 40);
  CHECK(samples_per_block(96) == 9);
  CHECK(samples_per_block(500) == 16);
  CHECK(samples_per_block(1) == 2);
  const Partition p = partition_time_blocks(g, 96, {});
  REQUIRE(p.part_count() == 20);
  const AdjacencyGraph adjacency = space_time_adjacency(g);
  std::size_t largest = 0;
  for (const PartShape& s : shapes(g, p)) {
    REQUIRE_FALSE(s.samples.empty());
    const std::size_t first = *s.samples.begin(), last = *s.samples.rbegin();
    // One whole block: samples [10k, 10k + 10).
    CHECK(first % 10 == 0);
    CHECK(last == first + 9);
    CHECK(s.samples.size() == 10);
    // The same agents at every sample of the block.
    for (const auto& agents : s.agents_at) CHECK(agents == s.agents_at.front());
    largest = std::max(largest, s.agents_at.front().size());
  }
  // Balanced groups: within METIS's 3 % of 48 / 5 agents, plus one for rounding.
  CHECK(static_cast<double>(largest) <= 1.03 * 48.0 / 5.0 + 1.0);
  // A sensible cut: far below what a random split of the agents would cut.
  CHECK(p.edge_cut < adjacency.edge_count() / 3);
}

TEST_CASE("block groups follow the formation edges: agents never joined by one are not grouped together") {
  // The rails at every sample and no edge between them: the groups are the rails, not the grid's rows (which
  // the positions alone would give).
  const MotionGraph g = eight_agents(rails);
  const Partition p = partition_time_blocks(g, 24, {});
  CHECK(even_and_odd(two_groups(g, p)));
  CHECK(p.edge_cut == 0);
}

TEST_CASE("block groups weigh each formation edge by the samples that hold it") {
  // The rails at every sample, and rungs 0-1, 2-3, 4-5, 6-7 at the first sample only. Unweighted, the union is a
  // ladder whose best halving cuts two rails ({0,1,2,3} | {4,5,6,7}); weighted by samples (rails 6, rungs 1) the
  // best halving cuts the four rungs and keeps the rails whole.
  MotionGraph g = eight_agents(rails);
  g.edges[0] = {{0, 1}, {0, 2}, {1, 3}, {2, 3}, {2, 4}, {3, 5}, {4, 5}, {4, 6}, {5, 7}, {6, 7}};
  const Partition p = partition_time_blocks(g, 24, {});
  CHECK(even_and_odd(two_groups(g, p)));
  CHECK(p.edge_cut == 4);  // the four rungs at the first sample
}

TEST_CASE("a block without formation edges groups consecutive agents") {
  const MotionGraph g = eight_agents({});
  const Partition p = partition_time_blocks(g, 24, {});
  CHECK(two_groups(g, p) == std::vector<std::set<std::size_t>>{{0, 1, 2, 3}, {4, 5, 6, 7}});
}

TEST_CASE("block parts are the same whatever the thread count, and more groups than agents give one agent each") {
  const MotionGraph g = grid_graph(8, 10, 60);
  Partition one, two;
  {
    const ThreadLimit limit(1);
    one = partition_time_blocks(g, 120, {.seed = 5});
  }
  {
    const ThreadLimit limit(2);
    two = partition_time_blocks(g, 120, {.seed = 5});
  }
  CHECK(one.part_of == two.part_of);
  CHECK(one.adjacent == two.adjacent);
  // One vertex a part: blocks of 2 samples, and each block's 80 agents in 80 groups (160 asked for).
  const Partition single = partition_time_blocks(g, 1, {});
  CHECK(single.part_count() == 30 * 80);
  for (const auto& list : single.parts) CHECK(list.size() == 2);
}

TEST_CASE("bad block partition options are ConfigErrors naming the option") {
  const MotionGraph g = grid_graph(2, 3, 4);
  CHECK_THROWS_WITH(partition_time_blocks(g, 0, {}), Contains("vertices per part 0"));
  CHECK_THROWS_AS(partition_time_blocks(g, -4, {}), ConfigError);
  CHECK_THROWS_WITH(partition_time_blocks(g, 100, {.imbalance = 1.0}), Contains("imbalance"));
}
