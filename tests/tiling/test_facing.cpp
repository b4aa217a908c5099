// The facing and action of laid characters: the patches' own root headings (a turn in place turns the agent by
// the patch's angle, a standing agent keeps its facing, bowing rows face each other), the patch each frame lies
// in, and the action table of the library.
#include <catch2/catch.hpp>

#include <throng/core/progress.h>
#include <throng/tiling/characters.h>

#include "tiling_scenes.h"

#include <cmath>
#include <numbers>
#include <optional>
#include <string>

using namespace throng;
using namespace throng::tiling;
using namespace throng::tiling::test;

namespace {

constexpr double pi = std::numbers::pi;

// Yaw of a ground orientation (a rotation about +z), in (−π, π].
double yaw(const CrowdMotion& m, std::size_t f, std::size_t n) {
  const Eigen::Quaterniond q = m.orientation(f, n);
  return std::atan2(2.0 * (q.w() * q.z() + q.x() * q.y()), 1.0 - 2.0 * (q.y() * q.y() + q.z() * q.z()));
}

// a − b wrapped to (−π, π].
double angle_between(double a, double b) { return std::remainder(a - b, 2.0 * pi); }

const std::string& action_name(const CrowdMotion& m, std::size_t f, std::size_t n) {
  return m.action_table.at(static_cast<std::size_t>(m.action(f, n))).name;
}

// Every present orientation a ground yaw: a unit quaternion with x = y = 0.
void require_ground_facings(const CrowdMotion& m) {
  REQUIRE_NOTHROW(m.validate("laid characters"));
  REQUIRE(m.orientations.size() == m.frame_count() * m.agent_count() * 4);
  REQUIRE(m.actions.size() == m.frame_count() * m.agent_count());
  for (std::size_t f = 0; f < m.frame_count(); ++f) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      if (!m.present(f, n)) continue;
      const Eigen::Quaterniond q = m.orientation(f, n);
      REQUIRE(q.x() == 0.0);
      REQUIRE(q.y() == 0.0);
      REQUIRE(std::abs(q.norm() - 1.0) < 1e-15);
    }
  }
}

// The agent walking fragment `fragment` in the laid copy (0, 0, 0) and present at frame `frame`.
std::optional<std::size_t> agent_in(const Characters& laid, FragmentRef fragment, std::size_t frame) {
  for (std::size_t n = 0; n < laid.pieces.size(); ++n) {
    for (const AgentPiece& p : laid.pieces[n]) {
      if (p.fragment == fragment && p.copy == std::array<int, 3>{0, 0, 0} && laid.motion.present(frame, n)) return n;
    }
  }
  return std::nullopt;
}

}  // namespace

TEST_CASE("the action table lists the standard actions, then each patch with its prop, once") {
  const PatchLibrary lib = builtin_library({"walk", "wait", "turn_in_place", "handshake", "box_pickup", "box_carry"});
  const PatchActions a = patch_actions(lib);
  REQUIRE(a.table.size() == standard_actions().size() + 5);  // walk is the standard walk
  for (std::size_t k = 0; k < standard_actions().size(); ++k) CHECK(a.table[k] == standard_actions()[k]);
  REQUIRE(a.of_fragment.size() == lib.types.size());
  for (std::size_t t = 0; t < lib.types.size(); ++t) {
    const PatchType& type = lib.types[t];
    for (std::size_t f = 0; f < type.fragments.size(); ++f) {
      const std::int32_t k = a.of_fragment[t][f];
      if (!type.fragments[f].is_character()) {
        CHECK(k == -1);  // the box stack of box_pickup: an occupant, not a character
        continue;
      }
      REQUIRE(k >= 0);
      CHECK(a.table[static_cast<std::size_t>(k)].name == type.name);
      // Box handlers carry the box; nobody else carries anything.
      const bool box = type.name.rfind("box", 0) == 0;
      CHECK(a.table[static_cast<std::size_t>(k)].prop == (box ? "box" : ""));
    }
  }
  CHECK(a.of_fragment[lib.find("walk")][0] == action_walk);
  // Both characters of the handshake share one entry.
  CHECK(a.of_fragment[lib.find("handshake")][0] == a.of_fragment[lib.find("handshake")][1]);
}

