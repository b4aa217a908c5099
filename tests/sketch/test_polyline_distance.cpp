// PolylineDistance (solver/sketch/src/polyline.h): the pruned query must give distance_to_polyline's bits for any
// polyline and point, since the agents' stroke weights (Eq. 2–3) come from it.
#include "polyline.h"

#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <vector>

using throng::Rng;
using throng::sketch::detail::distance_to_polyline;
using throng::sketch::detail::PolylineDistance;

namespace {

bool same_bits(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

// A random walk of `count` points from `origin`: steps of up to `step` metres, some of them zero (a repeated
// point), some straight runs (boxes of zero height).
std::vector<Eigen::Vector2d> walk(Rng& rng, std::size_t count, const Eigen::Vector2d& origin, double step) {
  std::vector<Eigen::Vector2d> points{origin};
  while (points.size() < count) {
    const double kind = rng.uniform();
    if (kind < 0.05) {
      points.push_back(points.back());
    } else if (kind < 0.2) {
      for (int i = 0; i < 20 && points.size() < count; ++i) points.push_back(points.back() + Eigen::Vector2d(step, 0));
    } else {
      points.push_back(points.back() + Eigen::Vector2d(rng.uniform(-step, step), rng.uniform(-step, step)));
    }
  }
  return points;
}

}  // namespace

TEST_CASE("the pruned distance to a polyline equals the full scan bit for bit") {
  Rng rng(11);
  for (std::size_t count : {1, 2, 3, 16, 17, 33, 300, 2000}) {
    for (const Eigen::Vector2d& origin : {Eigen::Vector2d(0, 0), Eigen::Vector2d(1e5, -3e4)}) {
      const std::vector<Eigen::Vector2d> points = walk(rng, count, origin, 1.5);
      const PolylineDistance distance(points);
      for (int q = 0; q < 400; ++q) {
        Eigen::Vector2d p;
        const double kind = rng.uniform();
        const Eigen::Vector2d& vertex = points[rng.below(points.size())];
        if (kind < 0.2) {
          p = vertex;  // on the polyline: distance 0
        } else if (kind < 0.4) {
          const Eigen::Vector2d& next = points[std::min(points.size() - 1, static_cast<std::size_t>(&vertex - points.data()) + 1)];
          p = vertex + rng.uniform() * (next - vertex);  // on a segment, up to rounding
        } else if (kind < 0.9) {
          p = vertex + Eigen::Vector2d(rng.normal(), rng.normal()) * 3.0;  // near
        } else {
          p = vertex + Eigen::Vector2d(rng.uniform(-1e4, 1e4), rng.uniform(-1e4, 1e4));  // far
        }
        INFO(count << " points from (" << origin.x() << ", " << origin.y() << "), query (" << p.x() << ", " << p.y() << ")");
        REQUIRE(same_bits(distance(p), distance_to_polyline(points, p)));
      }
    }
  }
}

TEST_CASE("the pruned distance finds the nearest run wherever it lies along the polyline") {
  // A long straight stroke east, then back west 2 m to the north: a point just south of the return leg's end
  // (near the stroke's start) is nearest to the last run although the first run's box is as near.
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i <= 100; ++i) points.emplace_back(i, 0);
  for (int i = 100; i >= 0; --i) points.emplace_back(i, 2);
  const PolylineDistance distance(points);
  CHECK(distance({50, 1.5}) == Approx(0.5));
  CHECK(distance({50, 0.25}) == Approx(0.25));
  CHECK(distance({-3, 2}) == Approx(3));
  CHECK(distance({200, 1}) == Approx(100));  // the turn (100, 0) → (100, 2)
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(50, 1.5), Eigen::Vector2d(0.5, 1.9), Eigen::Vector2d(99.5, 1.0)}) {
    CHECK(same_bits(distance(p), distance_to_polyline(points, p)));
  }
}
