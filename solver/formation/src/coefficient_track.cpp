#include "coefficient_track.h"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace throng::formation {
namespace {

// A coefficient shorter than this fraction of the row's longest has no meaningful direction.
constexpr double zero_fraction = 1e-12;

double wrap_to_pi(double a) {
  a = std::remainder(a, 2 * std::numbers::pi);  // in [−π, π]
  return a <= -std::numbers::pi ? a + 2 * std::numbers::pi : a;
}

// Which keyframe's direction each keyframe uses: itself when its length is meaningful, otherwise the nearest
// earlier one that is, otherwise the nearest later one; −1 when no keyframe has one.
std::vector<int> direction_sources(const Eigen::RowVectorXd& lengths) {
  const int k_count = static_cast<int>(lengths.size());
  const double tiny = zero_fraction * lengths.maxCoeff();
  std::vector<int> source(static_cast<std::size_t>(k_count), -1);
  int last = -1;
  for (int k = 0; k < k_count; ++k) {
    if (lengths(k) > tiny) last = k;
    source[static_cast<std::size_t>(k)] = last;
  }
  int next = -1;
  for (int k = k_count - 1; k >= 0; --k) {
    if (lengths(k) > tiny) next = k;
    if (source[static_cast<std::size_t>(k)] < 0) source[static_cast<std::size_t>(k)] = next;
  }
  return source;
}

// Shortest rotation taking unit a to unit b: unit axis and angle in [0, π].
void shortest_rotation(const Eigen::Vector3d& a, const Eigen::Vector3d& b, Eigen::Vector3d& axis, double& angle) {
  const Eigen::Vector3d cross = a.cross(b);
  const double sine = cross.norm();
  angle = std::atan2(sine, a.dot(b));
  if (sine > 1e-300 && angle < std::numbers::pi) {
    axis = cross / sine;
    return;
  }
  // Parallel or opposite: any axis perpendicular to a (the coordinate axis least aligned with a, deterministic).
  Eigen::Index least = 0;
  a.cwiseAbs().minCoeff(&least);
  axis = a.cross(Eigen::Vector3d::Unit(least)).normalized();
}

Eigen::Vector3d rotate(const Eigen::Vector3d& v, const Eigen::Vector3d& axis, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1 - c));
}

}  // namespace

CoefficientTrack::CoefficientTrack(const std::vector<Eigen::MatrixXd>& keys, int linear_rows)
    : linear_rows_(linear_rows), keys_(keys) {
  const int k_count = static_cast<int>(keys.size());
  const Eigen::Index m = keys.front().rows();
  dimension_ = static_cast<int>(keys.front().cols());
  length_.resize(m, k_count);
  for (int k = 0; k < k_count; ++k) length_.col(k) = keys[static_cast<std::size_t>(k)].rowwise().norm();
  if (dimension_ == 2) {
    angle_.setZero(m, k_count);
    for (Eigen::Index j = linear_rows_; j < m; ++j) {
      const std::vector<int> source = direction_sources(length_.row(j));
      for (int k = 0; k < k_count; ++k) {
        const int from = source[static_cast<std::size_t>(k)];
        const double raw = from < 0 ? 0.0 : std::atan2(keys[static_cast<std::size_t>(from)](j, 1), keys[static_cast<std::size_t>(from)](j, 0));
        angle_(j, k) = k == 0 ? raw : angle_(j, k - 1) + wrap_to_pi(raw - angle_(j, k - 1));
      }
    }
  } else {
    direction_.assign(static_cast<std::size_t>(k_count), Eigen::MatrixXd::Zero(m, 3));
    for (Eigen::Index j = linear_rows_; j < m; ++j) {
      const std::vector<int> source = direction_sources(length_.row(j));
      for (int k = 0; k < k_count; ++k) {
        const int from = source[static_cast<std::size_t>(k)];
        direction_[static_cast<std::size_t>(k)].row(j) =
            from < 0 ? Eigen::RowVector3d(1, 0, 0)
                     : Eigen::RowVector3d(keys[static_cast<std::size_t>(from)].row(j).normalized());
      }
    }
  }
}

CoefficientTrack::Interval CoefficientTrack::interval(const ControlKeys& keys) const {
  Interval out;
  out.keys = keys;
  if (dimension_ != 3) return out;
  const Eigen::Index m = length_.rows();
  out.axes.setZero(m, 9);
  out.angles.setZero(m, 3);
  // Rotation f turns keyframe keys[f]'s direction to keys[f+1]'s: n−1 → n, n → n+1, n+1 → n+2 (cumulative form).
  for (int f = 0; f < 3; ++f) {
    const Eigen::MatrixXd& from = direction_[static_cast<std::size_t>(keys.keys[static_cast<std::size_t>(f)])];
    const Eigen::MatrixXd& to = direction_[static_cast<std::size_t>(keys.keys[static_cast<std::size_t>(f + 1)])];
    for (Eigen::Index j = linear_rows_; j < m; ++j) {
      Eigen::Vector3d axis;
      double angle = 0.0;
      shortest_rotation(from.row(j).transpose(), to.row(j).transpose(), axis, angle);
      out.axes.block(j, 3 * f, 1, 3) = axis.transpose();
      out.angles(j, f) = angle;
    }
  }
  return out;
}

void CoefficientTrack::evaluate(const Interval& interval, const SplineWeights& w, Eigen::Ref<Eigen::MatrixXd> out) const {
  const auto& k = interval.keys.keys;
  const Eigen::Index m = length_.rows();
  // The linear rows: linear in the keyframes' rows.
  for (Eigen::Index j = 0; j < linear_rows_; ++j) {
    out.row(j).setZero();
    for (int i = 0; i < 4; ++i) out.row(j) += w.c[static_cast<std::size_t>(i)] * keys_[static_cast<std::size_t>(k[static_cast<std::size_t>(i)])].row(j);
  }
  for (Eigen::Index j = linear_rows_; j < m; ++j) {
    double length = 0.0;
    for (int i = 0; i < 4; ++i) length += w.c[static_cast<std::size_t>(i)] * length_(j, k[static_cast<std::size_t>(i)]);
    if (dimension_ == 2) {
      double angle = 0.0;
      for (int i = 0; i < 4; ++i) angle += w.c[static_cast<std::size_t>(i)] * angle_(j, k[static_cast<std::size_t>(i)]);
      out(j, 0) = length * std::cos(angle);
      out(j, 1) = length * std::sin(angle);
    } else {
      // Eq. 5 in cumulative form: u(t) = Rot(n+1→n+2)^{c2} Rot(n→n+1)^{c1+c2} Rot(n−1→n)^{−c−1} u_n.
      const double exponents[3] = {-w.c[0], w.c[2] + w.c[3], w.c[3]};
      Eigen::Vector3d u = direction_[static_cast<std::size_t>(k[1])].row(j).transpose();
      for (int f = 0; f < 3; ++f) {
        const double exponent = exponents[f];
        u = rotate(u, interval.axes.block(j, 3 * f, 1, 3).transpose(), exponent * interval.angles(j, f));
      }
      out.row(j) = length * u.transpose();
    }
  }
}

}  // namespace throng::formation