TEST_CASE("a laid turn in place turns the agent by the patch's angle, and a standing agent's facing does not change") {
  // wait (0–2 s) → turn_in_place (2–4 s) → wait (4–6 s) at one spot, placed at angle φ; the second wait faces
  // where the turn ended. Patch boundaries fall on frames (10 Hz).
  const PatchLibrary lib = builtin_library({"wait", "turn_in_place"});
  const std::size_t wait = lib.find("wait"), turn = lib.find("turn_in_place");
  const Fragment& turning = lib.types[turn].fragments[0];
  const double patch_turn = angle_between(turning.headings.back(), turning.headings.front());
  REQUIRE(std::abs(patch_turn - 0.5 * pi) < 1e-12);  // the built-in turns 90°
  const double phi = 0.7;
  const Environment env = box(8, 8, 6);
  Tiling t;
  t.instances.push_back(placed(lib, wait, {4, 4}, phi, 1.0));
  t.instances.push_back(placed(lib, turn, {4, 4}, phi, 3.0));
  t.instances.push_back(placed(lib, wait, {4, 4}, phi + patch_turn, 5.0));
  t.connections.push_back({{0, 0}, {1, 0}, {0, 0, 0}});
  t.connections.push_back({{1, 0}, {2, 0}, {0, 0, 0}});
  const Characters laid = lay_out(lib, t, *env.scene.region, LayoutOptions{10.0, {1, 1, 1}});
  const CrowdMotion& m = laid.motion;
  require_ground_facings(m);
  REQUIRE(m.agent_count() == 1);
  REQUIRE(m.frame_count() == 61);

  // Standing: the facing is φ throughout the first wait and φ + 90° throughout the second, to the last bit.
  for (std::size_t f = 0; f <= 20; ++f) CHECK(yaw(m, f, 0) == yaw(m, 0, 0));
  for (std::size_t f = 40; f <= 60; ++f) CHECK(yaw(m, f, 0) == yaw(m, 60, 0));
  CHECK(std::abs(angle_between(yaw(m, 0, 0), phi)) < 1e-12);
  // The turn: by exactly the patch's angle from its entry (frame 20) to its exit (frame 40), at the patch's rate
  // in between (the turtle turns uniformly over the 2 s).
  CHECK(std::abs(angle_between(yaw(m, 40, 0), yaw(m, 20, 0)) - patch_turn) < 1e-12);
  for (std::size_t f = 20; f <= 40; ++f) {
    const double expected = phi + patch_turn * (m.times[f] - 2.0) / 2.0;
    CHECK(std::abs(angle_between(yaw(m, f, 0), expected)) < 1e-9);
  }
  // The action names the patch of each frame (the earlier one on a frame exactly at a join).
  for (std::size_t f = 0; f <= 60; ++f) {
    INFO("frame " << f);
    CHECK(action_name(m, f, 0) == (f > 20 && f <= 40 ? "turn_in_place" : "wait"));
  }
}

