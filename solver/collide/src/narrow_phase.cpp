#include <throng/collide/narrow_phase.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace throng::collide {
namespace {

using Vec = Eigen::Vector2d;

double cross(const Vec& u, const Vec& v) { return u.x() * v.y() - u.y() * v.x(); }

// Parameter in [0, 1] of the point of segment a → b nearest to p.
double nearest_parameter(const Vec& a, const Vec& b, const Vec& p) {
  const Vec ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 == 0.0) return 0.0;
  return std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
}

// Closest points of segments p0 → p1 (parameter s) and q0 → q1 (parameter u): the distance and s.
struct SegmentPair {
  double s = 0.0;
  double distance = 0.0;
};

SegmentPair segment_distance(const Vec& p0, const Vec& p1, const Vec& q0, const Vec& q1) {
  const Vec d = p1 - p0, e = q1 - q0, w = q0 - p0;
  const double denominator = cross(d, e);
  if (denominator != 0.0) {  // proper crossing: distance 0 at the crossing
    const double s = cross(w, e) / denominator;
    const double u = cross(w, d) / denominator;
    if (s >= 0.0 && s <= 1.0 && u >= 0.0 && u <= 1.0) return {s, 0.0};
  }
  // Otherwise the minimum is at an end of one of the segments.
  SegmentPair best{0.0, std::numeric_limits<double>::infinity()};
  auto consider = [&](double s, double distance) {
    if (distance < best.distance || (distance == best.distance && s < best.s)) best = {s, distance};
  };
  for (double s : {0.0, 1.0}) {
    const Vec p = p0 + s * d;
    const double u = nearest_parameter(q0, q1, p);
    consider(s, (p - (q0 + u * e)).norm());
  }
  for (const Vec* q : {&q0, &q1}) {
    const double s = nearest_parameter(p0, p1, *q);
    consider(s, (p0 + s * d - *q).norm());
  }
  return best;
}

Penetration local(const Circle& c, const Vec& p0, const Vec& p1) {
  const double s = nearest_parameter(p0, p1, c.center);
  return {s, (p0 + s * (p1 - p0) - c.center).norm() - c.radius};
}

Penetration local(const Wall& w, const Vec& p0, const Vec& p1) {
  const SegmentPair closest = segment_distance(p0, p1, w.a, w.b);
  return {closest.s, closest.distance - 0.5 * w.thickness};
}

Penetration local(const ConvexPolygon& polygon, const Vec& p0, const Vec& p1) {
  const auto& v = polygon.vertices;
  const std::size_t n = v.size();
  // Edge k: n_k·p − c_k, outward unit normal (CCW order), linear in s: alpha_k + s beta_k.
  std::vector<double> alpha(n), beta(n);
  const Vec d = p1 - p0;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec e = v[(k + 1) % n] - v[k];
    const double length = e.norm();
    const Vec normal = length > 0 ? Vec(e.y() / length, -e.x() / length) : Vec(0, 0);
    alpha[k] = normal.dot(p0 - v[k]);
    beta[k] = normal.dot(d);
  }
  auto g = [&](double s) {
    double m = -std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k) m = std::max(m, alpha[k] + s * beta[k]);
    return m;
  };
  // g is convex and piecewise linear: its minimum is at an end or where two lines cross.
  Penetration best{0.0, g(0.0)};
  auto consider = [&](double s) {
    const double value = g(s);
    if (value < best.signed_distance || (value == best.signed_distance && s < best.s)) best = {s, value};
  };
  consider(1.0);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t l = k + 1; l < n; ++l) {
      const double slope = beta[k] - beta[l];
      if (slope == 0.0) continue;
      const double s = (alpha[l] - alpha[k]) / slope;
      if (s > 0.0 && s < 1.0) consider(s);
    }
  }
  if (best.signed_distance < 0.0) return best;  // enters the interior: g is the signed distance there
  // Outside (or touching): the Euclidean distance to the boundary, the nearest edge.
  Penetration outside{0.0, std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k < n; ++k) {
    const SegmentPair closest = segment_distance(p0, p1, v[k], v[(k + 1) % n]);
    if (closest.distance < outside.signed_distance ||
        (closest.distance == outside.signed_distance && closest.s < outside.s)) {
      outside = {closest.s, closest.distance};
    }
  }
  return outside;
}

