// Group motion editing at scale: graph build, precompute and per-drag solve, timed apart, for 50, 300, 1,000,
// 3,000 and 10,000 agents × 300 sampled frames, per method (solver.method direct on eigen = CHOLMOD, iterative =
// two-level CG; direct on petsc), and the shipped battlefield edit.
//
// Targets on the 2-core reference machine (issue 19): 1,000 agents precomputed ≤ 10 s, each drag ≤ 0.1 s, peak
// memory ≤ 2 GB, positions within 1 cm of the exact (direct) solve on the shipped scenes; 300 agents, each drag
// ≤ 0.05 s; 10,000 agents, a global drag ≤ 1 s (bench_scale has that one in its size study too).
//
// Run:   bench_edit --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
//        bench_edit --benchmark_filter='iterative/agents:(300|1000)/'      (one method, some sizes)
// Counters: precompute and drag cases report the heap the editor holds after precompute (mallinfo2
// difference: graph, features, the systems, factors or preconditioners) on each rank (memory_MB; memory_max_MB,
// memory_sum_MB over the ranks), the peak heap while it was built and precomputed (peak_MB), and the process's
// peak resident set so far (max_rss_MB: meaningful for the largest case of a run). Iterative drag cases also
// report the last drag's difference from the direct solve of the same request (error_m: the largest distance of a
// sample position; computed after the timing, for crowds of at most --edit_exact_max agents, 1,000 by default:
// the direct factor of 3,000 agents does not fit 24 GB), its CG iterations and their error estimate.
// PETSc on 2 ranks:  mpiexec -np 2 bench_edit --benchmark_filter=petsc ...  (iteration counts are fixed so the
// ranks' collective solves line up; only rank 0 prints).
#include "../../tests/edit/shipped_scenes.h"
#include "../../tests/graph/synthetic_crowd.h"
#include "../common/heap.h"

#include <throng/core/errors.h>
#include <throng/edit/edit.h>
#include <throng/linalg/mpi.h>
#include <throng/process/process.h>

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <memory>
#include <string>

