#include <throng/core/random.h>
#include <throng/graph/delaunay.h>

#include <catch2/catch.hpp>

#include <set>

using throng::delaunay_2d;

namespace {
using Points = Eigen::Matrix<double, Eigen::Dynamic, 2>;

double orient(const Points& p, const std::array<int, 3>& t) {
  const Eigen::Vector2d a = p.row(t[0]), b = p.row(t[1]), c = p.row(t[2]);
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}
}  // namespace

TEST_CASE("a square with a centre point gives 4 triangles and 8 edges") {
  Points p(5, 2);
  p << 0, 0, 2, 0, 2, 2, 0, 2, 1, 1;
  const auto t = delaunay_2d(p);
  CHECK(t.triangles.size() == 4);
  CHECK(t.edges.size() == 8);
  for (const auto& tri : t.triangles) CHECK(orient(p, tri) > 0);
  CHECK_FALSE(t.has_duplicates());
}

TEST_CASE("random points satisfy Euler's formula and the empty-circle property") {
  throng::Rng rng(11);
  Points p(60, 2);
  for (int i = 0; i < 60; ++i) p.row(i) << rng.uniform(0, 10), rng.uniform(0, 10);
  const auto t = delaunay_2d(p);
  // For a triangulation of n points with h on the hull: triangles = 2n − 2 − h, edges = 3n − 3 − h.
  const long n = 60;
  const long h = 3 * n - 3 - static_cast<long>(t.edges.size());
  CHECK(static_cast<long>(t.triangles.size()) == 2 * n - 2 - h);
  for (const auto& tri : t.triangles) {
    REQUIRE(orient(p, tri) > 0);
    const Eigen::Vector2d a = p.row(tri[0]), b = p.row(tri[1]), c = p.row(tri[2]);
    // Circumcentre of a, b, c.
    const double d = 2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
    const Eigen::Vector2d o((a.squaredNorm() * (b.y() - c.y()) + b.squaredNorm() * (c.y() - a.y()) + c.squaredNorm() * (a.y() - b.y())) / d,
                            (a.squaredNorm() * (c.x() - b.x()) + b.squaredNorm() * (a.x() - c.x()) + c.squaredNorm() * (b.x() - a.x())) / d);
    const double r = (a - o).norm();
    for (int i = 0; i < 60; ++i) {
      if (i == tri[0] || i == tri[1] || i == tri[2]) continue;
      CHECK((Eigen::Vector2d(p.row(i)) - o).norm() >= r * (1 - 1e-9));
    }
  }
}

TEST_CASE("collinear points give a path of edges and no triangles") {
  Points p(4, 2);
  p << 3, 0, 0, 0, 1, 0, 2, 0;
  const auto t = delaunay_2d(p);
  CHECK(t.triangles.empty());
  const std::vector<std::array<int, 2>> expected{{0, 3}, {1, 2}, {2, 3}};
  CHECK(t.edges == expected);
}

TEST_CASE("coincident points are reported against the earlier index") {
  Points p(4, 2);
  p << 0, 0, 1, 0, 0, 1, 1, 0;
  const auto t = delaunay_2d(p);
  CHECK(t.duplicate_of == std::vector<int>{-1, -1, -1, 1});
  CHECK(t.triangles.size() == 1);
}
