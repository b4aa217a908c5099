// Interpolating cubic splines through non-uniform knots (paper §6.2: "non-uniform cubic interpolating splines
// that pass through vertex v'(i,j) at time t'_i [Bartels et al. 1987]").
//
// The spline is C2: on each interval it is the cubic Hermite polynomial of the values and slopes at its two
// knots, and the slopes solve the tridiagonal system that makes the second derivative continuous at every
// interior knot. Two end conditions:
//  * not_a_knot (the default for every resampling in throng): the third derivative is also continuous at the
//    second and the second-to-last knot, so the first two and the last two intervals are each one cubic.
//    Decision: sampled trajectories have no reason to stop accelerating at a clip's ends, and a natural spline
//    forces zero acceleration there, which bends the speed profile near the ends — exactly what a time warp
//    tries to keep right. Not-a-knot reproduces any cubic polynomial exactly. With three knots it is the
//    parabola through them, with two the straight line (SciPy's CubicSpline makes the same choices).
//  * natural: zero second derivative at both ends.
//
// Many columns share one fit: the slope system depends only on the knots, so all columns are solved together
// (the time warp fits every agent's x, y and z through one shared set of warped times at once).
#pragma once

#include <Eigen/Core>

#include <span>
#include <vector>

namespace throng::timewarp {

enum class SplineEnd { not_a_knot, natural };

/// Row-major matrix: row i holds the values of every column at knot i (a crowd's [T][N][3] positions are a
/// #frames by 3·#agents matrix of this kind, without copying).
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class CubicSpline {
 public:
  /// Fits the spline through (knots[i], values row i).
  ///   knots   #knots ≥ 2, finite, strictly increasing (seconds, or any parameter)
  ///   values  #knots by #columns, finite
  /// Throws InputError when the knots are fewer than 2, not finite or not strictly increasing, or when the
  /// shapes disagree or a value is not finite.
  CubicSpline(std::vector<double> knots, RowMatrix values, SplineEnd end = SplineEnd::not_a_knot);

  /// Values (derivative 0), first or second derivatives (1, 2) at `at` (any order; outside [first, last knot]
  /// the end intervals' cubics are extended). At a knot the value is the knot's value exactly.
  ///   result  #at by #columns
  [[nodiscard]] RowMatrix evaluate(std::span<const double> at, int derivative = 0) const;

  /// One point, written into `out` (#columns).
  void evaluate(double at, int derivative, Eigen::Ref<Eigen::RowVectorXd> out) const;

  [[nodiscard]] const std::vector<double>& knots() const noexcept { return knots_; }
  [[nodiscard]] const RowMatrix& values() const noexcept { return values_; }
  /// First derivatives at the knots (#knots by #columns).
  [[nodiscard]] const RowMatrix& slopes() const noexcept { return slopes_; }
  [[nodiscard]] Eigen::Index columns() const noexcept { return values_.cols(); }

  /// The interval [knots[i], knots[i + 1]] holding `t` (the first or last one outside the knots).
  [[nodiscard]] std::size_t interval(double t) const noexcept;

 private:
  std::vector<double> knots_;
  RowMatrix values_;
  RowMatrix slopes_;
};

/// Solves the tridiagonal system with sub-diagonal `lower` (n−1), diagonal `diagonal` (n) and super-diagonal
/// `upper` (n−1) for every column of `rhs` (n by #columns), in place, by Gaussian elimination with partial
/// pivoting (LAPACK's dgtsv). Throws NumericalError when the matrix is singular.
void solve_tridiagonal(std::vector<double> lower, std::vector<double> diagonal, std::vector<double> upper, RowMatrix& rhs);

}  // namespace throng::timewarp
