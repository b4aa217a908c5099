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

/// Euclidean distance from `p` to the polyline (a single point if it has one point): the nearest of every
/// segment's nearest points, O(#points).
[[nodiscard]] double distance_to_polyline(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p);

/// distance_to_polyline for many points against one polyline (a stroke against every agent: 10,000 agents × 900
/// segments was 14 % of a 10,000-agent `throng sketch`), the same value bit for bit. The segments are kept in
/// runs of `run`, each with its bounding box; a query evaluates the run whose box is nearest first, then only
/// the runs whose box lies within the best distance so far plus a margin far above rounding (1e-9 × (1 m + the
/// largest coordinate of the polyline and the query)). The minimum over the evaluated segments is the minimum over all: a skipped segment's
/// computed distance, rounding included, is above the best. Keeps a copy of the points (at least one).
class PolylineDistance {
 public:
  static constexpr std::size_t run = 16;

  explicit PolylineDistance(std::vector<Eigen::Vector2d> points);
  [[nodiscard]] double operator()(const Eigen::Vector2d& p) const;

 private:
  struct Box {
    Eigen::Vector2d low, high;
  };
  std::vector<Eigen::Vector2d> points_;
  std::vector<Box> boxes_;  // run k: segments [k·run, min((k + 1)·run, #points − 1))
  double size_ = 0;         // the largest coordinate's magnitude
};

/// z of the 2-D cross product u × v.
[[nodiscard]] inline double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) noexcept {
  return u.x() * v.y() - u.y() * v.x();
}

}  // namespace throng::sketch::detail
