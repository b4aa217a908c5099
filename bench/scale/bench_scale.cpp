// Editing at scale (issue 8): drag latency against crowd size for local and global edits, global precompute
// time and memory per backend and rank count, and the machine's memory bandwidth to judge them against.
//
// Scenes: the tests' marching grid (tests/graph/synthetic_crowd.h), 1,000 to 10,000 agents × 300 frames, every
// frame sampled (300 samples). The request holds the first and the last frame of everyone and drags 20 agents
// of the formation's front row over frames 140..160 (an interactive drag of a small group inside a large crowd).
//
//  * local_drag/halo:H/agents:N  LocalEditor (local.parts = vertices / 5,000, local.halo = H): seconds per drag
//                             with the region's factorisations cached (counters: region vertices, region build
//                             seconds, memory held, METIS seconds).
//                             Target (issue 8): ≤ 0.1 s at 5,000 agents, whatever the crowd size.
//  * global_drag/B/agents:N   Editor on backend B: seconds per drag after precompute (counters: precompute
//                             seconds, memory held by the editor in MB, factor entries, bandwidth used by a drag).
//  * global_drag/petsc_asm/agents:N   the petsc backend with additive Schwarz (ICC blocks) instead of GAMG.
//  * stream_triad             a[i] = b[i] + s·c[i] over 3 × 128 MB: the memory bandwidth a drag is judged against.
//
// Results: besides the console, --scale_out=DIR (default bench-scale) gets scale.csv, scale.json and scale.svg
// (time and memory against agents) from the median of the repetitions (or the single run).
// Run:   bench_scale --benchmark_repetitions=3 --benchmark_report_aggregates_only=true --scale_out=out
// Ranks: mpiexec -np 2 bench_scale --benchmark_filter=petsc ... (fixed iteration counts keep the collective
// PETSc solves in step; rank 0 prints and writes).
#include "../../tests/graph/synthetic_crowd.h"
#include "chart.h"

#include <throng/core/errors.h>
#include <throng/edit/edit.h>
#include <throng/edit/local_edit.h>
#include <throng/linalg/mpi.h>

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <malloc.h>

