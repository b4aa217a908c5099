// The simulated motion: speed from the main line's timing (Eq. 5, 21), end of path, output sampling.
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "scenes.h"

using namespace throng::sketch;
using Catch::Matchers::WithinAbs;
using Catch::Matchers::WithinRel;
using Eigen::Vector2d;

namespace {

// 60 m east; the first 30 m drawn at 1 m/s, the rest at 3 m/s; a 6 m wide band.
Drawing slow_then_fast() {
  const auto centre = [](double s) { return Vector2d(s, 0); };
  const auto speed = [](double s) { return s < 30 ? 1.0 : 3.0; };
  Drawing d;
  d.strokes.push_back(scenes::drawn_stroke(
      centre, 60, 1.0, [](double) { return 0.0; }, speed));
  d.strokes.push_back(scenes::drawn_stroke(
      centre, 60, 1.0, [](double) { return 3.0; }, speed));
  d.strokes.push_back(scenes::drawn_stroke(
      centre, 60, 1.0, [](double) { return -3.0; }, speed));
  return d;
}

// First time agent a's x reaches `x` (linear between frames); NaN if it never does.
double time_at_x(const throng::CrowdMotion& m, std::size_t a, double x) {
  for (std::size_t f = 1; f < m.frame_count(); ++f) {
    const double x0 = m.position(f - 1, a).x(), x1 = m.position(f, a).x();
    if (x0 < x && x1 >= x) return m.times[f - 1] + (m.times[f] - m.times[f - 1]) * (x - x0) / (x1 - x0);
  }
  return std::nan("");
}

}  // namespace

TEST_CASE("every walking agent moves exactly v_k Δt per step, v_k at its target index (Eq. 21)") {
  const Drawing d = slow_then_fast();
  Options o;
  const Course course = analyse_strokes(d.strokes, o);
  Simulation sim(course, place_agents(course, 20, {}, o), {}, o);
  std::size_t moves = 0;
  while (!sim.finished() && sim.step_count() < 2000) {
    std::vector<Vector2d> before(sim.agent_count());
    std::vector<std::size_t> k(sim.agent_count());
    std::vector<AgentStatus> status(sim.agent_count());
    for (std::size_t j = 0; j < sim.agent_count(); ++j) {
      before[j] = sim.position(j);
      k[j] = sim.target_index(j);
      status[j] = sim.status(j);
    }
    sim.step();
    for (std::size_t j = 0; j < sim.agent_count(); ++j) {
      if (status[j] != AgentStatus::walking) continue;
      const double moved = (sim.position(j) - before[j]).norm();
      if (moved == 0) continue;  // F = 0: the agent stays
      REQUIRE_THAT(moved, WithinRel(course.speed[k[j]] * o.time_step_s, 1e-9));
      ++moves;
    }
  }
  CHECK(sim.finished());
  CHECK(moves > 20 * 100);
}

TEST_CASE("the crowd walks slow where the main line was drawn slowly and fast where it was drawn fast") {
  Options o;
  o.agent_count = 12;
  const SimulationResult r = simulate(slow_then_fast(), {}, o);
  REQUIRE(r.finished);
  for (std::size_t a = 0; a < 12; ++a) {
    const double slow = 15.0 / (time_at_x(r.motion, a, 25) - time_at_x(r.motion, a, 10));
    const double fast = 15.0 / (time_at_x(r.motion, a, 50) - time_at_x(r.motion, a, 35));
    // Each step is exactly v Δt long, so forward speed ≤ v; sideways avoidance costs a little of it.
    CHECK(slow <= 1.0 + 1e-9);
    CHECK(slow >= 0.85);
    CHECK(fast <= 3.0 + 1e-9);
    CHECK(fast >= 2.55);
  }
}

