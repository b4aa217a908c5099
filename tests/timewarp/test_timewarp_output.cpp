// What the time warp writes: the reported duration is that of the frames written, a small warp keeps every
// agent's last sample, and facing and actions pass through the resampling (issue 17's cases).
#include <throng/core/crowd_motion.h>
#include <throng/core/errors.h>
#include <throng/timewarp/resample.h>
#include <throng/timewarp/timewarp.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace throng;
using namespace throng::timewarp;

namespace {

// `agents` walkers along +x at 1.4 m/s, 0.5 m apart in y, `frames` frames at 2.5 Hz (the ETH/UCY rate).
CrowdMotion walkers(std::size_t agents, std::size_t frames) {
  CrowdMotion c = CrowdMotion::with_shape(frames, agents);
  for (std::size_t f = 0; f < frames; ++f) {
    c.times[f] = 0.4 * static_cast<double>(f);
    for (std::size_t a = 0; a < agents; ++a) c.position(f, a) << 1.4 * c.times[f], 0.5 * static_cast<double>(a), 0.0;
  }
  return c;
}

// Every step scaled by `k`: the warp (Eq. 12 against the unscaled crowd) scales every interval by k.
CrowdMotion scaled(CrowdMotion c, double k) {
  for (double& p : c.positions) p *= k;
  return c;
}

std::size_t present_frames(const CrowdMotion& c, std::size_t agent) {
  std::size_t n = 0;
  for (std::size_t f = 0; f < c.frame_count(); ++f) n += c.present(f, agent) ? 1 : 0;
  return n;
}

}  // namespace

TEST_CASE("timewarp reports the duration of the frames it wrote and not the warp's span") {
  // 1052 frames at 2.5 Hz end at 420.4 s; the warp stretches them to 420.52 s, beyond the last 2.5 Hz frame
  // (420.4 s) by less than half an interval: the frames written end at 420.4 s and the report says so.
  const CrowdMotion original = walkers(3, 1052);
  REQUIRE(original.times.back() == Approx(420.4));
  const Result r = time_warp(scaled(original, 420.52 / 420.4), original, Options{});
  CHECK(r.report.warped_duration_s == Approx(420.52).epsilon(1e-9));
  CHECK(r.report.duration_out_s == Approx(420.4).epsilon(1e-12));
  CHECK(r.report.duration_out_s == r.crowd.times.back() - r.crowd.times.front());
  CHECK(r.report.frames_out == 1052);
  CHECK(r.report.output_rate_hz == 2.5);
}

TEST_CASE("a warp of 27 ms keeps every agent's last sample") {
  // 26 frames (10 s at 2.5 Hz); every step is 0.27 % shorter than the reference's, so the warp shortens the clip
  // by 27 ms. Agent 3 enters at frame 3 and leaves after frame 20.
  CrowdMotion original = walkers(4, 26);
  for (std::size_t f = 0; f < original.frame_count(); ++f) {
    if (f < 3 || f > 20) original.position(f, 3).setConstant(absent);
  }
  const double k = (10.0 - 0.027) / 10.0;
  const CrowdMotion deformed = scaled(original, k);
  const Result r = time_warp(deformed, original, Options{});
  REQUIRE(r.report.warped_duration_s == Approx(10.0 - 0.027).epsilon(1e-12));
  // Before the fix the output ended at 9.6 s: 25 frames, every agent's sample at 10 s dropped.
  REQUIRE(r.crowd.frame_count() == 26);
  CHECK(r.crowd.times.back() == Approx(10.0));
  CHECK(r.report.duration_out_s == Approx(10.0));
  for (std::size_t a = 0; a < 4; ++a) {
    INFO("agent " << a);
    CHECK(present_frames(r.crowd, a) == present_frames(original, a));
  }
  // The walkers' last output frame holds their last position (the spline's end, held half a frame at most).
  for (std::size_t a = 0; a < 3; ++a) CHECK((r.crowd.position(25, a) - deformed.position(25, a)).norm() < 1e-12);
  // Agent 3: present at output frames 3..20 exactly, its last one holding its last sample (warped to 7.978 s).
  CHECK(!r.crowd.present(2, 3));
  CHECK(r.crowd.present(3, 3));
  CHECK(r.crowd.present(20, 3));
  CHECK(!r.crowd.present(21, 3));
  CHECK((r.crowd.position(20, 3) - deformed.position(20, 3)).norm() < 1e-12);
}

