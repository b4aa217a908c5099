// Merge as the inverse of split (issue 17): identical obstacles kept once, agents joined by identity (join_by id)
// so a crowd cut in two and merged back is the same crowd, one id at two places an error naming it, and facing and
// actions through split and merge.
#include "positions_by_id.h"
#include "../graph/synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/stitch/merge.h>
#include <throng/stitch/split.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numbers>

using namespace throng;
using namespace throng::stitch;
using Catch::Matchers::Contains;

namespace {

Scene four_walls() {
  Scene s;
  const Eigen::Vector2d corners[] = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  for (int k = 0; k < 4; ++k) s.obstacles.push_back(Obstacle{Wall{corners[k], corners[(k + 1) % 4], 0.1}, {}, ""});
  return s;
}

// A marching grid whose agents come and go: agent 1 leaves after frame 14, agent 4 enters at frame 9, agent 5 is
// present only from frame 20 on (so only the second half of a cut at 15 has it).
CrowdMotion comings_and_goings() {
  CrowdMotion c = test::marching_grid(2, 3, 30);
  c.velocities.assign(c.positions.size(), 0.0);
  for (std::size_t f = 0; f < 30; ++f) {
    for (std::size_t a = 0; a < 6; ++a) {
      const bool gone = (a == 1 && f > 14) || (a == 4 && f < 9) || (a == 5 && f < 20);
      if (gone) {
        c.position(f, a).setConstant(absent);
        Eigen::Map<Eigen::Vector3d>(c.velocities.data() + c.index(f, a)).setConstant(absent);
      } else {
        Eigen::Map<Eigen::Vector3d>(c.velocities.data() + c.index(f, a)) << 1.0, 0.1 * static_cast<double>(a), 0.0;
      }
    }
  }
  c.ids = {11, 12, 13, 14, 15, 16};
  c.species = {1, 1, 2, 2, 3, 3};
  return c;
}


}  // namespace

TEST_CASE("merge keeps one copy of identical obstacles") {
  const CrowdMotion c = test::marching_grid(2, 2, 10);
  const Scene walls = four_walls();
  MergeOptions o;
  o.on_id_clash = IdClash::shift;
  const Merged m = merge(c, walls, c, walls, o);
  CHECK(m.scene.obstacles.size() == 4);
  CHECK(m.report.shared_obstacles == 4);
  // One wall moved by a millimetre is another wall: kept.
  Scene moved = walls;
  std::get<Wall>(moved.obstacles[2].shape).a.x() += 1e-3;
  const Merged n = merge(c, walls, c, moved, o);
  CHECK(n.scene.obstacles.size() == 5);
  CHECK(n.report.shared_obstacles == 3);
  // A circle, and the same wall with another name, are other obstacles.
  Scene other = walls;
  other.obstacles[0].name = "gate";
  other.obstacles.push_back(Obstacle{Circle{{5, 5}, 1.0}, {}, ""});
  Scene scene_with_circle = walls;
  scene_with_circle.obstacles.push_back(Obstacle{Circle{{5, 5}, 1.0}, {}, ""});
  CHECK(merge_scenes(scene_with_circle, other).obstacles.size() == 6);
}

