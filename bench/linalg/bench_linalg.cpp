// The solver layer on editing-shaped systems: analyse, factorise and solve timed apart; real against complex
// factorisation; BLAS threads; constraints added through the Schur complement against a refactorisation; the
// petsc backend's preconditioners (the measurements behind SolverOptions' defaults).
//
// The system: a side × side formation (a triangulated grid, jittered) over T samples with the editing features
// (spatial per triangle corner, temporal per agent, spatiotemporal per neighbour), written as complex rows in
// real form over interleaved (x, y) pairs; the first and last samples pinned.
//
// Run: bench_linalg --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <throng/core/errors.h>
#include <throng/core/random.h>
#include <throng/linalg/least_squares.h>
#include <throng/linalg/mpi.h>
#include <throng/process/huge_pages.h>
#include <throng/process/process.h>

#include <benchmark/benchmark.h>

#include <complex>
#include <cstdio>
#include <unistd.h>
#include <vector>

namespace {

using namespace throng;
using Complex = std::complex<double>;
using Index = Eigen::Index;

struct System {
  linalg::SparseMatrix A;
  Eigen::VectorXd w, b, pin_values;
  std::vector<Index> pinned;
  Index vertices = 0;
};

System editing_system(int side, int samples) {
  const int n = side * side;
  auto id = [&](int t, int a, int b) { return t * n + a * side + b; };
  Rng rng(17);
  std::vector<Complex> p(static_cast<std::size_t>(n * samples));
  for (int t = 0; t < samples; ++t)
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b)
        p[static_cast<std::size_t>(id(t, a, b))] = Complex(a + 0.12 * t + rng.uniform(-0.2, 0.2), b + rng.uniform(-0.2, 0.2));
  std::vector<Eigen::Triplet<double>> entries;
  Index row = 0;
  auto feature = [&](int u, int v, int w) {  // v − (1 − c) u − c w, c from the positions
    const Complex c = (p[static_cast<std::size_t>(v)] - p[static_cast<std::size_t>(u)]) /
                      (p[static_cast<std::size_t>(w)] - p[static_cast<std::size_t>(u)]);
    const int vertex[3] = {v, u, w};
    const Complex coefficient[3] = {1.0, c - 1.0, -c};
    for (int k = 0; k < 3; ++k) {
      const Index x = 2 * static_cast<Index>(vertex[k]);
      entries.emplace_back(row, x, coefficient[k].real());
      entries.emplace_back(row, x + 1, -coefficient[k].imag());
      entries.emplace_back(row + 1, x, coefficient[k].imag());
      entries.emplace_back(row + 1, x + 1, coefficient[k].real());
    }
    row += 2;
  };
  for (int t = 0; t < samples; ++t)
    for (int a = 0; a + 1 < side; ++a)
      for (int b = 0; b + 1 < side; ++b) {
        const int tri[2][3] = {{id(t, a, b), id(t, a + 1, b), id(t, a + 1, b + 1)}, {id(t, a, b), id(t, a + 1, b + 1), id(t, a, b + 1)}};
        for (const auto& tr : tri)
          for (int k = 0; k < 3; ++k) feature(tr[k], tr[(k + 1) % 3], tr[(k + 2) % 3]);
      }
  for (int t = 1; t + 1 < samples; ++t)
    for (int j = 0; j < n; ++j) feature((t - 1) * n + j, t * n + j, (t + 1) * n + j);
  const int near[6][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}};
  for (int t = 1; t < samples; ++t)
    for (int a = 0; a < side; ++a)
      for (int b = 0; b < side; ++b)
        for (const auto& d : near) {
          const int aa = a + d[0], bb = b + d[1];
          if (aa >= 0 && bb >= 0 && aa < side && bb < side) feature(id(t - 1, a, b), id(t, a, b), id(t, aa, bb));
        }
  System s;
  s.vertices = static_cast<Index>(n) * samples;
  s.A.resize(row, 2 * s.vertices);
  s.A.setFromTriplets(entries.begin(), entries.end());
  s.w = Eigen::VectorXd::Ones(row);
  s.b = Eigen::VectorXd::Zero(row);
  for (int j = 0; j < n; ++j)
    for (int t : {0, samples - 1})
      for (int k = 0; k < 2; ++k) s.pinned.push_back(2 * static_cast<Index>(t * n + j) + k);
  s.pin_values.resize(static_cast<Index>(s.pinned.size()));
  for (Index k = 0; k < s.pin_values.size(); ++k) s.pin_values[k] = rng.uniform(-1, 1);
  return s;
}