TEST_CASE("resampling never widens an agent's presence into a frame where it is absent") {
  // A gap of one frame (frame 5) between two runs: with any slack, output frames nearest the gap stay absent.
  CrowdMotion c = walkers(1, 12);
  c.position(5, 0).setConstant(absent);
  std::vector<double> times;
  for (int g = 0; g < 12; ++g) times.push_back(0.4 * g);
  const CrowdMotion out = resample_crowd(c, c.times, times, SplineEnd::not_a_knot, false, 0.2);
  for (std::size_t f = 0; f < 12; ++f) CHECK(out.present(f, 0) == c.present(f, 0));
  CHECK_THROWS_AS(resample_crowd(c, c.times, times, SplineEnd::not_a_knot, false, -1.0), ConfigError);
}

TEST_CASE("facing and actions pass through the resampling and the warp") {
  // Two agents turning at a steady 10°/frame while they walk; at 1.2 s agent 0 stands, agent 1 waves a flag.
  CrowdMotion c = walkers(2, 8);
  c.orientations.assign(c.frame_count() * c.agent_count() * 4, 0.0);
  c.actions.assign(c.frame_count() * c.agent_count(), action_walk);
  c.action_table = standard_actions();
  c.action_table.push_back({"wave", "flag"});
  constexpr double deg = std::numbers::pi / 180.0;
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < 2; ++a) {
      c.orientation(f, a) = Eigen::Quaterniond(Eigen::AngleAxisd(10.0 * deg * static_cast<double>(f), Eigen::Vector3d::UnitZ()));
      c.action(f, a) = c.times[f] >= 1.2 - 1e-9 ? (a == 0 ? action_stand : 3) : action_walk;
    }
  }
  c.validate();
  auto yaw = [](const CrowdMotion& m, std::size_t f, std::size_t a) {
    const Eigen::Quaterniond q = m.orientation(f, a);
    return 2.0 * std::atan2(q.z(), q.w());
  };

  SECTION("resampled at the midpoints: the halfway facing, the earlier sample's action") {
    std::vector<double> mids;
    for (std::size_t f = 0; f + 1 < c.frame_count(); ++f) mids.push_back(c.times[f] + 0.2);
    const CrowdMotion out = resample_crowd(c, c.times, mids);
    REQUIRE(out.orientations.size() == mids.size() * 2 * 4);
    REQUIRE(out.action_table == c.action_table);
    out.validate();
    for (std::size_t k = 0; k < mids.size(); ++k) {
      for (std::size_t a = 0; a < 2; ++a) {
        CHECK(yaw(out, k, a) == Approx((10.0 * static_cast<double>(k) + 5.0) * deg).epsilon(1e-12));
        CHECK(out.action(k, a) == c.action(k, a));
      }
    }
    // Agent 1 with the switch at frame 3 (1.2 s): the midpoint 1.0 s is still walking, 1.4 s waving.
    CHECK(out.action(2, 1) == action_walk);
    CHECK(out.action(3, 1) == 3);
  }
  SECTION("an agent present in part of the frames has its facing and action there") {
    CrowdMotion p = c;
    p.position(0, 1).setConstant(absent);
    p.position(7, 1).setConstant(absent);
    const CrowdMotion out = resample_crowd(p, p.times, p.times);
    for (std::size_t f = 1; f < 7; ++f) {
      CHECK(yaw(out, f, 1) == Approx(10.0 * static_cast<double>(f) * deg));
      CHECK(out.action(f, 1) == p.action(f, 1));
    }
    CHECK(!out.present(0, 1));
    out.validate();
  }
  SECTION("the identity warp at a doubled output rate keeps them and the table") {
    Options o;
    o.output_rate_hz = 5.0;
    const Result r = time_warp(c, c, o);
    REQUIRE(r.crowd.frame_count() == 15);
    REQUIRE(r.crowd.action_table == c.action_table);
    r.crowd.validate();
    for (std::size_t g = 0; g < r.crowd.frame_count(); ++g) {
      CHECK(yaw(r.crowd, g, 0) == Approx(5.0 * static_cast<double>(g) * deg).margin(1e-9));
      if (g % 2 == 1) CHECK(r.crowd.action(g, 1) == c.action(g / 2, 1));  // between frames: the earlier one's
    }
  }
}
