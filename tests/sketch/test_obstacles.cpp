// Obstacle avoidance (Eq. 18–19 generalised) and the guarantee that no agent ends a step inside an obstacle.
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>

#include "scenes.h"

using namespace throng::sketch;
using Eigen::Vector2d;

namespace {

Drawing straight_band(double length, double half_width, double speed) {
  const auto centre = [](double s) { return Vector2d(s, 0); };
  const auto v = [=](double) { return speed; };
  Drawing d;
  d.strokes.push_back(scenes::drawn_stroke(
      centre, length, 0.5, [](double) { return 0.0; }, v));
  d.strokes.push_back(scenes::drawn_stroke(
      centre, length, 0.5, [=](double) { return half_width; }, v));
  d.strokes.push_back(scenes::drawn_stroke(
      centre, length, 0.5, [=](double) { return -half_width; }, v));
  return d;
}

// The smallest signed distance from any present agent's centre to any obstacle at the simulation's time.
double closest_approach(const Simulation& sim, const throng::Scene& scene) {
  double closest = 1e300;
  for (std::size_t j = 0; j < sim.agent_count(); ++j) {
    if (sim.status(j) == AgentStatus::removed) continue;
    for (const auto& o : scene.obstacles) {
      closest = std::min(closest, distance_to(o, sim.position(j), sim.time()).signed_distance);
    }
  }
  return closest;
}

}  // namespace

TEST_CASE("no agent ends a step overlapping a circle, a polygon, a wall or a moving obstacle") {
  const Drawing d = straight_band(40, 3, 1.3);
  throng::Scene scene;
  scene.obstacles.push_back({throng::Circle{{10, 1}, 1.0}, {}, "circle"});
  scene.obstacles.push_back({throng::ConvexPolygon{{{18, -2}, {21, -2}, {21, 0.5}, {18, 0.5}}}, {}, "square"});
  scene.obstacles.push_back({throng::Wall{{28, -3.5}, {28, 0.0}, 0.2}, {}, "wall"});
  // Sweeps north across the course, through the crowd, over 30 s.
  scene.obstacles.push_back({throng::Circle{{0, 0}, 1.5}, {{0, {14, -10}, 0}, {30, {14, 10}, 0}}, "cart"});
  Options o;
  const Course course = analyse_strokes(d.strokes, o);
  Simulation sim(course, place_agents(course, 40, scene, o), scene, o);
  double closest = closest_approach(sim, scene);
  while (!sim.finished() && sim.time() < 120) {
    sim.step();
    closest = std::min(closest, closest_approach(sim, scene));
    REQUIRE(closest >= o.agent_radius_m - 1e-9);
  }
  CHECK(sim.unresolved_obstacle_contacts() == 0);
  CHECK(sim.finished());  // the obstacles are avoided, not just survived: everyone gets past them
}

TEST_CASE("obstacle avoidance keeps agents at the obstacle distance when they can") {
  // One agent walking straight at a pillar on its path bends around it without touching the avoidance band
  // much: the force acts from obstacle_distance_m on (Eq. 18), the projection only at the body radius.
  const Drawing d = straight_band(30, 3, 1.3);
  throng::Scene scene;
  scene.obstacles.push_back({throng::Circle{{15, 0}, 1.0}, {}, "pillar"});
  Options o;
  o.obstacle_distance_m = 1.0;
  const Course course = analyse_strokes(d.strokes, o);
  Simulation sim(course, agent_parameters(course, {{0, 0}}, o), scene, o);
  double closest = 1e300;
  while (!sim.finished() && sim.time() < 60) {
    sim.step();
    closest = std::min(closest, closest_approach(sim, scene));
  }
  CHECK(sim.finished());
  CHECK(closest > 0.5 * o.obstacle_distance_m);
  CHECK(closest > o.agent_radius_m);
}

