#include "walkable_area.h"

#include <throng/core/errors.h>

#include <boost/geometry/algorithms/area.hpp>
#include <boost/geometry/algorithms/correct.hpp>
#include <boost/geometry/algorithms/difference.hpp>
#include <boost/geometry/algorithms/union.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/io/wkt/write.hpp>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>
#include <variant>

namespace throng::detail {
namespace {

namespace bg = boost::geometry;
using Point = bg::model::d2::point_xy<double>;
using Polygon = bg::model::polygon<Point, false>;  // counter-clockwise outer rings, closed
using MultiPolygon = bg::model::multi_polygon<Polygon>;

constexpr int circle_sides = 32;
constexpr double min_wall_width = 0.01;  // m: an ideal (zero-thickness) wall still blocks
constexpr double margin = 1.0;           // m around the agents and obstacles when the scene has no region

// The capsule of points within r of the segment a–b (a circle when a = b) as a polygon around it: each round end
// a half n-gon whose sides touch the circle (vertices at r / cos(π/n)), so the whole capsule is excluded.
Polygon around_capsule(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double r) {
  const double R = r / std::cos(EIGEN_PI / circle_sides);
  const Eigen::Vector2d d = b - a;
  const double theta = d.norm() > 0 ? std::atan2(d.y(), d.x()) : 0.0;
  Polygon p;
  // Counter-clockwise: around b from θ − 90° to θ + 90°, then around a from θ + 90° to θ + 270°.
  for (const auto& [centre, start] : {std::pair{b, theta - EIGEN_PI / 2}, std::pair{a, theta + EIGEN_PI / 2}}) {
    for (int i = 0; i <= circle_sides / 2; ++i) {
      const double angle = start + 2 * EIGEN_PI * i / circle_sides;
      bg::append(p.outer(), Point(centre.x() + R * std::cos(angle), centre.y() + R * std::sin(angle)));
    }
  }
  bg::append(p.outer(), p.outer().front());
  bg::correct(p);
  return p;
}

MultiPolygon obstacle_area(const Obstacle& ob) {
  MultiPolygon out;
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Circle>) {
          out.push_back(around_capsule(s.center, s.center, s.radius));
        } else if constexpr (std::is_same_v<S, ConvexPolygon>) {
          Polygon p;
          for (const auto& v : s.vertices) bg::append(p.outer(), Point(v.x(), v.y()));
          bg::append(p.outer(), Point(s.vertices.front().x(), s.vertices.front().y()));
          bg::correct(p);
          out.push_back(p);
        } else {
          out.push_back(around_capsule(s.a, s.b, std::max(s.thickness, min_wall_width) / 2));
        }
      },
      ob.shape);
  return out;
}

Polygon outer_boundary(const CrowdFile& crowd) {
  Eigen::AlignedBox2d box;
  if (crowd.scene.region) {
    box.extend(crowd.scene.region->min);
    box.extend(crowd.scene.region->max);
  } else {
    const CrowdMotion& m = crowd.motion;
    for (std::size_t t = 0; t < m.frame_count(); ++t) {
      for (std::size_t n = 0; n < m.agent_count(); ++n) {
        if (m.present(t, n)) box.extend(Eigen::Vector2d(m.position(t, n).head<2>()));
      }
    }
    for (const Obstacle& ob : crowd.scene.obstacles) {
      if (!ob.is_moving()) box.extend(bounds_at(ob, 0.0));
    }
    box.min().array() -= margin;
    box.max().array() += margin;
  }
  Polygon p;
  for (const Eigen::Vector2d& c : {box.corner(Eigen::AlignedBox2d::BottomLeft), box.corner(Eigen::AlignedBox2d::BottomRight),
                                   box.corner(Eigen::AlignedBox2d::TopRight), box.corner(Eigen::AlignedBox2d::TopLeft),
                                   box.corner(Eigen::AlignedBox2d::BottomLeft)}) {
    bg::append(p.outer(), Point(c.x(), c.y()));
  }
  return p;
}

}  // namespace

std::string walkable_area_wkt(const CrowdFile& crowd) {
  MultiPolygon blocked;
  std::size_t static_count = 0;
  for (const Obstacle& ob : crowd.scene.obstacles) {
    if (ob.is_moving()) continue;
    ++static_count;
    MultiPolygon merged;
    bg::union_(blocked, obstacle_area(ob), merged);
    blocked = std::move(merged);
  }
  if (static_count == 0) {
    throw ConfigError(std::string("a walkable area was asked for, but the crowd has no ") +
                      (crowd.scene.obstacles.empty() ? "obstacles" : "static obstacles (its obstacles all move)") +
                      " to build it from; export without the walkable area");
  }
  MultiPolygon free;
  bg::difference(outer_boundary(crowd), blocked, free);
  if (free.empty()) throw InputError("the crowd's obstacles cover its whole area: no walkable area is left");
  const auto largest = std::max_element(free.begin(), free.end(), [](const Polygon& a, const Polygon& b) { return bg::area(a) < bg::area(b); });
  std::ostringstream wkt;
  wkt << std::setprecision(17) << bg::wkt(*largest);
  return wkt.str();
}

}  // namespace throng::detail
