// Splines: they pass through their samples, are C2 (not-a-knot also C3 at the second and second-to-last knot),
// reproduce cubics, and the tridiagonal solver agrees with a dense solve.
#include <throng/core/errors.h>
#include <throng/core/random.h>
#include <throng/timewarp/spline.h>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <cmath>
#include <string>

using namespace throng;
using namespace throng::timewarp;

namespace {

// Strictly increasing knots with intervals between 0.05 and 2 (a 40× spread, like a strongly warped clip).
std::vector<double> random_knots(std::size_t n, Rng& rng) {
  std::vector<double> t{rng.uniform(-1, 1)};
  while (t.size() < n) t.push_back(t.back() + 0.05 + 1.95 * rng.uniform() * rng.uniform());
  return t;
}

RowMatrix random_values(std::size_t n, Eigen::Index columns, Rng& rng) {
  RowMatrix y(static_cast<Eigen::Index>(n), columns);
  for (Eigen::Index i = 0; i < y.size(); ++i) y.data()[i] = rng.uniform(-5, 5);
  return y;
}

double at(const CubicSpline& s, double t, int derivative, Eigen::Index column) {
  Eigen::RowVectorXd out(s.columns());
  s.evaluate(t, derivative, out);
  return out[column];
}

}  // namespace

TEST_CASE("splines pass through their samples with continuous first and second derivatives") {
  Rng rng(11);
  for (SplineEnd end : {SplineEnd::not_a_knot, SplineEnd::natural}) {
    for (std::size_t n : {2u, 3u, 4u, 7u, 40u}) {
      const std::string name = std::string(end == SplineEnd::natural ? "natural" : "not-a-knot") + ", " + std::to_string(n) + " knots";
      INFO(name);
      const std::vector<double> knots = random_knots(n, rng);
      const RowMatrix y = random_values(n, 3, rng);
      const CubicSpline s(knots, y, end);
      // Through the samples, exactly.
      const RowMatrix at_knots = s.evaluate(knots);
      CHECK(at_knots == y);
      // Continuity at interior knots: left and right limits (ε = 1e-9 of the shorter neighbouring interval)
      // differ only by the smooth change over 2ε. A jump would be of the size of the values over h or h².
      double scale2 = 0;
      for (double k : knots) scale2 = std::max(scale2, s.evaluate(std::span(&k, 1), 2).cwiseAbs().maxCoeff());
      for (std::size_t k = 1; k + 1 < n; ++k) {
        const double eps = 1e-9 * std::min(knots[k] - knots[k - 1], knots[k + 1] - knots[k]);
        for (Eigen::Index c = 0; c < 3; ++c) {
          const double slope_scale = std::abs(s.slopes()(static_cast<Eigen::Index>(k), c)) + scale2;
          CHECK(std::abs(at(s, knots[k] + eps, 0, c) - at(s, knots[k] - eps, 0, c)) <= 1e-7 * (1 + slope_scale));
          CHECK(std::abs(at(s, knots[k] + eps, 1, c) - at(s, knots[k] - eps, 1, c)) <= 1e-6 * (1 + scale2));
          CHECK(std::abs(at(s, knots[k] + eps, 2, c) - at(s, knots[k] - eps, 2, c)) <= 1e-6 * (1 + scale2));
        }
      }
      // End conditions.
      for (Eigen::Index c = 0; c < 3; ++c) {
        if (end == SplineEnd::natural && n > 2) {
          CHECK(std::abs(at(s, knots.front(), 2, c)) <= 1e-9 * (1 + scale2));
          CHECK(std::abs(at(s, knots.back(), 2, c)) <= 1e-9 * (1 + scale2));
        }
        if (end == SplineEnd::not_a_knot && n >= 4) {
          // The third derivative (constant per interval) agrees across the second and second-to-last knots.
          auto third = [&](std::size_t i) {
            const double a = knots[i], b = knots[i + 1];
            return (at(s, b, 2, c) - at(s, a, 2, c)) / (b - a);  // f'' is linear on [a, b]
          };
          const double s3 = scale2 / (knots[1] - knots[0]) + scale2 / (knots[n - 1] - knots[n - 2]);
          CHECK(std::abs(third(0) - third(1)) <= 1e-6 * (1 + s3));
          CHECK(std::abs(third(n - 2) - third(n - 3)) <= 1e-6 * (1 + s3));
        }
      }
    }
  }
}

