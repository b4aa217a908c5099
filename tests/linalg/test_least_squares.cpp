#include "problems.h"

#include <throng/core/errors.h>
#include <throng/linalg/least_squares.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <complex>

using throng::linalg::ConstrainedLeastSquares;
using throng::linalg::ConstraintError;
using throng::linalg::SingularMatrixError;
using throng::linalg::SolverOptions;
using throng::linalg::SparseMatrix;
using namespace throng::test;
using Eigen::Index;

namespace {

// Every test runs once per backend of this build ("eigen and petsc agree on every test system").
// Problems here have cond(AᵀWA) ≈ 1e2 (n = 60) and the KKT reference adds its own rounding. The direct backend:
// agreement to 1e-10 relative leaves three orders of margin above ε·cond while catching any wrong term (errors
// are O(1)). The iterative backend stops at a relative residual of rtol (SolverOptions::relative_tolerance), so
// its error is ≤ cond · rtol on the unknowns, amplified once more through the Schur complement built from such
// solves: cond² · rtol = 1e4 · rtol (1e-8 at the default 1e-12).
struct Backend {
  std::string name;
  SolverOptions options;
  double agree = 1e-10;
  [[nodiscard]] bool direct() const { return name == "eigen"; }
};

Backend backend_under_test() {
  Backend b;
  b.name = GENERATE(from_range(throng::linalg::available_backends()));
  b.options.backend = b.name;
  if (!b.direct()) b.agree = 1e4 * b.options.relative_tolerance;
  return b;
}

double relative_gap(const Eigen::MatrixXd& x, const Eigen::MatrixXd& y) {
  return (x - y).cwiseAbs().maxCoeff() / (1.0 + y.cwiseAbs().maxCoeff());
}

SparseMatrix sparse(const Eigen::MatrixXd& dense) { return dense.sparseView(); }

struct Fixture {
  Index n = 60;
  SparseMatrix A = random_objective(60, 1);
  Eigen::VectorXd w = random_weights(180, 2);
  Eigen::VectorXd b = random_matrix(180, 1, 3);
  std::vector<Index> pinned{3, 17, 42};
  Eigen::VectorXd pin_values = random_matrix(3, 1, 4);
  Eigen::MatrixXd C = [] {
    Eigen::MatrixXd c = Eigen::MatrixXd::Zero(2, 60);
    c(0, 5) = 1.0;   // x5 − x6 = d0 (a relative position)
    c(0, 6) = -1.0;
    c(1, 10) = 2.0;  // 2 x10 + x11 + x17 = d1 (touches a pinned unknown)
    c(1, 11) = 1.0;
    c(1, 17) = 1.0;
    return c;
  }();
  Eigen::VectorXd d = Eigen::Vector2d(0.25, -0.5);
};

}  // namespace

TEST_CASE("unconstrained least squares matches the dense normal equations") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  const Eigen::MatrixXd x = throng::linalg::solve_least_squares(f.A, f.w, f.b, {}, Eigen::MatrixXd(0, 1),
                                                                SparseMatrix(0, f.n), Eigen::MatrixXd(0, 1), be.options);
  const Eigen::VectorXd ref = dense_reference(f.A, f.w, f.b, {}, {}, Eigen::MatrixXd(0, f.n), {});
  CHECK(relative_gap(x, ref) < be.agree);
}

TEST_CASE("pins and general constraints match the dense KKT solution and are met") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.set_constraints(sparse(f.C));
  const Eigen::MatrixXd x = solver.solve(f.b, f.pin_values, f.d);
  const Eigen::VectorXd ref = dense_reference(f.A, f.w, f.b, f.pinned, f.pin_values, f.C, f.d);
  CHECK(relative_gap(x, ref) < be.agree);
  for (std::size_t k = 0; k < f.pinned.size(); ++k) CHECK(x(f.pinned[k], 0) == f.pin_values[static_cast<Index>(k)]);
  CHECK((f.C * x - f.d).cwiseAbs().maxCoeff() < 1e-12);
  CHECK(solver.report().constraint_rank == 2);
}

