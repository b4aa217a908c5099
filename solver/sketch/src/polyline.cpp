#include "polyline.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace throng::sketch::detail {

std::vector<double> arc_lengths(const std::vector<Eigen::Vector2d>& points) {
  std::vector<double> s(points.size(), 0.0);
  for (std::size_t k = 1; k < points.size(); ++k) s[k] = s[k - 1] + (points[k] - points[k - 1]).norm();
  return s;
}

ArcPosition locate(const std::vector<double>& cumulative, double s) {
  assert(!cumulative.empty());
  if (cumulative.size() == 1) return {0, 0.0};
  const double length = cumulative.back();
  s = std::clamp(s, 0.0, length);
  // First point with arc length > s; the segment ends there. Past the end: the last non-empty segment.
  auto it = std::upper_bound(cumulative.begin(), cumulative.end(), s);
  std::size_t end = it == cumulative.end() ? cumulative.size() - 1 : static_cast<std::size_t>(it - cumulative.begin());
  while (end > 1 && cumulative[end] == cumulative[end - 1]) --end;
  const std::size_t segment = end - 1;
  const double span = cumulative[end] - cumulative[segment];
  const double fraction = span > 0 ? std::clamp((s - cumulative[segment]) / span, 0.0, 1.0) : 0.0;
  return {segment, fraction};
}

Eigen::Vector2d point_at(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& cumulative, double s) {
  if (points.size() == 1) return points.front();
  const ArcPosition a = locate(cumulative, s);
  return (1.0 - a.fraction) * points[a.segment] + a.fraction * points[a.segment + 1];
}

double value_at(const std::vector<double>& values, const std::vector<double>& cumulative, double s) {
  if (values.size() == 1) return values.front();
  const ArcPosition a = locate(cumulative, s);
  return (1.0 - a.fraction) * values[a.segment] + a.fraction * values[a.segment + 1];
}

std::vector<Eigen::Vector2d> resample_at_fractions(const std::vector<Eigen::Vector2d>& points,
                                                   const std::vector<double>& fractions) {
  const std::vector<double> cumulative = arc_lengths(points);
  const double length = cumulative.back();
  std::vector<Eigen::Vector2d> out;
  out.reserve(fractions.size());
  for (double f : fractions) out.push_back(point_at(points, cumulative, f * length));
  return out;
}

double distance_to_polyline(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p) {
  assert(!points.empty());
  if (points.size() == 1) return (p - points.front()).norm();
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    const Eigen::Vector2d a = points[k];
    const Eigen::Vector2d ab = points[k + 1] - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    best2 = std::min(best2, (p - (a + t * ab)).squaredNorm());
  }
  return std::sqrt(best2);
}

}  // namespace throng::sketch::detail
