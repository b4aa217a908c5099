// Split, merge and transform: exact data in, exact data out, formation edges across merged groups, the id and
// timeline decisions, and the errors (empty selections, non-overlapping spans).
#include "../graph/synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/graph/motion_graph.h>
#include <throng/stitch/merge.h>
#include <throng/stitch/split.h>
#include <throng/stitch/transform.h>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

using namespace throng;
using namespace throng::stitch;

namespace {

CrowdMotion shifted_in_space(CrowdMotion c, double dx, double dy) {
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) {
      c.position(f, a).x() += dx;
      c.position(f, a).y() += dy;
    }
  }
  return c;
}

}  // namespace

TEST_CASE("a split by time keeps every value and the halves share the cut frame") {
  CrowdMotion c = test::marching_grid(2, 3, 30);
  c.velocities.assign(c.positions.size(), 0.5);
  c.species = {0, 1, 0, 1, 2, 2};
  const TimeSplit s = split_at_frame(c, 12);
  REQUIRE(s.first.frame_count() == 13);
  REQUIRE(s.second.frame_count() == 18);
  CHECK(s.first.frame_count() + s.second.frame_count() - 1 == c.frame_count());
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < 6; ++a) {
      if (f <= 12) CHECK(s.first.position(f, a) == c.position(f, a));
      if (f >= 12) CHECK(s.second.position(f - 12, a) == c.position(f, a));
    }
  }
  CHECK(s.second.times.front() == c.times[12]);
  CHECK(s.first.species == c.species);
  CHECK(s.second.velocities.size() == s.second.positions.size());
  CHECK(frame_nearest(c, 1.24) == 12);
  CHECK(frame_nearest(c, 1.26) == 13);
  CHECK_THROWS_AS(split_at_frame(c, 0), ConfigError);
  CHECK_THROWS_WITH(split_at_frame(c, 29), Catch::Contains("expected a frame in [1, 28]"));
  CHECK_THROWS_AS(frame_nearest(c, 10.0), ConfigError);
  // A part keeps the agents present somewhere in it, or (present_throughout) at all of it.
  for (std::size_t f = 20; f < 30; ++f) c.position(f, 4) << absent, absent, absent;
  for (std::size_t f = 0; f < 5; ++f) c.position(f, 5) << absent, absent, absent;
  CHECK(split_at_frame(c, 22).second.agent_count() == 5);
  CHECK(slice_frames(c, 0, 10, true).agent_count() == 5);
  CHECK(slice_frames(c, 0, 10, false).agent_count() == 6);
}

TEST_CASE("a split by agents takes ids or species, or the rest and empty selections are errors") {
  CrowdMotion c = test::marching_grid(2, 3, 10);  // ids 100..105
  c.species = {0, 1, 0, 1, 2, 2};
  const std::vector<std::size_t> chosen = select_agents(c, {{101}, {2}});
  CHECK(chosen == std::vector<std::size_t>{1, 4, 5});
  CHECK(select_agents(c, {{101}, {2}}, true) == std::vector<std::size_t>{0, 2, 3});
  const CrowdMotion part = take_agents(c, chosen);
  CHECK(part.ids == std::vector<std::int64_t>{101, 104, 105});
  CHECK(part.position(7, 1) == c.position(7, 4));
  CHECK_THROWS_AS(select_agents(c, {}), ConfigError);
  CHECK_THROWS_WITH(select_agents(c, {}), Catch::Contains("empty agent selection"));
  CHECK_THROWS_WITH(select_agents(c, {{7}, {}}), Catch::Contains("no agent with id 7") && Catch::Contains("100, 101"));
  CHECK_THROWS_WITH(select_agents(c, {{}, {9}}), Catch::Contains("no agent has species 9") && Catch::Contains("0, 1, 2"));
  CHECK_THROWS_AS(select_agents(c, {{}, {0, 1, 2}}, true), InputError);
}

