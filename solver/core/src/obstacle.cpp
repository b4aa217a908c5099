#include <throng/core/errors.h>
#include <throng/core/obstacle.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace throng {
namespace {

// Nearest point of segment a–b to p.
Eigen::Vector2d closest_on_segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  if (len2 == 0.0) return a;
  const double s = std::clamp((p - a).dot(ab) / len2, 0.0, 1.0);
  return a + s * ab;
}

double cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) { return u.x() * v.y() - u.y() * v.x(); }

// Distance of a local-frame point to a local-frame shape.
ObstacleDistance local_distance(const Circle& c, const Eigen::Vector2d& p) {
  ObstacleDistance d;
  const Eigen::Vector2d r = p - c.center;
  const double len = r.norm();
  d.normal = len > 0 ? Eigen::Vector2d(r / len) : Eigen::Vector2d(1, 0);
  d.nearest = c.center + c.radius * d.normal;
  d.signed_distance = len - c.radius;
  return d;
}

ObstacleDistance local_distance(const ConvexPolygon& poly, const Eigen::Vector2d& p) {
  ObstacleDistance d;
  const auto& v = poly.vertices;
  const std::size_t n = v.size();
  double best = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % n];
    if (cross(b - a, p - a) < 0) inside = false;  // right of a CCW edge: outside
    const Eigen::Vector2d q = closest_on_segment(a, b, p);
    const double dist = (p - q).norm();
    if (dist < best) {
      best = dist;
      d.nearest = q;
      const Eigen::Vector2d e = (b - a).normalized();
      d.normal = Eigen::Vector2d(e.y(), -e.x());  // outward for CCW order
    }
  }
  d.signed_distance = inside ? -best : best;
  if (!inside && best > 0) d.normal = (p - d.nearest) / best;
  return d;
}

ObstacleDistance local_distance(const Wall& w, const Eigen::Vector2d& p) {
  ObstacleDistance d;
  const double half = 0.5 * w.thickness;
  const Eigen::Vector2d q = closest_on_segment(w.a, w.b, p);
  const Eigen::Vector2d r = p - q;
  const double len = r.norm();
  if (len > 0) {
    d.normal = r / len;
  } else {
    const Eigen::Vector2d e = (w.b - w.a).norm() > 0 ? Eigen::Vector2d((w.b - w.a).normalized()) : Eigen::Vector2d(1, 0);
    d.normal = Eigen::Vector2d(-e.y(), e.x());
  }
  d.nearest = q + half * d.normal;
  d.signed_distance = len - half;
  return d;
}

Eigen::AlignedBox2d local_bounds(const Circle& c) {
  const Eigen::Vector2d r(c.radius, c.radius);
  return {c.center - r, c.center + r};
}
Eigen::AlignedBox2d local_bounds(const ConvexPolygon& p) {
  Eigen::AlignedBox2d box;
  for (const auto& v : p.vertices) box.extend(v);
  return box;
}
Eigen::AlignedBox2d local_bounds(const Wall& w) {
  const Eigen::Vector2d r(0.5 * w.thickness, 0.5 * w.thickness);
  Eigen::AlignedBox2d box(w.a.cwiseMin(w.b) - r, w.a.cwiseMax(w.b) + r);
  return box;
}

// Radius of the smallest disc about the local origin holding the shape: bounds a rotating shape.
double reach(const Obstacle& o) {
  const Eigen::AlignedBox2d box = std::visit([](const auto& s) { return local_bounds(s); }, o.shape);
  double r = 0;
  for (int corner = 0; corner < 4; ++corner) {
    r = std::max(r, box.corner(static_cast<Eigen::AlignedBox2d::CornerType>(corner)).norm());
  }
  return r;
}

bool finite(const Eigen::Vector2d& v) { return std::isfinite(v.x()) && std::isfinite(v.y()); }

}  // namespace

Eigen::Isometry2d pose_at(const Obstacle& obstacle, double time) {
  Eigen::Isometry2d pose = Eigen::Isometry2d::Identity();
  const auto& keys = obstacle.motion;
  if (keys.empty()) return pose;
  const PoseKey* a = &keys.front();
  const PoseKey* b = &keys.front();
  if (time >= keys.back().time) {
    a = b = &keys.back();
  } else if (time > keys.front().time) {
    const auto it = std::upper_bound(keys.begin(), keys.end(), time,
                                     [](double t, const PoseKey& k) { return t < k.time; });
    b = &*it;
    a = &*(it - 1);
  }
  const double s = (b->time > a->time) ? (time - a->time) / (b->time - a->time) : 0.0;
  const Eigen::Vector2d translation = (1 - s) * a->translation + s * b->translation;
  const double angle = (1 - s) * a->angle + s * b->angle;
  pose.translate(translation);
  pose.rotate(angle);
  return pose;
}

