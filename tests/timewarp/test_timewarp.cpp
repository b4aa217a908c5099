// The time warp (Eq. 12): identity on an undeformed clip, speeds restored after a stretching deformation,
// clamping reported, smoothing, presence, determinism and errors.
#include "../graph/synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/timewarp/resample.h>
#include <throng/timewarp/timewarp.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

using namespace throng;
using namespace throng::timewarp;

namespace {

// rows × cols agents 1 m apart walking along +x at `speed` m/s, `frames` frames of `dt` s.
CrowdMotion walking_group(int rows, int cols, std::size_t frames, double speed = 1.4, double dt = 0.1) {
  CrowdMotion c = CrowdMotion::with_shape(frames, static_cast<std::size_t>(rows * cols));
  for (std::size_t f = 0; f < frames; ++f) {
    c.times[f] = static_cast<double>(f) * dt;
    for (int r = 0; r < rows; ++r) {
      for (int k = 0; k < cols; ++k) {
        c.position(f, static_cast<std::size_t>(r * cols + k)) << speed * c.times[f] - r, k - 0.5 * (cols - 1), 0.0;
      }
    }
  }
  return c;
}

// The paths bulge sideways by `amplitude` m between x = x0 and x1 (positions move, times do not): longer paths,
// so faster walking there.
CrowdMotion bulge(CrowdMotion c, double x0, double x1, double amplitude) {
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) {
      auto p = c.position(f, a);
      if (p.x() > x0 && p.x() < x1) p.y() += amplitude * std::sin(std::numbers::pi * (p.x() - x0) / (x1 - x0));
    }
  }
  return c;
}

// RMS over agents and frame intervals of |speed − target| (finite differences of the crowd's own frames).
double speed_rms_error(const CrowdMotion& c, double target) {
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t f = 0; f + 1 < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) {
      if (!c.present(f, a) || !c.present(f + 1, a)) continue;
      const double v = (c.position(f + 1, a) - c.position(f, a)).norm() / (c.times[f + 1] - c.times[f]);
      sum += (v - target) * (v - target);
      ++count;
    }
  }
  return std::sqrt(sum / static_cast<double>(count));
}

}  // namespace

TEST_CASE("the time warp of an undeformed clip is the identity") {
  const CrowdMotion crowd = test::marching_grid(4, 5, 80, 1.0, 1.3, 0.1, 0.2, 0.1);
  const Result r = time_warp(crowd, crowd, Options{});
  // s_i = Σ a² / (Δt Σ a²) = 1/Δt up to rounding; the warped times are sums of the intervals.
  const double duration = crowd.times.back() - crowd.times.front();
  for (std::size_t i = 0; i < crowd.frame_count(); ++i) CHECK(std::abs(r.warp.warped_times[i] - crowd.times[i]) <= 1e-12 * duration);
  for (std::size_t i = 0; i + 1 < crowd.frame_count(); ++i) {
    CHECK(r.warp.inverse_intervals[i] * (crowd.times[i + 1] - crowd.times[i]) == Approx(1.0).epsilon(1e-13));
    CHECK(r.warp.bound[i] == 0);
  }
  CHECK(r.report.speed_deviation_before <= 1e-12);
  CHECK(r.report.speed_deviation_after <= 1e-12);
  // Resampled at the input's rate: the same frames, positions back to rounding (times agree to ~1e-15 s, speeds
  // are ~1.3 m/s).
  REQUIRE(r.crowd.frame_count() == crowd.frame_count());
  double gap = 0;
  for (std::size_t k = 0; k < crowd.positions.size(); ++k) gap = std::max(gap, std::abs(r.crowd.positions[k] - crowd.positions[k]));
  CHECK(gap <= 1e-9);
  CHECK(r.crowd.ids == crowd.ids);
  REQUIRE(r.crowd.velocities.size() == r.crowd.positions.size());
  CHECK(r.crowd.velocities[r.crowd.index(40, 3)] == Approx((crowd.position(41, 3).x() - crowd.position(39, 3).x()) / 0.2).epsilon(0.01));
}

