// Polyline helpers for strokes: cumulative arc length, points at an arc length, distance to a polyline.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace throng::sketch::detail {

/// Cumulative arc length: #points values, the first 0, the last the polyline's length (metres).
[[nodiscard]] std::vector<double> arc_lengths(const std::vector<Eigen::Vector2d>& points);

/// Where arc length `s` falls: the segment [segment, segment + 1] and the fraction along it.
/// `cumulative` from arc_lengths; s is clamped to [0, length]. Zero-length segments are skipped.
struct ArcPosition {
  std::size_t segment = 0;
  double fraction = 0.0;
};
[[nodiscard]] ArcPosition locate(const std::vector<double>& cumulative, double s);

/// The point at arc length `s` (clamped to the polyline).
[[nodiscard]] Eigen::Vector2d point_at(const std::vector<Eigen::Vector2d>& points,
                                       const std::vector<double>& cumulative, double s);

/// Linear interpolation of per-point `values` at arc length `s`.
[[nodiscard]] double value_at(const std::vector<double>& values, const std::vector<double>& cumulative, double s);

/// The polyline resampled at normalised arc lengths `fractions` (each in [0, 1]).
[[nodiscard]] std::vector<Eigen::Vector2d> resample_at_fractions(const std::vector<Eigen::Vector2d>& points,
                                                                 const std::vector<double>& fractions);

/// Euclidean distance from `p` to the polyline (a single point if it has one point).
[[nodiscard]] double distance_to_polyline(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p);

/// z of the 2-D cross product u × v.
[[nodiscard]] inline double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) noexcept {
  return u.x() * v.y() - u.y() * v.x();
}

}  // namespace throng::sketch::detail
