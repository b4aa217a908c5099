#include "problems.h"
#include "test_paths.h"

#include <algorithm>

#include <test_paths.h>
#include <throng/core/errors.h>
#include <throng/linalg/spd_solver.h>

#include <catch2/catch.hpp>

using namespace throng::linalg;

TEST_CASE("backends are chosen by name and unknown names are configuration errors") {
  const auto names = available_backends();
  REQUIRE_FALSE(names.empty());
  CHECK(names.front() == "eigen");
  CHECK(make_spd_solver({})->name() == "eigen");

  SolverOptions bad;
  bad.backend = "cuda";
  try {
    (void)make_spd_solver(bad);
    FAIL("an unknown backend was accepted");
  } catch (const throng::ConfigError& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("cuda") && Catch::Matchers::Contains("eigen"));
  }
}

TEST_CASE("the eigen backend solves an SPD system to rounding and reports CHOLMOD supernodal") {
  const SparseMatrix A = throng::test::random_objective(200, 21);
  const SparseMatrix Q = SparseMatrix(A.transpose()) * A;
  const Eigen::MatrixXd B = throng::test::random_matrix(200, 2, 22);
  auto solver = make_spd_solver({});
  solver->analyze(Q);
  solver->factorize(Q);
  Eigen::MatrixXd X(200, 2);
  solver->solve(B, X);
  // ‖QX − B‖ ≤ c·ε·‖Q‖‖X‖ for a backward-stable Cholesky.
  const double scale = Eigen::MatrixXd(Q).norm() * X.norm();
  CHECK((Q * X - B).norm() <= 1e-13 * scale);
  CHECK_THAT(solver->factorization_info().method, Catch::Matchers::Contains("CHOLMOD supernodal"));
  CHECK(solver->factorization_info().fallback_reason.empty());
  CHECK(solver->factorization_info().reciprocal_condition > 1e-6);
}

TEST_CASE("an indefinite matrix falls back to LDLT and is still rejected as singular") {
  // diag(1, −1, 1): CHOLMOD breaks down at the second pivot; LDLᵀ factors it but a negative pivot is not SPD.
  SparseMatrix Q(3, 3);
  Q.insert(0, 0) = 1.0;
  Q.insert(1, 1) = -1.0;
  Q.insert(2, 2) = 1.0;
  auto solver = make_spd_solver({});
  solver->analyze(Q);
  try {
    solver->factorize(Q);
    FAIL("an indefinite matrix was accepted");
  } catch (const SingularMatrixError& e) {
    CHECK(e.index() == 1);
    CHECK_FALSE(solver->factorization_info().fallback_reason.empty());
  }
}

namespace {

// Solves Q X = B with the petsc backend and the given options; returns ‖QX − B‖ / ‖B‖ and the method.
std::pair<double, std::string> petsc_solve(const std::string& options, const std::string& prefix) {
  const SparseMatrix A = throng::test::random_objective(300, 41);
  const SparseMatrix Q = SparseMatrix(A.transpose()) * A;
  const Eigen::MatrixXd B = throng::test::random_matrix(300, 2, 42);
  SolverOptions o;
  o.backend = "petsc";
  o.petsc_options = options;
  o.petsc_prefix = prefix;  // one prefix per case: options inserted for one case do not reach the next
  auto solver = make_spd_solver(o);
  solver->analyze(Q);
  solver->factorize(Q);
  Eigen::MatrixXd X(300, 2);
  solver->solve(B, X);
  return {(Q * X - B).norm() / B.norm(), solver->factorization_info().method};
}

bool has_petsc() {
  const auto names = available_backends();
  return std::find(names.begin(), names.end(), "petsc") != names.end();
}

}  // namespace

TEST_CASE("the petsc backend takes other Krylov methods and additive Schwarz on METIS parts") {
  if (!has_petsc()) throng::test::skip("this build has no PETSc (-DTHRONG_WITH_PETSC=OFF)");
  // CG's default test is on the true residual at 1e-12; cond(Q) ≈ 1e2 (problems.h) keeps other methods' own
  // (preconditioned) norms within a factor cond of it.
  const auto [cg, cg_method] = petsc_solve("", "t_cg_");
  CHECK(cg < 1e-11);
  // The default multigrid: hypre's BoomerAMG where PETSc has hypre (Debian's does), else PETSc's GAMG.
  CHECK_THAT(cg_method, Catch::Matchers::Contains("cg + hypre on 1 rank") || Catch::Matchers::Contains("cg + gamg on 1 rank"));
  // GAMG (smoothed aggregation with the caller's near null space) stays one option away.
  const auto [gamg, gamg_method] = petsc_solve("-pc_type gamg", "t_gamg_");
  CHECK(gamg < 1e-11);
  CHECK_THAT(gamg_method, Catch::Matchers::Contains("cg + gamg on 1 rank"));
  // MINRES supports only the preconditioned norm: the backend must not force the unpreconditioned one on it.
  const auto [minres, minres_method] = petsc_solve("-ksp_type minres", "t_minres_");
  CHECK(minres < 1e-9);
  CHECK_THAT(minres_method, Catch::Matchers::Contains("minres"));
  // ASM with ICC blocks, one block per METIS part of this rank.
  const auto [schwarz, schwarz_method] = petsc_solve("-pc_type asm -sub_pc_type icc -parts_per_rank 4", "t_asm_");
  CHECK(schwarz < 1e-11);
  CHECK_THAT(schwarz_method, Catch::Matchers::Contains("asm") && Catch::Matchers::Contains("4 METIS parts"));
}

