// The independent checker: hand-built tilings, good and bad in each of the ways it must catch.
#include <catch2/catch.hpp>

#include <algorithm>

#include <throng/core/errors.h>
#include <throng/tiling/check.h>

#include "tiling_scenes.h"

using namespace throng;
using namespace throng::tiling;
using namespace throng::tiling::test;

namespace {

// Two chains of 6 walks crossing a 12 × 12 m × 20 s box along x at y = 3 and y = 8, entering before x = 0.
Tiling two_chains(const PatchLibrary& lib) {
  Tiling t = walk_chain(lib, 6, -1.0, 3.0, 2.0);
  append(t, walk_chain(lib, 6, -2.0, 8.0, 5.0));
  return t;
}

}  // namespace

TEST_CASE("a hand-built perfect tiling passes every check") {
  const PatchLibrary lib = walk_library();
  const CheckReport r = check_tiling(lib, two_chains(lib), box(12, 12, 20), CheckOptions{});
  CHECK(r.perfect());
  CHECK(r.character_ends == 24);
  CHECK(r.connections == 10);
}

TEST_CASE("the checker finds a dangling exit") {
  const PatchLibrary lib = walk_library();
  Tiling t = two_chains(lib);
  // End the second chain after its third walk: the exit of walk 3 (instance 8, x = 5.8 m, 11 s) now dangles.
  t.instances.resize(9);
  t.connections.resize(7);
  const CheckReport r = check_tiling(lib, t, box(12, 12, 20), CheckOptions{});
  REQUIRE(r.count(FailureKind::dangling) == 1);
  CHECK(r.total() == 1);
  bool named = false;
  for (const Failure& f : r.failures) named = named || f.message.find("exit of instance 8") != std::string::npos;
  CHECK(named);
}

TEST_CASE("an end outside the region, in a source or in a sink needs no partner") {
  const PatchLibrary lib = walk_library();
  Environment env = box(12, 12, 20);
  // One walk in the middle: both ends dangle ...
  Tiling t;
  t.instances.push_back(placed(lib, 0, {6, 6}, 0, 10));
  CHECK(check_tiling(lib, t, env, CheckOptions{}).count(FailureKind::dangling) == 2);
  // ... not when its entry is in a source and its exit in a sink; a sink does not excuse an entry.
  env.sources.push_back({{4.7, 6}, 0.3, 8.5, 9.5});
  env.sinks.push_back({{7.3, 6}, 0.3, 10.5, 11.5});
  CHECK(check_tiling(lib, t, env, CheckOptions{}).perfect());
  std::swap(env.sources, env.sinks);
  CHECK(check_tiling(lib, t, env, CheckOptions{}).count(FailureKind::dangling) == 2);
}

TEST_CASE("the checker finds an overlap between instances but not within a character") {
  const PatchLibrary lib = walk_library();
  Tiling t = walk_chain(lib, 6, -1.0, 3.0, 2.0);
  // A second chain 0.4 m beside the first, at the same times: closer than the two radii (0.5 m).
  append(t, walk_chain(lib, 6, -1.0, 3.4, 2.0));
  const CheckReport r = check_tiling(lib, t, box(12, 12, 20), CheckOptions{});
  CHECK(r.count(FailureKind::overlap) >= 6);
  CHECK(r.count(FailureKind::dangling) == 0);
  // The same chain 0.6 m away is fine, and connected walks (one character) never overlap each other.
  Tiling apart = walk_chain(lib, 6, -1.0, 3.0, 2.0);
  append(apart, walk_chain(lib, 6, -1.0, 3.6, 2.0));
  CHECK(check_tiling(lib, apart, box(12, 12, 20), CheckOptions{}).perfect());
}