namespace {

using namespace throng;

int exact_max_agents = 1000;  // --edit_exact_max

// A battlefield-like block: rows × cols agents marching along a gentle arc for 599 frames, sampled every second
// frame (300 samples). The request holds the first frames and drags the last ones: the paper's head-and-tail
// edit.
struct Scene {
  CrowdMotion crowd;
  edit::Options options;
  edit::Request request;
};

// "direct" and "iterative" run on eigen; "petsc" is the direct method on the petsc backend.
void set_method(edit::Options& options, const std::string& method) {
  options.solver.backend = method == "petsc" ? "petsc" : "eigen";
  options.solver.method = method == "iterative" ? "iterative" : "direct";
}

Scene scene(int agents, const std::string& method) {
  int rows = 5, cols = 10;
  if (agents == 300) rows = 15, cols = 20;
  if (agents == 1000) rows = 25, cols = 40;
  if (agents == 3000) rows = 50, cols = 60;
  if (agents == 10000) rows = 100, cols = 100;
  Scene s{test::marching_grid(rows, cols, 599, 1.0, 1.2, 0.1, 0.1, 0.2), {}, {}};
  s.options.clip.sample_step = 2;
  set_method(s.options, method);
  edit::Drag head, tail;
  head.selection.last_frame = 2;
  tail.selection.first_frame = 596;
  tail.offset = Eigen::Vector2d(3.0, 4.0);
  tail.rotation = 0.2;
  s.request.drags = {head, tail};
  return s;
}

using bench::heap_mb;  // CHOLMOD, PETSc, hypre and Eigen allocate through malloc

void memory_counters(benchmark::State& state, double megabytes, double peak) {
  state.counters["memory_MB"] = megabytes;
  state.counters["memory_max_MB"] = mpi::max(megabytes);
  state.counters["memory_sum_MB"] = mpi::sum(megabytes);
  state.counters["peak_MB"] = peak;
  state.counters["max_rss_MB"] = bench::max_rss_mb();
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
  if (r.method == "iterative") {
    state.counters["iterations"] = r.iterations;
    state.counters["precompute_iterations"] = r.precompute_iterations;
    state.counters["error_estimate_m"] = r.solver_error_m;
    state.counters["coarse_size"] = static_cast<double>(r.coarse_size);
  }
  state.SetLabel(r.factorization);
}

// The largest distance between the editor's last result and the direct solve of the same request.
double error_against_direct(const Scene& s, const Eigen::Matrix<double, Eigen::Dynamic, 2>& result) {
  edit::Options direct = s.options;
  set_method(direct, "direct");
  edit::Editor exact(s.crowd, direct, s.request);
  exact.precompute();
  return (exact.deform(s.request) - result).rowwise().norm().maxCoeff();
}

void graph_build(benchmark::State& state, int agents) {
  const Scene s = scene(agents, "direct");
  std::unique_ptr<edit::Editor> editor;
  for (auto _ : state) {
    editor.reset();
    editor = std::make_unique<edit::Editor>(s.crowd, s.options, s.request);
    benchmark::DoNotOptimize(editor.get());
  }
  describe(state, editor->report());
}

void precompute(benchmark::State& state, int agents, const std::string& method) {
  const Scene s = scene(agents, method);
  std::unique_ptr<edit::Editor> editor;
  double held = 0, peak = 0;
  try {
    for (auto _ : state) {
      state.PauseTiming();
      editor.reset();
      const double before = heap_mb();
      bench::HeapPeak watch;
      editor = std::make_unique<edit::Editor>(s.crowd, s.options, s.request);
      state.ResumeTiming();
      editor->precompute();
      state.PauseTiming();
      held = heap_mb() - before;
      peak = watch.stop();
      state.ResumeTiming();
    }
    describe(state, editor->report());
    memory_counters(state, held, peak);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

void drag(benchmark::State& state, int agents, const std::string& method) {
  Scene s = scene(agents, method);
  try {
    const double before = heap_mb();
    bench::HeapPeak watch;
    edit::Editor editor(s.crowd, s.options, s.request);
    editor.precompute();
    const double held = heap_mb() - before;
    double step = 0;
    const Eigen::Matrix<double, Eigen::Dynamic, 2>* last = nullptr;
    for (auto _ : state) {
      // A new position for the dragged tail each time, as an interactive drag produces.
      s.request.drags[1].offset = Eigen::Vector2d(3.0 + 0.25 * step, 4.0 - 0.1 * step);
      step += 1;
      last = &editor.deform(s.request);
      benchmark::DoNotOptimize(last->data());
    }
    const double peak = watch.stop();
    describe(state, editor.report());
    memory_counters(state, held, peak);
    state.counters["refactorisations"] = editor.report().factorizations - 2;
    if (method == "iterative" && agents <= exact_max_agents && last != nullptr) state.counters["error_m"] = error_against_direct(s, *last);
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

// The shipped battlefield edit (50 agents × 791 samples, 30,000 of them handles): precompute and the job's drag,
// then a gesture of further drags of the tail; error_m against the direct solve of the last one.
void battlefield(benchmark::State& state, const std::string& method) {
  const test::ShippedEdit shipped = test::battlefield(THRONG_SOURCE_DIR);
  edit::Options options = shipped.job.options;
  set_method(options, method);
  edit::Request request = shipped.job.request;
  try {
    const double before = heap_mb();
    bench::HeapPeak watch;
    edit::Editor editor(shipped.crowd, options, request);
    editor.precompute();
    const double precompute_s = editor.report().precompute_seconds;
    const double held = heap_mb() - before;
    const Eigen::Vector2d offset = request.drags[1].offset;
    double step = 0;
    const Eigen::Matrix<double, Eigen::Dynamic, 2>* last = nullptr;
    for (auto _ : state) {
      request.drags[1].offset = offset + Eigen::Vector2d(0.5 * step, -0.3 * step);
      step += 1;
      last = &editor.deform(request);
      benchmark::DoNotOptimize(last->data());
    }
    describe(state, editor.report());
    memory_counters(state, held, watch.stop());
    state.counters["precompute_s"] = precompute_s;
    if (method == "iterative" && last != nullptr) {
      Scene s{shipped.crowd, options, request};
      state.counters["error_m"] = error_against_direct(s, *last);
    }
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

// Registered per size with fixed iteration counts (the same on every rank under mpiexec, where the PETSc
// solves are collective): small cases several times, the big ones once per repetition.
void register_benchmarks() {
  for (int agents : {50, 300, 1000, 3000, 10000}) {
    const std::string n = std::to_string(agents);
    benchmark::RegisterBenchmark(("graph_build/agents:" + n).c_str(), graph_build, agents)
        ->Iterations(agents <= 300 ? 5 : 1)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    for (const std::string method : {"direct", "iterative", "petsc"}) {
      if (method != "iterative" && agents > 3000) continue;  // factors beyond this machine's memory
      benchmark::RegisterBenchmark(("precompute/" + method + "/agents:" + n).c_str(), precompute, agents, method)
          ->Iterations(agents <= 50 ? 3 : 1)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      benchmark::RegisterBenchmark(("drag/" + method + "/agents:" + n).c_str(), drag, agents, method)
          ->Iterations(agents <= 1000 ? 10 : 4)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  for (const std::string method : {"direct", "iterative"}) {
    benchmark::RegisterBenchmark(("battlefield/" + method).c_str(), battlefield, method)
        ->Iterations(10)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
  const throng::Process process;  // the BLAS kernels the program uses
  // Under mpiexec every rank runs the same sequence (the PETSc solves are collective); rank 0 reports.
  if (process.world_rank() != 0) (void)std::freopen("/dev/null", "w", stdout);
  for (int k = 1; k < argc; ++k) {
    constexpr const char* key = "--edit_exact_max=";
    if (std::strncmp(argv[k], key, std::strlen(key)) == 0) {
      exact_max_agents = std::stoi(argv[k] + std::strlen(key));
      for (int j = k; j + 1 < argc; ++j) argv[j] = argv[j + 1];
      --argc;
      --k;
    }
  }
  register_benchmarks();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
