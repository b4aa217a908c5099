// A small SPMD program for the MPI tests (run as `mpiexec -np K linalg_probe [independent]`): checks the
// collectives of throng/linalg/mpi.h and that the petsc backend, distributed over the ranks (by METIS parts,
// with GAMG and with additive Schwarz on the parts), agrees with the eigen backend on a constrained
// least-squares problem. With `independent` (a farm: mpi::use_ranks_independently) every rank solves alone and
// the backend must say so. Prints one line per check; exits 1 on the first failure.
#include "../linalg/problems.h"

#include <throng/linalg/least_squares.h>
#include <throng/linalg/mpi.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

namespace {

int rank = 0;

void require(bool ok, const std::string& what) {
  if (rank == 0) std::printf("%s %s\n", ok ? "ok" : "FAILED", what.c_str());
  if (!ok) std::exit(1);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace throng;
  try {
    const bool independent = argc > 1 && std::string(argv[1]) == "independent";
    if (independent) mpi::use_ranks_independently();
    rank = mpi::rank();
    const int size = mpi::size();
    require(mpi::is_initialized() == mpi::launched_by_mpiexec(), "MPI starts by itself under mpiexec only");
    if (rank == 0) std::printf("ranks %d\n", size);

    // Collectives.
    std::vector<double> values = rank == 0 ? std::vector<double>{1.5, 2.5, 3.5} : std::vector<double>{};
    mpi::broadcast(values);
    require(values == std::vector<double>{1.5, 2.5, 3.5}, "broadcast of doubles");
    std::vector<std::byte> bytes;
    if (rank == 0) bytes = {std::byte{7}, std::byte{9}};
    mpi::broadcast(bytes);
    require(bytes.size() == 2 && bytes[1] == std::byte{9}, "broadcast of bytes");
    const std::vector<double> mine(static_cast<std::size_t>(rank + 1), static_cast<double>(rank));
    const auto gathered = mpi::gather(std::span<const double>(mine));
    if (rank == 0) {
      bool ok = static_cast<int>(gathered.size()) == size;
      for (int r = 0; ok && r < size; ++r) ok = gathered[static_cast<std::size_t>(r)] == std::vector<double>(static_cast<std::size_t>(r + 1), r);
      require(ok, "gather of doubles (ragged)");
    }
    const auto everyone = mpi::all_gather(std::span<const double>(mine));
    require(static_cast<int>(everyone.size()) == size && everyone.back().size() == static_cast<std::size_t>(size), "all_gather");
    require(mpi::sum(1.0) == size && mpi::max(rank) == size - 1, "sum and max");

    // The petsc backend against the eigen backend (every rank builds the same problem).
    const Eigen::Index n = 400;
    const linalg::SparseMatrix A = test::random_objective(n, 31);
    const Eigen::VectorXd w = test::random_weights(A.rows(), 32);
    const Eigen::MatrixXd b = test::random_matrix(A.rows(), 2, 33);
    const std::vector<Eigen::Index> pinned{0, 1, 200, 201};
    const Eigen::MatrixXd pins = test::random_matrix(4, 2, 34);
    linalg::SparseMatrix C(2, n);
    C.insert(0, 10) = 1.0;
    C.insert(0, 11) = -1.0;
    C.insert(1, 300) = 1.0;
    const Eigen::MatrixXd d = test::random_matrix(2, 2, 35);

    const Eigen::MatrixXd direct = linalg::solve_least_squares(A, w, b, pinned, pins, C, d);
    auto petsc_solve = [&](const std::string& options, const std::string& prefix) {
      linalg::SolverOptions petsc;
      petsc.backend = "petsc";
      petsc.petsc_options = options;
      petsc.petsc_prefix = prefix;
      linalg::ConstrainedLeastSquares solver(petsc);
      solver.set_objective(A, w);
      solver.set_pinned(pinned);
      solver.set_constraints(C);
      Eigen::MatrixXd x = solver.solve(b, pins, d);
      // Residual ≤ rtol relative and cond(Q) ≈ 1e2 (problems.h) bound the error near 1e2 · rtol, amplified once
      // more through the Schur complement of the two constraints: 1e4 · rtol (1e-8 at the default 1e-12).
      const double gap = (x - direct).cwiseAbs().maxCoeff() / (1.0 + direct.cwiseAbs().maxCoeff());
      if (rank == 0) std::printf("method %s, gap %.3g\n", solver.report().factorization.method.c_str(), gap);
      const std::string ranks_said = independent || size == 1 ? "on 1 rank" : "on " + std::to_string(size) + " ranks";
      require(solver.report().factorization.method.find(ranks_said) != std::string::npos, "the backend runs " + ranks_said);
      return std::make_pair(x, gap);
    };
    const double tolerance = 1e4 * linalg::SolverOptions{}.relative_tolerance;
    const auto [iterative, gap] = petsc_solve("", "throng_");
    require(gap < tolerance, "petsc agrees with eigen");
    const auto [gamg, gamg_gap] = petsc_solve("-pc_type gamg", "gamg_");
    require(gamg_gap < tolerance, "petsc with GAMG agrees with eigen");
    const auto [schwarz, schwarz_gap] = petsc_solve("-pc_type asm -sub_pc_type icc -parts_per_rank 2", "asm_");
    require(schwarz_gap < tolerance, "petsc with additive Schwarz on the parts agrees with eigen");
    // Every rank holds the whole, identical solution.
    const auto all = mpi::all_gather(std::span<const double>(iterative.data(), static_cast<std::size_t>(iterative.size())));
    bool same = true;
    for (const auto& other : all) same = same && other == all.front();
    require(same, "every rank has the same solution");
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rank %d: %s\n", rank, e.what());
    return 2;
  }
}
