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
// the direct factor of 3,000 agents does not fit 24 GB), its CG iterations and their error estimate, and over the
// timed drags the fastest and slowest (drag_fastest_s, drag_slowest_s) and the most CG iterations (iterations_most):
// the first drags of a gesture take more iterations than the later ones, whose start the earlier solutions give.
// The untimed drag before them, the first after the precompute, is reported apart (first_drag_s, its solve as the
// editor times it, and first_drag_iterations).
// PETSc on 2 ranks:  mpiexec -np 2 bench_edit --benchmark_filter=petsc ...  (iteration counts are fixed so the
// ranks' collective solves line up; only rank 0 prints).
// Sessions (`throng edit --session`, issue 16: each drag after the first ≤ 0.1 s at 300 agents, ≤ 0.03 s on the
// battlefield): session/<scene>/<method> times edit::Session::edit(), the whole in-process answer but for
// writing a file (the edit on the kept factorisation, resampling, the clip put back into the whole crowd, the
// guard, the request measured on the written frames), for drags after the first of the same handles with new
// offsets; `local` is the direct method on local edits (local.parts auto). session/<scene>/<method>/preview times
// edit::Session::preview(), the answer a plugin draws during a drag: the same solve on the kept editor, its
// sample positions copied out and their largest displacement measured, nothing after it (no file written).
#include "../../tests/edit/shipped_scenes.h"
#include "../../tests/graph/synthetic_crowd.h"
#include "../common/heap.h"

#include <throng/core/errors.h>
#include <throng/edit/edit.h>
#include <throng/edit/session.h>
#include <throng/linalg/mpi.h>
#include <throng/process/huge_pages.h>
#include <throng/process/process.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <limits>
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
    // A new position for the dragged tail each time, as an interactive drag produces.
    auto next_drag = [&] {
      s.request.drags[1].offset = Eigen::Vector2d(3.0 + 0.25 * step, 4.0 - 0.1 * step);
      step += 1;
      return &editor.deform(s.request);
    };
    // One untimed drag under the heap watcher: a drag's workspaces are kept, so later drags allocate no more.
    // The watcher (a thread reading mallinfo2 every 2 ms) is stopped before the timed drags: on a 2-core machine
    // it takes a core and the allocator's lock from the solver's two threads.
    const Eigen::Matrix<double, Eigen::Dynamic, 2>* last = next_drag();
    // The first drag after the precompute, whose start nothing but step 1's result gives (timed by the editor
    // itself, under the watcher).
    const double first_drag_s = editor.report().solve_seconds;
    const int first_drag_iterations = editor.report().iterations;
    const double peak = watch.stop();
    // The spread over the gesture: a drag's CG iterations (and so its time) fall as the solution history grows.
    double fastest = std::numeric_limits<double>::infinity(), slowest = 0;
    int most_iterations = 0;
    for (auto _ : state) {
      const auto drag_start = std::chrono::steady_clock::now();
      last = next_drag();
      benchmark::DoNotOptimize(last->data());
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - drag_start).count();
      fastest = std::min(fastest, seconds);
      slowest = std::max(slowest, seconds);
      most_iterations = std::max(most_iterations, editor.report().iterations);
    }
    state.counters["drag_fastest_s"] = fastest;
    state.counters["drag_slowest_s"] = slowest;
    state.counters["iterations_most"] = most_iterations;
    state.counters["first_drag_s"] = first_drag_s;
    state.counters["first_drag_iterations"] = first_drag_iterations;
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
    auto next_drag = [&] {
      request.drags[1].offset = offset + Eigen::Vector2d(0.5 * step, -0.3 * step);
      step += 1;
      return &editor.deform(request);
    };
    // As drag(): one untimed drag under the heap watcher, the timed ones without it.
    const Eigen::Matrix<double, Eigen::Dynamic, 2>* last = next_drag();
    const double peak = watch.stop();
    for (auto _ : state) {
      last = next_drag();
      benchmark::DoNotOptimize(last->data());
    }
    describe(state, editor.report());
    memory_counters(state, held, peak);
    state.counters["precompute_s"] = precompute_s;
    if (method == "iterative" && last != nullptr) {
      Scene s{shipped.crowd, options, request};
      state.counters["error_m"] = error_against_direct(s, *last);
    }
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