TEST_CASE("two groups sharing a time span merge into one graph with formation edges across them") {
  const CrowdMotion a = test::marching_grid(3, 3, 20, 1.0);            // ids 100..108
  const CrowdMotion b = shifted_in_space(test::marching_grid(2, 4, 20, 1.0), 0.0, 3.5);  // beside it, ids 100..107
  Scene sa, sb;
  sa.obstacles.push_back({Circle{{5, 5}, 1}, {}, "a"});
  sb.obstacles.push_back({Circle{{9, 5}, 1}, {}, "b"});
  const Merged m = merge(a, sa, b, sb);
  REQUIRE(m.crowd.agent_count() == 17);
  CHECK(m.crowd.frame_count() == 20);
  CHECK(m.scene.obstacles.size() == 2);
  // Ids clash (100..107): the second group's ids are shifted above the first's largest (108).
  CHECK(m.report.id_shift == 9);
  CHECK(m.crowd.ids[9] == 109);
  CHECK(m.crowd.ids.back() == 116);
  m.crowd.validate();
  CHECK(m.report.interpolated_frames_first + m.report.interpolated_frames_second == 0);
  CHECK(m.crowd.position(7, 12) == b.position(7, 3));
  CHECK(m.report.cross_edges > 0);
  // The motion graph of the merged crowd triangulates the union: edges join the groups at every sample.
  ClipOptions whole;
  const MotionGraph graph = build_motion_graph(make_clip(m.crowd, whole), {});
  for (const auto& edges : graph.edges) {
    std::size_t across = 0;
    for (const auto& e : edges) across += (e[0] < 9) != (e[1] < 9);
    CHECK(across >= 2);
  }
  MergeOptions strict;
  strict.on_id_clash = IdClash::error;
  CHECK_THROWS_WITH(merge(a, sa, b, sb, strict), Catch::Contains("8 agent ids are in both crowds"));

  // A long-edge threshold drops exactly the stored edges longer than it, across the groups and within them.
  double longest = 0;
  for (const auto& e : m.formation_edges) {
    longest = std::max(longest, (m.crowd.position(m.report.formation_frame, static_cast<std::size_t>(e[0])) -
                                 m.crowd.position(m.report.formation_frame, static_cast<std::size_t>(e[1]))).head<2>().norm());
  }
  MergeOptions short_edges;
  short_edges.max_edge_length = 1.6;
  REQUIRE(longest > short_edges.max_edge_length);
  const Merged cut = merge(a, sa, b, sb, short_edges);
  std::size_t kept = 0;
  for (const auto& e : m.formation_edges) {
    kept += (m.crowd.position(m.report.formation_frame, static_cast<std::size_t>(e[0])) -
             m.crowd.position(m.report.formation_frame, static_cast<std::size_t>(e[1]))).head<2>().norm() <= 1.6;
  }
  CHECK(cut.formation_edges.size() == kept);
  CHECK(cut.formation_edges.size() < m.formation_edges.size());
  CHECK(cut.report.cross_edges > 0);  // the groups stand 3.5 m apart centre to centre: their near rows stay joined
  CHECK(cut.report.cross_edges <= m.report.cross_edges);
  short_edges.max_edge_length = -1;
  CHECK_THROWS_WITH(merge(a, sa, b, sb, short_edges), Catch::Contains("max_edge_length"));
}

TEST_CASE("merging crowds whose spans do not overlap is an error unless the union is asked for") {
  const CrowdMotion a = test::marching_grid(2, 2, 10);  // 0 .. 0.9 s
  CrowdMotion b = test::marching_grid(2, 2, 10);
  for (double& t : b.times) t += 2.0;  // 2 .. 2.9 s
  CHECK_THROWS_AS(merge(a, {}, b, {}), InputError);
  CHECK_THROWS_WITH(merge(a, {}, b, {}), Catch::Contains("do not overlap") && Catch::Contains("[0, 0.9] s"));
  MergeOptions u;
  u.span = MergeSpan::union_of_spans;
  const Merged m = merge(a, {}, b, {}, u);
  CHECK(m.crowd.frame_count() == 20);
  CHECK(m.crowd.present(3, 0));
  CHECK_FALSE(m.crowd.present(13, 0));
  CHECK(m.crowd.present(13, 5));
  CHECK(m.report.cross_edges == 0);
  // Overlapping by a single frame is too little for a merged group.
  CrowdMotion touching = test::marching_grid(2, 2, 10);
  for (double& t : touching.times) t += 0.9;
  CHECK_THROWS_WITH(merge(a, {}, touching, {}), Catch::Contains("1 frame only"));
}

