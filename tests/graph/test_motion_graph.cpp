#include "synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/graph/delaunay.h>
#include <throng/graph/motion_graph.h>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

bool has_edge(const MotionGraph& g, std::size_t sample, int a, int b) {
  const std::array<int, 2> e{std::min(a, b), std::max(a, b)};
  return std::binary_search(g.edges[sample].begin(), g.edges[sample].end(), e);
}

Clip clip_of(const CrowdMotion& crowd) { return make_clip(crowd, {}); }

}  // namespace

TEST_CASE("without options the formation edges are each sample's Delaunay edges") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 6, 1.0, 1.2, 0.1, 0.5);
  const MotionGraph g = build_motion_graph(clip_of(crowd), {});
  REQUIRE(g.edges.size() == 6);
  for (std::size_t i = 0; i < 6; ++i) {
    const auto dt = delaunay_2d(g.clip.positions.middleRows(g.clip.vertex(i, 0), 12));
    CHECK(g.edges[i] == dt.edges);
    CHECK(g.triangles[i] == dt.triangles);
  }
}

TEST_CASE("the long-edge threshold drops exactly the edges longer than it, and their triangles") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 3, 1.0, 1.2, 0.1, 0.0, 0.2);
  const double limit = 1.3;
  FormationOptions options;
  options.max_edge_length = limit;
  const MotionGraph g = build_motion_graph(clip_of(crowd), options);
  for (std::size_t i = 0; i < g.sample_count(); ++i) {
    const auto points = g.clip.positions.middleRows(g.clip.vertex(i, 0), 12);
    const auto dt = delaunay_2d(points);
    std::size_t kept = 0;
    for (const auto& e : dt.edges) {
      const double length = (points.row(e[0]) - points.row(e[1])).norm();
      CHECK(has_edge(g, i, e[0], e[1]) == (length <= limit));
      kept += length <= limit;
    }
    CHECK(g.edges[i].size() == kept);
    for (const auto& t : g.triangles[i]) {
      for (int k = 0; k < 3; ++k) CHECK(has_edge(g, i, t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)]));
    }
  }
}

TEST_CASE("user edits add and remove edges over their frame range only") {
  // Agents 0..3 in a row (ids 100..103): Delaunay joins neighbours only (collinear points), plus jitter makes
  // triangles; an added edge 100–102 closes a triangle with 101.
  const CrowdMotion crowd = test::marching_grid(1, 4, 10, 1.0, 1.2, 0.1, 0.0, 0.0);
  FormationOptions options;
  options.edits.push_back({100, 102, 2, 5, true});
  options.edits.push_back({102, 103, 4, std::numeric_limits<std::size_t>::max(), false});
  const MotionGraph g = build_motion_graph(clip_of(crowd), options);
  for (std::size_t i = 0; i < 10; ++i) {
    CAPTURE(i);
    CHECK(has_edge(g, i, 0, 1));
    CHECK(has_edge(g, i, 0, 2) == (i >= 2 && i <= 5));
    CHECK(has_edge(g, i, 2, 3) == (i < 4));
    // Collinear agents: the added edge closes no triangle with a non-zero area.
    CHECK(g.triangles[i].empty());
  }

  // In a 2 × 2 grid (no jitter), Delaunay has 5 edges; add the missing diagonal and both triangles appear.
  const CrowdMotion square = test::marching_grid(2, 2, 2, 1.0, 1.2, 0.1, 0.0, 0.05, 9);
  const MotionGraph plain = build_motion_graph(clip_of(square), {});
  std::array<int, 2> missing{-1, -1};
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b)
      if (!has_edge(plain, 0, a, b)) missing = {a, b};
  REQUIRE(missing[0] >= 0);
  FormationOptions add;
  add.edits.push_back({100 + missing[0], 100 + missing[1], 0, 0, true});
  const MotionGraph edited = build_motion_graph(clip_of(square), add);
  CHECK(edited.edges[0].size() == 6);
  CHECK(edited.triangles[0].size() == 4);  // the two Delaunay triangles and the two the new diagonal closes
  CHECK(edited.edges[1].size() == 5);
}

TEST_CASE("edits naming agents or frames outside the clip are configuration errors") {
  const CrowdMotion crowd = test::marching_grid(2, 2, 10);
  FormationOptions o;
  o.edits.push_back({100, 555, 0, 3, true});
  CHECK_THROWS_WITH(build_motion_graph(clip_of(crowd), o), Contains("formation.edits[0]") && Contains("agent 555"));
  o.edits = {{100, 100, 0, 3, true}};
  CHECK_THROWS_WITH(build_motion_graph(clip_of(crowd), o), Contains("two different agents"));
  o.edits = {{100, 101, 20, 30, false}};
  CHECK_THROWS_WITH(build_motion_graph(clip_of(crowd), o), Contains("hold no sample"));
  o.edits.clear();
  o.max_edge_length = -1;
  CHECK_THROWS_AS(build_motion_graph(clip_of(crowd), o), ConfigError);
}

TEST_CASE("the graph does not depend on the thread count") {
  const CrowdMotion crowd = test::marching_grid(6, 7, 40, 1.0, 1.2, 0.1, 0.3, 0.3);
  MotionGraph one, two;
  {
    ThreadLimit limit(1);
    one = build_motion_graph(clip_of(crowd), {});
  }
  {
    ThreadLimit limit(2);
    two = build_motion_graph(clip_of(crowd), {});
  }
  CHECK(one.edges == two.edges);
  CHECK(one.triangles == two.triangles);
}
