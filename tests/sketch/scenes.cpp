#include "scenes.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace throng::sketch::scenes {

Stroke drawn_stroke(const CentreLine& centre, double length, double spacing,
                    const std::function<double(double)>& offset, const std::function<double(double)>& speed) {
  Stroke stroke;
  const auto segments = static_cast<std::size_t>(std::round(length / spacing));
  double time = 0.0;
  for (std::size_t m = 0; m <= segments; ++m) {
    const double s = length * static_cast<double>(m) / static_cast<double>(segments);
    const double ds = 1e-4;
    const Eigen::Vector2d c = centre(s);
    const Eigen::Vector2d t = (centre(std::min(s + ds, length)) - centre(std::max(s - ds, 0.0))).normalized();
    const Eigen::Vector2d left(-t.y(), t.x());
    if (m > 0)
      time += (length / static_cast<double>(segments)) / speed(s - 0.5 * length / static_cast<double>(segments));
    stroke.points.push_back(c + offset(s) * left);
    stroke.times.push_back(time);
  }
  return stroke;
}

Stroke straight_stroke(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::size_t points, double speed) {
  Stroke stroke;
  const double length = (b - a).norm();
  for (std::size_t m = 0; m < points; ++m) {
    const double f = static_cast<double>(m) / static_cast<double>(points - 1);
    stroke.points.push_back(a + f * (b - a));
    stroke.times.push_back(f * length / speed);
  }
  return stroke;
}

namespace {

// 80 m east, a left quarter circle of radius 20 m (31.4 m), then north (28.6 m to 140 m).
Eigen::Vector2d paper_centre(double s) {
  constexpr double straight = 80.0, radius = 20.0;
  const double arc = 0.5 * std::numbers::pi * radius;
  if (s <= straight) return {s, 0.0};
  if (s <= straight + arc) {
    const double a = (s - straight) / radius;
    return {straight + radius * std::sin(a), radius * (1 - std::cos(a))};
  }
  return {straight + radius, radius + (s - straight - arc)};
}

double smoothstep(double a, double b, double s) {
  const double x = std::clamp((s - a) / (b - a), 0.0, 1.0);
  return x * x * (3 - 2 * x);
}

}  // namespace

SketchScene paper_experiment() {
  SketchScene scene;
  scene.name = "paper_experiment";
  const CentreLine centre = paper_centre;
  auto half_width = [](double s) {
    return 4.0 + 4.0 * smoothstep(45.0, 70.0, s) -
           5.5 * smoothstep(paper_fast_from_m + 5.0, paper_fast_from_m + 25.0, s);
  };
  auto wobble = [](double s) {
    const double on = smoothstep(paper_wobbly_from_m, paper_wobbly_from_m + 3.0, s) *
                      (1.0 - smoothstep(paper_fast_from_m - 3.0, paper_fast_from_m, s));
    return on * 0.5 * std::sin(2 * std::numbers::pi * s / 4.0);
  };
  auto speed = [](double s) { return s < paper_fast_from_m ? 1.2 : 2.4; };
  const auto none = [](double) { return 0.0; };
  scene.drawing.strokes.push_back(drawn_stroke(centre, paper_length_m, 1.0, none, speed));
  scene.drawing.strokes.push_back(drawn_stroke(
      centre, paper_length_m, 0.5, [&](double s) { return half_width(s) + wobble(s); }, speed));
  scene.drawing.strokes.push_back(drawn_stroke(
      centre, paper_length_m, 0.5, [&](double s) { return -half_width(s) + wobble(s + 1.3); }, speed));
  scene.options.agent_count = 50;
  scene.options.smoothing_window = 5;
  scene.options.narrow_width_m = 4.0;
  scene.options.wide_width_m = 16.0;
  scene.options.narrow_distance_m = 1.0;
  scene.options.wide_distance_m = 2.5;
  scene.options.irregularity_max = 0.2;
  scene.options.output_rate_hz = 24.0;
  return scene;
}

SketchScene large_crowd() {
  SketchScene scene;
  scene.name = "large_crowd";
  // 260 m: 150 m east, then a gentle bend north-east.
  auto centre = [](double s) -> Eigen::Vector2d {
    if (s <= 150.0) return {s, 0.0};
    const double a = std::min((s - 150.0) / 200.0, 0.5);  // up to ~29° of turn over 100 m
    const double radius = 200.0;
    return {150.0 + radius * std::sin(a), radius * (1 - std::cos(a))};
  };
  const double length = 150.0 + 100.0;
  auto speed = [](double) { return 1.4; };
  const auto none = [](double) { return 0.0; };
  scene.drawing.strokes.push_back(drawn_stroke(centre, length, 1.0, none, speed));
  // Four auxiliary lines, at ±10 m and ±20 m: the outer pair sets the width, the inner pair spreads the targets
  // (Eq. 2–4 pull each agent's path toward its nearest strokes).
  for (const double offset : {20.0, 10.0, -10.0, -20.0}) {
    scene.drawing.strokes.push_back(drawn_stroke(centre, length, 1.0, [=](double) { return offset; }, speed));
  }

  auto& obstacles = scene.scene.obstacles;
  obstacles.push_back({Circle{{75.0, 8.0}, 1.5}, {}, "pillar north"});
  obstacles.push_back({Circle{{75.0, -10.0}, 1.5}, {}, "pillar south"});
  obstacles.push_back(
      {ConvexPolygon{{{95.0, 4.0}, {103.0, 4.0}, {104.0, 10.0}, {99.0, 13.0}, {94.0, 10.0}}}, {}, "kiosk"});
  obstacles.push_back({Wall{{125.0, 10.0}, {125.0, 30.0}, 0.6}, {}, "gate north"});
  obstacles.push_back({Wall{{125.0, -10.0}, {125.0, -30.0}, 0.6}, {}, "gate south"});
  // A cart crossing the course from south to north between the pillars and the kiosk.
  Obstacle cart{Circle{{0.0, 0.0}, 1.2}, {{0.0, {85.0, -30.0}, 0.0}, {60.0, {85.0, 30.0}, 0.0}}, "cart"};
  obstacles.push_back(cart);

  scene.options.agent_count = 2000;
  scene.options.narrow_distance_m = 0.8;
  scene.options.wide_distance_m = 1.2;
  scene.options.output_rate_hz = 10.0;
  // The whole crowd is past the gate by 190 s (seed 1); every agent arrives at about 350 s (duration 0).
  scene.options.duration_s = 200.0;
  return scene;
}

}  // namespace throng::sketch::scenes
