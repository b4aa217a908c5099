// What a user can get wrong, and the error each gives (type and message).
#include <throng/formation/formation.h>

#include <throng/core/errors.h>

#include "fixtures.h"

#include <catch2/catch.hpp>

#include <limits>

using namespace throng::formation;
using Catch::Matchers::Contains;

namespace {

Problem two_keyframes(int n = 12) {
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, throng::test::scattered(n, 3.0, 1), {}});
  p.keyframes.push_back(Keyframe{2.0, throng::test::scattered(n, 3.0, 2), {}});
  return p;
}

}  // namespace

TEST_CASE("a disconnected adjacency is an InputError naming the cut-off individuals") {
  Problem p;
  Eigen::MatrixXd line(4, 2);
  line << 0, 0, 1, 0, 2, 0, 3, 0;  // Delaunay of collinear points: the path 0-1-2-3
  p.keyframes.push_back(Keyframe{0.0, line, {}});
  p.keyframes.push_back(Keyframe{1.0, line.rowwise() + Eigen::RowVector2d(0, 1), {}});
  p.keyframes[1].edits.remove.push_back({1, 2});
  CHECK_THROWS_AS(animate_formation(p, Options{}), throng::InputError);
  CHECK_THROWS_WITH(animate_formation(p, Options{}),
                    Contains("keyframe 1") && Contains("disconnected") && Contains("individual 2, individual 3"));
}

TEST_CASE("a keyframe with a different count is an InputError") {
  Problem p = two_keyframes();
  p.keyframes.push_back(Keyframe{3.0, throng::test::scattered(11, 3.0, 3), {}});
  CHECK_THROWS_AS(animate_formation(p, Options{}), throng::InputError);
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("keyframe 2 has 11 individuals, keyframe 0 has 12"));
}

TEST_CASE("duplicate positions are an InputError naming both individuals") {
  Problem p = two_keyframes();
  p.keyframes[1].positions.row(7) = p.keyframes[1].positions.row(3);
  CHECK_THROWS_AS(animate_formation(p, Options{}), throng::InputError);
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("keyframe 1: individual 3 and individual 7 are at the same position"));
  // In 3-D too.
  Problem q;
  q.keyframes.push_back(Keyframe{0.0, throng::test::scattered(8, 3.0, 1, 0.5, 3), {}});
  q.keyframes.push_back(Keyframe{1.0, q.keyframes[0].positions, {}});
  q.keyframes[0].positions.row(5) = q.keyframes[0].positions.row(2);
  CHECK_THROWS_WITH(animate_formation(q, Options{}), Contains("individual 2 and individual 5 are at the same position"));
}

TEST_CASE("malformed keyframes are InputErrors") {
  Problem one = two_keyframes();
  one.keyframes.pop_back();
  CHECK_THROWS_WITH(animate_formation(one, Options{}), Contains("at least 2 are needed"));
  Problem backwards = two_keyframes();
  backwards.keyframes[1].time_s = 0.0;
  CHECK_THROWS_WITH(animate_formation(backwards, Options{}), Contains("keyframe times must increase strictly"));
  Problem nan = two_keyframes();
  nan.keyframes[0].positions(4, 1) = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(animate_formation(nan, Options{}), Contains("individual 4 has a non-finite coordinate"));
  Problem mixed = two_keyframes();
  mixed.keyframes[1].positions.conservativeResize(Eigen::NoChange, 3);
  mixed.keyframes[1].positions.col(2).setZero();
  CHECK_THROWS_AS(animate_formation(mixed, Options{}), throng::InputError);
  Problem ids = two_keyframes();
  ids.ids = std::vector<std::int64_t>(12, 5);
  CHECK_THROWS_WITH(animate_formation(ids, Options{}), Contains("id 5 is given twice"));
}