TEST_CASE("a manufactured solution is recovered exactly") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  const Eigen::VectorXd truth = random_matrix(f.n, 1, 9);
  const Eigen::VectorXd b = f.A * truth;
  Eigen::VectorXd pins(3);
  for (int k = 0; k < 3; ++k) pins[k] = truth[f.pinned[static_cast<std::size_t>(k)]];
  const Eigen::VectorXd d = f.C * truth;
  const Eigen::MatrixXd x = throng::linalg::solve_least_squares(f.A, f.w, b, f.pinned, pins, sparse(f.C), d, be.options);
  CHECK(relative_gap(x, truth) < be.agree);
}

TEST_CASE("new right-hand sides, pin values and constraint values reuse the factorisation") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.set_constraints(sparse(f.C));
  solver.precompute();
  REQUIRE(solver.report().analyses == 1);
  REQUIRE(solver.report().factorizations == 1);
  const int schur_columns = solver.report().schur_columns;

  for (std::uint64_t drag = 0; drag < 4; ++drag) {
    const Eigen::VectorXd b = random_matrix(180, 1, 100 + drag);
    const Eigen::VectorXd pins = random_matrix(3, 1, 200 + drag);
    const Eigen::VectorXd d = random_matrix(2, 1, 300 + drag);
    const Eigen::MatrixXd x = solver.solve(b, pins, d);
    // The reused factorisation gives the same bits as a fresh solver (direct); the iterative backend starts
    // each drag from the last solution, so it agrees to its tolerance.
    const Eigen::MatrixXd fresh = throng::linalg::solve_least_squares(f.A, f.w, b, f.pinned, pins, sparse(f.C), d, be.options);
    if (be.direct()) CHECK(x == fresh);
    else CHECK(relative_gap(x, fresh) < be.agree);
    CHECK(relative_gap(x, dense_reference(f.A, f.w, b, f.pinned, pins, f.C, d)) < be.agree);
  }
  CHECK(solver.report().analyses == 1);
  CHECK(solver.report().factorizations == 1);
  CHECK(solver.report().schur_columns == schur_columns);
}

TEST_CASE("several right-hand sides at once equal one at a time") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.set_constraints(sparse(f.C));
  const Eigen::MatrixXd B = random_matrix(180, 3, 11);
  const Eigen::MatrixXd P = random_matrix(3, 3, 12);
  const Eigen::MatrixXd D = random_matrix(2, 3, 13);
  const Eigen::MatrixXd X = solver.solve(B, P, D);
  for (Index c = 0; c < 3; ++c) {
    const Eigen::MatrixXd one = solver.solve(B.col(c), P.col(c), D.col(c));
    CHECK(relative_gap(X.col(c), one) < (be.direct() ? 1e-14 : be.agree));
  }
}

TEST_CASE("added constraints cost back-substitutions, not a refactorisation") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.set_constraints(sparse(f.C.topRows(1)));
  solver.precompute();
  const int columns_before = solver.report().schur_columns;
  solver.add_constraints(sparse(f.C.bottomRows(1)));
  CHECK_FALSE(solver.is_ready());
  const Eigen::MatrixXd x = solver.solve(f.b, f.pin_values, f.d);
  CHECK(solver.report().factorizations == 1);
  CHECK(solver.report().analyses == 1);
  CHECK(solver.report().schur_columns == columns_before + 1);
  CHECK(relative_gap(x, dense_reference(f.A, f.w, f.b, f.pinned, f.pin_values, f.C, f.d)) < be.agree);

  solver.clear_constraints();
  const Eigen::MatrixXd free = solver.solve(f.b, f.pin_values, Eigen::MatrixXd(0, 1));
  CHECK(solver.report().factorizations == 1);
  CHECK(relative_gap(free, dense_reference(f.A, f.w, f.b, f.pinned, f.pin_values, Eigen::MatrixXd(0, f.n), {})) < be.agree);
}