TEST_CASE("after a deformation that stretches paths, the warp brings speeds closer to the original's") {
  // 12 s at 1.4 m/s: x from 0 (front row) to 16.8 m; the paths bulge 2 m sideways between x = 4 and 12 m, which
  // speeds walkers up by up to 27 % there.
  SECTION("a row walking abreast is stretched alike: one shared warp undoes it") {
    const CrowdMotion original = walking_group(1, 5, 121);
    const CrowdMotion deformed = bulge(original, 4.0, 12.0, 2.0);
    const Result r = time_warp(deformed, original, Options{});
    const double output_before = speed_rms_error(deformed, 1.4), output_after = speed_rms_error(r.crowd, 1.4);
    std::printf("time warp, row abreast: Eq. 12 speed deviation %.4f -> %.2g m/s; output speed error %.4f -> %.4f m/s; "
                "duration %.2f -> %.2f s\n", r.report.speed_deviation_before, r.report.speed_deviation_after, output_before,
                output_after, r.report.duration_in_s, r.report.duration_out_s);
    CHECK(r.report.speed_deviation_before > 0.1);
    CHECK(r.report.speed_deviation_after <= 1e-12);  // every agent's step asks for the same s_i: exact
    // The output is resampled at 10 Hz between warped frames; its finite-difference speeds are close to 1.4.
    CHECK(output_after < 0.1 * output_before);
    // Outside the bulge nobody's speed changed, so those intervals keep their length.
    CHECK(r.warp.inverse_intervals[5] * 0.1 == Approx(1.0).epsilon(1e-12));
    CHECK(r.report.duration_out_s > r.report.duration_in_s + 0.5);
  }
  SECTION("a group three rows deep reaches the bulge row by row: the shared warp undoes much of it") {
    const CrowdMotion original = walking_group(3, 4, 121);
    const CrowdMotion deformed = bulge(original, 4.0, 12.0, 2.0);
    const Result r = time_warp(deformed, original, Options{});
    const double before = r.report.speed_deviation_before, after = r.report.speed_deviation_after;
    const double output_before = speed_rms_error(deformed, 1.4), output_after = speed_rms_error(r.crowd, 1.4);
    std::printf("time warp, group 3 rows deep: Eq. 12 speed deviation %.4f -> %.4f m/s; output speed error %.4f -> %.4f m/s; "
                "duration %.2f -> %.2f s\n", before, after, output_before, output_after, r.report.duration_in_s,
                r.report.duration_out_s);
    // Rows 1 m apart on an 8 m bulge see speed-ups up to ~π/8 out of phase, which no shared warp can all undo.
    CHECK(before > 0.1);
    CHECK(after < 0.6 * before);
    CHECK(output_after < 0.6 * output_before);
    CHECK(r.report.clamped_short + r.report.clamped_long == 0);
    CHECK(r.crowd.frame_count() > original.frame_count());
  }
}

TEST_CASE("the clamp keeps every interval ratio in its bounds and is reported") {
  const CrowdMotion original = walking_group(1, 3, 41);
  CrowdMotion deformed = original;
  // From frame 20 on everybody is 6 m further: interval 19 → 20 is 0.14 m long originally and 6.14 m now, so it
  // would need to last 44× longer.
  for (std::size_t f = 20; f < deformed.frame_count(); ++f) {
    for (std::size_t a = 0; a < 3; ++a) deformed.position(f, a).x() += 6.0;
  }
  Options o;
  o.max_interval_ratio = 4.0;
  const Result r = time_warp(deformed, original, o);
  CHECK(r.report.clamped_long == 1);
  CHECK(r.warp.bound[19] == 1);
  CHECK(r.warp.warped_times[20] - r.warp.warped_times[19] == Approx(0.4).epsilon(1e-12));
  for (std::size_t i = 0; i + 1 < deformed.frame_count(); ++i) {
    const double ratio = (r.warp.warped_times[i + 1] - r.warp.warped_times[i]) / 0.1;
    CHECK(ratio >= o.min_interval_ratio * (1 - 1e-12));
    CHECK(ratio <= o.max_interval_ratio * (1 + 1e-12));
  }
  // With smoothing the clamp is a constraint of the smoothed problem; the bounds still hold.
  o.smoothing_time = 0.5;
  const Result smooth = time_warp(deformed, original, o);
  CHECK(smooth.report.clamped_long >= 1);
  for (std::size_t i = 0; i + 1 < deformed.frame_count(); ++i) {
    const double ratio = (smooth.warp.warped_times[i + 1] - smooth.warp.warped_times[i]) / 0.1;
    CHECK(ratio >= o.min_interval_ratio * (1 - 1e-12));
    CHECK(ratio <= o.max_interval_ratio * (1 + 1e-12));
  }
}

