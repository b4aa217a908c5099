#include "problems.h"

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