TEST_CASE("without the Schur cache the answer is the same") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  SolverOptions no_cache = be.options;
  no_cache.schur_cache_megabytes = 0;
  const Eigen::MatrixXd cached = throng::linalg::solve_least_squares(f.A, f.w, f.b, f.pinned, f.pin_values, sparse(f.C), f.d, be.options);
  const Eigen::MatrixXd uncached =
      throng::linalg::solve_least_squares(f.A, f.w, f.b, f.pinned, f.pin_values, sparse(f.C), f.d, no_cache);
  CHECK(relative_gap(uncached, cached) < be.agree);
}

TEST_CASE("new weights refactorise without a new analysis and a new pinned set analyses again") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.precompute();
  const Eigen::VectorXd w2 = random_weights(180, 77);
  solver.set_weights(w2);
  const Eigen::MatrixXd x = solver.solve(f.b, f.pin_values, Eigen::MatrixXd(0, 1));
  CHECK(solver.report().analyses == 1);
  CHECK(solver.report().factorizations == 2);
  CHECK(relative_gap(x, dense_reference(f.A, w2, f.b, f.pinned, f.pin_values, Eigen::MatrixXd(0, f.n), {})) < be.agree);

  solver.set_pinned({0, 1});
  const Eigen::MatrixXd y = solver.solve(f.b, Eigen::Vector2d(1, 2), Eigen::MatrixXd(0, 1));
  CHECK(solver.report().analyses == 2);
  CHECK(relative_gap(y, dense_reference(f.A, w2, f.b, {0, 1}, Eigen::Vector2d(1, 2), Eigen::MatrixXd(0, f.n), {})) < be.agree);
}

TEST_CASE("redundant but consistent constraints are accepted") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  Eigen::MatrixXd C(3, f.n);
  C << f.C, 3.0 * f.C.row(0);  // the third row is the first, scaled
  const Eigen::Vector3d d(f.d[0], f.d[1], 3.0 * f.d[0]);
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.set_constraints(sparse(C));
  const Eigen::MatrixXd x = solver.solve(f.b, f.pin_values, d);
  CHECK(solver.report().constraint_rank == 2);
  CHECK(relative_gap(x, dense_reference(f.A, f.w, f.b, f.pinned, f.pin_values, f.C, f.d)) < be.agree);
}

TEST_CASE("contradictory constraints are a ConstraintError naming the rows") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  Eigen::MatrixXd C(3, f.n);
  C << f.C, f.C.row(0);
  const Eigen::Vector3d d(f.d[0], f.d[1], f.d[0] + 1.0);  // x5 − x6 = 0.25 and x5 − x6 = 1.25
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.set_constraints(sparse(C));
  try {
    (void)solver.solve(f.b, f.pin_values, d);
    FAIL("contradictory constraints were accepted");
  } catch (const ConstraintError& e) {
    CHECK(std::find(e.rows().begin(), e.rows().end(), 0) != e.rows().end());
    CHECK(std::find(e.rows().begin(), e.rows().end(), 2) != e.rows().end());
    CHECK(e.exit_code() == throng::ExitCode::not_converged);
    CHECK_THAT(e.what(), Catch::Matchers::Contains("contradict"));
  }
}

TEST_CASE("a constraint on pinned unknowns that disagrees with the pins is a ConstraintError") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(1, f.n);
  C(0, 3) = 1.0;  // x3 is pinned
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned(f.pinned);
  solver.set_constraints(sparse(C));
  const Eigen::VectorXd consistent = Eigen::VectorXd::Constant(1, f.pin_values[0]);
  CHECK_NOTHROW(solver.solve(f.b, f.pin_values, consistent));
  CHECK_THROWS_AS(solver.solve(f.b, f.pin_values, consistent.array() + 0.5), ConstraintError);
}

