// Tiling motion patches: the time to a perfect tiling (no dangling end) for each row of the paper's Figure 7,
// run from the configs/tile-*.yaml jobs, with the patches and characters reached; and the multi-start speed-up
// of 2 chains on 1 and 2 threads.
//
// Targets on this 2-core machine (a twentieth of the paper's minutes): static 907 patches (103 min in the paper)
// ≤ 5 min, repeating tile (126 min) ≤ 6 min, every row perfect. Counters: patches, characters, dangling (must be
// 0), phase1_s, phase2_s of the kept chain.
//
// Run: build/<dir>/bench/tiling/bench_tiling --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <throng/core/parallel.h>
#include <throng/core/progress.h>
#include <throng/io/config.h>
#include <throng/io/tiling_job.h>

#include <string>

using namespace throng;

namespace {

TilingJob load(const std::string& name) {
  return read_job<TilingJob>(ConfigNode::load_file(std::string(THRONG_SOURCE_DIR) + "/configs/" + name));
}

// One tiling per iteration of `job` with `threads` threads.
void run(benchmark::State& state, TilingJob job, std::size_t threads) {
  const ThreadLimit limit(threads);
  NoProgress quiet;
  const tiling::Prepared prepared = tiling::prepare(job, nullptr);  // the configs timed here use built-in patches
  tiling::TilingResult r;
  for (auto _ : state) {
    r = tiling::tile(prepared.library, job.environment, prepared.keyframes, job.options, quiet);
    benchmark::DoNotOptimize(r.tiling.instances.data());
  }
  const tiling::ChainReport& best = r.report.chains[r.report.best_chain];
  state.counters["patches"] = static_cast<double>(r.report.instances);
  state.counters["characters"] = static_cast<double>(r.report.characters);
  state.counters["dangling"] = static_cast<double>(r.report.dangling);
  state.counters["phase1_s"] = best.phase1_seconds;
  state.counters["phase2_s"] = best.phase2_seconds;
  if (!r.report.perfect()) state.SkipWithError("the tiling is not perfect");
}

// Figure 7, top row: static 12 × 12 m × 20 s at the paper's character counts (16, 34, 48, 60, 70); 0 = no
// limit (phase 1 fills the box: the densest tiling, over 907 patches).
void BM_Static(benchmark::State& state) {
  TilingJob job = load("tile-static.yaml");
  job.options.characters = static_cast<std::size_t>(state.range(0));
  run(state, std::move(job), 2);
}
BENCHMARK(BM_Static)->Arg(16)->Arg(34)->Arg(48)->Arg(60)->Arg(70)->Arg(190)->Arg(0)->Unit(benchmark::kSecond)->UseRealTime();

void BM_Dynamic(benchmark::State& state) { run(state, load("tile-dynamic.yaml"), 2); }
BENCHMARK(BM_Dynamic)->Unit(benchmark::kSecond)->UseRealTime();

void BM_Control(benchmark::State& state) { run(state, load("tile-control.yaml"), 2); }
BENCHMARK(BM_Control)->Unit(benchmark::kSecond)->UseRealTime();

// The repeating 10 × 10 m × 27 s tile at the paper's 55 characters, and at 62 (over the paper's 813 patches).
// (Unlimited density does not converge within search.max_steps: a wrapped tile has no side to leave by.)
void BM_Repeating(benchmark::State& state) {
  TilingJob job = load("tile-repeating.yaml");
  job.options.characters = static_cast<std::size_t>(state.range(0));
  run(state, std::move(job), 2);
}
BENCHMARK(BM_Repeating)->Arg(55)->Arg(62)->Unit(benchmark::kSecond)->UseRealTime();

void BM_Objects(benchmark::State& state) { run(state, load("tile-objects.yaml"), 2); }
BENCHMARK(BM_Objects)->Unit(benchmark::kSecond)->UseRealTime();

// Multi-start: 2 chains of the densest static row on 1 and 2 threads (same result bits; the speed-up is the
// ratio of the two times).
void BM_MultiStart(benchmark::State& state) {
  TilingJob job = load("tile-static.yaml");
  job.options.characters = 0;
  job.options.chains = 2;
  run(state, std::move(job), static_cast<std::size_t>(state.range(0)));
}
BENCHMARK(BM_MultiStart)->Arg(1)->Arg(2)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
