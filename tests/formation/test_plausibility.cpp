// The formation's plausibility guard (plausibility.h, issue 14): where the spline is faster than
// guard.max_speed_ratio × the stated speed it slows the whole formation down, the keyframes land on their warped
// frames with their positions, and the guard is a no-op when nothing is too fast or when it is disabled.
#include <throng/formation/formation.h>
#include <throng/formation/plausibility.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace throng;
using namespace throng::formation;

namespace {

// A 2 × 2 block that moves 4 m along +x between keyframes 2 s apart (2 m/s straight-line), stopping at each
// (tension 0): each interval's speed peaks at 1.5 × 2 = 3 m/s mid-way, above 1.25 × 2 = 2.5.
Problem stop_and_go() {
  Eigen::MatrixXd block(4, 2);
  block << 0, 0, 1.5, 0, 0, 1.5, 1.5, 1.5;
  Problem p;
  for (int k = 0; k < 3; ++k) p.keyframes.push_back(Keyframe{2.0 * k, block.rowwise() + Eigen::RowVector2d(4.0 * k, 0), {}});
  return p;
}

double fastest(const CrowdMotion& m) {
  double v = 0;
  for (std::size_t f = 1; f < m.frame_count(); ++f)
    for (std::size_t n = 0; n < m.agent_count(); ++n)
      v = std::max(v, (m.position(f, n) - m.position(f - 1, n)).norm() / (m.times[f] - m.times[f - 1]));
  return v;
}

}  // namespace

TEST_CASE("the formation guard slows the formation to 1.25 × the keyframes' speed and keeps the keyframes") {
  Options o;
  o.tension = 0.0;
  o.frame_rate_hz = 25;
  const Problem p = stop_and_go();
  Result r = animate_formation(p, o);
  const CrowdMotion before = r.motion;
  REQUIRE(keyframe_speed(before, r.keyframe_frames) == Approx(2.0));
  REQUIRE(fastest(before) > 2.9);  // the paper's timing: 3 m/s mid-interval

  guard_formation(r, o);
  const CrowdMotion& after = r.motion;
  CHECK(r.guard.warped);
  CHECK(r.guard.speed_limit == Approx(2.5));
  CHECK(fastest(after) <= 2.5 * (1 + 1e-3));
  CHECK(after.times.back() > before.times.back());  // slower: longer
  CHECK(after.frame_count() > before.frame_count());
  CHECK(after.times[1] - after.times[0] == Approx(before.times[1] - before.times[0]));  // same frame rate
  // The keyframes on their new frames, at their positions (to the resampling's rounding of time).
  REQUIRE(r.keyframe_frames.size() == 3);
  CHECK(r.keyframe_frames.front() == 0);
  CHECK(r.keyframe_frames.back() == after.frame_count() - 1);
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t n = 0; n < 4; ++n) {
      INFO("keyframe " << k << " individual " << n);
      const Eigen::Vector2d want = p.keyframes[k].positions.row(static_cast<Eigen::Index>(n)).transpose();
      CHECK((after.position(r.keyframe_frames[k], n).head<2>() - want).norm() < 0.05);
    }
  // Facings and actions travel with the frames.
  CHECK(after.orientations.size() == after.frame_count() * after.agent_count() * 4);
  CHECK(after.actions.size() == after.frame_count() * after.agent_count());
  CHECK_NOTHROW(after.validate("guarded formation"));
}

TEST_CASE("the formation guard: a stated speed sets the limit; disabled or not needed, it changes nothing") {
  Options o;
  o.tension = 0.0;
  o.frame_rate_hz = 25;
  const Problem p = stop_and_go();
  SECTION("max_speed 4 m/s and 10 m/s² allowed: 5 m/s is never reached, no kink, nothing changes, to the bit") {
    o.max_speed_mps = 4;
    o.guard.max_acceleration = 10;  // the stops accelerate at 6 m/s²
    Result r = animate_formation(p, o);
    const CrowdMotion before = r.motion;
    guard_formation(r, o);
    CHECK_FALSE(r.guard.warped);
    CHECK(r.motion.positions == before.positions);
    CHECK(r.motion.times == before.times);
  }
  SECTION("max_speed 1 m/s: slowed to 1.25 m/s") {
    o.max_speed_mps = 1;
    Result r = animate_formation(p, o);
    guard_formation(r, o);
    CHECK(fastest(r.motion) <= 1.25 * (1 + 1e-3));
  }
  SECTION("disabled: the paper's timing") {
    o.guard.enabled = false;
    Result r = animate_formation(p, o);
    const CrowdMotion before = r.motion;
    guard_formation(r, o);
    CHECK(r.motion.positions == before.positions);
    CHECK(r.keyframe_frames == std::vector<std::size_t>{0, 50, 100});
  }
}
