// Branch splits (FormationOptions::splits): every formation edge between a set of agents and the rest is cut
// over a frame range, and nothing else changes.
#include "synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/graph/features.h>
#include <throng/graph/motion_graph.h>

#include <catch2/catch.hpp>

#include <algorithm>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

// A 3 × 4 grid over 21 frames; the split side is agents 100..105 (graph agents 0..5: the first two rows across).
const std::vector<std::int64_t> side_ids{100, 101, 102, 103, 104, 105};
bool on_side(int agent) { return agent < 6; }

FormationOptions split_over(std::size_t first, std::size_t last) {
  FormationOptions o;
  o.splits.push_back({side_ids, first, last});
  return o;
}

}  // namespace

TEST_CASE("split: no formation edge or triangle crosses the cut inside its range, everything else is as before") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 21, 1.0, 1.2, 0.1, 0.4, 0.2);
  const MotionGraph whole = build_motion_graph(make_clip(crowd, {}), {});
  const MotionGraph cut = build_motion_graph(make_clip(crowd, {}), split_over(8, 15));
  std::size_t crossing_before = 0;
  for (std::size_t i = 0; i < whole.sample_count(); ++i) {
    const bool inside = i >= 8 && i <= 15;  // sample i is frame i (sample step 1)
    std::vector<std::array<int, 2>> kept;  // the edges that do not cross
    for (const auto& e : whole.edges[i]) {
      if (on_side(e[0]) == on_side(e[1])) {
        kept.push_back(e);
      } else if (inside) {
        ++crossing_before;
      }
    }
    if (inside) {
      CHECK(cut.edges[i] == kept);
      for (const auto& t : cut.triangles[i]) {
        CHECK((on_side(t[0]) == on_side(t[1]) && on_side(t[1]) == on_side(t[2])));
      }
      // The triangles within a side are all still there.
      for (const auto& t : whole.triangles[i]) {
        if (on_side(t[0]) == on_side(t[1]) && on_side(t[1]) == on_side(t[2])) {
          CHECK(std::binary_search(cut.triangles[i].begin(), cut.triangles[i].end(), t));
        }
      }
    } else {
      CHECK(cut.edges[i] == whole.edges[i]);
      CHECK(cut.triangles[i] == whole.triangles[i]);
    }
  }
  CHECK(crossing_before >= 8 * 3);  // the grid's rows are joined by at least 3 edges at every sample
}

TEST_CASE("split: temporal features stay, spatiotemporal ones across the cut go inside the range only") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 21, 1.0, 1.2, 0.1, 0.4, 0.2);
  const MotionGraph whole = build_motion_graph(make_clip(crowd, {}), {});
  const MotionGraph cut = build_motion_graph(make_clip(crowd, {}), split_over(8, 15));
  const FeatureSet a = compute_features(whole, {}), b = compute_features(cut, {});
  CHECK(b.temporal.size() == a.temporal.size());
  CHECK(b.spatiotemporal.size() < a.spatiotemporal.size());
  CHECK(b.spatial.size() < a.spatial.size());
  const auto n = static_cast<int>(cut.agent_count());
  for (const Feature& f : b.spatiotemporal) {  // (v(i−1, j), v(i, j), v(i, k)): j and k joined at sample i
    const int i = f.v / n, j = f.v % n, k = f.w % n;
    if (i >= 8 && i <= 15) CHECK(on_side(j) == on_side(k));
  }
}

TEST_CASE("split: an edge added across the cut is cut inside the split's range") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 11, 1.0, 1.2, 0.1, 0.0, 0.1);
  FormationOptions o = split_over(5, 10);
  o.edits.push_back({100, 111, 0, 10, true});  // graph agents 0 and 11: across the cut
  const MotionGraph g = build_motion_graph(make_clip(crowd, {}), o);
  const std::array<int, 2> added{0, 11};
  CHECK(std::binary_search(g.edges[4].begin(), g.edges[4].end(), added));
  CHECK_FALSE(std::binary_search(g.edges[5].begin(), g.edges[5].end(), added));
}

TEST_CASE("split: bad splits are configuration errors naming the entry") {
  const CrowdMotion crowd = test::marching_grid(2, 2, 5);
  auto build = [&](FormationSplit split) {
    FormationOptions o;
    o.splits = {FormationSplit{{100}, 0, 4}, split};
    return build_motion_graph(make_clip(crowd, {}), o);
  };
  CHECK_THROWS_WITH(build({{}, 0, 4}), Contains("formation.splits[1].agents: no agent given"));
  CHECK_THROWS_WITH(build({{100, 999}, 0, 4}), Contains("formation.splits[1].agents[1]: agent 999 is not in the clip"));
  CHECK_THROWS_WITH(build({{101, 101}, 0, 4}), Contains("formation.splits[1].agents[1]: agent 101 is named twice"));
  CHECK_THROWS_WITH(build({{100, 101, 102, 103}, 0, 4}), Contains("formation.splits[1].agents: all 4 agents of the clip are on one side"));
  CHECK_THROWS_WITH(build({{101}, 3, 2}), Contains("formation.splits[1]: first_frame 3 is after last_frame 2"));
  CHECK_THROWS_WITH(build({{101}, 7, 9}), Contains("formation.splits[1]: frames [7, 9] hold no sample of the clip [0, 4]"));
  CHECK_THROWS_AS(build({{101}, 7, 9}), ConfigError);
}
