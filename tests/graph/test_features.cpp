#include "synthetic_crowd.h"

#include <throng/core/parallel.h>
#include <throng/graph/features.h>

#include <catch2/catch.hpp>

#include <complex>

using namespace throng;
using Complex = std::complex<double>;

namespace {

Complex at(const Clip& clip, int vertex) { return {clip.positions(vertex, 0), clip.positions(vertex, 1)}; }

// The prediction f_c(u, w) of Eq. 2 at the given positions.
Complex predict(const Feature& f, const Clip& clip) {
  const Complex u = at(clip, f.u), w = at(clip, f.w);
  return u + f.c * (w - u) + f.offset;
}

MotionGraph graph_of(const CrowdMotion& crowd) { return build_motion_graph(make_clip(crowd, {}), {}); }

}  // namespace

TEST_CASE("every feature reproduces its vertex on the original graph (Eq. 1-2)") {
  CrowdMotion crowd = test::marching_grid(4, 5, 12, 1.0, 1.2, 0.1, 0.4, 0.2);
  // Agent 3 stands still for three frames: its temporal features there are degenerate.
  for (std::size_t f = 4; f <= 6; ++f) crowd.position(f, 3) = crowd.position(4, 3);
  const MotionGraph g = graph_of(crowd);
  const FeatureSet features = compute_features(g);
  std::size_t degenerate = 0;
  for (const auto* set : {&features.spatial, &features.temporal, &features.spatiotemporal}) {
    for (const Feature& f : *set) {
      // Positions are O(10 m): rounding in c = (v − u)/(w − u) and back leaves ~1e-15 relative.
      CHECK(std::abs(predict(f, g.clip) - at(g.clip, f.v)) < 1e-12);
      if (at(g.clip, f.u) == at(g.clip, f.w)) {
        CHECK(f.c == Complex(0.5, 0));  // the midpoint rule
        ++degenerate;
      }
    }
  }
  CHECK(degenerate == 1);  // the temporal feature at the middle of the three still frames
}

TEST_CASE("feature counts follow the graph: 3 per triangle, N(T-2) temporal, 2 per edge after the first sample") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 9, 1.0, 1.2, 0.1, 0.2, 0.2);
  const MotionGraph g = graph_of(crowd);
  const FeatureSet features = compute_features(g);
  std::size_t triangles = 0, edges_after_first = 0;
  for (std::size_t i = 0; i < g.sample_count(); ++i) {
    triangles += g.triangles[i].size();
    if (i > 0) edges_after_first += g.edges[i].size();
  }
  CHECK(features.spatial.size() == 3 * triangles);
  CHECK(features.temporal.size() == 12 * 7);
  CHECK(features.spatiotemporal.size() == 2 * edges_after_first);
  // Spatiotemporal features predict v(i, j) from v(i − 1, j) and a neighbour at sample i.
  for (const Feature& f : features.spatiotemporal) {
    CHECK(f.u == f.v - 12);
    CHECK(f.w / 12 == f.v / 12);
  }
}

TEST_CASE("local coordinates are invariant to similarity transforms and weights scale as 1/length²") {
  const CrowdMotion crowd = test::marching_grid(3, 3, 8, 1.0, 1.2, 0.1, 0.3, 0.2);
  CrowdMotion moved = crowd;
  const double s = 2.5;
  const Eigen::Rotation2Dd r(0.7);
  for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      const Eigen::Vector2d p = s * (r * crowd.position(f, a).head<2>()) + Eigen::Vector2d(40, -3);
      moved.position(f, a).head<2>() = p;
    }
  }
  const FeatureSet a = compute_features(graph_of(crowd));
  const FeatureSet b = compute_features(graph_of(moved));
  REQUIRE(a.spatial.size() == b.spatial.size());
  REQUIRE(a.spatiotemporal.size() == b.spatiotemporal.size());
  for (std::size_t k = 0; k < a.spatial.size(); ++k) {
    CHECK(std::abs(a.spatial[k].c - b.spatial[k].c) < 1e-12);
    CHECK_THAT(b.spatial[k].weight * s * s, Catch::Matchers::WithinRel(a.spatial[k].weight, 1e-12));
  }
  for (std::size_t k = 0; k < a.temporal.size(); ++k) CHECK(std::abs(a.temporal[k].c - b.temporal[k].c) < 1e-9);
}

TEST_CASE("weights are 1/(|vu|² + |vw|²) with the arm floor") {
  FeatureOptions o;
  o.min_length = 0.5;
  const Feature f = make_feature(0, 1, 2, {0, 0}, {1, 0}, {1, 2}, o);
  CHECK_THAT(f.weight, Catch::Matchers::WithinRel(1.0 / (1.0 + 4.0), 1e-15));
  CHECK(std::abs(f.c - Complex(0.2, -0.4)) < 1e-15);  // (1 − 0)/(1 + 2i) = (1 − 2i)/5
  const Feature still = make_feature(0, 1, 2, {3, 3}, {3, 3}, {3, 3}, o);
  CHECK(still.weight == 1.0 / 0.25);
  CHECK(still.c == Complex(0.5, 0));
}

TEST_CASE("features do not depend on the thread count") {
  const CrowdMotion crowd = test::marching_grid(5, 6, 30, 1.0, 1.2, 0.1, 0.3, 0.3);
  FeatureSet one, two;
  {
    ThreadLimit limit(1);
    one = compute_features(graph_of(crowd));
  }
  {
    ThreadLimit limit(2);
    two = compute_features(graph_of(crowd));
  }
  auto same = [](const std::vector<Feature>& x, const std::vector<Feature>& y) {
    if (x.size() != y.size()) return false;
    for (std::size_t k = 0; k < x.size(); ++k) {
      if (x[k].u != y[k].u || x[k].v != y[k].v || x[k].w != y[k].w || x[k].c != y[k].c || x[k].weight != y[k].weight) return false;
    }
    return true;
  };
  CHECK(same(one.spatial, two.spatial));
  CHECK(same(one.temporal, two.temporal));
  CHECK(same(one.spatiotemporal, two.spatiotemporal));
}
