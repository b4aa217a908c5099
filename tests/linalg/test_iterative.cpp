// The iterative building blocks: complex Hermitian kernels, the two-level preconditioner, block conjugate
// gradients and the solution history. What a wrong sign, a wrong band or a wrong reduction order would break.
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>
#include <throng/linalg/conjugate_gradients.h>
#include <throng/linalg/solution_history.h>
#include <throng/linalg/spd_solver.h>
#include <throng/linalg/two_level.h>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cstring>

using namespace throng;
using namespace throng::linalg;

namespace {

// A chain-structured complex Hermitian positive definite system like the editor's: `chains` chains of
// `length` unknowns, coupled strongly along each chain (4th order: second differences squared) and weakly to
// the next chain (a graph Laplacian across chains), with complex weights, plus a small diagonal so that it is
// definite. Unknown i of chain c is c·length + i.
ComplexSparse chain_system(int chains, int length, std::uint64_t seed) {
  Rng rng(seed);
  const int n = chains * length;
  Eigen::MatrixXcd dense = Eigen::MatrixXcd::Zero(n, n);
  auto add_row = [&](const std::vector<std::pair<int, Complex>>& row, double weight) {
    for (const auto& [p, a] : row)
      for (const auto& [q, b] : row) dense(p, q) += weight * std::conj(a) * b;
  };
  for (int c = 0; c < chains; ++c) {
    for (int i = 1; i + 1 < length; ++i) {  // second differences along the chain, a complex middle weight
      const Complex mid(-2.0 + rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1));
      add_row({{c * length + i - 1, 1.0}, {c * length + i, mid}, {c * length + i + 1, 1.0}}, 4.0);
    }
    for (int i = 0; i < length; ++i) {
      if (c + 1 < chains) add_row({{c * length + i, 1.0}, {(c + 1) * length + i, Complex(-1.0, rng.uniform(-0.2, 0.2))}}, 1.0);
      add_row({{c * length + i, 1.0}}, 1e-3);
    }
  }
  ComplexSparse A = dense.sparseView();
  A.makeCompressed();
  return A;
}

std::vector<std::vector<int>> chain_groups(int chains, int length) {
  std::vector<std::vector<int>> groups(static_cast<std::size_t>(chains));
  for (int c = 0; c < chains; ++c)
    for (int i = 0; i < length; ++i) groups[static_cast<std::size_t>(c)].push_back(c * length + i);
  return groups;
}

// Coarse functions: per block of 4 chains, constant and linear in the chain index, times hats every 5 unknowns.
ComplexSparse coarse_basis(int chains, int length) {
  std::vector<Eigen::Triplet<Complex>> t;
  const int nodes = (length - 1) / 5 + 1;
  for (int c = 0; c < chains; ++c) {
    for (int i = 0; i < length; ++i) {
      const int node = std::min(i / 5, nodes - 1);
      const double w1 = std::min(1.0, static_cast<double>(i - node * 5) / 5.0);
      for (int side = 0; side < 2; ++side) {
        const int k = node + side;
        const double w = side ? w1 : 1.0 - w1;
        if (w <= 0 || k >= nodes) continue;
        const int block = c / 4;
        t.emplace_back(c * length + i, (block * nodes + k) * 2, w);
        t.emplace_back(c * length + i, (block * nodes + k) * 2 + 1, w * (static_cast<double>(c % 4) - 1.5));
      }
    }
  }
  ComplexSparse U((chains) * length, ((chains + 3) / 4) * nodes * 2);
  U.setFromTriplets(t.begin(), t.end());
  U.makeCompressed();
  return U;
}

ComplexBlock random_block(Eigen::Index rows, Eigen::Index cols, std::uint64_t seed) {
  Rng rng(seed);
  ComplexBlock b(rows, cols);
  for (Eigen::Index i = 0; i < rows; ++i)
    for (Eigen::Index c = 0; c < cols; ++c) b(i, c) = Complex(rng.uniform(-1, 1), rng.uniform(-1, 1));
  return b;
}

bool same_bits(const ComplexBlock& a, const ComplexBlock& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && std::memcmp(a.data(), b.data(), sizeof(Complex) * static_cast<std::size_t>(a.size())) == 0;
}

double max_abs(const ComplexBlock& a) { return a.size() == 0 ? 0.0 : a.cwiseAbs().maxCoeff(); }

}  // namespace

