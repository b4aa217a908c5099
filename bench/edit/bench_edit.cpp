// Group motion editing at scale: graph build, precompute (analyse + factorise both steps) and per-drag solve,
// timed apart, for 50, 300, 1,000 and 3,000 agents × 300 sampled frames, per backend.
//
// Targets on the 2-core reference machine (issue 3): 1,000 agents precomputed ≤ 10 s with each drag ≤ 0.5 s;
// 300 agents, each drag ≤ 0.1 s. Paper: "less than one second on average" for groups of 50 to 300.
//
// Run:   bench_edit --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// PETSc on 2 ranks:  mpiexec -np 2 bench_edit --benchmark_filter=petsc ...  (iteration counts are fixed so the
// ranks' collective solves line up; only rank 0 prints).
// Memory: precompute and drag cases report the heap the editor holds after precompute (mallinfo2 difference:
// graph, features, both objectives, the solvers' blocks and the backend's factors or distributed rows and
// multigrid hierarchy) on each rank, as memory_MB (this rank), memory_max_MB and memory_sum_MB (over the ranks):
// run petsc cases under mpiexec -np 1 and -np 2 to compare memory per rank.
#include "../../tests/graph/synthetic_crowd.h"
#include "../common/heap.h"

#include <throng/core/errors.h>
#include <throng/edit/edit.h>
#include <throng/linalg/mpi.h>
#include <throng/process/process.h>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>
#include <string>

namespace {

using namespace throng;

// A battlefield-like block: rows × cols agents marching along a gentle arc for 599 frames, sampled every second
// frame (300 samples). The request holds the first frames and drags the last ones: the paper's head-and-tail
// edit.
struct Scene {
  CrowdMotion crowd;
  edit::Options options;
  edit::Request request;
};

Scene scene(int agents, const std::string& backend) {
  int rows = 5, cols = 10;
  if (agents == 300) rows = 15, cols = 20;
  if (agents == 1000) rows = 25, cols = 40;
  if (agents == 3000) rows = 50, cols = 60;
  Scene s{test::marching_grid(rows, cols, 599, 1.0, 1.2, 0.1, 0.1, 0.2), {}, {}};
  s.options.clip.sample_step = 2;
  s.options.solver.backend = backend;
  edit::Drag head, tail;
  head.selection.last_frame = 2;
  tail.selection.first_frame = 596;
  tail.offset = Eigen::Vector2d(3.0, 4.0);
  tail.rotation = 0.2;
  s.request.drags = {head, tail};
  return s;
}

using bench::heap_mb;  // CHOLMOD, PETSc, hypre and Eigen allocate through malloc

void memory_counters(benchmark::State& state, double megabytes) {
  state.counters["memory_MB"] = megabytes;
  state.counters["memory_max_MB"] = mpi::max(megabytes);
  state.counters["memory_sum_MB"] = mpi::sum(megabytes);
  state.counters["ranks"] = mpi::size();
}

void describe(benchmark::State& state, const edit::Report& r) {
  state.counters["unknowns"] = static_cast<double>(r.unknowns);
  state.counters["features"] = static_cast<double>(r.spatial_features + r.temporal_features + r.spatiotemporal_features);
  state.counters["factor_nnz"] = r.factor_nonzeros;
  state.counters["analyze_s"] = r.analyze_seconds;
  state.counters["factorize_s"] = r.factorize_seconds;
  state.counters["solve_s"] = r.solve_seconds;
  state.counters["step1_s"] = r.step1_seconds;
  state.counters["fit_s"] = r.fit_seconds;
  state.SetLabel(r.factorization);
}

void graph_build(benchmark::State& state, int agents) {
  const Scene s = scene(agents, "eigen");
  std::unique_ptr<edit::Editor> editor;
  for (auto _ : state) {
    editor = std::make_unique<edit::Editor>(s.crowd, s.options, s.request);
    benchmark::DoNotOptimize(editor.get());
  }
  describe(state, editor->report());
}

void precompute(benchmark::State& state, int agents, const std::string& backend) {
  const Scene s = scene(agents, backend);
  std::unique_ptr<edit::Editor> editor;
  double held = 0;
  try {
    for (auto _ : state) {
      state.PauseTiming();
      editor.reset();
      const double before = heap_mb();
      editor = std::make_unique<edit::Editor>(s.crowd, s.options, s.request);
      state.ResumeTiming();
      editor->precompute();
      state.PauseTiming();
      held = heap_mb() - before;
      state.ResumeTiming();
    }
    describe(state, editor->report());
    memory_counters(state, held);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

void drag(benchmark::State& state, int agents, const std::string& backend) {
  Scene s = scene(agents, backend);
  try {
    const double before = heap_mb();
    edit::Editor editor(s.crowd, s.options, s.request);
    editor.precompute();
    const double held = heap_mb() - before;
    double step = 0;
    for (auto _ : state) {
      // A new position for the dragged tail each time, as an interactive drag produces.
      s.request.drags[1].offset = Eigen::Vector2d(3.0 + 0.25 * step, 4.0 - 0.1 * step);
      step += 1;
      benchmark::DoNotOptimize(editor.deform(s.request).data());
    }
    describe(state, editor.report());
    memory_counters(state, held);
    state.counters["refactorisations"] = editor.report().factorizations - 2;
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

// Registered per size with fixed iteration counts (the same on every rank under mpiexec, where the PETSc
// solves are collective): small cases several times, the big ones once per repetition.
void register_benchmarks() {
  for (int agents : {50, 300, 1000, 3000}) {
    const std::string n = std::to_string(agents);
    benchmark::RegisterBenchmark(("graph_build/agents:" + n).c_str(), graph_build, agents)
        ->Iterations(agents <= 300 ? 5 : 1)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    for (const std::string backend : {"eigen", "petsc"}) {
      benchmark::RegisterBenchmark(("precompute/" + backend + "/agents:" + n).c_str(), precompute, agents, backend)
          ->Iterations(agents <= 50 ? 3 : 1)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      benchmark::RegisterBenchmark(("drag/" + backend + "/agents:" + n).c_str(), drag, agents, backend)
          ->Iterations(agents <= 300 ? 10 : 2)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const throng::Process process;  // the BLAS kernels the program uses
  // Under mpiexec every rank runs the same sequence (the PETSc solves are collective); rank 0 reports.
  if (process.world_rank() != 0) (void)std::freopen("/dev/null", "w", stdout);
  register_benchmarks();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