TEST_CASE("an undetermined unknown is a singular system naming it") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  // A graph Laplacian of a path (differences of neighbours): translation is free until something is pinned.
  const Index n = 30;
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i + 1 < n; ++i) {
    t.emplace_back(i, i, -1.0);
    t.emplace_back(i, i + 1, 1.0);
  }
  SparseMatrix A(n - 1, n);
  A.setFromTriplets(t.begin(), t.end());
  const Eigen::VectorXd w = Eigen::VectorXd::Ones(n - 1);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(n - 1);

  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(A, w);
  if (be.direct()) {
    CHECK_THROWS_AS(solver.precompute(), SingularMatrixError);
  } else {
    // An iterative backend sees only what the Krylov method sees: Q is positive semidefinite with a positive
    // diagonal and AᵀWb lies in its range, so CG may stop at one of the minimisers, or report the system.
    try {
      const Eigen::MatrixXd any = solver.solve(b, Eigen::MatrixXd(0, 1), Eigen::MatrixXd(0, 1));
      CHECK((SparseMatrix(A.transpose()) * (A * any - b)).cwiseAbs().maxCoeff() < 1e-9);
    } catch (const throng::NumericalError& e) {
      CHECK_THAT(e.what(), Catch::Matchers::Contains("singular") || Catch::Matchers::Contains("did not converge"));
    }
  }
  solver.set_pinned({0});
  const Eigen::MatrixXd x = solver.solve(b, Eigen::VectorXd::Constant(1, 2.0), Eigen::MatrixXd(0, 1));
  // Pinned at one end the path's Q has cond ≈ (4n/π)² ≈ 1.5e3: CG's 1e-12 relative residual allows
  // cond · 1e-12 · ‖x‖ (‖x‖ ≈ 31) ≈ 5e-8 on the unknowns.
  const double tolerance = be.direct() ? 1e-12 : 1e-7;
  for (Index i = 0; i < n; ++i) CHECK_THAT(x(i, 0), Catch::Matchers::WithinAbs(2.0 + static_cast<double>(i), tolerance));

  // An unknown that no row mentions: a zero diagonal, found by every backend before solving.
  SparseMatrix wider(n - 1, n + 1);
  wider.leftCols(n) = A;
  solver.set_objective(wider, w);
  solver.set_pinned({0});
  try {
    solver.precompute();
    FAIL("a free unknown outside the objective was accepted");
  } catch (const SingularMatrixError& e) {
    CHECK(e.exit_code() == throng::ExitCode::not_converged);
    CHECK_THAT(e.what(), Catch::Matchers::Contains("singular"));
  }
}

TEST_CASE("everything pinned needs no factorisation") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  std::vector<Index> all(static_cast<std::size_t>(f.n));
  for (Index i = 0; i < f.n; ++i) all[static_cast<std::size_t>(i)] = i;
  const Eigen::VectorXd values = random_matrix(f.n, 1, 5);
  const Eigen::MatrixXd x = throng::linalg::solve_least_squares(f.A, f.w, f.b, all, values, SparseMatrix(0, f.n),
                                                                Eigen::MatrixXd(0, 1), be.options);
  CHECK(x == values);
}

TEST_CASE("malformed calls are rejected before any work") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  ConstrainedLeastSquares solver(be.options);
  solver.set_objective(f.A, f.w);
  solver.set_pinned({3, 3});
  CHECK_THROWS_AS(solver.precompute(), std::invalid_argument);
  solver.set_pinned({f.n});
  CHECK_THROWS_AS(solver.precompute(), std::invalid_argument);
  CHECK_THROWS_AS(solver.set_weights(-f.w), std::invalid_argument);
  solver.set_pinned({});
  CHECK_THROWS_AS(solver.solve(f.b.head(10), Eigen::MatrixXd(0, 1), Eigen::MatrixXd(0, 1)), std::invalid_argument);
}

