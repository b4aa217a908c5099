// Bad strokes, bad options and bad starts give typed errors whose messages name the problem.
#include <throng/core/errors.h>
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <limits>

#include "scenes.h"

using namespace throng::sketch;
using Catch::Contains;

namespace {

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

std::vector<Stroke> good_strokes() {
  return {scenes::straight_stroke({0, 0}, {10, 0}, 11, 1.0), scenes::straight_stroke({0, 2}, {10, 2}, 11, 1.0)};
}

}  // namespace

TEST_CASE("a main line with one point is an input error") {
  auto strokes = good_strokes();
  strokes[0].points.resize(1);
  strokes[0].times.resize(1);
  CHECK_THROWS_AS(analyse_strokes(strokes, Options{}), throng::InputError);
  CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}),
                    Contains("stroke 0 (main line) has 1 point(s), expected at least 2"));
}

TEST_CASE("main-line time stamps that do not increase are an input error naming the point") {
  auto strokes = good_strokes();
  SECTION("equal") {
    strokes[0].times[4] = strokes[0].times[3];
    CHECK_THROWS_AS(analyse_strokes(strokes, Options{}), throng::InputError);
    CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}), Contains("time stamp 4") && Contains("not after"));
  }
  SECTION("decreasing") {
    strokes[0].times[7] = 1.0;
    CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}), Contains("time stamp 7 is 1 s, not after 6 s at point 6"));
  }
  SECTION("missing") {
    strokes[0].times.pop_back();
    CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}), Contains("10 time stamps for 11 points"));
  }
}

TEST_CASE("NaN in a stroke is an input error naming the stroke and point") {
  auto strokes = good_strokes();
  SECTION("a main-line coordinate") {
    strokes[0].points[2].y() = not_a_number;
    CHECK_THROWS_AS(analyse_strokes(strokes, Options{}), throng::InputError);
    CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}),
                      Contains("stroke 0 (main line) point 2") && Contains("finite"));
  }
  SECTION("an auxiliary coordinate") {
    strokes[1].points[5].x() = not_a_number;
    CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}), Contains("stroke 1 (auxiliary line) point 5"));
  }
  SECTION("a time stamp") {
    strokes[0].times[3] = not_a_number;
    CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}), Contains("time stamp 3 is nan"));
  }
}

TEST_CASE("missing or degenerate strokes are input errors") {
  auto strokes = good_strokes();
  CHECK_THROWS_WITH(analyse_strokes({strokes[0]}, Options{}), Contains("1 stroke(s) given"));
  strokes[1].points.assign(4, Eigen::Vector2d(3, 3));
  strokes[1].times.clear();
  CHECK_THROWS_AS(analyse_strokes(strokes, Options{}), throng::InputError);
  CHECK_THROWS_WITH(analyse_strokes(strokes, Options{}), Contains("stroke 1 (auxiliary line) has zero length"));
  auto still = good_strokes();
  for (auto& p : still[0].points) p = Eigen::Vector2d(1, 1);
  CHECK_THROWS_WITH(analyse_strokes(still, Options{}), Contains("stroke 0 (main line) has zero length"));
}

TEST_CASE("impossible options are config errors naming the field") {
  const auto strokes = good_strokes();
  auto expect = [&](Options o, const std::string& field) {
    CHECK_THROWS_AS(analyse_strokes(strokes, o), throng::ConfigError);
    CHECK_THROWS_WITH(analyse_strokes(strokes, o), Contains("sketch option " + field + " = "));
  };
  Options o;
  o.follow_radius_m = -1;
  expect(o, "follow_radius_m");
  o = {};
  o.time_step_s = 0;
  expect(o, "time_step_s");
  o = {};
  o.wide_width_m = o.narrow_width_m;
  expect(o, "wide_width_m");
  o = {};
  o.smoothing_window = -2;
  expect(o, "smoothing_window");
  o = {};
  o.irregularity_max = not_a_number;
  expect(o, "irregularity_max");
  o = {};
  o.avoid_weight = -1;
  expect(o, "avoid_weight");
  o = {};
  o.output_rate_hz = 0;
  expect(o, "output_rate_hz");
}

TEST_CASE("an agent starting inside an obstacle is an input error naming agent and obstacle") {
  Drawing drawing{good_strokes(), {{1, 1}, {5, 1}}};
  throng::Scene scene;
  scene.obstacles.push_back({throng::Circle{{5, 1}, 0.5}, {}, "fountain"});
  Options o;
  o.duration_s = 1;
  CHECK_THROWS_AS(simulate(drawing, scene, o), throng::InputError);
  CHECK_THROWS_WITH(simulate(drawing, scene, o), Contains("agent 1 starts at (5, 1) inside obstacle 0 ('fountain')"));
  drawing.initial_positions[1].x() = not_a_number;
  CHECK_THROWS_WITH(simulate(drawing, scene, o), Contains("initial position of agent 1"));
}
