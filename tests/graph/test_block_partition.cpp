// partition_time_blocks (throng/graph/partition.h): parts that are a block of consecutive samples × a group of
// agents, about vertices_per_part vertices each, the groups cut along the block's formation edges.
#include "partition_measures.h"
#include "spatial_pieces.h"
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

namespace {

// Formation edges of samples [first, last) cut by the partition.
std::size_t cut_in(const MotionGraph& g, const Partition& p, std::size_t first, std::size_t last) {
  const std::size_t n = g.agent_count();
  std::size_t cut = 0;
  for (std::size_t i = first; i < last; ++i) {
    for (const auto& e : g.edges[i]) cut += p.part_of[i * n + static_cast<std::size_t>(e[0])] != p.part_of[i * n + static_cast<std::size_t>(e[1])] ? 1 : 0;
  }
  return cut;
}

}  // namespace

TEST_CASE("a large block is cut into pieces by place, and a turning crowd keeps its pieces from block to block") {
  // 20 × 20 agents turning 0.5 rad/s over 120 samples; 24 vertices a part: 20 blocks of 6 samples, 100 groups each,
  // so each block is cut into pieces of at most 16 groups before METIS. Kept pieces let METIS group the same agents
  // alike in consecutive blocks: a part touches few parts of the blocks beside it. Cut afresh in every block (the
  // median along x of a turning grid takes other agents each time), it touched about twice as many.
  const MotionGraph g = build_motion_graph(make_clip(test::marching_grid(20, 20, 120, 1.0, 1.2, 0.1, 0.5, 0.1), {}), {});
  const Partition p = partition_time_blocks(g, 24, {});
  CHECK(p.part_count() == 20 * 100);
  for (const PartShape& s : shapes(g, p)) {
    CHECK(s.samples.size() == 6);
    CHECK(s.agents_at.front().size() <= 6);
  }
  CHECK(test::other_block_neighbours(g, p) < 3.0);  // 1.9 (4.6 cut afresh)
  // The first block's groups each lie within one of the pieces its agents' mean places make.
  const std::size_t n = g.agent_count();
  Eigen::Matrix<double, Eigen::Dynamic, 2> places = Eigen::Matrix<double, Eigen::Dynamic, 2>::Zero(static_cast<Eigen::Index>(n), 2);
  for (std::size_t i = 0; i < 6; ++i) places += g.clip.positions.middleRows(static_cast<Eigen::Index>(i * n), static_cast<Eigen::Index>(n));
  places /= 6.0;
  const auto pieces = detail::spatial_pieces(places, 100, 16);
  REQUIRE(pieces.size() == 8);
  std::vector<int> piece_of(n);
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    for (const int a : pieces[k].agents) piece_of[static_cast<std::size_t>(a)] = static_cast<int>(k);
  }
  for (const PartShape& s : shapes(g, p)) {
    if (*s.samples.begin() != 0) continue;
    std::set<int> touched;
    for (const std::size_t a : s.agents_at.front()) touched.insert(piece_of[a]);
    CHECK(touched.size() == 1);
  }
}

TEST_CASE("a crowd whose agents change places gets pieces cut afresh where the old ones no longer fit") {
  // 30 × 30 agents whose places are dealt out anew halfway (a seeded permutation); 96 vertices a part: blocks of 9
  // samples, 84 groups of about 11 agents each, in pieces of at most 16 groups. Pieces kept from the first half
  // would be scattered over the second, and METIS's groups with them. Cut afresh, the second half is grouped as
  // well as the first.
  CrowdMotion crowd = test::marching_grid(30, 30, 108, 1.0, 1.2, 0.1, 0.5, 0.1);
  std::vector<std::size_t> order(crowd.agent_count());
  for (std::size_t a = 0; a < order.size(); ++a) order[a] = (a * 347) % order.size();  // 347 is prime to 900
  for (std::size_t f = 54; f < crowd.frame_count(); ++f) {
    const CrowdMotion before = crowd;
    for (std::size_t a = 0; a < order.size(); ++a) crowd.position(f, a) = before.position(f, order[a]);
  }
  const MotionGraph g = build_motion_graph(make_clip(crowd, {}), {});
  const Partition p = partition_time_blocks(g, 96, {});
  const double first_half = static_cast<double>(cut_in(g, p, 0, 54)), second_half = static_cast<double>(cut_in(g, p, 54, 108));
  CHECK(second_half < 1.15 * first_half);  // 54,810 against 54,324 edges (117,072 with the first half's pieces kept)
}

TEST_CASE("block parts cut into pieces are the same whatever the thread count") {
  const MotionGraph g = build_motion_graph(make_clip(test::marching_grid(20, 20, 60, 1.0, 1.2, 0.1, 0.5, 0.1), {}), {});
  Partition one, two;
  {
    const ThreadLimit limit(1);
    one = partition_time_blocks(g, 24, {});
  }
  {
    const ThreadLimit limit(2);
    two = partition_time_blocks(g, 24, {});
  }
  CHECK(one.part_of == two.part_of);
}