// "direct" and "iterative" as set_method; "local": the direct method on local edits of parts of about
// local.vertices_per_part vertices (local.parts auto).
void set_session_method(edit::Options& options, const std::string& method) {
  set_method(options, method == "local" ? "direct" : method);
  if (method == "local") options.local.parts = edit::LocalOptions::by_size;
}

// Drags after the first in one session (edit::Session): the first request builds the editor (untimed), every
// timed one moves the dragged handles somewhere new and is answered in full (edit()) or as a preview (preview()).
// `move(request, step)` makes the step-th drag.
template <class Move>
void session_drags(benchmark::State& state, const CrowdMotion& motion, edit::Job job, bool preview, Move move) {
  const Crowd input{motion, {}, {}};
  try {
    edit::Session session(input, job);
    (void)session.edit(job.request);  // built
    int reused = 0, step = 0;
    bool warped = false;
    double displacement = 0;
    for (auto _ : state) {
      move(job.request, ++step);
      if (preview) {
        const edit::Preview answer = session.preview(job.request);
        displacement = answer.samples.max_displacement_m;
        benchmark::DoNotOptimize(answer.samples.positions.data());
      } else {
        const edit::Run run = session.edit(job.request);
        warped = warped || run.guard.warped;
        benchmark::DoNotOptimize(run.crowd.motion.positions.data());
      }
      reused += session.last_use() == edit::EditorUse::reused ? 1 : 0;
    }
    state.counters["reused"] = static_cast<double>(reused);  // = iterations: no drag refactorised or rebuilt
    state.counters["bit_identical"] = session.bit_identical() ? 1 : 0;
    if (preview) {
      state.counters["max_displacement_m"] = displacement;  // the last drag's: the samples moved
    } else {
      state.counters["guard_warped"] = warped ? 1 : 0;
    }
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

void session_300(benchmark::State& state, const std::string& method, bool guard, bool preview) {
  const Scene s = scene(300, "direct");
  edit::Job job;
  job.guard.enabled = guard;
  job.options = s.options;
  set_session_method(job.options, method);
  job.request = s.request;
  session_drags(state, s.crowd, job, preview, [](edit::Request& r, int step) {
    r.drags[1].offset = Eigen::Vector2d(3.0 + 0.25 * step, 4.0 - 0.1 * step);
  });
}

void session_battlefield(benchmark::State& state, const std::string& method, bool guard, bool preview) {
  const test::ShippedEdit shipped = test::battlefield(THRONG_SOURCE_DIR);
  edit::Job job = shipped.job;
  job.guard.enabled = guard;
  set_session_method(job.options, method);
  const Eigen::Vector2d offset = job.request.drags[1].offset;
  session_drags(state, shipped.crowd, job, preview, [offset](edit::Request& r, int step) {
    r.drags[1].offset = offset + Eigen::Vector2d(0.5 * step, -0.3 * step);
  });
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
  // guard:on is the job's default (the written crowd is guarded, guard.h); guard:off the paper's edit alone
  // (--set guard.enabled=false), what an interactive preview needs.
  for (const std::string method : {"direct", "iterative", "local"}) {
    for (const bool guard : {true, false}) {
      const std::string g = guard ? "/guard:on" : "/guard:off";
      benchmark::RegisterBenchmark(("session/agents:300/" + method + g).c_str(), session_300, method, guard, false)
          ->Iterations(10)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
      benchmark::RegisterBenchmark(("session/battlefield/" + method + g).c_str(), session_battlefield, method, guard,
                                   false)
          ->Iterations(10)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  // Previews (the guard does not run in one): 300 agents per method, the battlefield direct and local.
  for (const std::string method : {"direct", "iterative", "local"}) {
    benchmark::RegisterBenchmark(("session/agents:300/" + method + "/preview").c_str(), session_300, method, false,
                                 true)
        ->Iterations(10)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
    if (method == "iterative") continue;
    benchmark::RegisterBenchmark(("session/battlefield/" + method + "/preview").c_str(), session_battlefield, method,
                                 false, true)
        ->Iterations(10)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
}

}  // namespace

int main(int argc, char** argv) {
  throng::restart_with_huge_pages(argv);  // as the program does (throng/process/huge_pages.h)
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