ObstacleDistance distance_to(const Obstacle& obstacle, const Eigen::Vector2d& point, double time) {
  if (!obstacle.is_moving()) {
    return std::visit([&](const auto& s) { return local_distance(s, point); }, obstacle.shape);
  }
  const Eigen::Isometry2d pose = pose_at(obstacle, time);
  const Eigen::Vector2d local = pose.inverse() * point;
  ObstacleDistance d = std::visit([&](const auto& s) { return local_distance(s, local); }, obstacle.shape);
  d.nearest = pose * d.nearest;
  d.normal = pose.linear() * d.normal;
  return d;
}

Eigen::AlignedBox2d bounds_at(const Obstacle& obstacle, double time) {
  const Eigen::AlignedBox2d local = std::visit([](const auto& s) { return local_bounds(s); }, obstacle.shape);
  if (!obstacle.is_moving()) return local;
  const Eigen::Isometry2d pose = pose_at(obstacle, time);
  Eigen::AlignedBox2d box;
  for (int corner = 0; corner < 4; ++corner) {
    box.extend(pose * local.corner(static_cast<Eigen::AlignedBox2d::CornerType>(corner)));
  }
  return box;
}

Eigen::AlignedBox2d bounds_over(const Obstacle& obstacle, double t0, double t1) {
  if (!obstacle.is_moving()) return bounds_at(obstacle, t0);
  // The translation is piecewise linear, so its extremes over [t0, t1] are at t0, t1 or a key inside;
  // rotation is bounded by the disc of the shape's reach about the moving origin.
  const double r = reach(obstacle);
  Eigen::AlignedBox2d box;
  auto add = [&](double t) {
    const Eigen::Vector2d c = pose_at(obstacle, t).translation();
    box.extend(c - Eigen::Vector2d(r, r));
    box.extend(c + Eigen::Vector2d(r, r));
  };
  add(t0);
  add(t1);
  for (const auto& k : obstacle.motion) {
    if (k.time > t0 && k.time < t1) add(k.time);
  }
  return box;
}

void validate(const Obstacle& obstacle, const std::string& what) {
  auto fail = [&](const std::string& message) { throw InputError(what + ": " + message); };
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Circle>) {
          if (!finite(s.center)) fail("circle centre is not finite");
          if (!(std::isfinite(s.radius) && s.radius > 0)) fail("circle radius " + std::to_string(s.radius) + ", expected > 0");
        } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
          const auto& v = s.vertices;
          if (v.size() < 3) fail("polygon has " + std::to_string(v.size()) + " vertices, expected at least 3");
          for (const auto& p : v) {
            if (!finite(p)) fail("polygon vertex is not finite");
          }
          for (std::size_t i = 0; i < v.size(); ++i) {
            const auto& a = v[i];
            const auto& b = v[(i + 1) % v.size()];
            const auto& c = v[(i + 2) % v.size()];
            if (cross(b - a, c - b) < 0) {
              fail("polygon is not convex and counter-clockwise at vertex " + std::to_string((i + 1) % v.size()));
            }
          }
        } else {
          if (!finite(s.a) || !finite(s.b)) fail("wall end point is not finite");
          if (!(std::isfinite(s.thickness) && s.thickness >= 0)) fail("wall thickness " + std::to_string(s.thickness) + ", expected ≥ 0");
        }
      },
      obstacle.shape);
  for (std::size_t i = 0; i < obstacle.motion.size(); ++i) {
    const auto& k = obstacle.motion[i];
    if (!std::isfinite(k.time) || !finite(k.translation) || !std::isfinite(k.angle)) {
      fail("motion key " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && !(k.time > obstacle.motion[i - 1].time)) {
      fail("motion key times not strictly increasing at key " + std::to_string(i));
    }
  }
}

void move_rigidly(Obstacle& obstacle, const Eigen::Isometry2d& motion, double rotation) {
  if (obstacle.is_moving()) {
    for (PoseKey& key : obstacle.motion) {
      key.translation = motion * key.translation;
      key.angle += rotation;
    }
    return;
  }
  std::visit(
      [&](auto& shape) {
        using S = std::decay_t<decltype(shape)>;
        if constexpr (std::is_same_v<S, Circle>) {
          shape.center = motion * shape.center;
        } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
          for (Eigen::Vector2d& v : shape.vertices) v = motion * v;
        } else {
          shape.a = motion * shape.a;
          shape.b = motion * shape.b;
        }
      },
      obstacle.shape);
}

}  // namespace throng