TEST_CASE("tiled characters face along their patches' headings and act the patch they are in") {
  NoProgress quiet;
  SECTION("a keyframed turn in place among waits, starts and stops") {
    const PatchLibrary lib = builtin_library({"walk", "stop", "start", "wait", "turn_in_place"});
    const Environment env = box(8, 8, 8);
    Keyframe k;
    k.type = lib.find("turn_in_place");
    k.transform = Transform{{4, 4}, 0.3, 4.0};  // turns over 3–5 s, undeformed (keyframed)
    const TilingResult r = tile(lib, env, {k}, quick_options(11), quiet);
    // The patches' own headings: no facing-rate limit (its own test below).
    const Characters laid = lay_out(lib, r.tiling, *env.scene.region, LayoutOptions{10.0, {1, 1, 1}, 0.0});
    const CrowdMotion& m = laid.motion;
    require_ground_facings(m);
    REQUIRE(r.tiling.instances[0].keyframed);
    const auto agent = agent_in(laid, {0, 0}, 40);
    REQUIRE(agent);
    // Inside the patch and at its exit the agent faces 0.3 rad turned by the patch's 90° at the patch's rate.
    for (std::size_t f = 31; f <= 50; ++f) {
      const double expected = 0.3 + 0.5 * pi * (m.times[f] - 3.0) / 2.0;
      CHECK(std::abs(angle_between(yaw(m, f, *agent), expected)) < 1e-9);
    }
    // Every turn in place of the tiling, deformed or not, turns its character by the patch's angle: the
    // deformation adds no rotation to a character standing on the spot.
    std::size_t turns = 0;
    for (const Instance& inst : r.tiling.instances) {
      if (inst.type != k.type) continue;
      ++turns;
      const Path& p = inst.paths[0];
      CHECK(std::abs(angle_between(p.headings.back(), p.headings.front()) - 0.5 * pi) < 1e-9);
    }
    CHECK(turns >= 1);

    // Every present frame: the action names a patch the agent walks at that time; away from the joins (a frame on
    // a segment between two samples of one fragment) the facing is the deformed path's heading at that time,
    // interpolated the shorter way between the samples. A standing patch (wait) keeps one facing, bit for bit.
    // (On the first segment of a fragment the laid path starts from its predecessor's last sample, whose heading
    // matches within the stitching threshold only.)
    const double period = periods(*env.scene.region).z();
    std::size_t faced = 0, waits = 0;
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      for (std::size_t f = 0; f < m.frame_count(); ++f) {
        if (!m.present(f, n)) continue;
        const double t = m.times[f];
        bool named = false;
        INFO("agent " << n << " frame " << f << " action " << action_name(m, f, n));
        for (const AgentPiece& piece : laid.pieces[n]) {
          const Instance& inst = r.tiling.instances[piece.fragment.instance];
          const Path& p = inst.paths[piece.fragment.fragment];
          const double shift = piece.copy[2] * period;
          if (t < p.times.front() + shift - 1e-9 || t > p.times.back() + shift + 1e-9) continue;
          named = named || action_name(m, f, n) == lib.types[inst.type].name;
          for (std::size_t s = 1; s + 1 < p.times.size(); ++s) {
            const double a = p.times[s] + shift, b = p.times[s + 1] + shift;
            if (t < a || t > b) continue;
            const double u = (t - a) / (b - a);
            const double h = p.headings[s] + u * angle_between(p.headings[s + 1], p.headings[s]);
            CHECK(std::abs(angle_between(yaw(m, f, n), h)) < 1e-9);
            ++faced;
            if (lib.types[inst.type].name == "wait") {
              ++waits;
              CHECK(p.headings[s + 1] == p.headings[s]);
              const double w = p.headings[s];
              CHECK(m.orientation(f, n).coeffs() == Eigen::Vector4d(0, 0, std::sin(0.5 * w), std::cos(0.5 * w)));
            }
          }
        }
        CHECK(named);
      }
    }
    CHECK(faced > 0);
    CHECK(waits > 0);
  }
  SECTION("bowing rows face each other, then turn round") {
    const PatchLibrary lib = builtin_library({"walk", "turn_left", "turn_right", "stop", "start", "wait", "bow_rows"});
    const Environment env = box(10, 10, 10, {true, true, false});
    Keyframe k;
    k.type = lib.find("bow_rows");
    k.transform = Transform{{5, 5}, 0.0, 5.0};
    const TilingResult r = tile(lib, env, {k}, quick_options(9), quiet);
    const Characters laid = lay_out(lib, r.tiling, *env.scene.region, LayoutOptions{10.0, {1, 1, 1}});
    const CrowdMotion& m = laid.motion;
    require_ground_facings(m);
    REQUIRE(r.tiling.instances[0].keyframed);
    // The patch (5.8 s, centred on 5 s): brake 2.1–3.6 s, bow 3.6–5.6 s, about-turn 5.6–6.4 s, leave.
    const std::size_t bowing = 46, after = 66;
    for (std::uint32_t i = 0; i < 5; ++i) {
      const auto a = agent_in(laid, {0, i}, bowing), b = agent_in(laid, {0, 9 - i}, bowing);
      REQUIRE(a);
      REQUIRE(b);
      CHECK(std::abs(std::abs(angle_between(yaw(m, bowing, *a), yaw(m, bowing, *b))) - pi) < 1e-9);
      CHECK(action_name(m, bowing, *a) == "bow_rows");
      REQUIRE(m.present(after, *a));
      CHECK(std::abs(std::abs(angle_between(yaw(m, after, *a), yaw(m, bowing, *a))) - pi) < 1e-9);
    }
  }
}

