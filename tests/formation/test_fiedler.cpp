// The Fiedler vector that the automatic hierarchy bisects by: every solver (dense, shift-invert on a sparse
// factor, plain Lanczos) against a dense reference computed here, on graphs of both kinds the automatic choice
// tells apart, and on a disconnected subset.
#include "fiedler.h"

#include "adjacency.h"
#include "fixtures.h"

#include <Eigen/Eigenvalues>

#include <catch2/catch.hpp>

#include <numeric>

using namespace throng::formation;

namespace {

std::vector<std::string> names(int n) { return std::vector<std::string>(static_cast<std::size_t>(n), "individual"); }

// Delaunay graph of n points in a w × h rectangle at least 0.6 apart: long and thin, so λ2 (one wave along the
// length) is well below λ3 and the Fiedler vector is defined to a sign.
Adjacency strip(int n, double w, double h, std::uint64_t seed) {
  Eigen::MatrixXd p(n, 2);
  throng::Rng rng(seed);
  int placed = 0;
  while (placed < n) {
    const Eigen::RowVector2d q(rng.uniform(0.0, w), rng.uniform(0.0, h));
    bool ok = true;
    for (int i = 0; i < placed && ok; ++i) ok = (p.row(i).head<2>() - q).norm() >= 0.6;
    if (ok) p.row(placed++) = q;
  }
  return delaunay_adjacency(p, "strip", names(n));
}

Eigen::MatrixXd dense_laplacian(const Adjacency& g, const std::vector<int>& subset) {
  std::vector<int> local(static_cast<std::size_t>(g.count), -1);
  for (std::size_t i = 0; i < subset.size(); ++i) local[static_cast<std::size_t>(subset[i])] = static_cast<int>(i);
  const auto m = static_cast<Eigen::Index>(subset.size());
  Eigen::MatrixXd l = Eigen::MatrixXd::Zero(m, m);
  for (const auto& [edge, w] : g.weights) {
    const int a = local[static_cast<std::size_t>(edge.first)], b = local[static_cast<std::size_t>(edge.second)];
    if (a < 0 || b < 0) continue;
    l(a, b) -= w;
    l(b, a) -= w;
    l(a, a) += w;
    l(b, b) += w;
  }
  return l;
}

std::vector<int> everyone(int n) {
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  return all;
}

// f against the reference eigenpairs of L: unit, orthogonal to the constant vector, Rayleigh quotient λ2 (to the
// solvers' relative tolerance), and within the angle to v2 that its residual allows (Davis–Kahan:
// sin∠(f, v2) ≤ ‖Lf − ρf‖ / (λ3 − λ2)); the sign rule.
void check_fiedler(const Eigen::VectorXd& f, const Eigen::MatrixXd& l) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> reference(l);
  const Eigen::VectorXd& lambda = reference.eigenvalues();
  REQUIRE(lambda(2) - lambda(1) > 0.01 * lambda(1));  // the scene keeps λ2 simple
  const double scale = lambda(lambda.size() - 1);
  CHECK(f.norm() == Catch::Detail::Approx(1.0).margin(1e-12));
  CHECK(std::abs(f.sum()) <= 1e-10 * std::sqrt(static_cast<double>(f.size())));
  const double rho = f.dot(l * f);
  CHECK(rho == Catch::Detail::Approx(lambda(1)).epsilon(1e-6));
  const double residual = (l * f - rho * f).norm();
  CHECK(residual <= 1e-5 * scale);  // converged, not merely near
  const double cosine = std::min(1.0, std::abs(f.dot(reference.eigenvectors().col(1))));
  CHECK(std::sqrt(1.0 - cosine * cosine) <= residual / (lambda(2) - lambda(1)) + 1e-7);
  Eigen::Index largest = 0;
  f.cwiseAbs().maxCoeff(&largest);
  CHECK(f(largest) > 0);
}

}  // namespace

TEST_CASE("Fiedler vector: every solver finds λ2's eigenvector of a nearly planar graph (one keyframe)") {
  const Adjacency g = strip(600, 90.0, 8.0, 5);
  const std::vector<int> all = everyone(600);
  const Eigen::MatrixXd l = dense_laplacian(g, all);
  for (FiedlerSolver solver : {FiedlerSolver::automatic, FiedlerSolver::dense, FiedlerSolver::shift_invert, FiedlerSolver::lanczos}) {
    INFO("solver " << static_cast<int>(solver));
    check_fiedler(fiedler_vector(g, all, solver), l);
  }
}

TEST_CASE("Fiedler vector: every solver finds λ2's eigenvector of a graph summed over unrelated keyframes") {
  // Two unrelated scatters of the same individuals: an expander, whose sparse factor is nearly dense.
  Adjacency g = strip(600, 90.0, 8.0, 5);
  const Adjacency other = strip(600, 90.0, 8.0, 6);
  for (const auto& [edge, w] : other.weights) g.weights[edge] += w;
  const std::vector<int> all = everyone(600);
  const Eigen::MatrixXd l = dense_laplacian(g, all);
  for (FiedlerSolver solver : {FiedlerSolver::automatic, FiedlerSolver::dense, FiedlerSolver::shift_invert, FiedlerSolver::lanczos}) {
    INFO("solver " << static_cast<int>(solver));
    check_fiedler(fiedler_vector(g, all, solver), l);
  }
}

TEST_CASE("Fiedler vector of a subset: only the induced edges count, and a disconnected subset is split by component") {
  // Two strips side by side joined by a bridge of individuals; the subset leaves the bridge out.
  const Adjacency left = strip(450, 40.0, 8.0, 7);
  Adjacency g;
  g.count = 1000;
  for (const auto& [edge, w] : left.weights) {
    g.weights[edge] = w;                                       // individuals 0..449
    g.weights[{edge.first + 550, edge.second + 550}] = w;      // individuals 550..999, the same shape
  }
  for (int b = 450; b < 550; ++b) {                            // the bridge: a path 449 - 450 - ... - 549 - 550
    g.weights[{b - 1, b}] = 1.0;
    g.weights[{b, b + 1}] = 1.0;
  }
  std::vector<int> subset;
  for (int i = 0; i < 1000; ++i)
    if (i < 450 || i >= 550) subset.push_back(i);
  for (FiedlerSolver solver : {FiedlerSolver::automatic, FiedlerSolver::dense, FiedlerSolver::shift_invert, FiedlerSolver::lanczos}) {
    INFO("solver " << static_cast<int>(solver));
    const Eigen::VectorXd f = fiedler_vector(g, subset, solver);
    REQUIRE(f.size() == 900);
    // λ2 = 0: constant on each component, ±1/√900, opposite signs, the first individual's positive.
    const double level = 1.0 / std::sqrt(900.0);
    CHECK((f.head(450).array() - f(0)).abs().maxCoeff() <= 1e-6 * level);
    CHECK((f.tail(450).array() - f(899)).abs().maxCoeff() <= 1e-6 * level);
    CHECK(std::abs(f(0)) == Catch::Detail::Approx(level).epsilon(1e-6));
    CHECK(f(0) > 0);
    CHECK(f(899) < 0);
  }
  // With the bridge the subset is connected: λ2 is small but not 0, and its vector still separates the strips.
  const Eigen::VectorXd f = fiedler_vector(g, everyone(1000));
  CHECK(f.head(450).maxCoeff() * f.tail(450).minCoeff() < 0);
  check_fiedler(f, dense_laplacian(g, everyone(1000)));
}