TEST_CASE("the halves of a crowd cut in time and merged joined by id are the crowd again") {
  const CrowdMotion c = comings_and_goings();
  const Scene walls = four_walls();
  const TimeSplit s = split_at_frame(c, 15);
  REQUIRE(s.first.agent_count() == 5);   // agent 16 only comes later
  REQUIRE(s.second.agent_count() == 5);  // agent 12 has left
  MergeOptions o;
  o.span = MergeSpan::union_of_spans;
  o.join_by = JoinBy::id;
  const Merged m = merge(s.first, walls, s.second, walls, o);
  CHECK(m.report.joined == 4);
  CHECK(m.report.id_shift == 0);
  CHECK(m.report.interpolated_frames_first + m.report.interpolated_frames_second == 0);
  REQUIRE(m.crowd.frame_count() == c.frame_count());
  CHECK(m.crowd.times == c.times);
  REQUIRE(m.crowd.agent_count() == c.agent_count());
  const auto original = test::positions_by_id(c), merged = test::positions_by_id(m.crowd);
  REQUIRE(merged.size() == original.size());
  for (const auto& [id, values] : original) {
    INFO("agent " << id);
    REQUIRE(merged.count(id) == 1);
    CHECK(test::same_values(merged.at(id), values));
  }
  CHECK(m.crowd.velocities.size() == m.crowd.positions.size());
  CHECK(m.scene.obstacles.size() == 4);
  for (std::size_t a = 0; a < m.crowd.agent_count(); ++a) {
    const auto at = std::find(c.ids.begin(), c.ids.end(), m.crowd.ids[a]) - c.ids.begin();
    CHECK(m.crowd.species[a] == c.species[static_cast<std::size_t>(at)]);
  }
  m.crowd.validate();

  SECTION("without join_by the people seen in both halves become two agents (renumbered)") {
    o.join_by = JoinBy::none;
    const Merged twice = merge(s.first, walls, s.second, walls, o);
    CHECK(twice.crowd.agent_count() == 10);
    CHECK(twice.report.id_shift == 16 - 11);  // the first half's ids end at 15
    CHECK(twice.report.joined == 0);
  }
  SECTION("the halves may overlap by more than the cut frame where their samples agree") {
    const CrowdMotion head = slice_frames(c, 0, 20), tail = slice_frames(c, 10, 29);
    const Merged again = merge(head, walls, tail, walls, o);
    const auto joined = test::positions_by_id(again.crowd);
    REQUIRE(joined.size() == original.size());
    for (const auto& [id, values] : original) CHECK(test::same_values(joined.at(id), values));
  }
  SECTION("one id at two places at one frame is an error naming the id, the time and the frames") {
    CrowdMotion tail = s.second;
    const auto agent = static_cast<std::size_t>(std::find(tail.ids.begin(), tail.ids.end(), 13) - tail.ids.begin());
    tail.position(0, agent).x() += 0.5;
    CHECK_THROWS_AS(merge(s.first, walls, tail, walls, o), InputError);
    CHECK_THROWS_WITH(merge(s.first, walls, tail, walls, o),
                      Contains("agent 13") && Contains("frame 15 of the first, 0 of the second") && Contains("join_tolerance"));
    // Within the tolerance it is one sample.
    tail.position(0, agent).x() -= 0.5 - 1e-9;
    CHECK_NOTHROW(merge(s.first, walls, tail, walls, o));
    o.join_tolerance_m = -1;
    CHECK_THROWS_AS(merge(s.first, walls, tail, walls, o), ConfigError);
  }
}