namespace {

using namespace throng;
using Clock = std::chrono::steady_clock;

constexpr std::size_t frames = 300;

// Heap memory in use, MB (glibc's mallinfo2: arena and mmapped blocks in use). A difference of two readings is
// what the code between them holds, whatever earlier cases freed (a resident-set difference is not: freed pages
// stay resident and are reused). CHOLMOD, PETSc and Eigen allocate through malloc; OpenBLAS's small work
// buffers do not and are not counted.
double heap_mb() {
  const struct mallinfo2 m = mallinfo2();
  return static_cast<double>(m.uordblks + m.hblkhd) / (1024.0 * 1024.0);
}

struct Scene {
  CrowdMotion crowd;
  edit::Options options;
  edit::Request request;
};

Scene scene(int agents, const std::string& backend) {
  const int cols = agents <= 1000 ? 40 : agents <= 2000 ? 50 : 100;
  const int rows = agents / cols;
  Scene s{test::marching_grid(rows, cols, frames, 1.0, 1.2, 0.1, 0.1, 0.2), {}, {}};
  s.options.solver.backend = backend;
  edit::Drag head, tail, group;
  head.selection.last_frame = 0;
  tail.selection.first_frame = -1;
  group.selection.first_frame = 140;
  group.selection.last_frame = 160;
  for (int j = 0; j < 20; ++j) group.selection.agents.push_back(100 + cols / 2 - 10 + j);  // the front row's middle
  group.offset = Eigen::Vector2d(1.0, 0.5);
  s.request.drags = {head, tail, group};
  return s;
}

// A new offset per drag, as an interactive drag produces.
void next_offset(Scene& s, double step) { s.request.drags[2].offset = Eigen::Vector2d(1.0 + 0.05 * step, 0.5 - 0.02 * step); }

void local_drag(benchmark::State& state, int agents, int halo) {
  Scene s = scene(agents, "eigen");
  s.options.local.parts = std::max(1, agents * static_cast<int>(frames) / 5000);  // parts of ~5,000 vertices
  s.options.local.halo = halo;
  try {
    const double before = heap_mb();
    edit::LocalEditor editor(s.crowd, s.options, s.request);
    const auto start = Clock::now();
    (void)editor.deform(s.request);  // builds and factorises the region
    const double build = std::chrono::duration<double>(Clock::now() - start).count();
    double step = 1;
    for (auto _ : state) {
      next_offset(s, step++);
      benchmark::DoNotOptimize(editor.deform(s.request).data());
    }
    const edit::Report& r = editor.report();
    state.counters["agents"] = agents;
    state.counters["parts"] = r.parts;
    state.counters["region_parts"] = r.region_parts;
    state.counters["region_vertices"] = static_cast<double>(r.region_vertices);
    state.counters["region_build_s"] = build;
    state.counters["partition_s"] = r.partition_seconds;
    state.counters["memory_MB"] = heap_mb() - before;
    state.counters["regions_built"] = r.regions_built;
    state.SetLabel(r.factorization);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

void global_drag(benchmark::State& state, int agents, const std::string& backend, const std::string& petsc_options) {
  Scene s = scene(agents, backend);
  s.options.solver.petsc_options = petsc_options;
  try {
    const double before = heap_mb();
    edit::Editor editor(s.crowd, s.options, s.request);
    editor.precompute();
    double step = 1;
    for (auto _ : state) {
      next_offset(s, step++);
      benchmark::DoNotOptimize(editor.deform(s.request).data());
    }
    const edit::Report& r = editor.report();
    state.counters["agents"] = agents;
    state.counters["unknowns"] = static_cast<double>(r.unknowns);
    state.counters["precompute_s"] = r.precompute_seconds;
    state.counters["memory_MB"] = heap_mb() - before;
    state.counters["factor_entries"] = r.factor_nonzeros;
    // A drag is two triangular solve pairs (steps 1 and 2): each reads its factor twice, ≥ 12 bytes an entry
    // (8 value + 4 index; complex factors hold 16-byte values, so this is a lower bound).
    state.counters["drag_bytes_GB"] = 2.0 * r.factor_nonzeros * 12.0 / 1e9;
    state.counters["ranks"] = mpi::size();
    state.SetLabel(r.factorization);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

void stream_triad(benchmark::State& state) {
  const std::size_t n = std::size_t{16} << 20;  // 16 Mi doubles = 128 MB per array
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  for (auto _ : state) {
    for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + 3.0 * c[i];
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(3 * n * sizeof(double)));
  state.counters["bandwidth_GBps"] =
      benchmark::Counter(static_cast<double>(3 * n * sizeof(double)) / 1e9, benchmark::Counter::kIsIterationInvariantRate);
}

// Sizes per case: the global direct solve stops where its factor no longer fits this 23 GB machine comfortably.
void register_benchmarks() {
  benchmark::RegisterBenchmark("stream_triad", stream_triad)->Iterations(10)->Unit(benchmark::kMillisecond)->UseRealTime();
  for (int halo : {0, 1}) {
    for (int agents : {1000, 2000, 5000, 10000}) {
      const std::string n = std::to_string(agents);
      benchmark::RegisterBenchmark(("local_drag/halo:" + std::to_string(halo) + "/agents:" + n).c_str(), local_drag, agents, halo)
          ->Iterations(10)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  for (int agents : {1000, 2000}) {
    benchmark::RegisterBenchmark(("global_drag/eigen/agents:" + std::to_string(agents)).c_str(), global_drag, agents, "eigen", "")
        ->Iterations(3)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
  if (mpi::has_petsc()) {
    for (int agents : {1000, 2000, 5000}) {
      benchmark::RegisterBenchmark(("global_drag/petsc/agents:" + std::to_string(agents)).c_str(), global_drag, agents, "petsc", "")
          ->Iterations(2)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
    // The preconditioner choice: additive Schwarz (one block per rank, incomplete Cholesky inside; the symmetric
    // "basic" variant so CG applies) against the default algebraic multigrid.
    for (int agents : {1000, 2000}) {
      benchmark::RegisterBenchmark(("global_drag/petsc_asm/agents:" + std::to_string(agents)).c_str(), global_drag, agents,
                                   "petsc", "-pc_type asm -pc_asm_type basic -sub_pc_type icc")
          ->Iterations(2)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

// Keeps the console output and records one row per case: the median aggregate, or the run itself without
// repetitions.
class Recorder final : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& run : runs) {
      const bool aggregate = run.run_type == Run::RT_Aggregate;
      if (run.error_occurred || (aggregate && run.aggregate_name != "median") || (!aggregate && run.repetitions > 1)) continue;
      scale::Row row;
      row.name = run.run_name.function_name;
      row.ranks = throng::mpi::size();
      row.repetitions = static_cast<int>(run.repetitions);
      row.seconds = run.GetAdjustedRealTime() / 1e3;  // the cases report milliseconds
      for (const auto& [key, counter] : run.counters) row.values[key] = counter.value;
      rows.push_back(std::move(row));
    }
  }
  std::vector<scale::Row> rows;
};

}  // namespace

int main(int argc, char** argv) {
  // Under mpiexec every rank runs the same sequence (the PETSc solves are collective); rank 0 reports.
  const bool writer = !throng::mpi::launched_by_mpiexec() || throng::mpi::rank() == 0;
  if (!writer) (void)std::freopen("/dev/null", "w", stdout);
  std::string out_dir = "bench-scale";
  std::vector<char*> args;
  for (int k = 0; k < argc; ++k) {
    if (std::strncmp(argv[k], "--scale_out=", 12) == 0) {
      out_dir = argv[k] + 12;
    } else {
      args.push_back(argv[k]);
    }
  }
  int count = static_cast<int>(args.size());
  register_benchmarks();
  benchmark::Initialize(&count, args.data());
  Recorder recorder;
  benchmark::RunSpecifiedBenchmarks(&recorder);
  benchmark::Shutdown();
  if (writer && !recorder.rows.empty()) {
    scale::write_results(out_dir, recorder.rows);
    std::fprintf(stderr, "bench_scale: wrote %s/scale.csv, scale.json, scale.svg\n", out_dir.c_str());
  }
  return 0;
}
