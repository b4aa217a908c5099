#include <throng/core/errors.h>
#include <throng/timewarp/spline.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace throng::timewarp {

void solve_tridiagonal(std::vector<double> lower, std::vector<double> diagonal, std::vector<double> upper, RowMatrix& rhs) {
  const std::size_t n = diagonal.size();
  if (n == 0) return;
  // LAPACK dgtsv: eliminate the sub-diagonal row by row, swapping rows when the sub-diagonal entry is larger
  // (the swap fills a second super-diagonal, kept in `lower`, which is no longer needed as such).
  std::vector<double> second(n, 0.0);  // second super-diagonal: entry (i, i + 2)
  auto singular = [&](std::size_t row) {
    throw NumericalError("tridiagonal system is singular at row " + std::to_string(row) + " of " + std::to_string(n));
  };
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (std::abs(diagonal[i]) >= std::abs(lower[i])) {
      if (diagonal[i] == 0.0) singular(i);
      const double factor = lower[i] / diagonal[i];
      diagonal[i + 1] -= factor * upper[i];
      rhs.row(static_cast<Eigen::Index>(i + 1)) -= factor * rhs.row(static_cast<Eigen::Index>(i));
    } else {
      const double factor = diagonal[i] / lower[i];
      diagonal[i] = lower[i];
      const double below = diagonal[i + 1];
      diagonal[i + 1] = upper[i] - factor * below;
      if (i + 2 < n) {
        second[i] = upper[i + 1];
        upper[i + 1] = -factor * second[i];
      }
      upper[i] = below;
      const auto r = static_cast<Eigen::Index>(i);
      // Row r becomes the old row r + 1; row r + 1 becomes old row r − factor × old row r + 1.
      rhs.row(r).swap(rhs.row(r + 1));
      rhs.row(r + 1) -= factor * rhs.row(r);
    }
  }
  if (diagonal[n - 1] == 0.0) singular(n - 1);
  // Back substitution with the upper triangle (diagonal, upper, second).
  for (std::size_t k = n; k-- > 0;) {
    const auto i = static_cast<Eigen::Index>(k);
    if (k + 1 < n) rhs.row(i) -= upper[k] * rhs.row(i + 1);
    if (k + 2 < n) rhs.row(i) -= second[k] * rhs.row(i + 2);
    rhs.row(i) /= diagonal[k];
  }
}

namespace {

void check_knots(const std::vector<double>& knots, const RowMatrix& values) {
  if (knots.size() < 2) throw InputError("a spline needs at least 2 knots, got " + std::to_string(knots.size()));
  if (static_cast<std::size_t>(values.rows()) != knots.size()) {
    throw InputError("a spline's values have " + std::to_string(values.rows()) + " rows for " +
                     std::to_string(knots.size()) + " knots");
  }
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) throw InputError("spline knot " + std::to_string(i) + " is not finite");
    if (i > 0 && !(knots[i] > knots[i - 1])) {
      throw InputError("spline knots are not strictly increasing at knot " + std::to_string(i) + " (" +
                       std::to_string(knots[i - 1]) + " then " + std::to_string(knots[i]) + ")");
    }
  }
  if (!values.allFinite()) throw InputError("a spline's values hold a NaN or infinite entry");
}

