// Editing at scale (issue 8): drag latency and memory against crowd size, frames, ranks and threads, for local
// and global edits, strong and weak scaling, and the machine's memory bandwidth to judge them against.
//
// Scenes: the tests' marching grid (tests/graph/synthetic_crowd.h), every frame sampled. The request holds the
// first and the last frame of everyone and drags 20 agents of the formation's front row over the middle 21
// frames (an interactive drag of a small group inside a large crowd). Cases, named study/series/key:x:
//  * size/local_drag/halo:H/agents:N     LocalEditor, N agents × 300 frames, local.parts: auto with
//                                        local.vertices_per_part = --scale_vertices_per_part (default: the
//                                        option's default), local.halo = H: seconds per drag with the region's
//                                        factorisations cached (counters: region vertices, region build seconds,
//                                        memory, METIS seconds, step 1 seconds, and the region's edge in time
//                                        (edit::BoundaryStep): edge_added_m, what the edit added to a step across
//                                        it; edge_reference_m, the agent's fastest input step it is judged
//                                        against; edge_step_m, that step; edge_jump = is_jump()).
//                                        Target: ≤ 0.1 s at 5,000 agents, whatever the crowd size.
//  * parts/local_drag/halo:H/vertices_per_part:V   the same drag at --scale_parts_agents (5,000) agents × 300
//                                        frames for each part size of --scale_part_sizes: the trade between a
//                                        drag's cost and the jump at the region's edge that picks the defaults.
//  * size/global_drag/B/agents:N         Editor with B = eigen or petsc (the direct method on that backend) or
//                                        iterative (two-level CG, 2 threads): seconds per drag after precompute
//                                        (precompute seconds, memory, factor entries, bytes a drag must read;
//                                        iterative: CG iterations of the last drag). Target: iterative ≤ 1 s at
//                                        10,000 agents.
//  * frames/local_drag/halo:1/frames:F,  1,000 agents × F frames.
//    frames/global_drag/petsc/frames:F
//  * strong/<local_drag|global_drag/petsc>/threads:T   fixed size (--scale_strong_agents × 300 frames) on T
//                                        threads; run under mpiexec -np 1 and -np 2: x = workers = ranks × threads.
//  * weak/global_drag/petsc/threads:T    --scale_weak_agents agents per worker (ranks × threads) × 300 frames.
//  * stream_triad                        a[i] = b[i] + s·c[i] over 3 × 128 MB: the memory bandwidth.
// Memory: heap in use held by the case (mallinfo2 difference) on each rank; memory_max_MB and memory_sum_MB over
// the ranks. After the run every case with memory gets stream_sweeps: how many times the drag could have streamed
// everything the solver holds at the measured bandwidth (seconds · GB/s / GB held); a direct solve needs 4 passes
// over its factors (2 steps × forward and back), CG + GAMG about 2 passes per iteration; bandwidth_fraction,
// for the direct backend, is the factor bytes a drag must read over the drag's seconds, as a fraction of triad.
//
// Sizes are arguments (comma-separated lists), so a run stays as long as it needs to be:
//   --scale_agents=1000,2000,5000,10000  --scale_frames=100,300,1000  --scale_threads=1,2  --scale_halos=0,1,2
//   --scale_vertices_per_part=N  --scale_part_sizes=1000,2000,5000  --scale_parts_agents=5000
//   --scale_eigen_max=2000 (the direct global solve's largest crowd: its factors outgrow 23 GB beyond)
//   --scale_strong_agents=2000  --scale_weak_agents=1000  --scale_out=DIR (default bench-scale)
// plus Google Benchmark's own --benchmark_filter. Results: the console, and DIR/scale.csv, scale.json and one
// scale-<study>.svg per study (rows of other runs already in DIR/scale.json are kept: runs under mpiexec -np 1
// and -np 2 build one table). Commands: bench/scale/README.md.
// Ranks: mpiexec -np 2 bench_scale --benchmark_filter='strong|weak' ... (fixed iteration counts keep the
// collective PETSc solves in step; rank 0 prints and writes).
#include "../../tests/graph/synthetic_crowd.h"
#include "../common/heap.h"
#include "chart.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/edit/edit.h>
#include <throng/edit/local_edit.h>
#include <throng/linalg/mpi.h>
#include <throng/process/huge_pages.h>
#include <throng/process/process.h>

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace throng;
using Clock = std::chrono::steady_clock;

// The sweep's sizes (from the --scale_* arguments).
struct Sweep {
  std::vector<int> agents{1000, 2000, 5000, 10000};
  std::vector<int> frames{100, 300, 1000};
  std::vector<int> threads{1, 2};
  std::vector<int> halos{0, 1, 2};
  int vertices_per_part = edit::LocalOptions{}.vertices_per_part;
  std::vector<int> part_sizes{1000, 2000, 5000};
  int parts_agents = 5000;
  int eigen_max = 2000;
  int strong_agents = 2000;
  int weak_agents = 1000;
};