TEST_CASE("smoothing makes the warp vary less, and tends to the closed form as it vanishes") {
  const CrowdMotion original = walking_group(3, 4, 121);
  const CrowdMotion deformed = bulge(original, 4.0, 12.0, 2.0);
  auto variation = [](const Warp& w) {
    double v = 0;
    for (std::size_t i = 0; i + 1 < w.inverse_intervals.size(); ++i) v += std::abs(w.inverse_intervals[i + 1] - w.inverse_intervals[i]);
    return v;
  };
  Options o;
  const Warp sharp = time_warp(deformed, original, o).warp;
  o.smoothing_time = 1.0;
  const Result smooth = time_warp(deformed, original, o);
  CHECK(variation(smooth.warp) < 0.5 * variation(sharp));
  // Smoothing trades some of Eq. 12 for smoothness: worse fit than the closed form, still far better than none.
  CHECK(smooth.report.speed_deviation_after > time_warp(deformed, original, Options{}).report.speed_deviation_after);
  CHECK(smooth.report.speed_deviation_after < 0.6 * smooth.report.speed_deviation_before);
  o.smoothing_time = 1e-6;
  const Warp tiny = time_warp(deformed, original, o).warp;
  for (std::size_t i = 0; i < sharp.inverse_intervals.size(); ++i) {
    CHECK(tiny.inverse_intervals[i] == Approx(sharp.inverse_intervals[i]).epsilon(1e-6));
  }
}

TEST_CASE("agents entering and leaving keep their presence through the warp") {
  const CrowdMotion original = walking_group(2, 3, 61);
  CrowdMotion deformed = bulge(original, 2.0, 6.0, 1.0);
  CrowdMotion reference = original;
  for (std::size_t f = 0; f < 61; ++f) {
    if (f < 10 || f > 40) {
      deformed.position(f, 4) << absent, absent, absent;
      reference.position(f, 4) << absent, absent, absent;
    }
  }
  const Result r = time_warp(deformed, reference, Options{});
  // Present over its warped samples' span, widened to the output frames nearest its first and last samples: by
  // half an output interval (0.05 s at 10 Hz), but less than half the way to the frames where it is absent.
  const std::vector<double>& w = r.warp.warped_times;
  const double enter = w[10] - std::min(0.05, 0.5 * (w[10] - w[9])), leave = w[40] + std::min(0.05, 0.5 * (w[41] - w[40]));
  for (std::size_t k = 0; k < r.crowd.frame_count(); ++k) {
    const double t = r.crowd.times[k];
    INFO("output time " << t << ", present from " << enter << " to " << leave);
    CHECK(r.crowd.present(k, 4) == (t >= enter - 1e-9 && t <= leave + 1e-9));
    CHECK(r.crowd.present(k, 0));
  }
  r.crowd.validate("warped crowd");
}

TEST_CASE("the warped crowd has the same bits with one thread and with two") {
  const CrowdMotion original = test::marching_grid(6, 8, 90, 1.0, 1.2, 0.1, 0.3, 0.2);
  const CrowdMotion deformed = bulge(original, 1.0, 6.0, 1.5);
  Options o;
  o.smoothing_time = 0.3;
  o.output_rate_hz = 24;
  Result one, two;
  {
    ThreadLimit limit(1);
    one = time_warp(deformed, original, o);
  }
  {
    ThreadLimit limit(2);
    two = time_warp(deformed, original, o);
  }
  CHECK(one.crowd.positions == two.crowd.positions);
  CHECK(one.crowd.velocities == two.crowd.velocities);
  CHECK(one.warp.warped_times == two.warp.warped_times);
}

TEST_CASE("a reference that does not fit and bad options are errors naming what is wrong") {
  const CrowdMotion original = walking_group(1, 3, 21);
  CrowdMotion other_ids = original;
  other_ids.ids[1] = 77;
  CHECK_THROWS_AS(time_warp(other_ids, original, Options{}), InputError);
  CHECK_THROWS_WITH(time_warp(other_ids, original, Options{}), Catch::Contains("agent 77") && Catch::Contains("not in the reference"));
  CrowdMotion shifted = original;
  for (double& t : shifted.times) t += 0.05;
  CHECK_THROWS_WITH(time_warp(shifted, original, Options{}), Catch::Contains("has no reference frame"));
  Options o;
  o.min_interval_ratio = 0;
  CHECK_THROWS_AS(time_warp(original, original, o), ConfigError);
  o = Options{};
  o.max_interval_ratio = 0.5;
  CHECK_THROWS_WITH(time_warp(original, original, o), Catch::Contains("max_interval_ratio"));
  o = Options{};
  o.smoothing_time = -1;
  CHECK_THROWS_WITH(time_warp(original, original, o), Catch::Contains("smoothing_time"));
  CHECK_THROWS_AS(uniform_times(0, 1, 0), ConfigError);
}
