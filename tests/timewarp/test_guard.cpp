// The plausibility guard (throng/timewarp/guard.h): it leaves plausible motion alone, slows a crowd down by one
// shared warp where an agent got too fast, smooths kinks, and — on the edit library's output, where a drag
// stretches paths and bends them where it starts — brings the result within the limits of the independent
// checker.
#include "../graph/synthetic_crowd.h"

#include <throng/check/motion_check.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/edit/edit.h>
#include <throng/timewarp/guard.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace throng;
using namespace throng::timewarp;

namespace {

// One agent walking +x at 1.2 m/s, 10 frames per second, 20 s; `bend(t)` adds a sideways offset.
template <class Bend>
CrowdMotion walker(Bend bend) {
  CrowdMotion c = CrowdMotion::with_shape(201, 1, 0.25);
  for (std::size_t f = 0; f < 201; ++f) {
    c.times[f] = 0.1 * static_cast<double>(f);
    c.position(f, 0) = Eigen::Vector3d(1.2 * c.times[f], bend(c.times[f]), 0);
  }
  return c;
}

check::Limits limits_for(const CrowdMotion& source) {
  const check::Statistics s = check::measure(source, {}, check::Settings{});
  check::Limits l;
  l.max_speed = 1.25 * s.speed.max;
  l.max_acceleration = std::max(l.max_acceleration, s.acceleration.max);
  l.acceleration_p99 = std::max(l.acceleration_p99, s.acceleration.p99);
  l.max_turning_rate = l.turning_rate_p99 = check::unlimited;  // the guard bounds speed and acceleration
  return l;
}

}  // namespace

TEST_CASE("plausible motion goes through the guard unchanged") {
  const CrowdMotion c = walker([](double t) { return 0.5 * std::sin(0.3 * t); });
  const GuardResult r = guard(c, source_of(c, c), GuardOptions{});
  CHECK(r.crowd.positions == c.positions);
  CHECK(r.crowd.times == c.times);
  CHECK_FALSE(r.report.warped);
  CHECK(r.report.windows == 0);
  CHECK(r.report.kinks_before == 0);
}

TEST_CASE("a stretch of path walked too fast is slowed by the warp, ramped, and the clip gets longer") {
  // The source walks at 1.2 m/s; the output has a 4 s stretch at 2.4 m/s (a detour walked in the old time).
  const CrowdMotion source = walker([](double) { return 0.0; });
  CrowdMotion fast = source;
  double x = 0;
  for (std::size_t f = 1; f < 201; ++f) {
    const double t = fast.times[f];
    const double speed = 1.2 * (1 + 0.5 * (1 - std::cos(std::numbers::pi * std::clamp((t - 8) / 4, 0.0, 2.0))) / 1);
    x += 0.1 * std::min(speed, 2.4);
    fast.position(f, 0).x() = x;
  }
  GuardOptions o;
  const GuardResult r = guard(fast, source_of(fast, source), o);
  REQUIRE(r.report.warped);
  CHECK(r.report.speed_limit == Approx(1.5));
  CHECK(r.report.max_speed_before > 2.3);
  CHECK(r.report.max_speed_after <= 1.5 * (1 + 1e-3));  // the splines through the warped knots: rounding only
  CHECK(r.report.duration_after > r.report.duration_before);
  CHECK(r.report.largest_stretch >= 2.3 / 1.5);
  // Resampled at the input's rate, starting where it started; the path is the same (same end point).
  CHECK(r.crowd.times.front() == fast.times.front());
  CHECK(r.crowd.times[1] - r.crowd.times[0] == Approx(0.1));
  CHECK(r.crowd.position(0, 0) == fast.position(0, 0));
  // The ramp keeps the slow-down itself gentle: within the acceleration limit.
  std::string broken;
  for (const check::Violation& v : check::check(check::measure(r.crowd, {}, check::Settings{}), limits_for(source)).violations) {
    broken += check::describe(v) + "; ";
  }
  INFO(broken);
  CHECK(broken.empty());
}

