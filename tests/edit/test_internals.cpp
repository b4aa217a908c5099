// The edit layer's private building blocks: the triangle fit of step 2 and the output spline.
#include "resample.h"
#include "systems.h"

#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <Eigen/Geometry>

using namespace throng;
using namespace throng::edit;
using Triangle = Eigen::Matrix<double, 3, 2>;

namespace {

Triangle random_triangle(Rng& rng) {
  Triangle t;
  for (int k = 0; k < 3; ++k) t.row(k) << rng.uniform(-5, 5), rng.uniform(-5, 5);
  return t;
}

// Igarashi et al. 2005, as written: the least-squares similar copy of `from` (q ≈ [a −b; b a] p + t), then
// scaled about its centroid back to the size of `from`.
Triangle igarashi_fit(const Triangle& from, const Triangle& to) {
  Eigen::Matrix<double, 6, 4> M;
  Eigen::Matrix<double, 6, 1> rhs;
  for (int k = 0; k < 3; ++k) {
    M.row(2 * k) << from(k, 0), -from(k, 1), 1, 0;
    M.row(2 * k + 1) << from(k, 1), from(k, 0), 0, 1;
    rhs.segment<2>(2 * k) = to.row(k).transpose();
  }
  const Eigen::Vector4d s = M.colPivHouseholderQr().solve(rhs);
  Triangle fitted;
  for (int k = 0; k < 3; ++k) fitted.row(k) = (M.middleRows<2>(2 * k) * s).transpose();
  const Eigen::RowVector2d centre = fitted.colwise().mean();
  const double scale = std::hypot(s[0], s[1]);
  for (int k = 0; k < 3; ++k) fitted.row(k) = centre + (fitted.row(k) - centre) / scale;
  return fitted;
}

}  // namespace

TEST_CASE("the rigid fit recovers a rotation and translation, and equals Igarashi's fit scaled back") {
  Rng rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Triangle from = random_triangle(rng);
    const Eigen::Rotation2Dd turn(rng.uniform(-3, 3));
    const Eigen::RowVector2d shift(rng.uniform(-9, 9), rng.uniform(-9, 9));
    Triangle moved;
    for (int k = 0; k < 3; ++k) moved.row(k) = (turn * from.row(k).transpose()).transpose() + shift;
    CHECK((fit_without_scale(from, moved) - moved).cwiseAbs().maxCoeff() < 1e-12);

    // A deformed (scaled and sheared) target: both fits agree; the fit keeps the original edge lengths.
    const Triangle to = 1.7 * moved + 0.3 * random_triangle(rng);
    const Triangle ours = fit_without_scale(from, to);
    CHECK((ours - igarashi_fit(from, to)).cwiseAbs().maxCoeff() < 1e-10);
    for (int k = 0; k < 3; ++k) {
      CHECK_THAT((ours.row(k) - ours.row((k + 1) % 3)).norm(),
                 Catch::Matchers::WithinRel((from.row(k) - from.row((k + 1) % 3)).norm(), 1e-12));
    }
  }
}

TEST_CASE("the natural cubic spline hits its knots, reproduces lines and is smooth") {
  const std::vector<double> knots{0.0, 0.4, 1.0, 1.3, 2.0, 2.2};
  Eigen::MatrixXd y(6, 2);
  y << 0, 1, 2, -1, 1, 0, 3, 2, -1, 1, 0, 0;
  std::vector<double> at;
  for (double t = 0; t <= 2.2; t += 0.01) at.push_back(t);
  for (double t : knots) at.push_back(t);
  std::sort(at.begin(), at.end());
  const Eigen::MatrixXd s = natural_cubic_spline(knots, y, at);
  for (std::size_t k = 0; k < knots.size(); ++k) {
    const auto p = static_cast<Eigen::Index>(std::lower_bound(at.begin(), at.end(), knots[k]) - at.begin());
    CHECK(s.row(p) == y.row(static_cast<Eigen::Index>(k)));
  }
  // Lines stay lines.
  Eigen::MatrixXd line(6, 1);
  for (int k = 0; k < 6; ++k) line(k) = 3.0 - 2.0 * knots[static_cast<std::size_t>(k)];
  const Eigen::MatrixXd l = natural_cubic_spline(knots, line, at);
  for (std::size_t p = 0; p < at.size(); ++p) CHECK_THAT(l(static_cast<Eigen::Index>(p)), Catch::Matchers::WithinAbs(3.0 - 2.0 * at[p], 1e-12));
  // First and second derivatives continuous at interior knots: one-sided differences with step h agree to
  // O(h · |y'''|) (≈ 1e-4 here), while a kink (a piecewise linear interpolant) would differ by O(1).
  const double h = 1e-5;
  for (std::size_t k = 1; k + 1 < knots.size(); ++k) {
    const double t = knots[k];
    const Eigen::MatrixXd v = natural_cubic_spline(knots, y, {t - 2 * h, t - h, t, t + h, t + 2 * h});
    const Eigen::RowVectorXd left = (v.row(2) - v.row(1)) / h, right = (v.row(3) - v.row(2)) / h;
    const Eigen::RowVectorXd left2 = (v.row(2) - 2 * v.row(1) + v.row(0)) / (h * h);
    const Eigen::RowVectorXd right2 = (v.row(4) - 2 * v.row(3) + v.row(2)) / (h * h);
    CHECK((left - right).cwiseAbs().maxCoeff() < 1e-3);
    CHECK((left2 - right2).cwiseAbs().maxCoeff() < 0.5);
  }
}