TEST_CASE("the complex kernels: A x, b − A x and column dots agree with dense arithmetic") {
  const ComplexSparse A = chain_system(6, 20, 3);
  const Eigen::MatrixXcd dense(A);
  const ComplexBlock X = random_block(A.cols(), 3, 4), B = random_block(A.rows(), 3, 5);
  ComplexBlock Y, R;
  multiply(A, X, Y);
  residual(A, X, B, R);
  const Eigen::MatrixXcd expected = dense * Eigen::MatrixXcd(X);
  // Sums of ~10 products of O(10) numbers: rounding ~1e-14.
  CHECK((Eigen::MatrixXcd(Y) - expected).cwiseAbs().maxCoeff() < 1e-12);
  CHECK((Eigen::MatrixXcd(R) - (Eigen::MatrixXcd(B) - expected)).cwiseAbs().maxCoeff() < 1e-12);
  const auto dots = column_dots(X, B);
  for (Eigen::Index c = 0; c < 3; ++c) CHECK(std::abs(dots[static_cast<std::size_t>(c)] - Eigen::MatrixXcd(X).col(c).dot(Eigen::MatrixXcd(B).col(c))) < 1e-12);
  // Hermitian: xᴴ A x is real.
  ComplexBlock AX;
  multiply(A, X, AX);
  CHECK(std::abs(column_dots(X, AX)[0].imag()) < 1e-10 * std::abs(column_dots(X, AX)[0].real()));
}

TEST_CASE("two-level conjugate gradients solve to the stated tolerance, every column, from any start") {
  const int chains = 24, length = 40;
  const ComplexSparse A = chain_system(chains, length, 7);
  TwoLevelPreconditioner M(A, chain_groups(chains, length), coarse_basis(chains, length));
  CHECK(M.info().coarse_size > 0);
  CHECK(M.info().damping > 0);
  CHECK(M.info().damping <= 1);
  const ComplexBlock B = random_block(A.rows(), 3, 8);
  const Eigen::MatrixXcd exact = Eigen::MatrixXcd(A).ldlt().solve(Eigen::MatrixXcd(B));
  for (double tolerance : {1e-4, 1e-8}) {
    CAPTURE(tolerance);
    ComplexBlock X = ComplexBlock::Zero(A.rows(), 3);
    const CgReport report = conjugate_gradients(A, M, B, X, {tolerance}, 500);
    CHECK(report.iterations > 1);
    for (double estimate : report.error_estimate) CHECK(estimate <= tolerance);
    // The contract: the estimate is what is left, so the error is within the tolerance.
    CHECK((Eigen::MatrixXcd(X) - exact).cwiseAbs().maxCoeff() <= tolerance);
  }
  // Started at the solution: no step.
  ComplexBlock X = exact;
  const ComplexBlock start = X;
  const CgReport at_solution = conjugate_gradients(A, M, B, X, {1e-6}, 500);
  CHECK(at_solution.iterations <= 1);
  CHECK((Eigen::MatrixXcd(X) - exact).cwiseAbs().maxCoeff() <= 1e-6);
}

TEST_CASE("the multiplicative cycle needs fewer iterations than the additive one and both converge") {
  const int chains = 24, length = 40;
  const ComplexSparse A = chain_system(chains, length, 9);
  const ComplexBlock B = random_block(A.rows(), 1, 10);
  int iterations[2] = {0, 0};
  for (TwoLevelCycle cycle : {TwoLevelCycle::additive, TwoLevelCycle::multiplicative}) {
    TwoLevelOptions o;
    o.cycle = cycle;
    TwoLevelPreconditioner M(A, chain_groups(chains, length), coarse_basis(chains, length), o);
    ComplexBlock X = ComplexBlock::Zero(A.rows(), 1);
    iterations[cycle == TwoLevelCycle::multiplicative] = conjugate_gradients(A, M, B, X, {1e-8}, 500).iterations;
  }
  CAPTURE(iterations[0], iterations[1]);
  CHECK(iterations[1] < iterations[0]);
  // Without a coarse space the smoother alone is far slower: the coarse level does the work across chains.
  TwoLevelPreconditioner smoother_only(A, chain_groups(chains, length), ComplexSparse(A.rows(), 0));
  ComplexBlock X = ComplexBlock::Zero(A.rows(), 1);
  const int alone = conjugate_gradients(A, smoother_only, B, X, {1e-8}, 2000).iterations;
  CAPTURE(alone);
  CHECK(alone > iterations[0]);
}