TEST_CASE("not-a-knot splines reproduce cubic polynomials, and two knots give the straight line") {
  Rng rng(3);
  const std::vector<double> knots = random_knots(9, rng);
  auto cubic = [](double t) { return 0.5 - 1.5 * t + 0.25 * t * t + 0.125 * t * t * t; };
  auto cubic1 = [](double t) { return -1.5 + 0.5 * t + 0.375 * t * t; };
  RowMatrix y(9, 1);
  for (int i = 0; i < 9; ++i) y(i, 0) = cubic(knots[static_cast<std::size_t>(i)]);
  const CubicSpline s(knots, y);
  for (double t = knots.front(); t <= knots.back(); t += 0.0371) {
    const double scale = 1 + std::abs(cubic(t));
    CHECK(std::abs(at(s, t, 0, 0) - cubic(t)) <= 1e-11 * scale * 100);
    CHECK(std::abs(at(s, t, 1, 0) - cubic1(t)) <= 1e-9 * scale * 100);
  }
  // Two knots: the line, for both end conditions.
  for (SplineEnd end : {SplineEnd::not_a_knot, SplineEnd::natural}) {
    const CubicSpline line({0.0, 2.0}, (RowMatrix(2, 1) << 1.0, 5.0).finished(), end);
    CHECK(at(line, 0.5, 0, 0) == Approx(2.0).epsilon(1e-14));
    CHECK(at(line, 1.7, 1, 0) == Approx(2.0).epsilon(1e-14));
    CHECK(at(line, 1.7, 2, 0) == Approx(0.0).margin(1e-14));
  }
}

TEST_CASE("the tridiagonal solver agrees with a dense LU solve, also where pivoting is needed") {
  Rng rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const std::size_t n = 1 + static_cast<std::size_t>(rng.below(12));
    std::vector<double> lower(n - 1), diagonal(n), upper(n - 1);
    Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      // Small diagonals make row swaps necessary.
      diagonal[i] = trial % 2 ? rng.uniform(-0.1, 0.1) : rng.uniform(2, 4);
      dense(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)) = diagonal[i];
      if (i + 1 < n) {
        lower[i] = rng.uniform(-1, 1);
        upper[i] = rng.uniform(-1, 1);
        dense(static_cast<Eigen::Index>(i + 1), static_cast<Eigen::Index>(i)) = lower[i];
        dense(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i + 1)) = upper[i];
      }
    }
    RowMatrix rhs = random_values(n, 2, rng);
    const Eigen::MatrixXd expected = dense.fullPivLu().solve(Eigen::MatrixXd(rhs));
    solve_tridiagonal(lower, diagonal, upper, rhs);
    const double cond = dense.norm() * dense.inverse().norm();
    INFO("n = " << n << ", condition ≈ " << cond);
    CHECK((Eigen::MatrixXd(rhs) - expected).cwiseAbs().maxCoeff() <= 1e-13 * cond * (1 + expected.cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("bad knots are input errors naming the knot") {
  CHECK_THROWS_AS(CubicSpline({0.0}, RowMatrix::Zero(1, 1)), InputError);
  CHECK_THROWS_WITH(CubicSpline({0.0, 1.0, 1.0}, RowMatrix::Zero(3, 1)), Catch::Contains("not strictly increasing at knot 2"));
  CHECK_THROWS_WITH(CubicSpline({0.0, 1.0}, RowMatrix::Zero(3, 1)), Catch::Contains("3 rows for 2 knots"));
  RowMatrix rhs = RowMatrix::Ones(2, 1);
  CHECK_THROWS_AS(solve_tridiagonal({0.0}, {0.0, 0.0}, {0.0}, rhs), NumericalError);
}