TEST_CASE("at the end of the path agents stop, or are removed") {
  Options o;
  o.agent_count = 15;
  SECTION("stop: every agent arrives near its end point, or at the crowd standing there, and stays present") {
    const SimulationResult r = simulate(slow_then_fast(), {}, o);
    REQUIRE(r.finished);
    REQUIRE_NOTHROW(r.motion.validate("stop"));
    const std::size_t last = r.motion.frame_count() - 1;
    CHECK(r.motion.times[last] >= *std::max_element(r.arrival_time_s.begin(), r.arrival_time_s.end()));
    // The standing crowd of n agents covers a disc of radius ρ = √(n s² (√3/2) / π); an agent joins it within
    // 2 (R + ρ) of its own end point at the latest (sketch.h). n ≤ 15 here.
    const double s = r.course.standard_distance.back();
    const double reach = 2 * (o.follow_radius_m + std::sqrt(15 * s * s * std::sqrt(3.0) / 2 / std::numbers::pi));
    const std::size_t K = r.course.point_count();
    for (std::size_t a = 0; a < 15; ++a) {
      REQUIRE(std::isfinite(r.arrival_time_s[a]));
      for (std::size_t f = 0; f <= last; ++f) REQUIRE(r.motion.present(f, a));
      // Position at the first frame at or after its arrival (frames are every step here).
      const auto f = static_cast<std::size_t>(std::ceil(r.arrival_time_s[a] * o.output_rate_hz - 1e-9));
      const Vector2d end = target_point(r.course, r.agents, a, K - 1);
      CHECK((r.motion.position(f, a).head<2>() - end).norm() <= reach + 1e-9);
      // Standing agents only make room (half an overlap per step): they stay near where they stopped.
      CHECK((r.motion.position(last, a) - r.motion.position(f, a)).norm() < s);
    }
  }
  SECTION("remove: each agent is present until it arrives and absent afterwards") {
    o.end_of_path = EndOfPath::remove;
    const SimulationResult r = simulate(slow_then_fast(), {}, o);
    REQUIRE(r.finished);
    REQUIRE_NOTHROW(r.motion.validate("remove"));
    for (std::size_t a = 0; a < 15; ++a) {
      const double arrived = r.arrival_time_s[a];
      REQUIRE(std::isfinite(arrived));
      for (std::size_t f = 0; f < r.motion.frame_count(); ++f) {
        const double t = r.motion.times[f];
        if (t <= arrived + 1e-9) CHECK(r.motion.present(f, a));
        if (t > arrived + o.time_step_s + 1e-9) CHECK_FALSE(r.motion.present(f, a));
      }
    }
    for (std::size_t a = 0; a < 15; ++a) CHECK_FALSE(r.motion.present(r.motion.frame_count() - 1, a));
  }
}

TEST_CASE("agents that arrive while nobody stands at the end reach their own end point") {
  // With nobody standing, the standing crowd's disc has radius 0 and the only way to arrive is the target rule:
  // within R of the last target, or past the line through it across the path (at most one step v Δt beyond the
  // line, having been outside R before the step). The count of standing agents is what sets the join radius:
  // miscounting walkers as standing makes the first agents stop metres short (4.7 m on the paper's course).
  const auto check_first_arrivals = [](const Drawing& d, const throng::Scene& scene, const Options& o,
                                       std::size_t count) {
    const Course course = analyse_strokes(d.strokes, o);
    Simulation sim(course, place_agents(course, count, scene, o), scene, o);
    const std::size_t K = course.point_count();
    const double bound = o.follow_radius_m + course.speed[K - 1] * o.time_step_s;
    std::size_t checked = 0;
    while (!sim.finished() && sim.time() < o.max_duration_s) {
      bool anyone_standing = false;
      for (std::size_t j = 0; j < sim.agent_count(); ++j) anyone_standing |= sim.status(j) == AgentStatus::arrived;
      if (anyone_standing) break;
      sim.step();
      for (std::size_t j = 0; j < sim.agent_count(); ++j) {
        if (sim.status(j) != AgentStatus::arrived) continue;
        const double miss = (sim.position(j) - target_point(course, sim.agents(), j, K - 1)).norm();
        INFO("agent " << j << " arrived at t = " << sim.time() << " s, " << miss << " m from its end point");
        CHECK(miss <= bound + 1e-9);
        ++checked;
      }
    }
    CHECK(checked >= 1);
  };
  SECTION("a band drawn slow then fast") {
    Options o;
    check_first_arrivals(slow_then_fast(), {}, o, 15);
  }
  SECTION("the paper's experiment") {
    const scenes::SketchScene paper = scenes::paper_experiment();
    check_first_arrivals(paper.drawing, paper.scene, paper.options, paper.options.agent_count);
  }
}

TEST_CASE("output frames are at the output rate and lie on the simulated motion") {
  Options o;
  o.agent_count = 10;
  o.duration_s = 12;
  o.output_rate_hz = 24;  // not a multiple of the 25 Hz step rate: frames fall between steps
  const SimulationResult r = simulate(slow_then_fast(), {}, o);
  REQUIRE(r.motion.frame_count() == 12 * 24 + 1);
  REQUIRE(r.motion.agent_count() == 10);
  REQUIRE_NOTHROW(r.motion.validate("sampling"));
  for (std::size_t f = 0; f < r.motion.frame_count(); ++f) {
    CHECK_THAT(r.motion.times[f], WithinAbs(static_cast<double>(f) / 24.0, 1e-12));
    for (std::size_t a = 0; a < 10; ++a) CHECK(r.motion.position(f, a).z() == 0.0);
  }
  // Agents never move faster than the fastest drawn speed between two frames.
  for (std::size_t f = 1; f < r.motion.frame_count(); ++f) {
    for (std::size_t a = 0; a < 10; ++a) {
      CHECK((r.motion.position(f, a) - r.motion.position(f - 1, a)).norm() <= 3.0 / 24.0 + 1e-9);
    }
  }
  // The same run at the step rate gives the same positions at the shared times (0, 1, 2 ... s).
  o.output_rate_hz = 25;
  const SimulationResult at_steps = simulate(slow_then_fast(), {}, o);
  for (std::size_t second = 0; second <= 12; ++second) {
    for (std::size_t a = 0; a < 10; ++a) {
      CHECK((r.motion.position(24 * second, a) - at_steps.motion.position(25 * second, a)).norm() < 1e-9);
    }
  }
}