TEST_CASE("bad PETSc options are configuration errors naming them") {
  if (!has_petsc()) throng::test::skip("this build has no PETSc (-DTHRONG_WITH_PETSC=OFF)");
  for (const std::string options : {"-ksp_type bogus", "-pc_type nonsense", "-parts_per_rank 0"}) {
    CAPTURE(options);
    try {
      (void)petsc_solve(options, "t_bad" + std::to_string(options.size()) + "_");
      FAIL("accepted");
    } catch (const throng::ConfigError& e) {
      CHECK(e.exit_code() == throng::ExitCode::usage);
    }
  }
}

TEST_CASE("the eigen backend adopts an analysis only for the pattern it was made for") {
  const SparseMatrix A1 = throng::test::random_objective(120, 51), A2 = throng::test::random_objective(120, 52);
  const SparseMatrix Q1 = SparseMatrix(A1.transpose()) * A1, Q2 = SparseMatrix(A2.transpose()) * A2;
  REQUIRE(Q1.rows() == Q2.rows());
  auto first = make_spd_solver({});
  first->analyze(Q1);
  // Another pattern of the same size: refused, and the solver is left as it was (still needs analyze()).
  auto second = make_spd_solver({});
  CHECK_FALSE(second->adopt_analysis(*first, Q2));
  second->analyze(Q2);
  second->factorize(Q2);
  // The same pattern with other values: adopted, factorised with its own values.
  auto third = make_spd_solver({});
  REQUIRE(third->adopt_analysis(*first, Q1));
  third->factorize(2.0 * Q1);
  const Eigen::MatrixXd B = throng::test::random_matrix(120, 1, 53);
  Eigen::MatrixXd X(120, 1), Y(120, 1);
  third->solve(B, X);
  second->solve(B, Y);
  // Backward stable Cholesky: residuals at ε · ‖Q‖ · ‖X‖ (cond ≈ 1e2, problems.h).
  CHECK((2.0 * Q1 * X - B).norm() <= 1e-13 * Eigen::MatrixXd(2.0 * Q1).norm() * X.norm());
  CHECK((Q2 * Y - B).norm() <= 1e-13 * Eigen::MatrixXd(Q2).norm() * Y.norm());
  // A backend of another kind is never adopted from.
  if (has_petsc()) {
    SolverOptions petsc;
    petsc.backend = "petsc";
    petsc.petsc_prefix = "t_adopt_";
    auto iterative = make_spd_solver(petsc);
    iterative->analyze(Q1);
    CHECK_FALSE(third->adopt_analysis(*iterative, Q1));
    CHECK_FALSE(iterative->adopt_analysis(*first, Q1));
  }
}

TEST_CASE("the petsc backend is iterative by default and direct as preonly with a Cholesky factor") {
  if (!has_petsc()) throng::test::skip("this build has no PETSc (-DTHRONG_WITH_PETSC=OFF)");
  CHECK(make_spd_solver({})->is_direct());  // eigen
  const SparseMatrix A = throng::test::random_objective(300, 41);
  const SparseMatrix Q = SparseMatrix(A.transpose()) * A;
  for (const auto& [options, direct] : {std::pair<std::string, bool>{"", false},
                                        {"-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps", true}}) {
    CAPTURE(options);
    SolverOptions o;
    o.backend = "petsc";
    o.petsc_options = options;
    o.petsc_prefix = direct ? "t_direct_" : "t_iterative_";
    auto solver = make_spd_solver(o);
    solver->analyze(Q);
    CHECK(solver->is_direct() == direct);
    CHECK(solver->owned_columns().empty());  // one rank reads every column
    solver->factorize(Q);
    const Eigen::MatrixXd B = throng::test::random_matrix(300, 1, 42);
    Eigen::MatrixXd X(300, 1);
    solver->solve(B, X);
    // Direct: a backward-stable Cholesky leaves ~ε · cond(Q) ≈ 1e-14 relative (cond ≈ 1e2, problems.h), 1e-11
    // with margin; iterative: CG stops at relative_tolerance on this residual.
    const double tolerance = direct ? 1e-11 : 10 * o.relative_tolerance;
    CHECK((Q * X - B).norm() <= tolerance * B.norm());
  }
}