TEST_CASE("edits naming non-edges or unknown individuals are ConfigErrors") {
  Problem p = two_keyframes();
  p.edits.remove.push_back({0, 0});
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("edits.remove[0]") && Contains("two different individuals"));
  p.edits.remove = {{0, 40}};
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("individual 40 does not exist"));
  // Find a pair that is not a Delaunay edge in keyframe 0: the farthest pair of a scatter never is.
  const Eigen::MatrixXd& x = p.keyframes[0].positions;
  Pair far{0, 1};
  double best = 0.0;
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; ++j)
      if ((x.row(i) - x.row(j)).norm() > best) {
        best = (x.row(i) - x.row(j)).norm();
        far = {i, j};
      }
  p.edits.remove.clear();
  p.keyframes[0].edits.remove = {far};
  CHECK_THROWS_AS(animate_formation(p, Options{}), throng::ConfigError);
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("keyframe 0 edits.remove[0]") && Contains("not adjacent"));
  p.keyframes[0].edits.remove.clear();
  p.keyframes[0].edits.scale.push_back(EdgeScale{{far}, {}, 2.0});
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("cannot be scaled"));
  p.keyframes[0].edits.scale = {EdgeScale{{}, {1, 2, 3}, -1.0}};
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("factor") && Contains("> 0"));
}

TEST_CASE("a malformed hierarchy is a ConfigError") {
  Problem p = two_keyframes();
  Group root;
  root.members = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
  p.hierarchy = root;
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("individual 11 is in no group"));
  Group sub;
  sub.name = "tail";
  sub.members = {10, 11};
  root.subgroups.push_back(sub);
  p.hierarchy = root;
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("individual 10 is in both"));
  root.members.pop_back();
  root.subgroups.push_back(Group{});
  p.hierarchy = root;
  CHECK_THROWS_WITH(animate_formation(p, Options{}), Contains("is empty"));
}

TEST_CASE("options out of range are ConfigErrors") {
  const Problem p = two_keyframes();
  auto fails = [&](auto change, const char* key) {
    Options o;
    change(o);
    CHECK_THROWS_AS(animate_formation(p, o), throng::ConfigError);
    CHECK_THROWS_WITH(animate_formation(p, o), Contains(key));
  };
  fails([](Options& o) { o.frame_rate_hz = 0; }, "frame_rate");
  fails([](Options& o) { o.tension = 1.5; }, "tension");
  fails([](Options& o) { o.auto_group_size = 1; }, "auto_group_size");
  fails([](Options& o) { o.auto_cluster_size = 1; }, "auto_cluster_size");
  fails([](Options& o) { o.radius_m = -1; }, "radius");
  fails([](Options& o) { o.collision.enabled = true; o.collision.min_distance_m = 0; }, "collision.min_distance");
  fails([](Options& o) { o.collision.enabled = true; o.collision.smoothing_passes = 0; }, "smoothing_passes");
}

TEST_CASE("keyframes from a crowd: every agent present at the chosen frames") {
  throng::CrowdMotion m = throng::CrowdMotion::with_shape(5, 3);
  m.times = {0, 1, 2, 3, 4};
  for (std::size_t f = 0; f < 5; ++f)
    for (std::size_t i = 0; i < 3; ++i) m.position(f, i) = Eigen::Vector3d(static_cast<double>(i), static_cast<double>(f), 0.5);
  const auto keys = keyframes_from_motion(m, {1, 4});
  REQUIRE(keys.size() == 2);
  CHECK(keys[1].time_s == 4.0);
  CHECK(keys[1].positions.cols() == 2);
  CHECK(keys[1].positions(2, 0) == 2.0);
  CHECK(keyframes_from_motion(m, {0, 2}, 3)[0].positions(0, 2) == 0.5);
  m.position(2, 1) = Eigen::Vector3d::Constant(throng::absent);
  CHECK_THROWS_WITH(keyframes_from_motion(m, {0, 2}), Contains("agent 1 is absent at frame 2"));
  CHECK_THROWS_AS(keyframes_from_motion(m, {9}), throng::InputError);
}