TEST_CASE("facing and actions pass through split and merge") {
  CrowdMotion c = comings_and_goings();
  const std::size_t T = c.frame_count(), N = c.agent_count();
  c.orientations.assign(T * N * 4, absent);
  c.actions.assign(T * N, -1);
  c.action_table = standard_actions();
  c.action_table.push_back({"wave", "flag"});
  for (std::size_t f = 0; f < T; ++f) {
    for (std::size_t a = 0; a < N; ++a) {
      if (!c.present(f, a)) continue;
      const double yaw = 0.05 * static_cast<double>(f) + 0.3 * static_cast<double>(a);
      c.orientation(f, a) = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
      c.action(f, a) = static_cast<std::int32_t>((f / 7 + a) % 4);
    }
  }
  c.validate();
  const TimeSplit s = split_at_frame(c, 15);
  SECTION("split copies them exactly") {
    REQUIRE(s.second.action_table == c.action_table);
    REQUIRE(s.second.orientations.size() == s.second.frame_count() * s.second.agent_count() * 4);
    for (std::size_t f = 0; f < s.second.frame_count(); ++f) {
      for (std::size_t k = 0; k < s.second.agent_count(); ++k) {
        const auto a = static_cast<std::size_t>(std::find(c.ids.begin(), c.ids.end(), s.second.ids[k]) - c.ids.begin());
        if (!c.present(15 + f, a)) continue;
        CHECK(s.second.orientation(f, k).coeffs() == c.orientation(15 + f, a).coeffs());
        CHECK(s.second.action(f, k) == c.action(15 + f, a));
      }
    }
    s.first.validate();
    s.second.validate();
  }
  SECTION("merged back joined by id, they are the original's") {
    MergeOptions o;
    o.span = MergeSpan::union_of_spans;
    o.join_by = JoinBy::id;
    const Merged m = merge(s.first, {}, s.second, {}, o);
    REQUIRE(m.crowd.action_table == c.action_table);
    m.crowd.validate();
    for (std::size_t k = 0; k < m.crowd.agent_count(); ++k) {
      const auto a = static_cast<std::size_t>(std::find(c.ids.begin(), c.ids.end(), m.crowd.ids[k]) - c.ids.begin());
      for (std::size_t f = 0; f < T; ++f) {
        REQUIRE(m.crowd.present(f, k) == c.present(f, a));
        if (!c.present(f, a)) continue;
        CHECK(m.crowd.orientation(f, k).coeffs() == c.orientation(f, a).coeffs());
        CHECK(m.crowd.action(f, k) == c.action(f, a));
      }
    }
  }
  SECTION("on other frame times they are interpolated: slerped facing, the earlier sample's action") {
    CrowdMotion later = test::marching_grid(1, 2, 30);
    for (double& t : later.times) t += 0.05;  // halfway between c's frames
    const Merged m = merge(c, {}, later, {}, MergeOptions{});
    REQUIRE(m.report.interpolated_frames_first > 0);
    m.crowd.validate();
    // The overlap starts at 0.05 s, halfway between c's frames 0 and 1: agent 0's yaw halfway, frame 0's action.
    REQUIRE(m.crowd.times[0] == Approx(0.05));
    const Eigen::Quaterniond q = m.crowd.orientation(0, 0);
    CHECK(2.0 * std::atan2(q.z(), q.w()) == Approx(0.025).epsilon(1e-9));
    CHECK(m.crowd.action(0, 0) == c.action(0, 0));
  }
  SECTION("a crowd without them gets the defaults from its path, and the action tables become one") {
    CrowdMotion plain = test::marching_grid(1, 2, 30);
    plain.ids = {100, 101};
    CrowdMotion waving = c;
    waving.action_table = {{"wave", "flag"}, {"walk", ""}, {"stand", ""}, {"run", ""}};  // another order
    MergeOptions o;
    const Merged m = merge(plain, {}, waving, {}, o);
    m.crowd.validate();
    REQUIRE(m.crowd.action_table.size() == 4);
    CHECK(m.crowd.action_table == (std::vector<ActionKind>{{"walk", ""}, {"stand", ""}, {"run", ""}, {"wave", "flag"}}));
    // The plain crowd's agents face along their march (+x) and walk or stand by their speed.
    for (std::size_t f = 0; f < m.crowd.frame_count(); ++f) {
      for (std::size_t k = 0; k < 2; ++k) CHECK(m.crowd.action(f, k) == path_action(plain, f, k));
      // The waving crowd's entries are renumbered: its "wave" (0) is the merged table's 3.
      for (std::size_t k = 2; k < m.crowd.agent_count(); ++k) {
        const std::size_t a = k - 2;
        if (!c.present(f, a)) continue;
        CHECK(m.crowd.action_table[static_cast<std::size_t>(m.crowd.action(f, k))] ==
              waving.action_table[static_cast<std::size_t>(waving.action(f, a))]);
      }
    }
  }
}
