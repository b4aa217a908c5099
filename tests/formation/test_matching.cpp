// Individual matching between keyframes (beyond the paper): minimum-cost assignment after alignment.
#include <throng/formation/formation.h>

#include "fixtures.h"

#include <catch2/catch.hpp>

using namespace throng::formation;

TEST_CASE("matching recovers a shuffled correspondence, also under rotation, and animates as if given") {
  const int n = 35;
  const Eigen::MatrixXd source = throng::test::scattered(n, 5.0, 12, 0.7);
  // The target: the source stretched a little, turned, moved, slightly perturbed, and its rows shuffled.
  Eigen::MatrixXd target = throng::test::rigid_2d(source * 1.1, 0.6, {20.0, -4.0});
  throng::Rng rng(77);
  for (int i = 0; i < n; ++i) target.row(i) += Eigen::RowVector2d(rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05));
  std::vector<int> shuffle(n);
  for (int i = 0; i < n; ++i) shuffle[static_cast<std::size_t>(i)] = (i * 11 + 3) % n;  // row shuffle[i] of the file holds individual i
  Eigen::MatrixXd file(n, 2);
  for (int i = 0; i < n; ++i) file.row(shuffle[static_cast<std::size_t>(i)]) = target.row(i);

  Problem given, unknown;
  given.keyframes = {Keyframe{0.0, source, {}}, Keyframe{5.0, target, {}}};
  unknown.keyframes = {Keyframe{0.0, source, {}}, Keyframe{5.0, file, {}}};
  Options o;
  o.match_individuals = true;
  const Result matched = animate_formation(unknown, o);
  REQUIRE(matched.correspondence.size() == 2);
  CHECK(matched.correspondence[1] == shuffle);
  o.match_individuals = false;
  const Result reference = animate_formation(given, o);
  CHECK(matched.motion.positions == reference.motion.positions);
}

TEST_CASE("matching a keyframe to itself is the identity") {
  const Eigen::MatrixXd source = throng::test::scattered(20, 3.0, 4);
  Problem p;
  p.keyframes = {Keyframe{0.0, source, {}}, Keyframe{1.0, source, {}}, Keyframe{2.0, source, {}}};
  Options o;
  o.match_individuals = true;
  const Result r = animate_formation(p, o);
  for (const auto& c : r.correspondence)
    for (int i = 0; i < 20; ++i) CHECK(c[static_cast<std::size_t>(i)] == i);
}