TEST_CASE("conjugate gradients give the same bits for any thread count, and a block equals its columns") {
  const int chains = 40, length = 120;  // 4,800 unknowns: several row blocks for the parallel kernels
  const ComplexSparse A = chain_system(chains, length, 11);
  const ComplexBlock B = random_block(A.rows(), 2, 12);
  ComplexBlock results[2];
  for (std::size_t threads : {std::size_t{1}, std::size_t{2}}) {
    const ThreadLimit limit(threads);
    TwoLevelPreconditioner M(A, chain_groups(chains, length), coarse_basis(chains, length));
    results[threads - 1] = ComplexBlock::Zero(A.rows(), 2);
    (void)conjugate_gradients(A, M, B, results[threads - 1], {1e-7}, 500);
  }
  CHECK(same_bits(results[0], results[1]));
  // Column by column: each column runs its own CG; the coarse solves of a block may round differently.
  TwoLevelPreconditioner M(A, chain_groups(chains, length), coarse_basis(chains, length));
  for (Eigen::Index c = 0; c < 2; ++c) {
    ComplexBlock x = ComplexBlock::Zero(A.rows(), 1);
    const ComplexBlock b = B.col(c);
    (void)conjugate_gradients(A, M, b, x, {1e-7}, 500);
    CHECK((Eigen::MatrixXcd(x).col(0) - Eigen::MatrixXcd(results[0]).col(c)).cwiseAbs().maxCoeff() < 2e-7);
  }
}

TEST_CASE("a solution history starts the next solve at the Galerkin solution of its span") {
  const int chains = 12, length = 30;
  const ComplexSparse A = chain_system(chains, length, 13);
  const Eigen::MatrixXcd dense(A);
  const auto solve = [&](const ComplexBlock& b) { return ComplexBlock(dense.ldlt().solve(Eigen::MatrixXcd(b))); };
  SolutionHistory history(3);
  const ComplexBlock b1 = random_block(A.rows(), 1, 14), b2 = random_block(A.rows(), 1, 15);
  ComplexBlock x, r;
  history.start(b1, x, r);
  CHECK(max_abs(x) == 0);  // nothing kept: zero start, residual b
  CHECK(same_bits(r, b1));
  const ComplexBlock x1 = solve(b1), x2 = solve(b2);
  ComplexBlock Ax1, Ax2;
  multiply(A, x1, Ax1);
  multiply(A, x2, Ax2);
  history.add(x1, Ax1);
  history.add(x2, Ax2);
  CHECK(history.size() == 2);
  // A right-hand side in the span is solved exactly by the start, and the residual is b − A x.
  const ComplexBlock b = Complex(0.3, -0.2) * b1 + Complex(-1.1, 0.4) * b2;
  history.start(b, x, r);
  const ComplexBlock exact = solve(b);
  CHECK(max_abs(ComplexBlock(x - exact)) < 1e-9 * max_abs(exact));
  ComplexBlock check;
  residual(A, x, b, check);
  CHECK(max_abs(ComplexBlock(r - check)) < 1e-9 * max_abs(b));
  // A right-hand side outside it: the start is the energy-norm best in the span, so its energy error is below
  // that of either kept solution scaled optimally (here: below the zero start's).
  const ComplexBlock b3 = random_block(A.rows(), 1, 16);
  history.start(b3, x, r);
  const ComplexBlock e = x - solve(b3), e0 = solve(b3);
  ComplexBlock Ae, Ae0;
  multiply(A, e, Ae);
  multiply(A, e0, Ae0);
  CHECK(column_dots(e, Ae)[0].real() <= column_dots(e0, Ae0)[0].real());
  // A solution already in the span adds nothing; the capacity bounds what is kept.
  history.add(x1, Ax1);
  CHECK(history.size() == 2);
  const ComplexBlock x3 = solve(b3);
  ComplexBlock Ax3;
  multiply(A, x3, Ax3);
  history.add(x3, Ax3);
  const ComplexBlock x4 = solve(random_block(A.rows(), 1, 17));
  ComplexBlock Ax4;
  multiply(A, x4, Ax4);
  history.add(x4, Ax4);
  CHECK(history.size() == 3);
}

