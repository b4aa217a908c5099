// Spacing between agents: smooth strokes give even spacing, irregular strokes varied spacing (Eq. 8–15), and
// agent avoidance keeps agents apart (Eq. 16–17).
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "crowd_stats.h"
#include "scenes.h"

using namespace throng::sketch;
using namespace throng::sketch::test;
using Eigen::Vector2d;

namespace {

// A straight 100 m course between auxiliary lines at ±5 m, wobbling by `wobble` metres (4 m wavelength).
Drawing band(double wobble) {
  const auto centre = [](double s) { return Vector2d(s, 0); };
  const auto speed = [](double) { return 1.3; };
  Drawing d;
  d.strokes.push_back(scenes::drawn_stroke(
      centre, 100, 0.5, [](double) { return 0.0; }, speed));
  d.strokes.push_back(scenes::drawn_stroke(
      centre, 100, 0.25, [=](double s) { return 5 + wobble * std::sin(2 * std::numbers::pi * s / 4); }, speed));
  d.strokes.push_back(scenes::drawn_stroke(
      centre, 100, 0.25, [=](double s) { return -5 + wobble * std::sin(2 * std::numbers::pi * s / 4 + 1); }, speed));
  return d;
}

// Each agent's nearest-neighbour distance averaged over the frames from `from_s` on (the crowd walking steadily).
std::vector<double> spacing_per_agent(const throng::CrowdMotion& m, double from_s) {
  std::vector<double> sum(m.agent_count(), 0.0);
  std::size_t frames = 0;
  for (std::size_t f = 0; f < m.frame_count(); ++f) {
    if (m.times[f] < from_s) continue;
    const std::vector<double> d = nearest_neighbour_distances(m, f);
    for (std::size_t a = 0; a < d.size(); ++a) sum[a] += d[a];
    ++frames;
  }
  for (double& s : sum) s /= static_cast<double>(frames);
  return sum;
}

}  // namespace

// The per-agent draw u_j ∈ [0.5, 1) spreads the avoidance distance r = s (1 + u e) over [1.5 s, 2 s) at full
// irregularity: a coefficient of variation of at most 0.5/√12/1.75 ≈ 0.082. The test measures each agent's
// nearest-neighbour distance averaged over 30 s (so the v Δt jitter of Eq. 21 averages out, with a short step
// to keep it small), drops the 10 % most and least spaced agents (stragglers, agents squeezed at the edge), and
// compares the spread.
TEST_CASE("smooth strokes give even spacing at the standard distance, irregular strokes varied spacing") {
  Options o;
  o.agent_count = 60;
  o.duration_s = 40;
  o.time_step_s = 0.025;
  o.output_rate_hz = 5;

  const Drawing smooth = band(0.0), wobbly = band(0.5);
  const Course smooth_course = analyse_strokes(smooth.strokes, o);
  const Course wobbly_course = analyse_strokes(wobbly.strokes, o);
  const double s = smooth_course.standard_distance[100];
  REQUIRE(smooth_course.correction_scale[100] == 0.0);
  REQUIRE(wobbly_course.correction_scale[100] == 1.0);

  const SimulationResult even = simulate(smooth, {}, o);
  const SimulationResult varied = simulate(wobbly, {}, o);
  const std::vector<double> even_spacing = trimmed(spacing_per_agent(even.motion, 10), 0.1);
  const std::vector<double> varied_spacing_all = spacing_per_agent(varied.motion, 10);
  const std::vector<double> varied_spacing = trimmed(varied_spacing_all, 0.1);
  const double cv_even = coefficient_of_variation(even_spacing);
  const double cv_varied = coefficient_of_variation(varied_spacing);
  INFO("standard distance " << s << ", smooth: mean " << mean(even_spacing) << " cv " << cv_even << "; irregular: mean "
                            << mean(varied_spacing) << " cv " << cv_varied);
  // Smooth: everyone keeps about s.
  CHECK(std::abs(mean(even_spacing) / s - 1) < 0.1);
  CHECK(cv_even < 0.035);
  // Irregular: larger and varied spacing, set by each agent's own draw.
  CHECK(mean(varied_spacing) > 1.4 * s);
  CHECK(cv_varied > 1.6 * cv_even);
  const Course course = analyse_strokes(wobbly.strokes, o);
  const AgentParameters agents = place_agents(course, o.agent_count, {}, o);
  CHECK(correlation(agents.correction_draw, varied_spacing_all) > 0.3);
}

TEST_CASE("agent avoidance keeps agents further apart than without it") {
  Options o;
  o.agent_count = 60;
  o.duration_s = 30;
  o.output_rate_hz = 5;
  const SimulationResult with = simulate(band(0.0), {}, o);
  o.avoid_weight = 0;
  const SimulationResult without = simulate(band(0.0), {}, o);
  double closest_with = 1e300, closest_without = 1e300, mean_with = 0, mean_without = 0;
  std::size_t frames = 0;
  for (std::size_t f = 0; f < with.motion.frame_count(); ++f) {
    if (with.motion.times[f] < 10) continue;
    const auto a = nearest_neighbour_distances(with.motion, f), b = nearest_neighbour_distances(without.motion, f);
    closest_with = std::min(closest_with, *std::min_element(a.begin(), a.end()));
    closest_without = std::min(closest_without, *std::min_element(b.begin(), b.end()));
    mean_with += mean(a);
    mean_without += mean(b);
    ++frames;
  }
  INFO("closest " << closest_with << " vs " << closest_without << ", mean " << mean_with / frames << " vs "
                  << mean_without / frames);
  CHECK(closest_with > 2 * o.agent_radius_m);  // bodies never overlap with avoidance on
  CHECK(closest_with > 2 * closest_without);
  CHECK(mean_with > 1.2 * mean_without);
}
