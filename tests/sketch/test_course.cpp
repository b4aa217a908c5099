// The stroke parameters (paper §4, Eq. 1, 5–12) on strokes whose values can be computed by hand.
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "scenes.h"

using namespace throng::sketch;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using Eigen::Vector2d;

namespace {

// Main line along x from 0 to 10, one point per metre; 1 s per metre for x ≤ 5, 0.5 s per metre after.
Stroke slow_then_fast_main() {
  Stroke s;
  double t = 0;
  for (int x = 0; x <= 10; ++x) {
    if (x > 0) t += x <= 5 ? 1.0 : 0.5;
    s.points.emplace_back(x, 0);
    s.times.push_back(t);
  }
  return s;
}

Stroke line(Vector2d a, Vector2d b) { return {{a, b}, {}}; }

// Options with round numbers for Eq. 7: W_N = 2, W_W = 6, s_N = 1, s_W = 3.
Options round_options() {
  Options o;
  o.narrow_width_m = 2;
  o.wide_width_m = 6;
  o.narrow_distance_m = 1;
  o.wide_distance_m = 3;
  o.smoothing_window = 2;
  return o;
}

}  // namespace

TEST_CASE("speed is each main-line segment's length over its drawing time (Eq. 5)") {
  const Course c = analyse_strokes({slow_then_fast_main(), line({0, 3}, {10, 3})}, Options{});
  REQUIRE(c.point_count() == 11);
  for (std::size_t k = 1; k <= 5; ++k) CHECK_THAT(c.speed[k], WithinRel(1.0, 1e-12));
  for (std::size_t k = 6; k <= 10; ++k) CHECK_THAT(c.speed[k], WithinRel(2.0, 1e-12));
  CHECK(c.speed[0] == c.speed[1]);

  Options scaled;
  scaled.speed_scale = 0.5;
  const Course half = analyse_strokes({slow_then_fast_main(), line({0, 3}, {10, 3})}, scaled);
  for (std::size_t k = 0; k < 11; ++k) CHECK_THAT(half.speed[k], WithinRel(0.5 * c.speed[k], 1e-12));
}

TEST_CASE("a pen pause merges into the next segment, which becomes slower") {
  Stroke main;
  main.points = {{0, 0}, {0, 0}, {2, 0}, {4, 0}};
  main.times = {0, 1, 3, 4};
  const Course c = analyse_strokes({main, line({0, 1}, {4, 1})}, Options{});
  REQUIRE(c.point_count() == 3);
  CHECK_THAT(c.speed[1], WithinRel(2.0 / 3.0, 1e-12));  // 2 m in 3 s including the 1 s pause
  CHECK_THAT(c.speed[2], WithinRel(2.0, 1e-12));
}

TEST_CASE("auxiliary lines correspond to the main line by normalised arc length") {
  // Main points at x = 0, 1, 10 (fractions 0, 0.1, 1); the auxiliary line is twice as long.
  Stroke main;
  main.points = {{0, 0}, {1, 0}, {10, 0}};
  main.times = {0, 1, 2};
  const Course c = analyse_strokes({main, line({0, 2}, {20, 2})}, Options{});
  REQUIRE(c.auxiliary_count() == 1);
  CHECK_THAT(c.auxiliary[0][0].x(), WithinAbs(0.0, 1e-12));
  CHECK_THAT(c.auxiliary[0][1].x(), WithinAbs(2.0, 1e-12));
  CHECK_THAT(c.auxiliary[0][2].x(), WithinAbs(20.0, 1e-12));
}

TEST_CASE("resampling the main line keeps its speeds and makes its spacing uniform") {
  Stroke main;
  main.points = {{0, 0}, {4, 0}, {10, 0}};
  main.times = {0, 4, 7};  // 1 m/s, then 2 m/s
  Options o;
  o.resample_spacing_m = 0.5;
  const Course c = analyse_strokes({main, line({0, 2}, {10, 2})}, o);
  REQUIRE(c.point_count() == 21);
  for (std::size_t k = 1; k < c.point_count(); ++k) {
    CHECK_THAT((c.main[k] - c.main[k - 1]).norm(), WithinAbs(0.5, 1e-12));
    CHECK_THAT(c.speed[k], WithinRel(c.main[k].x() <= 4.0 + 1e-9 ? 1.0 : 2.0, 1e-9));
  }
}

TEST_CASE("width is measured between the farthest smoothed points on each side (Eq. 6–7)") {
  const Options o = round_options();
  SECTION("one auxiliary line: its distance to the main line") {
    const Course c = analyse_strokes({slow_then_fast_main(), line({0, 3}, {10, 3})}, o);
    for (std::size_t k = 0; k < 11; ++k) {
      CHECK_THAT(c.width[k], WithinAbs(3.0, 1e-12));
      CHECK_THAT(c.standard_distance[k], WithinAbs(1.5, 1e-12));  // 1 + (3 − 1)/(6 − 2) · (3 − 2)
    }
  }
  SECTION("lines on both sides: the distance between them") {
    const Course c = analyse_strokes({slow_then_fast_main(), line({0, 3}, {10, 3}), line({0, -2}, {10, -2})}, o);
    for (std::size_t k = 0; k < 11; ++k) {
      CHECK_THAT(c.width[k], WithinAbs(5.0, 1e-12));
      CHECK_THAT(c.standard_distance[k], WithinAbs(2.5, 1e-12));
    }
  }
  SECTION("two lines on one side: the farther one") {
    const Course c = analyse_strokes({slow_then_fast_main(), line({0, 2}, {10, 2}), line({0, 4}, {10, 4})}, o);
    for (std::size_t k = 0; k < 11; ++k) CHECK_THAT(c.width[k], WithinAbs(4.0, 1e-12));
  }
  SECTION("the standard distance is clamped outside [W_N, W_W]") {
    const Course narrow = analyse_strokes({slow_then_fast_main(), line({0, 1}, {10, 1})}, o);
    const Course wide = analyse_strokes({slow_then_fast_main(), line({0, 9}, {10, 9})}, o);
    CHECK(narrow.standard_distance[4] == o.narrow_distance_m);
    CHECK(wide.standard_distance[4] == o.wide_distance_m);
  }
  SECTION("a widening band gives a growing standard distance") {
    const Course c = analyse_strokes({slow_then_fast_main(), line({0, 2}, {10, 6})}, o);
    for (std::size_t k = 1; k < 11; ++k) {
      CHECK(c.width[k] > c.width[k - 1]);
      CHECK(c.standard_distance[k] > c.standard_distance[k - 1]);
    }
  }
}

