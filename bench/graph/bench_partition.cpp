// Partitioning a motion graph for local edits (partition_time_blocks, throng/graph/partition.h) against the
// crowd's size: 1,000 to 20,000 agents × 300 samples, the bench_scale crowd (the tests' marching grid), parts
// of 500 vertices (local edits' default). Issue 19 asks for partitioning that grows linearly with the crowd:
// Google Benchmark's fit of time against N is printed as BM_PartitionTimeBlocks_BigO and _RMS (oN: the
// coefficient; its RMS is the relative misfit of a linear law).
//   BM_PartitionTimeBlocks  the whole call (block graphs, METIS per block, the Partition's lists); counters
//                           region0 and region1: the mean vertices of a local drag's region with halo 0 and 1
//                           over 400 drags at seeded random places (20 consecutive agents of a row over 21
//                           samples: the parts they reach and their neighbours, parts_within), so a change to the
//                           parts is judged by the regions it makes on average, not at bench_scale's one place;
//                           cross_block: parts of other blocks adjacent to a part, on average
//   BM_PartitionLists       the last stage alone: make_partition of given labels (before 5 December 2026 it went
//                           through space_time_adjacency: 21, 44, 137 and 287 ms at these sizes, one core)
//
// Run: bench_partition --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include "../../tests/graph/partition_measures.h"
#include "../../tests/graph/synthetic_crowd.h"

#include <throng/core/parallel.h>
#include <throng/graph/partition.h>

#include <benchmark/benchmark.h>

#include <array>
#include <random>
#include <set>

namespace {

using namespace throng;

// N agents in 40 columns up to 1,000 agents, 50 up to 2,000 and 100 beyond (as bench_scale), for 300 samples.
int columns_of(int agents) { return agents <= 1000 ? 40 : agents <= 2000 ? 50 : 100; }

MotionGraph graph_of(int agents) {
  const int cols = columns_of(agents);
  const CrowdMotion crowd = test::marching_grid(std::max(1, agents / cols), cols, 300, 1.0, 1.2, 0.1, 0.1, 0.2);
  return build_motion_graph(make_clip(crowd, ClipOptions{}), {});
}

// Mean vertices of the regions (halo 0 and 1) of 400 drags of 20 consecutive agents of a row (agent row × cols +
// column) over 21 samples, at places drawn with a fixed seed.
std::array<double, 2> mean_regions(const MotionGraph& graph, const Partition& p, int cols) {
  const auto n = static_cast<int>(graph.agent_count()), samples = static_cast<int>(graph.sample_count()), rows = n / cols;
  std::mt19937 rng(7);
  std::array<double, 2> sum{0, 0};
  constexpr int drags = 400;
  for (int t = 0; t < drags; ++t) {
    const int row = std::uniform_int_distribution<int>(0, rows - 1)(rng);
    const int column = std::uniform_int_distribution<int>(0, cols - 20)(rng);
    const int first = std::uniform_int_distribution<int>(0, samples - 21)(rng);
    std::set<int> reached;
    for (int i = first; i < first + 21; ++i) {
      for (int c = column; c < column + 20; ++c) reached.insert(p.part_of[static_cast<std::size_t>(i * n + row * cols + c)]);
    }
    const std::vector<int> seeds(reached.begin(), reached.end());
    for (int halo : {0, 1}) {
      for (const int part : parts_within(p, seeds, halo)) sum[static_cast<std::size_t>(halo)] += static_cast<double>(p.parts[static_cast<std::size_t>(part)].size());
    }
  }
  return {sum[0] / drags, sum[1] / drags};
}

void BM_PartitionTimeBlocks(benchmark::State& state) {
  const MotionGraph graph = graph_of(static_cast<int>(state.range(0)));
  ThreadLimit threads(static_cast<std::size_t>(state.range(1)));
  Partition p;
  for (auto _ : state) p = partition_time_blocks(graph, 500, {});
  state.SetComplexityN(static_cast<std::int64_t>(graph.agent_count()));
  state.counters["parts"] = p.part_count();
  state.counters["edge_cut"] = static_cast<double>(p.edge_cut);
  state.counters["vertices"] = static_cast<double>(graph.vertex_count());
  const auto regions = mean_regions(graph, p, columns_of(static_cast<int>(state.range(0))));
  state.counters["region0"] = regions[0];
  state.counters["region1"] = regions[1];
  state.counters["cross_block"] = test::other_block_neighbours(graph, p);
}

void BM_PartitionLists(benchmark::State& state) {
  const MotionGraph graph = graph_of(static_cast<int>(state.range(0)));
  ThreadLimit threads(static_cast<std::size_t>(state.range(1)));
  const std::vector<int> labels = partition_time_blocks(graph, 500, {}).part_of;
  for (auto _ : state) benchmark::DoNotOptimize(make_partition(graph, labels).edge_cut);
  state.SetComplexityN(static_cast<std::int64_t>(graph.agent_count()));
}

void sizes(benchmark::internal::Benchmark* b) {
  for (int agents : {1000, 2000, 5000, 10000, 20000}) b->Args({agents, 2});
  b->ArgNames({"agents", "threads"})->Unit(benchmark::kMillisecond)->UseRealTime()->Complexity(benchmark::oN);
}

}  // namespace

BENCHMARK(BM_PartitionTimeBlocks)->Apply(sizes);
BENCHMARK(BM_PartitionLists)->Apply(sizes);
