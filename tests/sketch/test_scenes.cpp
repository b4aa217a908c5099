// The paper's experiment (§6): the crowd follows the course's changes of speed and spread.
#include <throng/sketch/sketch.h>

#include <catch2/catch.hpp>
#include <cmath>

#include "crowd_stats.h"
#include "scenes.h"

using namespace throng::sketch;
using Eigen::Vector2d;

namespace {

struct Snapshot {
  Vector2d centroid{0, 0};
  Eigen::AlignedBox2d box;
  std::size_t present = 0;
};

Snapshot snapshot(const throng::CrowdMotion& m, std::size_t f) {
  Snapshot s;
  for (std::size_t a = 0; a < m.agent_count(); ++a) {
    if (!m.present(f, a)) continue;
    const Vector2d p = m.position(f, a).head<2>();
    s.centroid += p;
    s.box.extend(p);
    ++s.present;
  }
  s.centroid /= static_cast<double>(s.present);
  return s;
}

}  // namespace

TEST_CASE("the paper experiment: the crowd finishes, speeds up where drawn fast, spreads where drawn wide") {
  const scenes::SketchScene paper = scenes::paper_experiment();
  const SimulationResult r = simulate(paper.drawing, paper.scene, paper.options);
  REQUIRE(r.finished);
  REQUIRE(r.motion.agent_count() == 50);
  REQUIRE_NOTHROW(r.motion.validate("paper experiment"));
  CHECK(r.motion.times.back() < 200);  // 140 m at 1.2–2.4 m/s, with the crowd's own length

  // Centroid speed over 10 s in the slow first part and in the fast last straight (x ≈ 100, going north).
  const auto frame_at = [&](double t) {
    return static_cast<std::size_t>(std::round(t * paper.options.output_rate_hz));
  };
  const double slow =
      (snapshot(r.motion, frame_at(20)).centroid - snapshot(r.motion, frame_at(10)).centroid).norm() / 10;
  CHECK(slow > 1.0);
  CHECK(slow <= 1.2 + 1e-9);
  // The walking agents' speed in the fast part: displacement over 1 s while y is in [25, 45], before arrival.
  double fastest_part = 0;
  std::size_t samples = 0;
  for (std::size_t a = 0; a < 50; ++a) {
    for (std::size_t f = 0; f + 24 < r.motion.frame_count(); f += 24) {
      const Vector2d p0 = r.motion.position(f, a).head<2>(), p1 = r.motion.position(f + 24, a).head<2>();
      if (p0.y() > 25 && p1.y() < 45 && p0.x() > 95 && r.motion.times[f + 24] < r.arrival_time_s[a]) {
        fastest_part += (p1 - p0).norm();
        ++samples;
      }
    }
  }
  REQUIRE(samples > 50);
  CHECK(fastest_part / static_cast<double>(samples) > 2.0);  // drawn at 2.4 m/s, twice the first part

  // Spread across the course: at its widest (half-width 8 m, x ≈ 65–75) the crowd is wider than at the start
  // (half-width 4 m) and than near the end (half-width 2.5 m, going north, width measured along x).
  const double start_width = snapshot(r.motion, 0).box.sizes().y();
  double wide_width = 0, end_width = 1e300;
  for (std::size_t f = 0; f < r.motion.frame_count(); ++f) {
    const Snapshot s = snapshot(r.motion, f);
    if (s.centroid.x() > 65 && s.centroid.x() < 75 && s.centroid.y() < 3)
      wide_width = std::max(wide_width, s.box.sizes().y());
    if (s.centroid.y() > 35 && s.centroid.x() > 95) end_width = std::min(end_width, s.box.sizes().x());
  }
  INFO("width at start " << start_width << ", in the wide part " << wide_width << ", near the end " << end_width);
  CHECK(wide_width > 1.5 * start_width);
  CHECK(wide_width > 2.0 * end_width);
}