std::vector<int> int_list(const char* text) {
  std::vector<int> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) out.push_back(std::stoi(item));
  }
  return out;
}

using bench::heap_mb;

struct Scene {
  CrowdMotion crowd;
  edit::Options options;
  edit::Request request;
};

Scene scene(int agents, int frames, const std::string& backend) {
  const int cols = agents <= 1000 ? 40 : agents <= 2000 ? 50 : 100;
  const int rows = std::max(1, agents / cols);
  Scene s{test::marching_grid(rows, cols, static_cast<std::size_t>(frames), 1.0, 1.2, 0.1, 0.1, 0.2), {}, {}};
  // "eigen" and "petsc": the direct method on that backend; "iterative": two-level CG (edit's iterative_steps.h).
  s.options.solver.backend = backend == "petsc" ? "petsc" : "eigen";
  s.options.solver.method = backend == "iterative" ? "iterative" : "direct";
  edit::Drag head, tail, group;
  head.selection.last_frame = 0;
  tail.selection.first_frame = -1;
  group.selection.first_frame = frames / 2 - 10;
  group.selection.last_frame = frames / 2 + 10;
  for (int j = 0; j < 20; ++j) group.selection.agents.push_back(100 + cols / 2 - 10 + j);  // the front row's middle
  group.offset = Eigen::Vector2d(1.0, 0.5);
  s.request.drags = {head, tail, group};
  return s;
}

// A new offset per drag, as an interactive drag produces.
void next_offset(Scene& s, double step) { s.request.drags[2].offset = Eigen::Vector2d(1.0 + 0.05 * step, 0.5 - 0.02 * step); }

// The counters every case shares: size, threads, ranks, workers, memory on this rank and over the ranks.
void common_counters(benchmark::State& state, int agents, int frames, int threads, double memory_mb) {
  state.counters["agents"] = agents;
  state.counters["frames"] = frames;
  state.counters["threads"] = threads;
  state.counters["ranks"] = mpi::size();
  state.counters["workers"] = threads * mpi::size();
  state.counters["memory_MB"] = memory_mb;
  state.counters["memory_max_MB"] = mpi::max(memory_mb);
  state.counters["memory_sum_MB"] = mpi::sum(memory_mb);
}

