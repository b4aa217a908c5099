// Per-agent parameters (Eq. 2–4, 13, 15) and automatic placement.
#include <throng/core/errors.h>
#include <throng/core/random.h>
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "scenes.h"

using namespace throng::sketch;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using Eigen::Vector2d;

namespace {

// Main line y = 0, auxiliary lines y = +2 and y = −2, x from 0 to 20.
std::vector<Stroke> band_strokes() {
  return {scenes::straight_stroke({0, 0}, {20, 0}, 21, 1.0), scenes::straight_stroke({0, 2}, {20, 2}, 21, 1.0),
          scenes::straight_stroke({0, -2}, {20, -2}, 21, 1.0)};
}

}  // namespace

TEST_CASE("weights are inverse-square distances normalised to sum to one (Eq. 2–3)") {
  const Course c = analyse_strokes(band_strokes(), Options{});
  const AgentParameters a = agent_parameters(c, {{5, 1}}, Options{});
  // l = 1 (main), 1 (y = 2), 3 (y = −2): 1/l² = 1, 1, 1/9.
  const double L = 1 + 1 + 1.0 / 9;
  CHECK_THAT(a.weights(0, 0), WithinRel(1 / L, 1e-12));
  CHECK_THAT(a.weights(0, 1), WithinRel(1 / L, 1e-12));
  CHECK_THAT(a.weights(0, 2), WithinRel((1.0 / 9) / L, 1e-12));
  // Eq. 4: p' = q_1 + Σ o_i V_i, V = (0, 2) and (0, −2).
  for (std::size_t k = 0; k < c.point_count(); ++k) {
    const Vector2d p = target_point(c, a, 0, k);
    CHECK_THAT(p.x(), WithinAbs(c.main[k].x(), 1e-12));
    CHECK_THAT(p.y(), WithinAbs((2 - 2.0 / 9) / L, 1e-12));
  }
}

TEST_CASE("weights of any agent sum to one") {
  const Course c = analyse_strokes(band_strokes(), Options{});
  throng::Rng rng(3);
  std::vector<Vector2d> start;
  for (int j = 0; j < 200; ++j) start.emplace_back(rng.uniform(-5, 25), rng.uniform(-6, 6));
  const AgentParameters a = agent_parameters(c, start, Options{});
  for (Eigen::Index j = 0; j < a.weights.rows(); ++j) {
    CHECK_THAT(a.weights.row(j).sum(), WithinAbs(1.0, 1e-14));
    CHECK((a.weights.row(j).array() >= 0).all());
  }
}

TEST_CASE("an agent on a stroke (l = 0) gives that stroke all the weight and follows it") {
  const Course c = analyse_strokes(band_strokes(), Options{});
  const AgentParameters a = agent_parameters(c, {{3, 0}, {7, 2}, {0, -2}}, Options{});
  CHECK(a.weights(0, 0) == 1.0);
  CHECK(a.weights(1, 1) == 1.0);
  CHECK(a.weights(2, 2) == 1.0);
  for (std::size_t k = 0; k < c.point_count(); ++k) {
    CHECK(target_point(c, a, 0, k) == c.main[k]);
    CHECK((target_point(c, a, 1, k) - c.smoothed[0][k]).norm() < 1e-12);
    CHECK((target_point(c, a, 2, k) - c.smoothed[1][k]).norm() < 1e-12);
  }
}

