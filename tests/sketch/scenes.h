// Stroke-driven crowd scenes as data, shared by the tests and the benchmarks (and the source of the example
// configs configs/sketch_*.yaml): the paper's experiment and a large crowd around obstacles.
#pragma once

#include <throng/core/scene.h>
#include <throng/sketch/sketch.h>

#include <Eigen/Core>
#include <functional>
#include <string>

namespace throng::sketch::scenes {

/// A drawing, its surroundings and the options to run it with.
struct SketchScene {
  std::string name;
  Drawing drawing;
  Scene scene;
  Options options;
};

/// A stroke along a parametric centre line c(s) (s = arc length, metres, in [0, length]), offset sideways by
/// `offset(s)` metres (positive: left of the direction of travel), sampled every `spacing` metres of the centre
/// line, drawn at `speed(s)` m/s along the centre line (times integrate 1/speed).
using CentreLine = std::function<Eigen::Vector2d(double)>;
[[nodiscard]] Stroke drawn_stroke(const CentreLine& centre, double length, double spacing,
                                  const std::function<double(double)>& offset,
                                  const std::function<double(double)>& speed);

/// A straight stroke from `a` to `b` with `points` points drawn at `speed` m/s.
[[nodiscard]] Stroke straight_stroke(const Eigen::Vector2d& a, const Eigen::Vector2d& b, std::size_t points,
                                     double speed);

/// The paper's experiment (§6, Fig. 4): 50 agents on a 140 m course that changes speed, spread and
/// irregularity along the way. Centre line: 80 m east, a left quarter turn of radius 20 m, then north.
///   0–40 m    half-width 4 m, smooth, drawn at 1.2 m/s
///   40–80 m   widening to half-width 8 m, wobbly (±0.5 m, 4 m wavelength), 1.2 m/s
///   80–140 m  narrowing to half-width 2.5 m, smooth, drawn twice as fast (2.4 m/s)
/// No obstacles. Main line sampled every metre.
[[nodiscard]] SketchScene paper_experiment();
/// Arc-length marks of paper_experiment's parts (metres along the main line).
inline constexpr double paper_wobbly_from_m = 40.0;
inline constexpr double paper_fast_from_m = 80.0;
inline constexpr double paper_length_m = 140.0;

/// A large crowd: 2,000 agents on a 40 m wide, 250 m long course past two pillars (circles), a kiosk (convex
/// polygon), a gate of two thick walls leaving a 20 m opening, and a cart (a circle) crossing the course. Four
/// auxiliary lines (±10 m, ±20 m). 200 s of crowd time: the whole crowd gets past the
/// obstacles (the last agent arrives at about 350 s).
[[nodiscard]] SketchScene large_crowd();

}  // namespace throng::sketch::scenes