TEST_CASE("crowds on different frame times are merged on the union of their times through splines") {
  // Straight walks at constant speed: cubic splines reproduce them exactly at the other crowd's times.
  const CrowdMotion a = test::marching_grid(2, 2, 21, 1.0, 1.3, 0.1, 0.0, 0.0);
  CrowdMotion b = shifted_in_space(test::marching_grid(2, 2, 21, 1.0, 1.3, 0.1, 0.0, 0.0), 0, 5);
  for (double& t : b.times) t += 0.05;
  const Merged m = merge(a, {}, b, {});
  // Overlap 0.05 .. 2.0 s: a's frames 1..20 (0.1 .. 2.0 s) and b's 0..19 (0.05 .. 1.95 s), interleaved; each crowd
  // is interpolated at the other's 20 times.
  CHECK(m.crowd.frame_count() == 40);
  CHECK(m.report.interpolated_frames_first == 20);
  CHECK(m.report.interpolated_frames_second == 20);
  for (std::size_t g = 0; g < m.crowd.frame_count(); ++g) {
    const double t = m.crowd.times[g];
    for (std::size_t k = 0; k < 4; ++k) {
      CHECK(m.crowd.position(g, k).x() == Approx(a.position(0, k).x() + 1.3 * t).margin(1e-12));
      CHECK(m.crowd.position(g, 4 + k).x() == Approx(b.position(0, k).x() + 1.3 * (t - 0.05)).margin(1e-12));
    }
  }
}

TEST_CASE("a transform moves the crowd and its scene rigidly and retimes them") {
  CrowdMotion c = test::marching_grid(2, 3, 11);
  c.velocities.assign(c.positions.size(), 0.0);
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < 6; ++a) c.velocities[c.index(f, a)] = 1.2;
  }
  Scene s;
  s.obstacles.push_back({Circle{{4, 0}, 1}, {}, "pillar"});
  s.obstacles.push_back({ConvexPolygon{{{0, -5}, {1, -5}, {1, -4}}}, {}, "kiosk"});
  s.obstacles.push_back({Circle{{0, 0}, 0.5}, {{0.0, {1, 1}, 0.0}, {1.0, {2, 1}, 0.0}}, "cart"});
  s.region = Region{{-10, -10}, {10, 10}, 0, 5, {true, false, false}};
  CrowdMotion moved = c;
  Scene moved_scene = s;
  TransformOptions o;
  o.rotation = std::numbers::pi / 2;
  o.pivot = Eigen::Vector2d(1, 1);
  o.translation = {10, 0};
  o.time_scale = 2;
  o.time_shift = 3;
  o.id_offset = 1000;
  o.species = 4;
  transform(moved, moved_scene, o);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(o.rotation).toRotationMatrix();
  auto expect = [&](const Eigen::Vector2d& p) -> Eigen::Vector2d { return Eigen::Vector2d(1, 1) + R * (p - Eigen::Vector2d(1, 1)) + o.translation; };
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    CHECK(moved.times[f] == Approx(2 * c.times[f] + 3));
    for (std::size_t a = 0; a < 6; ++a) CHECK((moved.position(f, a).head<2>() - expect(c.position(f, a).head<2>())).norm() <= 1e-12);
  }
  CHECK(moved.velocities[moved.index(3, 2) + 1] == Approx(0.6));  // (1.2, 0) rotated by 90°, halved
  CHECK(moved.ids.front() == 1100);
  CHECK(moved.species == std::vector<std::int32_t>(6, 4));
  CHECK((std::get<Circle>(moved_scene.obstacles[0].shape).center - expect({4, 0})).norm() <= 1e-12);
  CHECK((std::get<ConvexPolygon>(moved_scene.obstacles[1].shape).vertices[2] - expect({1, -4})).norm() <= 1e-12);
  // The cart: its pose at the retimed time is the moved pose.
  const Eigen::Vector2d cart_then = pose_at(s.obstacles[2], 0.5) * Eigen::Vector2d(0.5, 0);
  const Eigen::Vector2d cart_now = pose_at(moved_scene.obstacles[2], 2 * 0.5 + 3) * Eigen::Vector2d(0.5, 0);
  CHECK((cart_now - expect(cart_then)).norm() <= 1e-12);
  // A quarter turn swaps the region's periodic axes.
  CHECK(moved_scene.region->periodic == std::array<bool, 3>{false, true, false});
  CHECK(moved_scene.region->t1 == Approx(13));
  moved_scene.validate();

  SECTION("a new frame rate resamples through splines") {
    CrowdMotion straight = test::marching_grid(1, 2, 11, 1.0, 1.5, 0.1, 0.0, 0.0);
    Scene none;
    TransformOptions r;
    r.frame_rate_hz = 25;
    transform(straight, none, r);
    CHECK(straight.frame_count() == 26);
    CHECK(straight.position(5, 1).x() == Approx(1.5 * 0.2 + straight.position(0, 1).x()).margin(1e-12));
  }
  SECTION("bad values are errors") {
    TransformOptions bad;
    bad.time_scale = 0;
    CHECK_THROWS_AS(transform(moved, moved_scene, bad), ConfigError);
    bad = TransformOptions{};
    bad.id_offset = -2000;
    CHECK_THROWS_WITH(transform(moved, moved_scene, bad), Catch::Contains("negative id"));
  }
}
