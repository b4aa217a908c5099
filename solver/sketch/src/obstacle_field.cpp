#include "obstacle_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

namespace throng::sketch::detail {
namespace {

// A body overlaps an obstacle when its centre is closer than radius − this to the boundary (metres).
// Projection puts it at exactly the radius, so rounding never makes a projected agent "overlap" again.
constexpr double contact_tolerance_m = 1e-9;
// Projection passes over the nearby obstacles before falling back.
constexpr int projection_passes = 8;
// Facing a boundary within this cosine of square-on, the agent keeps its side instead of going "forward".
constexpr double square_on = 0.1;

}  // namespace

void ObstacleField::rebuild(const NeighbourGrid& grid, double t0, double t1) {
  grid_ = &grid;
  boxes_.clear();
  shape_boxes_.clear();
  ids_.clear();
  start_.assign(grid.cell_count() + 1, 0);
  if (scene_.obstacles.empty()) return;
  const double grow = std::max({reach_, radius_, radius_ + look_ahead_});
  const double shape_grow = std::max(reach_, radius_);
  struct Span {
    std::size_t c0, c1, r0, r1;
  };
  std::vector<Span> spans;
  spans.reserve(scene_.obstacles.size());
  for (const Obstacle& o : scene_.obstacles) {
    const Eigen::AlignedBox2d b = bounds_over(o, t0, t1);
    boxes_.emplace_back(b.min() - Eigen::Vector2d(grow, grow), b.max() + Eigen::Vector2d(grow, grow));
    shape_boxes_.emplace_back(b.min() - Eigen::Vector2d(shape_grow, shape_grow), b.max() + Eigen::Vector2d(shape_grow, shape_grow));
    const Eigen::AlignedBox2d& g = boxes_.back();
    spans.push_back({grid.column(g.min().x()), grid.column(g.max().x()), grid.row(g.min().y()), grid.row(g.max().y())});
  }
  // Two passes (count, fill) into a compressed row layout, obstacles in index order within a cell.
  const std::size_t nx = grid.columns();
  for (const Span& s : spans) {
    for (std::size_t r = s.r0; r <= s.r1; ++r) {
      for (std::size_t c = s.c0; c <= s.c1; ++c) ++start_[r * nx + c + 1];
    }
  }
  for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
  ids_.resize(start_.back());
  std::vector<std::uint32_t> cursor(start_.begin(), start_.end() - 1);
  for (std::uint32_t o = 0; o < spans.size(); ++o) {
    const Span& s = spans[o];
    for (std::size_t r = s.r0; r <= s.r1; ++r) {
      for (std::size_t c = s.c0; c <= s.c1; ++c) ids_[cursor[r * nx + c]++] = o;
    }
  }
}

ObstacleResponse ObstacleField::respond(const Eigen::Vector2d& p, double t, const Eigen::Vector2d& pull,
                                        const Eigen::Vector2d& heading, const Eigen::Vector2d& course_point,
                                        std::int8_t side, std::uint32_t agent) const {
  ObstacleResponse r;
  r.pull = pull;
  double pressing = std::numeric_limits<double>::infinity();
  ObstacleDistance contact;
  Eigen::AlignedBox2d contact_box;
  for_each_near(p, [&](std::uint32_t o, const Obstacle& obstacle) {
    const ObstacleDistance d = distance_to(obstacle, p, t);
    if (d.signed_distance >= reach_) return;
    r.push += (reach_ - d.signed_distance) * d.normal;
    if (slide_ && d.normal.dot(pull) < 0 && d.signed_distance < pressing) {
      pressing = d.signed_distance;
      contact = d;
      contact_box = shape_boxes_[o];  // not grown by look_ahead: the side rule sees the obstacle's own extent
    }
  });
  if (!std::isfinite(pressing)) return r;  // no contact: the side is forgotten

  // Slide: the pull turned along the boundary of the most pressing obstacle, its length kept.
  Eigen::Vector2d tangent(-contact.normal.y(), contact.normal.x());
  const Eigen::Vector2d left(-heading.y(), heading.x());
  const double forward = tangent.dot(heading);
  if (std::abs(forward) > square_on) {
    if (forward < 0) tangent = -tangent;
  } else {
    if (side == 0) {
      // The course passing beside the obstacle (its main line outside the obstacle's lateral extent) decides;
      // else the side of the obstacle's centre the agent is on; else the pull's lean; else parity.
      const Eigen::Vector2d half = 0.5 * contact_box.sizes();
      const double extent = half.x() * std::abs(left.x()) + half.y() * std::abs(left.y());
      const double course = left.dot(course_point - contact_box.center());
      const double offset = left.dot(p - contact_box.center());
      const double lean = pull.dot(left);
      const double decider = std::abs(course) > extent ? course : offset != 0 ? offset : lean;
      side = decider != 0 ? (decider > 0 ? 1 : -1) : (agent % 2 == 0 ? 1 : -1);
    }
    if (tangent.dot(left) * side < 0) tangent = -tangent;
  }
  r.side = side != 0 ? side : (tangent.dot(left) >= 0 ? 1 : -1);
  r.pull = pull.norm() * tangent;
  return r;
}

Eigen::Vector2d ObstacleField::push(const Eigen::Vector2d& p, double t) const {
  Eigen::Vector2d f = Eigen::Vector2d::Zero();
  for_each_near(p, [&](std::uint32_t, const Obstacle& obstacle) {
    const ObstacleDistance d = distance_to(obstacle, p, t);
    if (d.signed_distance < reach_) f += (reach_ - d.signed_distance) * d.normal;
  });
  return f;
}

Eigen::Vector2d ObstacleField::brake(const Eigen::Vector2d& p, double t0, double t1, Eigen::Vector2d u,
                                     double deceleration) const {
  const double dt = t1 - t0;
  const double walking = u.norm();
  for_each_near(p, [&](std::uint32_t, const Obstacle& obstacle) {
    // The gap at the step's start, closed over the step by the agent's speed toward the boundary and the
    // boundary's own speed toward p (a moving obstacle: measured over the step at p).
    const ObstacleDistance d = distance_to(obstacle, p, t0);
    const double gap = std::max(0.0, d.signed_distance - radius_);
    if (gap > look_ahead_) return;
    const double receding = obstacle.is_moving() ? (distance_to(obstacle, p, t1).signed_distance - d.signed_distance) / dt : 0.0;
    const double closing = -u.dot(d.normal) - receding;  // the normal points from the obstacle to p
    const double allowed = std::min(std::sqrt(2.0 * deceleration * gap), gap / dt);
    if (closing <= allowed) return;
    u += (closing - allowed) * d.normal;
    const double away = u.dot(d.normal);
    if (away > 0 && u.squaredNorm() > walking * walking) {  // stepping aside: keep |u|, the side step first
      const Eigen::Vector2d along = u - away * d.normal;
      const double room = walking > away ? std::sqrt(walking * walking - away * away) : 0.0;
      const double length = along.norm();
      u = away * d.normal + (length > room ? Eigen::Vector2d(along * (room / length)) : along);
    }
  });
  return u;
}

double ObstacleField::fastest_boundary_speed() const {
  double fastest = 0.0;
  for (const Obstacle& o : scene_.obstacles) {
    const double extent = std::visit(
        [](const auto& shape) -> double {
          using S = std::decay_t<decltype(shape)>;
          if constexpr (std::is_same_v<S, Circle>) {
            return shape.center.norm() + shape.radius;
          } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
            double r = 0.0;
            for (const Eigen::Vector2d& v : shape.vertices) r = std::max(r, v.norm());
            return r;
          } else {
            return std::max(shape.a.norm(), shape.b.norm()) + 0.5 * shape.thickness;
          }
        },
        o.shape);
    for (std::size_t k = 1; k < o.motion.size(); ++k) {
      const PoseKey& a = o.motion[k - 1];
      const PoseKey& b = o.motion[k];
      const double span = b.time - a.time;
      fastest = std::max(fastest, ((b.translation - a.translation).norm() + std::abs(b.angle - a.angle) * extent) / span);
    }
  }
  return fastest;
}