TEST_CASE("the checker finds characters of one instance overlapping, unless their patch brings them together") {
  // A pass whose two characters are pulled 0.2 m toward each other at the crossing: 0.41 m apart, radii 0.5 m.
  PatchLibrary lib = builtin_library({"pass"});
  const Environment env = box(12, 12, 20);
  REQUIRE(contact_pairs(lib.types[0]).empty());
  Instance crossing = placed(lib, 0, {6, 6}, 0.0, 10.0);
  const CheckReport clear = check_tiling(lib, {{crossing}, {}}, env, CheckOptions{});
  CHECK(clear.count(FailureKind::overlap) == 0);
  // Each character moved whole (no stretch, no bend) 0.1 m toward the other's centroid.
  const auto centroid = [&](std::size_t f) {
    Eigen::Vector2d c(0, 0);
    for (const Eigen::Vector2d& p : crossing.paths[f].positions) c += p;
    return Eigen::Vector2d(c / static_cast<double>(crossing.paths[f].positions.size()));
  };
  const Eigen::Vector2d towards = (centroid(1) - centroid(0)).normalized();
  for (Eigen::Vector2d& p : crossing.paths[0].positions) p += 0.1 * towards;
  for (Eigen::Vector2d& p : crossing.paths[1].positions) p -= 0.1 * towards;
  const CheckReport r = check_tiling(lib, {{crossing}, {}}, env, CheckOptions{});
  CHECK(r.count(FailureKind::overlap) == 1);
  const auto overlap = std::find_if(r.failures.begin(), r.failures.end(), [](const Failure& f) { return f.kind == FailureKind::overlap; });
  REQUIRE(overlap != r.failures.end());
  CHECK(overlap->message.find("instance 0 ('pass') fragment 0 and instance 0 ('pass') fragment 1") != std::string::npos);
  // The same paths as the patch's own: it declares the contact (a couple walking arm in arm), nothing fails.
  PatchLibrary close = lib;
  close.types[0].fragments = {};
  for (std::size_t f = 0; f < 2; ++f) {
    Fragment fr = lib.types[0].fragments[f];
    for (std::size_t s = 0; s < fr.sample_count(); ++s) fr.positions[s] = crossing.paths[f].positions[s] - Eigen::Vector2d(6, 6);
    close.types[0].fragments.push_back(fr);
  }
  REQUIRE(contact_pairs(close.types[0]).size() == 1);
  const Instance as_recorded = placed(close, 0, {6, 6}, 0.0, 10.0);
  CHECK(check_tiling(close, {{as_recorded}, {}}, env, CheckOptions{}).count(FailureKind::overlap) == 0);
}

TEST_CASE("the checker finds an over-stretched, over-bent or time-shifted patch") {
  const PatchLibrary lib = walk_library();
  const Environment env = box(12, 12, 20);
  CheckOptions options;
  options.limits.speed_ratio = 0;  // the paper's limits alone (test_deformation.cpp tests the speed limit)
  // Limits per 0.1 s sample (3 frames of 30 Hz): stretch 9 cm, bend 21°, time shift 0.054 s.
  SECTION("stretch") {
    Tiling t = two_chains(lib);
    for (std::size_t s = 11; s < 21; ++s) t.instances[2].paths[0].positions[s].x() += 0.12;  // one segment 12 cm longer
    for (std::size_t s = 0; s < 21; ++s) t.instances[3].paths[0].positions[s].x() += 0.12;   // keep the chain joined
    for (std::size_t k = 4; k < 6; ++k) {
      for (auto& p : t.instances[k].paths[0].positions) p.x() += 0.12;
    }
    const CheckReport r = check_tiling(lib, t, env, options);
    CHECK(r.count(FailureKind::deformation) == 1);
    CHECK(r.total() == 1);
    // 6 cm is within the limit.
    Tiling ok = two_chains(lib);
    for (std::size_t s = 11; s < 21; ++s) ok.instances[2].paths[0].positions[s].x() += 0.06;
    for (std::size_t k = 3; k < 6; ++k) {
      for (auto& p : ok.instances[k].paths[0].positions) p.x() += 0.06;
    }
    CHECK(check_tiling(lib, ok, env, options).perfect());
  }
  SECTION("bend") {
    Tiling t = two_chains(lib);
    t.instances[2].paths[0].positions[10].y() += 0.06;  // a kink of about 2 × 25° at sample 10
    const CheckReport r = check_tiling(lib, t, env, options);
    CHECK(r.count(FailureKind::deformation) >= 1);
  }
  SECTION("time shift") {
    Tiling t = two_chains(lib);
    for (std::size_t s = 11; s < 21; ++s) t.instances[2].paths[0].times[s] += 0.08;
    for (std::size_t k = 3; k < 6; ++k) {
      for (double& x : t.instances[k].paths[0].times) x += 0.08;
    }
    const CheckReport r = check_tiling(lib, t, env, options);
    CHECK(r.count(FailureKind::deformation) == 1);
    CHECK(r.total() == 1);
  }
}