void local_drag(benchmark::State& state, int agents, int frames, int halo, int vertices_per_part, int threads) {
  const ThreadLimit limit(static_cast<std::size_t>(threads));
  Scene s = scene(agents, frames, "eigen");
  s.options.solver.blas_threads = threads;
  s.options.local.parts = edit::LocalOptions::by_size;
  s.options.local.vertices_per_part = vertices_per_part;
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
    common_counters(state, agents, frames, threads, heap_mb() - before);
    state.counters["parts"] = r.parts;
    state.counters["region_parts"] = r.region_parts;
    state.counters["region_vertices"] = static_cast<double>(r.region_vertices);
    state.counters["region_build_s"] = build;
    state.counters["partition_s"] = r.partition_seconds;
    state.counters["regions_built"] = r.regions_built;
    state.counters["vertices_per_part"] = vertices_per_part;
    state.counters["factor_entries"] = r.factor_nonzeros;
    state.counters["step1_s"] = r.step1_seconds;  // of the last drag: the pin basis makes it a dense product
    const edit::BoundaryStep edge = editor.boundary_step();
    state.counters["edge_added_m"] = edge.added_m;
    state.counters["edge_reference_m"] = edge.reference_m();
    state.counters["edge_step_m"] = edge.edited_m;
    state.counters["edge_jump"] = edge.is_jump() ? 1 : 0;
    state.SetLabel(r.factorization);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

void global_drag(benchmark::State& state, int agents, int frames, const std::string& backend, int threads) {
  const ThreadLimit limit(static_cast<std::size_t>(threads));
  Scene s = scene(agents, frames, backend);
  s.options.solver.blas_threads = threads;
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
    common_counters(state, agents, frames, threads, heap_mb() - before);
    state.counters["unknowns"] = static_cast<double>(r.unknowns);
    state.counters["precompute_s"] = r.precompute_seconds;
    state.counters["factor_entries"] = r.factor_nonzeros;
    // A direct drag is two triangular solve pairs (steps 1 and 2): each reads its factor twice, ≥ 12 bytes an
    // entry (8 value + 4 index; complex factors hold 16-byte values, so this is a lower bound). 0 for petsc.
    state.counters["drag_bytes_GB"] = backend == "iterative" ? 0.0 : 2.0 * r.factor_nonzeros * 12.0 / 1e9;
    if (backend == "iterative") state.counters["iterations"] = r.iterations;
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

template <typename... Args>
void add(const std::string& name, int iterations, Args&&... args) {
  benchmark::RegisterBenchmark(name.c_str(), std::forward<Args>(args)...)
      ->Iterations(iterations)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

void register_benchmarks(const Sweep& sweep) {
  benchmark::RegisterBenchmark("stream_triad", stream_triad)->Iterations(10)->Unit(benchmark::kMillisecond)->UseRealTime();
  const bool petsc = mpi::has_petsc();
  // Size: agents × 300 frames.
  for (int halo : sweep.halos) {
    for (int agents : sweep.agents) {
      add("size/local_drag/halo:" + std::to_string(halo) + "/agents:" + std::to_string(agents), 10, local_drag, agents, 300, halo,
          sweep.vertices_per_part, 1);
    }
  }
  // Part size at a fixed crowd.
  for (int halo : sweep.halos) {
    for (int size : sweep.part_sizes) {
      add("parts/local_drag/halo:" + std::to_string(halo) + "/vertices_per_part:" + std::to_string(size), 10, local_drag,
          sweep.parts_agents, 300, halo, size, 1);
    }
  }
  for (int agents : sweep.agents) {
    if (agents <= sweep.eigen_max) {
      add("size/global_drag/eigen/agents:" + std::to_string(agents), 3, global_drag, agents, 300, "eigen", 1);
    }
    add("size/global_drag/iterative/agents:" + std::to_string(agents), 10, global_drag, agents, 300, "iterative", 2);
    if (petsc) add("size/global_drag/petsc/agents:" + std::to_string(agents), 2, global_drag, agents, 300, "petsc", 1);
  }
  // Frames: 1,000 agents × F frames.
  for (int frames : sweep.frames) {
    add("frames/local_drag/halo:1/frames:" + std::to_string(frames), 10, local_drag, 1000, frames, 1, sweep.vertices_per_part, 1);
    if (petsc) add("frames/global_drag/petsc/frames:" + std::to_string(frames), 2, global_drag, 1000, frames, "petsc", 1);
  }
  // Strong (fixed size) and weak (size per worker fixed) scaling over threads; ranks by mpiexec -np.
  for (int threads : sweep.threads) {
    const std::string t = std::to_string(threads);
    add("strong/local_drag/halo:1/threads:" + t, 10, local_drag, sweep.strong_agents, 300, 1, sweep.vertices_per_part, threads);
    if (petsc) {
      add("strong/global_drag/petsc/threads:" + t, 2, global_drag, sweep.strong_agents, 300, "petsc", threads);
      const int weak = sweep.weak_agents * threads * mpi::size();
      add("weak/global_drag/petsc/threads:" + t, 2, global_drag, weak, 300, "petsc", threads);
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
  throng::restart_with_huge_pages(argv);  // as the program does (throng/process/huge_pages.h)
  const throng::Process process;  // the BLAS kernels the program uses
  // Under mpiexec every rank runs the same sequence (the PETSc solves are collective); rank 0 reports.
  const bool writer = process.world_rank() == 0;
  if (!writer) (void)std::freopen("/dev/null", "w", stdout);
  std::string out_dir = "bench-scale";
  Sweep sweep;
  std::vector<char*> args;
  const std::vector<std::pair<std::string, std::function<void(const char*)>>> options{
      {"--scale_out=", [&](const char* v) { out_dir = v; }},
      {"--scale_agents=", [&](const char* v) { sweep.agents = int_list(v); }},
      {"--scale_frames=", [&](const char* v) { sweep.frames = int_list(v); }},
      {"--scale_threads=", [&](const char* v) { sweep.threads = int_list(v); }},
      {"--scale_halos=", [&](const char* v) { sweep.halos = int_list(v); }},
      {"--scale_vertices_per_part=", [&](const char* v) { sweep.vertices_per_part = std::stoi(v); }},
      {"--scale_part_sizes=", [&](const char* v) { sweep.part_sizes = int_list(v); }},
      {"--scale_parts_agents=", [&](const char* v) { sweep.parts_agents = std::stoi(v); }},
      {"--scale_eigen_max=", [&](const char* v) { sweep.eigen_max = std::stoi(v); }},
      {"--scale_strong_agents=", [&](const char* v) { sweep.strong_agents = std::stoi(v); }},
      {"--scale_weak_agents=", [&](const char* v) { sweep.weak_agents = std::stoi(v); }}};
  for (int k = 0; k < argc; ++k) {
    bool ours = false;
    for (const auto& [key, apply] : options) {
      if (std::strncmp(argv[k], key.c_str(), key.size()) == 0) {
        apply(argv[k] + key.size());
        ours = true;
      }
    }
    if (!ours) args.push_back(argv[k]);
  }
  int count = static_cast<int>(args.size());
  register_benchmarks(sweep);
  benchmark::Initialize(&count, args.data());
  Recorder recorder;
  benchmark::RunSpecifiedBenchmarks(&recorder);
  benchmark::Shutdown();
  if (writer && !recorder.rows.empty()) {
    scale::write_results(out_dir, recorder.rows);
    std::fprintf(stderr, "bench_scale: wrote %s/scale.csv, scale.json, scale-<study>.svg\n", out_dir.c_str());
  }
  return 0;
}
