// Shared scenes and measurements for the formation tests.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/random.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <numbers>

namespace throng::test {

/// n points in a disc of `radius` (2-D) or ball (3-D), at least `gap` apart (dart throwing, seeded).
inline Eigen::MatrixXd scattered(int n, double radius, std::uint64_t seed, double gap = 0.5, int dimension = 2) {
  Rng rng(seed);
  Eigen::MatrixXd p(n, dimension);
  int placed = 0;
  while (placed < n) {
    Eigen::RowVectorXd q(dimension);
    for (int a = 0; a < dimension; ++a) q(a) = rng.uniform(-radius, radius);
    if (q.norm() > radius) continue;
    bool ok = true;
    for (int i = 0; i < placed && ok; ++i) ok = (p.row(i) - q).norm() >= gap;
    if (ok) p.row(placed++) = q;
  }
  return p;
}

/// Rotation by `angle` about the origin then translation (2-D rows).
inline Eigen::MatrixXd rigid_2d(const Eigen::MatrixXd& p, double angle, const Eigen::RowVector2d& shift) {
  const Eigen::Matrix2d r = Eigen::Rotation2Dd(angle).toRotationMatrix();
  return (p * r.transpose()).rowwise() + shift;
}

/// Positions of every agent at frame f (#agents by 3).
inline Eigen::MatrixXd frame_of(const CrowdMotion& m, std::size_t f) { return m.frame(f); }

/// Largest |d_ij(f) − d_ij(0)| over frames and pairs.
inline double largest_distance_change(const CrowdMotion& m) {
  const Eigen::MatrixXd first = m.frame(0);
  double worst = 0.0;
  for (std::size_t f = 1; f < m.frame_count(); ++f) {
    const Eigen::MatrixXd now = m.frame(f);
    for (Eigen::Index i = 0; i < now.rows(); ++i)
      for (Eigen::Index j = i + 1; j < now.rows(); ++j)
        worst = std::max(worst, std::abs((now.row(i) - now.row(j)).norm() - (first.row(i) - first.row(j)).norm()));
  }
  return worst;
}

/// Summed path length of every agent.
inline double total_path_length(const CrowdMotion& m) {
  double sum = 0.0;
  for (std::size_t f = 1; f < m.frame_count(); ++f) sum += (m.frame(f) - m.frame(f - 1)).rowwise().norm().sum();
  return sum;
}

/// Smallest distance between two agents over all frames.
inline double closest_pair_distance(const CrowdMotion& m) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < m.frame_count(); ++f) {
    const Eigen::MatrixXd p = m.frame(f);
    for (Eigen::Index i = 0; i < p.rows(); ++i)
      for (Eigen::Index j = i + 1; j < p.rows(); ++j) best = std::min(best, (p.row(i) - p.row(j)).norm());
  }
  return best;
}

/// Machine epsilon.
inline constexpr double eps = std::numeric_limits<double>::epsilon();

}  // namespace throng::test