TEST_CASE("a guess joins the history's span in the Galerkin start") {
  const int chains = 12, length = 30;
  const ComplexSparse A = chain_system(chains, length, 21);
  const Eigen::MatrixXcd dense(A);
  const auto solve = [&](const ComplexBlock& b) { return ComplexBlock(dense.ldlt().solve(Eigen::MatrixXcd(b))); };
  const auto product = [&](const ComplexBlock& x) {
    ComplexBlock y;
    multiply(A, x, y);
    return y;
  };
  const auto energy = [&](const ComplexBlock& e) { return column_dots(e, product(e))[0].real(); };
  const ComplexBlock b1 = random_block(A.rows(), 1, 22), b2 = random_block(A.rows(), 1, 23), b3 = random_block(A.rows(), 1, 24);
  const ComplexBlock x1 = solve(b1), x2 = solve(b2), x3 = solve(b3);
  SolutionHistory history(3);
  ComplexBlock x, r, check;
  // Nothing kept: the start is the guess scaled to the Galerkin optimum, exact when b is A times a multiple of it.
  const ComplexBlock scaled = Complex(0.7, 0.4) * b3;
  history.start(scaled, x3, product(x3), x, r);
  CHECK(max_abs(ComplexBlock(x - Complex(0.7, 0.4) * x3)) < 1e-9 * max_abs(x3));
  history.add(x1, product(x1));
  history.add(x2, product(x2));
  // b in span{A x1, A x2, A g}: the start with g solves it, the start without does not; r is b − A x.
  const ComplexBlock b = Complex(0.3, -0.2) * b1 + Complex(-1.1, 0.4) * b2 + Complex(0.5, 0.9) * b3;
  const ComplexBlock exact = solve(b);
  history.start(b, x3, product(x3), x, r);
  CHECK(max_abs(ComplexBlock(x - exact)) < 1e-9 * max_abs(exact));
  residual(A, x, b, check);
  CHECK(max_abs(ComplexBlock(r - check)) < 1e-9 * max_abs(b));
  ComplexBlock plain, plain_r;
  history.start(b, plain, plain_r);
  CHECK(max_abs(ComplexBlock(plain - exact)) > 1e-3 * max_abs(exact));
  // Any b: the larger span's start is at least as close in energy as the plain one, and as the guess alone.
  const ComplexBlock b4 = random_block(A.rows(), 1, 25), g = random_block(A.rows(), 1, 26);
  const ComplexBlock exact4 = solve(b4);
  history.start(b4, g, product(g), x, r);
  history.start(b4, plain, plain_r);
  const Complex best = column_dots(g, b4)[0] / column_dots(g, product(g))[0];
  CHECK(energy(ComplexBlock(x - exact4)) <= energy(ComplexBlock(plain - exact4)) * (1 + 1e-12));
  CHECK(energy(ComplexBlock(x - exact4)) <= energy(ComplexBlock(best * g - exact4)) * (1 + 1e-12));
  residual(A, x, b4, check);
  CHECK(max_abs(ComplexBlock(r - check)) < 1e-9 * max_abs(b4));
  // A guess in the span adds nothing: the start is the plain one.
  const ComplexBlock in_span = Complex(2.0, -1.0) * x1 + Complex(0.5, 0.0) * x2;
  history.start(b4, in_span, product(in_span), x, r);
  CHECK(max_abs(ComplexBlock(x - plain)) < 1e-9 * max_abs(plain));
  CHECK_THROWS_AS(history.start(b4, ComplexBlock(g.topRows(5)), product(g), x, r), std::invalid_argument);
}

TEST_CASE("an indefinite matrix, bad groups and a solve that cannot converge are errors") {
  const int chains = 6, length = 10;
  ComplexSparse A = chain_system(chains, length, 18);
  // Bad groups: an unknown missing, one twice.
  auto groups = chain_groups(chains, length);
  groups.back().pop_back();
  CHECK_THROWS_AS(TwoLevelPreconditioner(A, groups, coarse_basis(chains, length)), std::invalid_argument);
  groups = chain_groups(chains, length);
  groups[0].push_back(groups[1][0]);
  CHECK_THROWS_AS(TwoLevelPreconditioner(A, groups, coarse_basis(chains, length)), std::invalid_argument);
  CHECK_THROWS_AS(TwoLevelPreconditioner(A, chain_groups(chains, length), ComplexSparse(3, 2)), std::invalid_argument);
  // Not positive definite: a negative diagonal entry breaks a chain's band factor.
  ComplexSparse bad = A;
  bad.coeffRef(5, 5) = -1.0;
  CHECK_THROWS_AS(TwoLevelPreconditioner(bad, chain_groups(chains, length), coarse_basis(chains, length)), SingularMatrixError);
  // An iteration cap it cannot meet.
  TwoLevelPreconditioner M(A, chain_groups(chains, length), ComplexSparse(A.rows(), 0));
  const ComplexBlock B = random_block(A.rows(), 1, 19);
  ComplexBlock X = ComplexBlock::Zero(A.rows(), 1);
  try {
    (void)conjugate_gradients(A, M, B, X, {1e-14}, 2);
    FAIL("no error for an unreachable tolerance");
  } catch (const NumericalError& e) {
    CHECK_THAT(e.what(), Catch::Matchers::Contains("did not converge"));
  }
}