TEST_CASE("a laid facing turns at most max_facing_rate per second, and is the patches' heading once it has caught up") {
  // Stops, starts and waits joined with different headings: without the limit the character snaps round between
  // two frames (a standing character's heading is not matched at a join).
  NoProgress quiet;
  const PatchLibrary lib = builtin_library({"walk", "stop", "start", "wait", "turn_in_place"});
  const Environment env = box(8, 8, 8);
  const TilingResult r = tile(lib, env, {}, quick_options(11), quiet);
  const Characters free = lay_out(lib, r.tiling, *env.scene.region, LayoutOptions{10.0, {1, 1, 1}, 0.0});
  const LayoutOptions limited_options{10.0, {1, 1, 1}};
  REQUIRE(limited_options.max_facing_rate_rad_s == 1.5 * pi);
  const Characters limited = lay_out(lib, r.tiling, *env.scene.region, limited_options);
  const CrowdMotion& a = free.motion;
  const CrowdMotion& b = limited.motion;
  REQUIRE(a.agent_count() == b.agent_count());
  for (std::size_t f = 0; f < a.frame_count(); ++f) {  // only the facing changes
    for (std::size_t n = 0; n < a.agent_count(); ++n) {
      REQUIRE(a.present(f, n) == b.present(f, n));
      if (a.present(f, n)) REQUIRE(a.position(f, n) == b.position(f, n));
    }
  }
  const double max_turn = 1.5 * pi / 10.0;
  std::size_t snaps = 0, lagging = 0, frames = 0;
  for (std::size_t n = 0; n < b.agent_count(); ++n) {
    bool previous = false;
    for (std::size_t f = 0; f < b.frame_count(); ++f) {
      if (!b.present(f, n)) {
        previous = false;
        continue;
      }
      INFO("agent " << n << " frame " << f);
      ++frames;
      if (!previous) {
        CHECK(b.orientation(f, n).coeffs() == a.orientation(f, n).coeffs());  // a run starts at the patch's heading
      } else {
        const double turn = std::abs(angle_between(yaw(b, f, n), yaw(b, f - 1, n)));
        CHECK(turn <= max_turn + 1e-9);
        snaps += std::abs(angle_between(yaw(a, f, n), yaw(a, f - 1, n))) > max_turn + 1e-9;
        // Either the patches' heading, bit for bit, or a turn toward it at the full rate.
        if (b.orientation(f, n).coeffs() != a.orientation(f, n).coeffs()) {
          ++lagging;
          CHECK(std::abs(turn - max_turn) < 1e-9);
        }
      }
      previous = true;
    }
  }
  CHECK(snaps > 0);    // the scene has snaps to limit
  CHECK(lagging > 0);
  CHECK(lagging < frames / 20);  // and the limit acts only around them
}