// dθ/dt of the obstacle's pose at `time` (the angle is interpolated linearly between keys, unwrapped).
double angular_rate(const Obstacle& obstacle, double time) {
  const auto& keys = obstacle.motion;
  for (std::size_t k = 0; k + 1 < keys.size(); ++k) {
    if (time >= keys[k].time && time <= keys[k + 1].time && keys[k + 1].time > keys[k].time) {
      return (keys[k + 1].angle - keys[k].angle) / (keys[k + 1].time - keys[k].time);
    }
  }
  return 0.0;
}

}  // namespace

Approach closest_approach(const Vec& a0, const Vec& a1, const Vec& b0, const Vec& b1) {
  const Vec start = a0 - b0;
  const Vec change = (a1 - b1) - start;
  const double speed2 = change.squaredNorm();
  double s = 0.0;
  if (speed2 > 0.0) s = std::clamp(-start.dot(change) / speed2, 0.0, 1.0);
  Approach out;
  out.s = s;
  out.offset = start + s * change;
  out.distance = out.offset.norm();
  return out;
}

Penetration deepest_penetration(const Shape& shape, const Vec& p0, const Vec& p1) {
  return std::visit([&](const auto& s) { return local(s, p0, p1); }, shape);
}

Penetration deepest_penetration(const Obstacle& obstacle, const Vec& p0, const Vec& p1, double t0, double t1,
                                double chord_tolerance) {
  constexpr int max_chords = 4096;
  if (!obstacle.is_moving()) return deepest_penetration(obstacle.shape, p0, p1);
  // Cut [t0, t1] at the pose keys: between two cuts the pose moves linearly.
  std::vector<double> cuts{0.0};
  for (const PoseKey& key : obstacle.motion) {
    if (key.time > t0 && key.time < t1) cuts.push_back((key.time - t0) / (t1 - t0));
  }
  cuts.push_back(1.0);
  Penetration best{0.0, std::numeric_limits<double>::infinity()};
  auto point = [&](double s) { return Vec(p0 + s * (p1 - p0)); };
  auto to_local = [&](double s) { return Vec(pose_at(obstacle, t0 + s * (t1 - t0)).inverse() * point(s)); };
  auto angle = [&](double s) {
    const Eigen::Isometry2d pose = pose_at(obstacle, t0 + s * (t1 - t0));
    return std::atan2(pose.linear()(1, 0), pose.linear()(0, 0));
  };
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double sa = cuts[c], sb = cuts[c + 1];
    if (sb <= sa) continue;
    int pieces = 1;
    double curvature = 0.0;  // bound on |q''| of the local path q(s) = R(−θ(s)) (p(s) − c(s)) over the cut
    const double turn = angle(sb) - angle(sa);
    if (turn != 0.0) {
      // θ, p and c are linear in s here: with u = p − c (linear, u' = u1) and ω = θ', q'' = R(−θ)(−2ωJu1 − ω²u),
      // so |q''| ≤ 2|ω||u1| + ω² max|u| (max at an end: |u| is convex). A chord of length h in s is within
      // h²|q''|/8 of the path.
      const double omega = angular_rate(obstacle, t0 + 0.5 * (sa + sb) * (t1 - t0)) * (t1 - t0);  // per unit s
      const Vec ua = point(sa) - pose_at(obstacle, t0 + sa * (t1 - t0)).translation();
      const Vec ub = point(sb) - pose_at(obstacle, t0 + sb * (t1 - t0)).translation();
      const Vec u1 = (ub - ua) / (sb - sa);
      curvature = 2.0 * std::abs(omega) * u1.norm() + omega * omega * std::max(ua.norm(), ub.norm());
      const double needed = std::ceil((sb - sa) * std::sqrt(curvature / (8.0 * chord_tolerance)));
      pieces = static_cast<int>(std::clamp(needed, 1.0, static_cast<double>(max_chords)));
    }
    const double h = (sb - sa) / pieces;
    const double chord_error = h * h * curvature / 8.0;
    for (int k = 0; k < pieces; ++k) {
      const double u0 = sa + h * k, u1 = k + 1 == pieces ? sb : sa + h * (k + 1);
      const Penetration piece = deepest_penetration(obstacle.shape, to_local(u0), to_local(u1));
      const double s = u0 + piece.s * (u1 - u0);
      const double value = piece.signed_distance - chord_error;  // never above the true minimum (1-Lipschitz)
      if (value < best.signed_distance) best = {s, value};
    }
  }
  return best;
}

}  // namespace throng::collide