TEST_CASE("per-agent draws lie between 0.5 and 1, fixed per agent and seed, and set the avoidance distance") {
  Stroke zigzag;
  for (int k = 0; k <= 20; ++k) zigzag.points.emplace_back(k, 2 + 0.5 * (k % 2 == 0 ? 1 : -1));
  const Stroke main = scenes::straight_stroke({0, 0}, {20, 0}, 21, 1.0);
  Options o;
  const Course c = analyse_strokes({main, zigzag}, o);
  std::vector<Vector2d> start;
  for (int j = 0; j < 100; ++j) start.emplace_back(0.1 * j, 1.0);
  const AgentParameters a = agent_parameters(c, start, o);
  const AgentParameters fewer = agent_parameters(c, std::vector<Vector2d>(start.begin(), start.begin() + 10), o);
  o.seed = 99;
  const AgentParameters reseeded = agent_parameters(c, start, o);
  double lo = 1, hi = 0;
  int same_as_reseeded = 0;
  for (std::size_t j = 0; j < 100; ++j) {
    const double u = a.correction_draw[j];
    lo = std::min(lo, u);
    hi = std::max(hi, u);
    if (j < 10) CHECK(fewer.correction_draw[j] == u);  // agent j's draw does not depend on the agent count
    same_as_reseeded += reseeded.correction_draw[j] == u;
    // Eq. 15 as read: r = s (1 + u · min(E/E_MAX, 1)).
    for (std::size_t k = 0; k < c.point_count(); k += 5) {
      CHECK_THAT(avoidance_distance(c, a, j, k),
                 WithinRel(c.standard_distance[k] * (1 + u * c.correction_scale[k]), 1e-15));
    }
  }
  CHECK(lo >= 0.5);
  CHECK(hi < 1.0);
  CHECK(hi - lo > 0.4);  // 100 draws from U(0.5, 1) span most of it
  CHECK(same_as_reseeded == 0);
}

TEST_CASE("automatic placement fills the band between the outer auxiliary lines at the standard distance") {
  const scenes::SketchScene scene = scenes::paper_experiment();
  const Course c = analyse_strokes(scene.drawing.strokes, scene.options);
  const AgentParameters a = place_agents(c, 50, scene.scene, scene.options);
  REQUIRE(a.agent_count() == 50);
  const double s_min = *std::min_element(c.standard_distance.begin(), c.standard_distance.end());
  for (std::size_t i = 0; i < 50; ++i) {
    // Placed near the start (the first 50 agents fit in the first part of the course) ...
    CHECK(a.start[i].x() < 40);
    CHECK(a.start[i].x() >= -1e-12);
    // ... between the auxiliary lines (smoothed), which run at y = ±4 there.
    CHECK(std::abs(a.start[i].y()) <= 4.0 + 1e-9);
    CHECK(a.first_target[i] < c.point_count());
    for (std::size_t j = 0; j < i; ++j) CHECK((a.start[i] - a.start[j]).norm() >= s_min * (1 - 1e-9));
  }
  // The first row spans the band at the start: 8 m wide at s = 1.5 m gives 6 agents.
  const auto first_row = std::count_if(a.start.begin(), a.start.end(), [](const Vector2d& p) { return p.x() == 0.0; });
  CHECK(first_row == 6);
  // Deterministic.
  const AgentParameters again = place_agents(c, 50, scene.scene, scene.options);
  CHECK(again.start == a.start);
}

TEST_CASE("automatic placement keeps clear of obstacles and agents apart, and fails when the count cannot fit") {
  const std::vector<Stroke> strokes = band_strokes();
  Options o;
  const Course c = analyse_strokes(strokes, o);
  throng::Scene scene;
  scene.obstacles.push_back({throng::Circle{{3, 0}, 1.0}, {}, "pillar"});
  const AgentParameters a = place_agents(c, 30, scene, o);
  const double clearance = std::max(o.obstacle_distance_m, o.agent_radius_m);
  for (std::size_t i = 0; i < a.agent_count(); ++i) {
    CHECK(distance_to(scene.obstacles[0], a.start[i], 0.0).signed_distance >= clearance - 1e-12);
    for (std::size_t j = 0; j < i; ++j) CHECK((a.start[i] - a.start[j]).norm() >= o.narrow_distance_m * (1 - 1e-9));
  }
  // A 4 m × 20 m band at s ≈ 0.84 m holds about 5 × 28 agents; 1,000 cannot fit.
  CHECK_THROWS_AS(place_agents(c, 1000, scene, o), throng::ConfigError);
  CHECK_THROWS_WITH(place_agents(c, 1000, scene, o), Catch::Contains("agent_count = 1000"));
}