// Slopes making the Hermite pieces C2 (and satisfying the end conditions); see the header.
RowMatrix fit_slopes(const std::vector<double>& x, const RowMatrix& y, SplineEnd end) {
  const std::size_t n = x.size();
  const Eigen::Index columns = y.cols();
  std::vector<double> h(n - 1);
  RowMatrix delta(static_cast<Eigen::Index>(n - 1), columns);  // secant slopes δ_i
  for (std::size_t i = 0; i + 1 < n; ++i) {
    h[i] = x[i + 1] - x[i];
    const auto r = static_cast<Eigen::Index>(i);
    delta.row(r) = (y.row(r + 1) - y.row(r)) / h[i];
  }
  RowMatrix s(static_cast<Eigen::Index>(n), columns);
  if (n == 2) {  // the straight line (both end conditions)
    s.row(0) = delta.row(0);
    s.row(1) = delta.row(0);
    return s;
  }
  std::vector<double> lower(n - 1, 0.0), diagonal(n, 0.0), upper(n - 1, 0.0);
  // Interior rows: h_i s_{i−1} + 2 (h_{i−1} + h_i) s_i + h_{i−1} s_{i+1} = 3 (h_i δ_{i−1} + h_{i−1} δ_i).
  for (std::size_t i = 1; i + 1 < n; ++i) {
    lower[i - 1] = h[i];
    diagonal[i] = 2.0 * (h[i - 1] + h[i]);
    upper[i] = h[i - 1];
    const auto r = static_cast<Eigen::Index>(i);
    s.row(r) = 3.0 * (h[i] * delta.row(r - 1) + h[i - 1] * delta.row(r));
  }
  const auto last = static_cast<Eigen::Index>(n - 1);
  if (end == SplineEnd::natural) {
    // s''(x_0) = 0: 2 s_0 + s_1 = 3 δ_0;  s''(x_{n−1}) = 0: s_{n−2} + 2 s_{n−1} = 3 δ_{n−2}.
    diagonal[0] = 2.0;
    upper[0] = 1.0;
    s.row(0) = 3.0 * delta.row(0);
    lower[n - 2] = 1.0;
    diagonal[n - 1] = 2.0;
    s.row(last) = 3.0 * delta.row(last - 1);
  } else if (n == 3) {
    // Not-a-knot with three knots: the parabola through them, whose end slopes average to each secant.
    diagonal[0] = 1.0;
    upper[0] = 1.0;
    s.row(0) = 2.0 * delta.row(0);
    lower[1] = 1.0;
    diagonal[2] = 1.0;
    s.row(2) = 2.0 * delta.row(1);
  } else {
    // Third derivative continuous at x_1:
    //   h_1 s_0 + (h_0 + h_1) s_1 = ((h_0 + 2 (h_0 + h_1)) h_1 δ_0 + h_0² δ_1) / (h_0 + h_1)
    const double d0 = h[0] + h[1];
    diagonal[0] = h[1];
    upper[0] = d0;
    s.row(0) = ((h[0] + 2.0 * d0) * h[1] * delta.row(0) + h[0] * h[0] * delta.row(1)) / d0;
    // ... and at x_{n−2}:
    //   (h_{n−3} + h_{n−2}) s_{n−2} + h_{n−3} s_{n−1} = (h_{n−2}² δ_{n−3} + (2 (h_{n−3} + h_{n−2}) + h_{n−2}) h_{n−3} δ_{n−2}) / (h_{n−3} + h_{n−2})
    const double a = h[n - 3], b = h[n - 2], d1 = a + b;
    lower[n - 2] = d1;
    diagonal[n - 1] = a;
    s.row(last) = (b * b * delta.row(last - 2) + (2.0 * d1 + b) * a * delta.row(last - 1)) / d1;
  }
  solve_tridiagonal(std::move(lower), std::move(diagonal), std::move(upper), s);
  return s;
}

}  // namespace

CubicSpline::CubicSpline(std::vector<double> knots, RowMatrix values, SplineEnd end)
    : knots_(std::move(knots)), values_(std::move(values)) {
  check_knots(knots_, values_);
  slopes_ = fit_slopes(knots_, values_, end);
}

std::size_t CubicSpline::interval(double t) const noexcept {
  const auto it = std::upper_bound(knots_.begin() + 1, knots_.end() - 1, t);
  return static_cast<std::size_t>(it - knots_.begin()) - 1;
}

void CubicSpline::evaluate(double at, int derivative, Eigen::Ref<Eigen::RowVectorXd> out) const {
  const std::size_t i = interval(at);
  const auto r = static_cast<Eigen::Index>(i);
  const double h = knots_[i + 1] - knots_[i];
  const double u = (at - knots_[i]) / h;
  // Cubic Hermite basis on [0, 1] and its derivatives with respect to t = knot_i + u h.
  double h00, h10, h01, h11;
  switch (derivative) {
    case 0:
      h00 = (2 * u - 3) * u * u + 1;
      h10 = ((u - 2) * u + 1) * u * h;
      h01 = (3 - 2 * u) * u * u;
      h11 = (u - 1) * u * u * h;
      break;
    case 1:
      h00 = (6 * u - 6) * u / h;
      h10 = (3 * u - 4) * u + 1;
      h01 = (6 - 6 * u) * u / h;
      h11 = (3 * u - 2) * u;
      break;
    case 2:
      h00 = (12 * u - 6) / (h * h);
      h10 = (6 * u - 4) / h;
      h01 = (6 - 12 * u) / (h * h);
      h11 = (6 * u - 2) / h;
      break;
    default:
      throw std::invalid_argument("CubicSpline::evaluate: derivative " + std::to_string(derivative) + " is not 0, 1 or 2");
  }
  out = h00 * values_.row(r) + h10 * slopes_.row(r) + h01 * values_.row(r + 1) + h11 * slopes_.row(r + 1);
}

RowMatrix CubicSpline::evaluate(std::span<const double> at, int derivative) const {
  RowMatrix out(static_cast<Eigen::Index>(at.size()), values_.cols());
  Eigen::RowVectorXd row(values_.cols());
  for (std::size_t p = 0; p < at.size(); ++p) {
    evaluate(at[p], derivative, row);
    out.row(static_cast<Eigen::Index>(p)) = row;
  }
  return out;
}

}  // namespace throng::timewarp