TEST_CASE("the checker finds a broken seam of a repeating tile and accepts a matched one") {
  const PatchLibrary lib = walk_library();
  // Four walks fill a 10.4 m × 8 s loop periodic in x and t: the last exit (x = 10.4, t = 8) continues into the
  // first entry (x = 0, t = 0) one period on: image (1, 0, 1).
  const Environment env = box(10.4, 10, 8, {true, false, true});
  Tiling t = walk_chain(lib, 4, 0.0, 5.0, 0.0);
  t.connections.push_back({{3, 0}, {0, 0}, {1, 0, 1}});
  CHECK(check_tiling(lib, t, env, CheckOptions{}).perfect());

  SECTION("wrong image") {
    t.connections.back().image = {1, 0, 0};
    const CheckReport r = check_tiling(lib, t, env, CheckOptions{});
    CHECK(r.count(FailureKind::seam) == 1);
    CHECK(r.count(FailureKind::connection) == 0);
  }
  SECTION("moved across the seam") {
    for (auto& p : t.instances[0].paths[0].positions) p.y() += 0.2;
    for (auto& p : t.instances[1].paths[0].positions) p.y() += 0.2;
    const CheckReport r = check_tiling(lib, t, env, CheckOptions{});
    CHECK(r.count(FailureKind::seam) == 1);
    CHECK(r.count(FailureKind::connection) == 1);
  }
  SECTION("an image on a non-periodic axis") {
    t.connections.back().image = {1, 1, 1};
    CHECK(check_tiling(lib, t, env, CheckOptions{}).count(FailureKind::seam) == 1);
  }
}

TEST_CASE("the checker finds obstacles, broken interpersonal constraints, moved keyframes, double connections") {
  const PatchLibrary lib = builtin_library({"walk", "meet"});
  Environment env = box(12, 12, 20);
  Tiling t = walk_chain(lib, 6, -1.0, 3.0, 2.0);
  SECTION("obstacle") {
    env.scene.obstacles.resize(1);
    env.scene.obstacles[0].shape.emplace<Circle>(Circle{{6.0, 3.3}, 0.2});
    const CheckReport r = check_tiling(lib, t, env, CheckOptions{});
    CHECK(r.count(FailureKind::obstacle) >= 1);
    CHECK(r.total() == r.count(FailureKind::obstacle));
  }
  SECTION("interpersonal") {
    Instance meet = placed(lib, 1, {6, 9}, 0, 10);
    CHECK(check_tiling(lib, Tiling{{meet}, {}}, env, CheckOptions{}).count(FailureKind::interpersonal) == 0);
    for (auto& p : meet.paths[1].positions) p.x() += 0.05;
    CHECK(check_tiling(lib, Tiling{{meet}, {}}, env, CheckOptions{}).count(FailureKind::interpersonal) >= 1);
  }
  SECTION("keyframe") {
    t.instances[2].keyframed = true;
    CHECK(check_tiling(lib, t, env, CheckOptions{}).perfect());
    for (auto& p : t.instances[2].paths[0].positions) p.y() += 1e-3;
    CHECK(check_tiling(lib, t, env, CheckOptions{}).count(FailureKind::keyframe) == 1);
  }
  SECTION("an exit connected twice") {
    t.connections.push_back(t.connections.front());
    CHECK(check_tiling(lib, t, env, CheckOptions{}).count(FailureKind::connection) == 2);
  }
}

TEST_CASE("malformed tilings are input errors") {
  const PatchLibrary lib = walk_library();
  Tiling t = walk_chain(lib, 2, 0.0, 3.0, 2.0);
  SECTION("type") {
    t.instances[1].type = 5;
    CHECK_THROWS_AS(check_tiling(lib, t, box(12, 12, 20), CheckOptions{}), InputError);
  }
  SECTION("path length") {
    t.instances[1].paths[0].times.pop_back();
    CHECK_THROWS_AS(check_tiling(lib, t, box(12, 12, 20), CheckOptions{}), InputError);
  }
  SECTION("connection") {
    t.connections.push_back({{0, 3}, {1, 0}, {0, 0, 0}});
    CHECK_THROWS_AS(check_tiling(lib, t, box(12, 12, 20), CheckOptions{}), InputError);
  }
}