TEST_CASE("filtered, an agent walking head-on at a pillar brakes in time instead of being stopped dead at it") {
  // The pillar sits on the agent's line; the slide turns the path force only within obstacle_distance_m (0.5 m),
  // too late to turn at max_acceleration from 1.3 m/s. Braking from the stopping distance keeps every change of
  // the walking velocity within the step's bound plus the brake's own (2 max_acceleration), and the move is never
  // cut at the boundary (which would be a stop from 1.3 m/s in one step: over 30 m/s²).
  const Drawing d = straight_band(30, 3, 1.3);
  throng::Scene scene;
  scene.obstacles.push_back({throng::Circle{{12, 0}, 1.0}, {}, "pillar"});
  Options o;
  const Course course = analyse_strokes(d.strokes, o);
  for (const double lateral : {0.0, 0.05, -0.2}) {
    CAPTURE(lateral);
    Simulation sim(course, agent_parameters(course, {{0, lateral}}, o), scene, o);
    Vector2d previous_step = Vector2d::Zero();
    double largest_change = 0, closest = 1e300;
    while (!sim.finished() && sim.time() < 60) {
      const Vector2d before = sim.position(0);
      sim.step();
      const Vector2d step = sim.position(0) - before;
      largest_change = std::max(largest_change, (step - previous_step).norm() / (o.time_step_s * o.time_step_s));
      previous_step = step;
      closest = std::min(closest, closest_approach(sim, scene));
    }
    CHECK(sim.finished());  // it goes round
    CHECK(largest_change <= 2 * o.max_acceleration_m_s2);
    CHECK(closest >= o.agent_radius_m - 1e-9);
    CHECK(sim.unresolved_obstacle_contacts() == 0);
  }
}

TEST_CASE("fast agents cannot jump a thin wall") {
  // Drawn at 20 m/s with 0.1 s steps: 2 m per step, eight times the wall's reach of one body radius.
  const Drawing d = straight_band(30, 3, 20.0);
  throng::Scene scene;
  // Long enough that agents sliding along it (at 20 m/s) cannot reach an end within the test.
  scene.obstacles.push_back({throng::Wall{{15, -1000}, {15, 1000}, 0.0}, {}, "fence"});
  Options o;
  o.time_step_s = 0.1;
  const Course course = analyse_strokes(d.strokes, o);
  Simulation sim(course, place_agents(course, 20, scene, o), scene, o);
  for (int step = 0; step < 200; ++step) {
    sim.step();
    for (std::size_t j = 0; j < sim.agent_count(); ++j) REQUIRE(sim.position(j).x() <= 15 - o.agent_radius_m + 1e-9);
  }
  CHECK(sim.unresolved_obstacle_contacts() == 0);
}

TEST_CASE("the large scene keeps every agent out of every obstacle at every step, past all of them") {
  // 60 s: the head of the crowd is past the gate (x 125), most of it past the pillars (x 75), the cart (x 85,
  // crossing until 60 s) and the kiosk (x 94–104). Checked at every step, where the guarantee holds.
  const scenes::SketchScene large = scenes::large_crowd();
  const Options& o = large.options;
  const Course course = analyse_strokes(large.drawing.strokes, o);
  Simulation sim(course, place_agents(course, o.agent_count, large.scene, o), large.scene, o);
  REQUIRE(sim.agent_count() >= 2000);
  const auto& obstacles = large.scene.obstacles;
  std::vector<double> closest(obstacles.size(), 1e300);
  while (sim.time() < 60 - 1e-9) {
    sim.step();
    for (std::size_t j = 0; j < sim.agent_count(); ++j) {
      for (std::size_t b = 0; b < obstacles.size(); ++b) {
        closest[b] = std::min(closest[b], distance_to(obstacles[b], sim.position(j), sim.time()).signed_distance);
      }
    }
    for (std::size_t b = 0; b < obstacles.size(); ++b) {
      INFO(obstacles[b].name << " at t = " << sim.time() << " s");
      REQUIRE(closest[b] >= o.agent_radius_m - 1e-9);
    }
  }
  CHECK(sim.unresolved_obstacle_contacts() == 0);
  // The crowd reached every obstacle (some agent came within the push distance), and part of it is through the
  // gate.
  for (std::size_t b = 0; b < obstacles.size(); ++b) {
    INFO(obstacles[b].name);
    CHECK(closest[b] < o.agent_radius_m + o.obstacle_distance_m);
  }
  std::size_t through_gate = 0;
  for (std::size_t j = 0; j < sim.agent_count(); ++j) through_gate += sim.position(j).x() > 126 ? 1 : 0;
  CHECK(through_gate >= 50);
}
