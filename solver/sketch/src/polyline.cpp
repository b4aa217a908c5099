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

namespace {

// The squared distance from p to segment [a, b] as distance_to_polyline computes it (one definition, so both
// give the same bits).
double segment_distance2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).squaredNorm();
}

}  // namespace

double distance_to_polyline(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& p) {
  assert(!points.empty());
  if (points.size() == 1) return (p - points.front()).norm();
  double best2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < points.size(); ++k) best2 = std::min(best2, segment_distance2(points[k], points[k + 1], p));
  return std::sqrt(best2);
}

PolylineDistance::PolylineDistance(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {
  assert(!points_.empty());
  for (const Eigen::Vector2d& q : points_) size_ = std::max(size_, q.cwiseAbs().maxCoeff());
  const std::size_t segments = points_.size() - 1;
  for (std::size_t first = 0; first < segments; first += run) {
    const std::size_t end = std::min(first + run, segments);
    Box box{points_[first], points_[first]};
    for (std::size_t k = first + 1; k <= end; ++k) {
      box.low = box.low.cwiseMin(points_[k]);
      box.high = box.high.cwiseMax(points_[k]);
    }
    boxes_.push_back(box);
  }
}

double PolylineDistance::operator()(const Eigen::Vector2d& p) const {
  if (points_.size() == 1) return (p - points_.front()).norm();
  // A run can hold a segment nearer than `best2` only if its box is within √best2 + margin of p.
  const double margin = 1e-9 * (1.0 + std::max(size_, p.cwiseAbs().maxCoeff()));
  auto box2 = [&](const Box& b) {
    const double dx = std::max({b.low.x() - p.x(), 0.0, p.x() - b.high.x()});
    const double dy = std::max({b.low.y() - p.y(), 0.0, p.y() - b.high.y()});
    return dx * dx + dy * dy;
  };
  auto reach2 = [&](double best2) {
    const double r = std::sqrt(best2) + margin;
    return r * r;
  };
  const std::size_t segments = points_.size() - 1;
  auto evaluate = [&](std::size_t k, double best2) {
    for (std::size_t i = k * run, end = std::min(i + run, segments); i < end; ++i) {
      best2 = std::min(best2, segment_distance2(points_[i], points_[i + 1], p));
    }
    return best2;
  };
  std::size_t nearest = 0;
  double nearest2 = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    const double b2 = box2(boxes_[k]);
    if (b2 < nearest2) nearest2 = b2, nearest = k;
  }
  double best2 = evaluate(nearest, std::numeric_limits<double>::infinity());
  double reach = reach2(best2);
  for (std::size_t k = 0; k < boxes_.size(); ++k) {
    if (k == nearest || box2(boxes_[k]) > reach) continue;
    best2 = evaluate(k, best2);
    reach = reach2(best2);
  }
  return std::sqrt(best2);
}

}  // namespace throng::sketch::detail