TEST_CASE("complex pairs: the complex factorisation gives the real one's answer, and odd pins fall back") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  // A complex-linear objective over 40 complex unknowns written in real form: each complex row a·z gives the
  // real rows [Re a, −Im a; Im a, Re a] on the interleaved pair.
  const Index pairs = 40;
  throng::Rng rng(8);
  std::vector<Eigen::Triplet<double>> t;
  Index row = 0;
  auto complex_row = [&](std::initializer_list<std::pair<Index, std::complex<double>>> terms) {
    for (const auto& [z, a] : terms) {
      t.emplace_back(row, 2 * z, a.real());
      t.emplace_back(row, 2 * z + 1, -a.imag());
      t.emplace_back(row + 1, 2 * z, a.imag());
      t.emplace_back(row + 1, 2 * z + 1, a.real());
    }
    row += 2;
  };
  for (Index k = 0; k < 3 * pairs; ++k) {
    const auto a = static_cast<Index>(rng.below(pairs)), b = static_cast<Index>(rng.below(pairs));
    complex_row({{a, {rng.uniform(-1, 1), rng.uniform(-1, 1)}}, {b, {rng.uniform(-1, 1), rng.uniform(-1, 1)}}});
  }
  for (Index z = 0; z < pairs; ++z) complex_row({{z, {1.0 + rng.uniform(), 0.0}}});
  SparseMatrix A(row, 2 * pairs);
  A.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd w(row);
  for (Index r = 0; r < row; r += 2) w[r] = w[r + 1] = rng.uniform(0.5, 2.0);  // one weight per complex row
  const Eigen::VectorXd b = random_matrix(row, 1, 61);

  for (const std::vector<Index>& pinned : {std::vector<Index>{4, 5, 20, 21}, std::vector<Index>{4, 5, 21}}) {
    const Eigen::VectorXd pins = random_matrix(static_cast<Index>(pinned.size()), 1, 62);
    ConstrainedLeastSquares real(be.options), complex(be.options);
    real.set_objective(A, w);
    real.set_pinned(pinned);
    complex.set_objective(A, w);
    complex.set_pinned(pinned);
    complex.set_complex_pairs(true);
    const Eigen::MatrixXd x_real = real.solve(b, pins, Eigen::MatrixXd(0, 1));
    const Eigen::MatrixXd x_complex = complex.solve(b, pins, Eigen::MatrixXd(0, 1));
    CAPTURE(pinned.size());
    CHECK(relative_gap(x_complex, x_real) < be.agree);
    const bool whole_pairs = pinned.size() % 2 == 0;
    if (be.direct()) {
      CHECK_THAT(complex.report().factorization.method,
                 Catch::Matchers::Contains(whole_pairs ? "complex LLᴴ" : "LLᵀ"));
    }
  }
}

TEST_CASE("pin values as coordinates in a basis give the solve with the expanded values") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  // Six pinned unknowns as B u: two unknowns share coordinate 0, a rotation-like pair mixes coordinates 1 and 2,
  // the last two have coordinates of their own (3 and 4).
  const std::vector<Index> pinned{3, 17, 42, 43, 50, 8};
  std::vector<Eigen::Triplet<double>> t{{0, 0, 1.0}, {1, 0, 1.0}, {2, 1, 0.6}, {2, 2, -0.8}, {3, 1, 0.8},
                                        {3, 2, 0.6}, {4, 3, 1.0}, {5, 4, 1.0}};
  SparseMatrix B(6, 5);
  B.setFromTriplets(t.begin(), t.end());
  ConstrainedLeastSquares in_basis(be.options), expanded(be.options);
  for (ConstrainedLeastSquares* solver : {&in_basis, &expanded}) {
    solver->set_objective(f.A, f.w);
    solver->set_pinned(pinned);
    solver->set_constraints(sparse(f.C));
  }
  in_basis.set_pin_basis(B);
  in_basis.precompute();
  // A direct backend solves Q_FF Z = Q_FP B in precompute (one column per coordinate); an iterative one does not.
  CHECK(in_basis.report().basis_columns == (be.direct() ? 5 : 0));
  CHECK(in_basis.precomputes_basis() == be.direct());
  for (std::uint64_t drag = 0; drag < 3; ++drag) {
    const Eigen::MatrixXd u = random_matrix(5, 2, 400 + drag);
    const Eigen::MatrixXd b = random_matrix(180, 2, 500 + drag / 2);  // b repeats once (500, 500, 501): the cached Q⁻¹ r_b path
    const Eigen::MatrixXd d = random_matrix(2, 2, 600 + drag);
    const Eigen::MatrixXd x = in_basis.solve_in_basis(b, u, d);
    const Eigen::MatrixXd pins = B * u;
    const Eigen::MatrixXd y = expanded.solve(b, pins, d);
    for (std::size_t k = 0; k < pinned.size(); ++k) {
      CHECK(x.row(pinned[k]) == pins.row(static_cast<Index>(k)));  // pins are placed, not solved for
    }
    // Direct: Q⁻¹ r_b − Z u and Q⁻¹ (r_b − Q_FP B u) differ by rounding only, ε · cond ≈ 1e-14; 1e-12 leaves
    // margin. Iterative: the same solve from different starting points, each within the backend's tolerance.
    CHECK(relative_gap(x, y) < (be.direct() ? 1e-12 : be.agree));
    for (Index c = 0; c < 2; ++c) {
      const Eigen::VectorXd ref = dense_reference(f.A, f.w, b.col(c), pinned, pins.col(c), f.C, d.col(c));
      CHECK(relative_gap(x.col(c), ref) < be.agree);
    }
  }
  CHECK(in_basis.report().factorizations == 1);
  CHECK(in_basis.report().basis_columns == (be.direct() ? 5 : 0));
  CHECK_THROWS_AS(expanded.solve_in_basis(f.b, Eigen::VectorXd::Zero(5), f.d), std::invalid_argument);
  // A basis whose rows do not match the pinned unknowns is refused.
  in_basis.set_pin_basis(SparseMatrix(B.topRows(4)));
  CHECK_THROWS_AS(in_basis.precompute(), std::invalid_argument);
}