bool ObstacleField::overlaps(const Eigen::Vector2d& p, double t) const {
  bool hit = false;
  for_each_near(p, [&](std::uint32_t, const Obstacle& obstacle) {
    if (!hit) hit = distance_to(obstacle, p, t).signed_distance < radius_ - contact_tolerance_m;
  });
  return hit;
}

bool ObstacleField::keep_clear(Eigen::Vector2d from, Eigen::Vector2d& to, double t) const {
  const Eigen::Vector2d move = to - from;
  const double length = move.norm();
  const double spacing = 0.5 * radius_;
  if (length > spacing) {
    const auto samples = static_cast<int>(std::ceil(length / spacing));
    for (int i = 1; i < samples; ++i) {
      if (overlaps(from + (static_cast<double>(i) / samples) * move, t)) {
        to = from + (static_cast<double>(i - 1) / samples) * move;
        break;
      }
    }
  }
  for (int pass = 0; pass < projection_passes; ++pass) {
    bool moved = false;
    for_each_near(to, [&](std::uint32_t, const Obstacle& obstacle) {
      const ObstacleDistance d = distance_to(obstacle, to, t);
      if (d.signed_distance < radius_ - contact_tolerance_m) {
        to = d.nearest + radius_ * d.normal;
        moved = true;
      }
    });
    if (!moved) return true;
  }
  if (!overlaps(to, t)) return true;
  if (!overlaps(from, t)) {
    to = from;
    return true;
  }
  return false;
}

}  // namespace throng::sketch::detail