linalg::ConstrainedLeastSquares solver_for(const System& s, const linalg::SolverOptions& options, bool complex_pairs) {
  linalg::ConstrainedLeastSquares solver(options);
  solver.set_objective(s.A, s.w);
  solver.set_pinned(s.pinned);
  solver.set_complex_pairs(complex_pairs);
  return solver;
}

// args: side, samples, complex (0/1), BLAS threads
void BM_Factorize(benchmark::State& state) {
  const System s = editing_system(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  linalg::SolverOptions options;
  options.blas_threads = static_cast<int>(state.range(3));
  for (auto _ : state) {
    state.PauseTiming();
    auto solver = std::make_unique<linalg::ConstrainedLeastSquares>(options);
    solver->set_objective(s.A, s.w);
    solver->set_pinned(s.pinned);
    solver->set_complex_pairs(state.range(2) != 0);
    state.ResumeTiming();
    solver->precompute();
    state.counters["factor_entries"] = solver->report().factorization.factor_nonzeros;
    state.counters["analyse_s"] = solver->report().analyze_seconds;
    state.counters["factorise_s"] = solver->report().factorize_seconds;
    state.SetLabel(solver->report().factorization.method);
  }
  state.counters["unknowns"] = static_cast<double>(2 * s.vertices);
}

void BM_Solve(benchmark::State& state) {
  const System s = editing_system(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  linalg::SolverOptions options;
  options.blas_threads = static_cast<int>(state.range(3));
  auto solver = solver_for(s, options, state.range(2) != 0);
  solver.precompute();
  Eigen::VectorXd pins = s.pin_values;
  for (auto _ : state) {
    pins.array() += 0.01;  // a new drag: new pin values, same factorisation
    benchmark::DoNotOptimize(solver.solve(s.b, pins, Eigen::MatrixXd(0, 1)).data());
  }
  state.SetLabel(solver.report().factorization.method);
}

// Adding `k` constraint rows to a factorised problem (Schur complement) against refactorising with them.
void BM_AddConstraints(benchmark::State& state) {
  const System s = editing_system(10, 100);
  const auto k = static_cast<Index>(state.range(0));
  const bool refactorise = state.range(1) != 0;
  linalg::SparseMatrix C(k, s.A.cols());
  for (Index r = 0; r < k; ++r) C.insert(r, 2 * (s.vertices / 2 + 7 * r)) = 1.0;  // x of some middle vertices
  const Eigen::VectorXd d = Eigen::VectorXd::Constant(k, 0.5);
  auto solver = solver_for(s, {}, true);
  solver.precompute();
  for (auto _ : state) {
    state.PauseTiming();
    solver.clear_constraints();
    if (refactorise) solver.set_weights(s.w);  // forces a new factorisation, as a KKT rebuild would
    solver.precompute();
    state.ResumeTiming();
    solver.add_constraints(C);
    benchmark::DoNotOptimize(solver.solve(s.b, s.pin_values, d).data());
  }
}

// Resident memory of this process now (MB), from /proc/self/statm; 0 where that file is missing.
double resident_megabytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (f == nullptr) return 0;
  long pages = 0, resident = 0;
  const int read = std::fscanf(f, "%ld %ld", &pages, &resident);
  std::fclose(f);
  return read == 2 ? static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / 1048576.0 : 0.0;
}

// The petsc backend's preconditioners: args side, preconditioner (0 the default, BoomerAMG with the backend's
// settings, 1 GAMG, 2 mumps Cholesky, 3 additive Schwarz with ICC blocks on one METIS part per rank, 4 the same
// on 4 parts per rank). Run on 1 and 2 ranks (mpiexec -np 2 bench_linalg --benchmark_filter=Petsc): counters per
// solve, memory as max and sum over ranks (resident set: the system, the solver's blocks and the backend's rows
// and hierarchy; each rank builds the same A, then assembles and keeps only its own columns of Q_FF and Q_PF).
void BM_PetscSetupAndSolve(benchmark::State& state) {
  const System s = editing_system(static_cast<int>(state.range(0)), 300);
  linalg::SolverOptions options;
  options.backend = "petsc";
  const char* pcs[] = {"", "-pc_type gamg", "-pc_type cholesky -pc_factor_mat_solver_type mumps",
                       "-pc_type asm -sub_pc_type icc", "-pc_type asm -sub_pc_type icc -parts_per_rank 4"};
  options.petsc_options = pcs[state.range(1)];
  options.petsc_prefix = "bench" + std::to_string(state.range(1)) + "_";
  try {
    for (auto _ : state) {
      const double before = resident_megabytes();
      auto solver = solver_for(s, options, false);
      solver.precompute();
      benchmark::DoNotOptimize(solver.solve(s.b, s.pin_values, Eigen::MatrixXd(0, 1)).data());
      const double grown = resident_megabytes() - before;
      state.counters["iterations"] = solver.report().last_solve.iterations;
      state.counters["setup_s"] = solver.report().factorize_seconds;
      state.counters["solve_s"] = solver.report().solve_seconds;
      state.counters["ranks"] = mpi::size();
      state.counters["rss_max_MB"] = mpi::max(resident_megabytes());
      state.counters["rss_sum_MB"] = mpi::sum(resident_megabytes());
      state.counters["grown_max_MB"] = mpi::max(grown);
      state.SetLabel(solver.report().factorization.method);
    }
  } catch (const Error& e) {
    state.SkipWithError(e.what());
  }
}

}  // namespace