TEST_CASE("a shared analysis is adopted for the same pattern and refused for another") {
  const Backend be = backend_under_test();
  CAPTURE(be.name);
  Fixture f;
  ConstrainedLeastSquares first(be.options);
  first.set_objective(f.A, f.w);
  first.set_pinned(f.pinned);
  first.analyze();

  // Same A (same pattern), other weights: the direct backend copies the symbolic analysis; the iterative one
  // cannot and analyses itself. Either way the answer is this solver's own.
  const Eigen::VectorXd w2 = random_weights(180, 78);
  ConstrainedLeastSquares same(be.options);
  same.set_objective(f.A, w2);
  same.set_pinned(f.pinned);
  same.share_analysis(&first);
  const Eigen::MatrixXd x_same = same.solve(f.b, f.pin_values, Eigen::MatrixXd(0, 1));
  CHECK(same.report().analyses == 1);
  CHECK(same.report().adopted_analyses == (be.direct() ? 1 : 0));
  CHECK(relative_gap(x_same, dense_reference(f.A, w2, f.b, f.pinned, f.pin_values, Eigen::MatrixXd(0, f.n), {})) < be.agree);

  // Another pattern with the same number of free unknowns: refused, analysed anew, right answer.
  const SparseMatrix A2 = random_objective(60, 5);
  const bool same_pattern = A2.nonZeros() == f.A.nonZeros() &&
                            std::equal(A2.innerIndexPtr(), A2.innerIndexPtr() + A2.nonZeros(), f.A.innerIndexPtr());
  REQUIRE_FALSE(same_pattern);
  ConstrainedLeastSquares other(be.options);
  other.set_objective(A2, f.w);
  other.set_pinned(f.pinned);
  other.share_analysis(&first);
  const Eigen::MatrixXd x_other = other.solve(f.b, f.pin_values, Eigen::MatrixXd(0, 1));
  CHECK(other.report().analyses == 1);
  CHECK(other.report().adopted_analyses == 0);
  CHECK(relative_gap(x_other, dense_reference(A2, f.w, f.b, f.pinned, f.pin_values, Eigen::MatrixXd(0, f.n), {})) < be.agree);

  // Other pins (another free set): refused as well.
  ConstrainedLeastSquares repinned(be.options);
  repinned.set_objective(f.A, f.w);
  repinned.set_pinned({0, 1});
  repinned.share_analysis(&first);
  const Eigen::MatrixXd x_repinned = repinned.solve(f.b, Eigen::Vector2d(1, 2), Eigen::MatrixXd(0, 1));
  CHECK(repinned.report().adopted_analyses == 0);
  CHECK(relative_gap(x_repinned, dense_reference(f.A, f.w, f.b, {0, 1}, Eigen::Vector2d(1, 2), Eigen::MatrixXd(0, f.n), {})) < be.agree);
}