TEST_CASE("a kink is smoothed within its window and nowhere else") {
  // A right-angle turn at 10 s: 1.2 m/s east, then 1.2 m/s north — 17 m/s² at the corner frame.
  CrowdMotion kinked = CrowdMotion::with_shape(201, 1, 0.25);
  for (std::size_t f = 0; f < 201; ++f) {
    const double t = 0.1 * static_cast<double>(f);
    kinked.times[f] = t;
    kinked.position(f, 0) = t <= 10 ? Eigen::Vector3d(1.2 * t, 0, 0) : Eigen::Vector3d(12, 1.2 * (t - 10), 0);
  }
  const Source source{1.2, std::vector<double>(201, 0.0)};
  GuardOptions o;
  const GuardResult r = guard(kinked, source, o);
  CHECK(r.report.kinks_before > 0);
  CHECK(r.report.kinks_after == 0);
  CHECK_FALSE(r.report.warped);
  CHECK(r.report.max_acceleration_after <= o.max_acceleration * (1 + 1e-9));
  // Frames farther from the corner than the widest window keep their positions; the corner is cut by at most
  // what the widest window allows (the bridge stays inside the corner's hull: ≤ 1.2 m/s × max_window_time).
  const auto widest = static_cast<std::size_t>(std::ceil(o.max_window_time / 0.1)) + 2;
  for (std::size_t f = 0; f < 201; ++f) {
    if (f + widest < 100 || f > 100 + widest) CHECK(r.crowd.position(f, 0) == kinked.position(f, 0));
  }
  CHECK(r.report.largest_shift <= 1.2 * o.max_window_time);
  CHECK(r.report.largest_shift > 0);
}

TEST_CASE("the guard gives the same bits with one thread and with two") {
  CrowdMotion c = test::marching_grid(3, 4, 121, 1.0, 1.3, 0.1, 0.4, 0.2, 3);
  for (std::size_t f = 60; f < 121; ++f) {
    for (std::size_t a = 0; a < 12; ++a) c.position(f, a).y() += 3.0;  // a jump: every agent kinks, and speeds
  }
  const Source s = source_of(c, test::marching_grid(3, 4, 121, 1.0, 1.3, 0.1, 0.4, 0.2, 3));
  GuardResult one, two;
  {
    const ThreadLimit limit(1);
    one = guard(c, s, GuardOptions{});
  }
  {
    const ThreadLimit limit(2);
    two = guard(c, s, GuardOptions{});
  }
  CHECK(one.report.warped);
  CHECK(one.crowd.positions == two.crowd.positions);
  CHECK(one.crowd.times == two.crowd.times);
}

TEST_CASE("the edit library's output, guarded, is within the checker's limits, unguarded it is not") {
  // A marching group whose last 3 s are dragged 8 m sideways (the battlefield edit in small): the paths between
  // stretch (faster walkers) and bend where the drag starts. This is where `throng edit` should call the guard
  // (docs: the coordinator wires it into the edit command; the test shows the library output it must take).
  const CrowdMotion input = test::marching_grid(3, 4, 201, 1.2, 1.3, 1.0 / 24, 0.0, 0.1, 7);
  edit::Options options;
  options.clip.sample_step = 12;
  edit::Request request;
  edit::Drag head;
  head.selection.first_frame = 0;
  head.selection.last_frame = 0;
  edit::Drag tail;
  tail.selection.first_frame = -72;
  tail.offset = Eigen::Vector2d(0, 8);
  request.drags = {head, tail};
  const edit::Result edited = edit::edit_group_motion(input, options, request);
  const check::Limits limits = limits_for(input);
  const check::Verdict before = check::check(check::measure(edited.crowd, {}, check::Settings{}), limits);
  REQUIRE_FALSE(before.passed());
  const GuardResult guarded = guard(edited.crowd, source_of(edited.crowd, input), GuardOptions{});
  const check::Verdict after = check::check(check::measure(guarded.crowd, {}, check::Settings{}), limits);
  std::string broken;
  for (const check::Violation& v : after.violations) broken += check::describe(v) + "; ";
  INFO(broken);
  CHECK(after.passed());
  CHECK(guarded.report.kinks_after == 0);
}
