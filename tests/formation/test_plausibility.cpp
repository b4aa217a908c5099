// The formation's plausibility guard (plausibility.h, issue 14): where the spline is faster than
// guard.max_speed_ratio × the stated speed it lengthens that keyframe interval (whole frames) and remakes the
// formation, every keyframe still hit exactly on a frame, and it changes nothing when nothing is too fast or when
// it is disabled.
#include <throng/formation/formation.h>
#include <throng/formation/plausibility.h>
#include <throng/core/progress.h>

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
  NoProgress quiet;
  Problem p = stop_and_go();
  Result r = animate_formation(p, o);
  const CrowdMotion before = r.motion;
  REQUIRE(keyframe_speed(before, r.keyframe_frames) == Approx(2.0));
  REQUIRE(fastest(before) > 2.9);  // the paper's timing: 3 m/s mid-interval

  guard_formation(p, r, o, quiet);
  const CrowdMotion& after = r.motion;
  CHECK(r.guard.warped);
  CHECK(r.guard.speed_limit == Approx(2.5));
  CHECK(fastest(after) <= 2.5);
  CHECK(r.guard.largest_stretch > 1.2);
  CHECK(after.times.back() > before.times.back());  // slower: longer
  CHECK(after.times[1] - after.times[0] == Approx(before.times[1] - before.times[0]));  // same frame rate
  // The keyframes re-timed to whole frames, each hit exactly at its frame.
  REQUIRE(r.keyframe_frames.size() == 3);
  CHECK(r.keyframe_frames.front() == 0);
  CHECK(r.keyframe_frames.back() == after.frame_count() - 1);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(after.times[r.keyframe_frames[k]] == Approx(p.keyframes[k].time_s).margin(1e-9));
    for (std::size_t n = 0; n < 4; ++n) {
      INFO("keyframe " << k << " individual " << n);
      const Eigen::Vector2d want = stop_and_go().keyframes[k].positions.row(static_cast<Eigen::Index>(n)).transpose();
      CHECK((after.position(r.keyframe_frames[k], n).head<2>() - want).norm() < 1e-9);
    }
  }
  // Facings and actions made with the new times.
  CHECK(after.orientations.size() == after.frame_count() * after.agent_count() * 4);
  CHECK(after.actions.size() == after.frame_count() * after.agent_count());
  CHECK_NOTHROW(after.validate("guarded formation"));
}

TEST_CASE("the formation guard: a stated speed sets the limit and disabled or not needed it changes nothing") {
  Options o;
  o.tension = 0.0;
  o.frame_rate_hz = 25;
  NoProgress quiet;
  Problem p = stop_and_go();
  SECTION("max_speed 4 m/s and 10 m/s² allowed: 5 m/s is never reached, no kink, nothing changes, to the bit") {
    o.max_speed_mps = 4;
    o.guard.max_acceleration = 10;  // the stops accelerate at 6 m/s²
    Result r = animate_formation(p, o);
    const CrowdMotion before = r.motion;
    guard_formation(p, r, o, quiet);
    CHECK_FALSE(r.guard.warped);
    CHECK(r.motion.positions == before.positions);
    CHECK(r.motion.times == before.times);
  }
  SECTION("max_speed 1 m/s: slowed to 1.25 m/s") {
    o.max_speed_mps = 1;
    Result r = animate_formation(p, o);
    guard_formation(p, r, o, quiet);
    CHECK(fastest(r.motion) <= 1.25);
  }
  SECTION("disabled: the paper's timing") {
    o.guard.enabled = false;
    Result r = animate_formation(p, o);
    const CrowdMotion before = r.motion;
    guard_formation(p, r, o, quiet);
    CHECK(r.motion.positions == before.positions);
    CHECK(r.keyframe_frames == std::vector<std::size_t>{0, 50, 100});
    CHECK(p.keyframes.back().time_s == 4.0);
  }
}