// Zig-zag auxiliary line y_k = 2 + 0.5 (−1)^k at x = k: its distance to the main line alternates 2.5, 1.5, so
// G_k = (−1)^k exactly (Eq. 8). With δ = 2 an interior window holds 5 values of alternating sign: mean ±1/5,
// variance 1 − 1/25 = 0.96. At k = 0 the window is truncated to 3 values: mean 1/3, variance 8/9.
TEST_CASE("irregularity is the windowed variance of the distance change (Eq. 8–12) on a zig-zag") {
  Stroke zigzag;
  for (int k = 0; k <= 10; ++k) zigzag.points.emplace_back(k, 2 + 0.5 * (k % 2 == 0 ? 1 : -1));
  Options o = round_options();
  o.irregularity_gain = 2.0;
  o.irregularity_max = 1.0;
  const Course c = analyse_strokes({slow_then_fast_main(), zigzag}, o);
  REQUIRE(c.distance_change[0].size() == 10);
  for (std::size_t k = 0; k < 10; ++k) CHECK_THAT(c.distance_change[0][k], WithinAbs(k % 2 == 0 ? 1.0 : -1.0, 1e-12));
  for (std::size_t k = 2; k <= 7; ++k) CHECK_THAT(c.irregularity[k], WithinAbs(2.0 * 0.96, 1e-12));
  CHECK_THAT(c.irregularity[0], WithinAbs(2.0 * 8.0 / 9.0, 1e-12));
  for (std::size_t k = 0; k < 11; ++k) CHECK(c.correction_scale[k] == 1.0);  // E ≥ E_MAX: clamped (Eq. 13)

  SECTION("smoothing (Eq. 1) averages the zig-zag over the window and keeps the end points") {
    CHECK_THAT(c.smoothed[0][0].y(), WithinAbs(2.5, 1e-12));              // window shrunk to the point itself
    CHECK_THAT(c.smoothed[0][1].y(), WithinAbs(2.0 + 0.5 / 3.0, 1e-12));  // 3 points: 2.5, 1.5, 2.5
    for (std::size_t k = 2; k <= 8; ++k) {
      CHECK_THAT(c.smoothed[0][k].y(), WithinAbs(2.0 + (k % 2 == 0 ? 0.1 : -0.1), 1e-12));  // 5 points
    }
    CHECK_THAT(c.smoothed[0][10].y(), WithinAbs(2.5, 1e-12));
  }
}

TEST_CASE("a straight or evenly widening auxiliary line has no irregularity") {
  const Options o = round_options();
  for (const Stroke& aux : {line({0, 3}, {10, 3}), line({0, 2}, {10, 6})}) {
    const Course c = analyse_strokes({slow_then_fast_main(), aux}, o);
    for (std::size_t k = 0; k < c.point_count(); ++k) {
      CHECK_THAT(c.irregularity[k], WithinAbs(0.0, 1e-24));
      CHECK(c.correction_scale[k] < 1e-20);
    }
  }
}

TEST_CASE("the paper experiment's parameters change along the course as drawn") {
  const scenes::SketchScene scene = scenes::paper_experiment();
  const Course c = analyse_strokes(scene.drawing.strokes, scene.options);
  const std::vector<double> s = [&] {
    std::vector<double> along(c.point_count(), 0.0);
    for (std::size_t k = 1; k < along.size(); ++k) along[k] = along[k - 1] + (c.main[k] - c.main[k - 1]).norm();
    return along;
  }();
  auto max_over = [&](const std::vector<double>& v, double from, double to) {
    double m = -1;
    for (std::size_t k = 0; k < v.size(); ++k) {
      if (s[k] >= from && s[k] <= to) m = std::max(m, v[k]);
    }
    return m;
  };
  // Irregular only where the auxiliary lines wobble; faster where the main line was drawn faster.
  CHECK(max_over(c.correction_scale, 50, 75) > 0.5);
  CHECK(max_over(c.correction_scale, 0, 30) < 0.01);
  CHECK(max_over(c.correction_scale, 95, 140) < 0.1);
  CHECK_THAT(max_over(c.speed, 85, 140), WithinRel(2.0 * max_over(c.speed, 5, 75), 1e-6));
  // Wider (and so a larger standard distance) in the middle than at either end.
  CHECK(max_over(c.standard_distance, 65, 80) > max_over(c.standard_distance, 0, 10) + 0.5);
  CHECK(max_over(c.standard_distance, 65, 80) > max_over(c.standard_distance, 120, 140) + 0.5);
}
