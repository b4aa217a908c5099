// The geometric interpolation (§3.3 Eq. 4, §4.1, §4.5): each item's coefficient vector (α_j, β_j[, γ_j]) across
// the keyframes, in polar form.
#pragma once

#include "spline.h"

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// Coefficient rows of every keyframe (K matrices #items by d, d = 2 or 3, in the keyframes' aligned bases; or,
/// for the polar baseline, the items' positions about the group's barycentre). The first `linear_rows` rows
/// (the spectral method: 1, the barycentre direction e1; the polar baseline: 0) are interpolated linearly with
/// the spline weights. The other rows j:
///   2-D: length r and angle θ, each a spline of the keyframes' values; angles are unwrapped so that consecutive
///        keyframes differ by at most π (the shorter way round, Eq. 4);
///   3-D: length a spline; direction u(t) = Rot(u_{n+1}→u_{n+2})^{c2} Rot(u_n→u_{n+1})^{c1+c2} Rot(u_{n−1}→u_n)^{−c−1} u_n
///        with Rot(u→v) the shortest rotation — slerp for two keyframes, Eq. 5 in cumulative form for more (each
///        turn between consecutive keyframes, as the 2-D angles are unwrapped between consecutive keyframes).
/// A zero coefficient has no direction: it takes its neighbour keyframe's (so the point moves straight through
/// the origin of that coefficient instead of turning).
class CoefficientTrack {
 public:
  CoefficientTrack() = default;
  explicit CoefficientTrack(const std::vector<Eigen::MatrixXd>& keys, int linear_rows = 1);

  /// Per-interval data (the 3-D rotations between the control keyframes); cheap in 2-D.
  struct Interval {
    ControlKeys keys;
    Eigen::MatrixXd axes;    ///< 3-D: #items by 9, unit axes of Rot(n−1→n), Rot(n→n+1), Rot(n+1→n+2)
    Eigen::MatrixXd angles;  ///< 3-D: #items by 3, their angles
  };
  [[nodiscard]] Interval interval(const ControlKeys& keys) const;

  /// Coefficients (#items by d) at spline weights `w` of an interval.
  void evaluate(const Interval& interval, const SplineWeights& w, Eigen::Ref<Eigen::MatrixXd> out) const;

  [[nodiscard]] int dimension() const noexcept { return dimension_; }

 private:
  int dimension_ = 2;
  int linear_rows_ = 1;
  std::vector<Eigen::MatrixXd> keys_;  // as given (the linear rows are used)
  Eigen::MatrixXd length_;             // #items by K
  Eigen::MatrixXd angle_;              // 2-D: #items by K, unwrapped
  std::vector<Eigen::MatrixXd> direction_;  // 3-D: K of #items by 3, unit
};

}  // namespace throng::formation
