#include <throng/core/errors.h>
#include <throng/core/obstacle.h>
#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace throng;
using Approx = Catch::Detail::Approx;

namespace {
ConvexPolygon unit_square() { return {{{0, 0}, {1, 0}, {1, 1}, {0, 1}}}; }
}  // namespace

TEST_CASE("circle distance is signed and its nearest point lies on the circle") {
  Obstacle o{Circle{{1, 1}, 0.5}, {}, "c"};
  const auto out = distance_to(o, {3, 1}, 0);
  CHECK(out.signed_distance == Approx(1.5));
  CHECK(out.nearest.isApprox(Eigen::Vector2d(1.5, 1)));
  const auto in = distance_to(o, {1.2, 1}, 0);
  CHECK(in.signed_distance == Approx(-0.3));
  CHECK(in.normal.isApprox(Eigen::Vector2d(1, 0)));
}

TEST_CASE("polygon distance: outside, inside and the outward normal") {
  Obstacle o{unit_square(), {}, "sq"};
  CHECK(distance_to(o, {2, 0.5}, 0).signed_distance == Approx(1.0));
  CHECK(distance_to(o, {2, 2}, 0).signed_distance == Approx(std::sqrt(2.0)));
  const auto in = distance_to(o, {0.9, 0.5}, 0);
  CHECK(in.signed_distance == Approx(-0.1));
  CHECK(in.nearest.isApprox(Eigen::Vector2d(1, 0.5)));
  CHECK(in.normal.isApprox(Eigen::Vector2d(1, 0)));
}

TEST_CASE("polygon signed distance agrees with brute-force sampling of the boundary") {
  Obstacle o{ConvexPolygon{{{0, 0}, {2, 0}, {3, 1}, {1, 2}}}, {}, "quad"};
  Rng rng(7);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d p(rng.uniform(-1, 4), rng.uniform(-1, 3));
    double best = 1e9;
    const auto& v = std::get<ConvexPolygon>(o.shape).vertices;
    for (std::size_t k = 0; k < v.size(); ++k) {
      for (int s = 0; s <= 2000; ++s) {
        const Eigen::Vector2d q = v[k] + (v[(k + 1) % v.size()] - v[k]) * (s / 2000.0);
        best = std::min(best, (p - q).norm());
      }
    }
    const auto d = distance_to(o, p, 0);
    CHECK(std::abs(d.signed_distance) == Approx(best).margin(2e-3));
    CHECK((p - d.nearest).norm() == Approx(std::abs(d.signed_distance)).margin(1e-12));
  }
}

TEST_CASE("wall is a capsule of half its thickness") {
  Obstacle o{Wall{{0, 0}, {4, 0}, 0.2}, {}, "w"};
  CHECK(distance_to(o, {2, 1}, 0).signed_distance == Approx(0.9));
  CHECK(distance_to(o, {5, 0}, 0).signed_distance == Approx(0.9));
  CHECK(distance_to(o, {2, 0.05}, 0).signed_distance == Approx(-0.05));
}

TEST_CASE("moving obstacle follows its pose keys and holds them outside") {
  Obstacle o{Circle{{0, 0}, 1}, {{0, {0, 0}, 0}, {2, {4, 0}, 0}}, "m"};
  CHECK(distance_to(o, {2, 0}, 1).signed_distance == Approx(-1));
  CHECK(distance_to(o, {4, 0}, 5).signed_distance == Approx(-1));
  CHECK(distance_to(o, {0, 0}, -3).signed_distance == Approx(-1));
  const auto box = bounds_over(o, 0, 2);
  CHECK(box.contains(Eigen::Vector2d(-1, 0)));
  CHECK(box.contains(Eigen::Vector2d(5, 0)));
}

TEST_CASE("rotating polygon: the pose rotates the shape about its local origin") {
  Obstacle o{unit_square(), {{0, {0, 0}, 0}, {1, {0, 0}, std::numbers::pi / 2}}, "r"};
  // At t = 1 the square covers [-1, 0] × [0, 1].
  CHECK(distance_to(o, {-0.5, 0.5}, 1).signed_distance < 0);
  CHECK(distance_to(o, {0.5, 0.5}, 1).signed_distance > 0);
  CHECK(bounds_at(o, 1).contains(Eigen::Vector2d(-0.9, 0.9)));
}

TEST_CASE("validate rejects a clockwise polygon, a zero radius and decreasing keys") {
  CHECK_THROWS_AS(validate(Obstacle{ConvexPolygon{{{0, 0}, {0, 1}, {1, 1}, {1, 0}}}, {}, ""}, "p"), InputError);
  CHECK_THROWS_WITH(validate(Obstacle{Circle{{0, 0}, 0}, {}, ""}, "obstacle 3"), Catch::Contains("obstacle 3"));
  CHECK_THROWS_AS(validate(Obstacle{Circle{{0, 0}, 1}, {{1, {0, 0}, 0}, {1, {1, 0}, 0}}, ""}, "m"), InputError);
  CHECK_NOTHROW(validate(Obstacle{unit_square(), {}, ""}, "ok"));
}