// 50 agents (7 × 7) and 300 agents (17 × 17) over 300 samples; real / complex; 1 / 2 BLAS threads.
BENCHMARK(BM_Factorize)
    ->Args({7, 300, 0, 1})->Args({7, 300, 1, 1})->Args({17, 300, 0, 1})->Args({17, 300, 1, 1})->Args({17, 300, 1, 2})
    ->ArgNames({"side", "samples", "complex", "blas"})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_Solve)
    ->Args({7, 300, 0, 1})->Args({7, 300, 1, 1})->Args({17, 300, 0, 1})->Args({17, 300, 1, 1})->Args({17, 300, 1, 2})
    ->ArgNames({"side", "samples", "complex", "blas"})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AddConstraints)->Args({16, 0})->Args({16, 1})->Args({128, 0})->Args({128, 1})
    ->ArgNames({"rows", "refactorise"})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_PetscSetupAndSolve)
    ->Args({7, 0})->Args({7, 1})->Args({7, 2})->Args({7, 3})->Args({7, 4})
    ->Args({17, 0})->Args({17, 1})->Args({17, 2})->Args({17, 3})->Args({17, 4})
    ->ArgNames({"side", "pc"})->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

int main(int argc, char** argv) {
  throng::restart_with_huge_pages(argv);  // as the program does (throng/process/huge_pages.h)
  const throng::Process process;  // the BLAS kernels the program uses
  // Under mpiexec every rank runs the same sequence (the PETSc solves are collective); rank 0 reports.
  if (process.world_rank() != 0) (void)std::freopen("/dev/null", "w", stdout);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
