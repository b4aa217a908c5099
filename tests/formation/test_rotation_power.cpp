// Real powers of orthogonal matrices (rotation_power.h): the exactness every keyframe hit relies on.
#include "rotation_power.h"

#include "fixtures.h"

#include <throng/core/errors.h>
#include <throng/core/random.h>

#include <Eigen/Dense>

#include <catch2/catch.hpp>

#include <algorithm>
#include <numbers>

using throng::formation::RotationPower;
using throng::test::eps;

namespace {

Eigen::MatrixXd random_orthogonal(int n, std::uint64_t seed) {
  throng::Rng rng(seed);
  Eigen::MatrixXd a(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a(i, j) = rng.normal();
  Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ();
  if (q.determinant() < 0) q.col(0) *= -1.0;
  return q;
}

// Q · blockdiag(rotations by `angles`, then `ones` (±1 entries)) · Qᵀ.
Eigen::MatrixXd with_spectrum(const std::vector<double>& angles, const std::vector<double>& ones, std::uint64_t seed) {
  const int n = static_cast<int>(2 * angles.size() + ones.size());
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t p = 0; p < angles.size(); ++p) {
    const auto i = static_cast<Eigen::Index>(2 * p);
    u(i, i) = u(i + 1, i + 1) = std::cos(angles[p]);
    u(i + 1, i) = std::sin(angles[p]);
    u(i, i + 1) = -std::sin(angles[p]);
  }
  for (std::size_t k = 0; k < ones.size(); ++k) {
    const auto i = static_cast<Eigen::Index>(2 * angles.size() + k);
    u(i, i) = ones[k];
  }
  const Eigen::MatrixXd q = random_orthogonal(n, seed);
  return q * u * q.transpose();
}

// The properties of an exact power, to a tolerance of a few hundred n·ε (rounding in O(n) sums of O(n) terms).
void check_powers(const Eigen::MatrixXd& g, const char* name) {
  INFO(name);
  const auto n = static_cast<double>(g.rows());
  const double tol = 200.0 * n * eps;
  const RotationPower r(g);
  const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(g.rows(), g.cols());
  CHECK((r.power(1.0) - g).cwiseAbs().maxCoeff() <= tol);
  CHECK((r.power(0.0) - identity).cwiseAbs().maxCoeff() <= tol);
  CHECK((r.power(-1.0) - g.transpose()).cwiseAbs().maxCoeff() <= tol);
  CHECK((r.power(0.5) * r.power(0.5) - g).cwiseAbs().maxCoeff() <= tol);
  CHECK((r.power(0.3) * r.power(0.7) - g).cwiseAbs().maxCoeff() <= tol);
  const Eigen::MatrixXd half = r.power(0.37);
  CHECK((half.transpose() * half - identity).cwiseAbs().maxCoeff() <= tol);
  if (!r.is_identity()) {
    CHECK((r.basis().transpose() * r.basis() - identity).cwiseAbs().maxCoeff() <= tol);
  }
  for (double a : r.angles()) {
    CHECK(a > 0.0);
    CHECK(a <= std::numbers::pi);
  }
}

}  // namespace

TEST_CASE("rotation powers are exact for random rotations of several sizes") {
  for (int n : {1, 2, 3, 7, 40, 161}) {
    INFO("n = " << n);
    check_powers(random_orthogonal(n, 100 + static_cast<std::uint64_t>(n)), "random");
  }
}

TEST_CASE("rotation powers recover the constructed angles, including repeated ones and π") {
  const std::vector<double> angles{0.3, 0.3, 0.3, 1.2, 2.5, 2.5, std::numbers::pi - 1e-9, 1e-9, 0.7};
  const Eigen::MatrixXd g = with_spectrum(angles, {1.0, 1.0, -1.0, -1.0, 1.0}, 7);
  check_powers(g, "repeated angles");
  const RotationPower r(g);
  std::vector<double> found = r.angles();
  std::sort(found.begin(), found.end());
  std::vector<double> expected = angles;
  expected.push_back(std::numbers::pi);  // the −1 pair
  std::sort(expected.begin(), expected.end());
  REQUIRE(found.size() == expected.size());
  for (std::size_t i = 0; i < found.size(); ++i) CHECK(found[i] == Catch::Detail::Approx(expected[i]).margin(1e-12));
}

TEST_CASE("near-identity rotations and the identity itself") {
  std::vector<double> small;
  for (int p = 0; p < 30; ++p) small.push_back(1e-7 * (1 + p % 4));  // many tiny, partly repeated angles
  check_powers(with_spectrum(small, {1.0, 1.0, 1.0}, 3), "near identity");
  const RotationPower id(Eigen::MatrixXd::Identity(50, 50));
  CHECK(id.is_identity());
  CHECK(id.power(0.4).isIdentity(0.0));
  check_powers(with_spectrum({}, {1, 1, 1, 1, -1, -1, -1, -1}, 9), "reflection pairs");
}

TEST_CASE("rotate() applies a different exponent to each group of columns") {
  const Eigen::MatrixXd g = random_orthogonal(12, 4);
  const RotationPower r(g);
  Eigen::MatrixXd c = Eigen::MatrixXd::Random(12, 6);  // three groups of two columns
  Eigen::MatrixXd w = r.basis().transpose() * c;
  r.rotate(w, {0.0, 0.25, 1.0}, 2);
  const Eigen::MatrixXd x = r.basis() * w;
  const double tol = 200.0 * 12 * eps;
  CHECK((x.middleCols(0, 2) - c.middleCols(0, 2)).cwiseAbs().maxCoeff() <= tol);
  CHECK((x.middleCols(2, 2) - r.power(0.25) * c.middleCols(2, 2)).cwiseAbs().maxCoeff() <= tol);
  CHECK((x.middleCols(4, 2) - g * c.middleCols(4, 2)).cwiseAbs().maxCoeff() <= tol);
}

TEST_CASE("a matrix with determinant -1 is refused") {
  Eigen::MatrixXd reflection = random_orthogonal(5, 2);
  reflection.col(0) *= -1.0;
  CHECK_THROWS_AS(RotationPower(reflection), throng::NumericalError);
}
