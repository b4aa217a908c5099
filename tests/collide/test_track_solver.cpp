// One trajectory's constrained deformation (solver/collide/src/track_solver.h, private to the library): the
// three implementations of the one method agree to rounding and meet every push exactly, for pushes anywhere —
// the windowed elimination's edge cases included (window at the first or last free vertex, the whole track,
// single-vertex pushes next to a pin, no pins at all).
#include "track_solver.h"

#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace throng;
using namespace throng::collide;
using Displacement = Eigen::Matrix<double, Eigen::Dynamic, 2>;

namespace {

// A wavy walk of `length` vertices (0.05 m steps, turning), as a sketch would make.
Displacement walk(int length, std::uint64_t seed) {
  Rng rng(seed);
  Displacement p(length, 2);
  double heading = 0.0;
  Eigen::Vector2d at(0, 0);
  for (int k = 0; k < length; ++k) {
    p.row(k) = at.transpose();
    heading += rng.uniform(-0.2, 0.2);
    at += 0.05 * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  }
  return p;
}

// Pushes on disjoint vertices starting at `first`, every `stride` vertices up to `last`: point pushes on
// (k, k + 1) at a random fraction, or on k alone (as next to a pin); targets up to 0.05 m.
std::vector<PointConstraint> pushes(const std::vector<char>& pinned, int first, int last, int stride, Rng& rng) {
  std::vector<PointConstraint> out;
  for (int k = first; k <= last; k += stride) {
    if (pinned[static_cast<std::size_t>(k)] != 0) continue;
    const Eigen::Vector2d target(rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05));
    const bool pair = k + 1 <= last && pinned[static_cast<std::size_t>(k) + 1] == 0 && rng.below(3) != 0;
    if (pair) {
      const double s = rng.uniform(0.0, 1.0);
      out.push_back({k, k + 1, 1.0 - s, s, target});
    } else {
      out.push_back({k, k, 1.0, 0.0, target});
    }
  }
  return out;
}

}  // namespace

TEST_CASE("the elimination, Schur and linalg track solvers agree and meet every push, wherever the pushes are") {
  const int length = 200;
  const Displacement positions = walk(length, 3);
  Rng rng(17);
  // Both energies: smoothing in time (the default; its rows along the path differ from those across, so x and
  // y are coupled per vertex) and the frame-based one (smoothing_time 0).
  for (const double smoothing_time : {1.0, 0.0})
  for (bool pin_ends : {true, false}) {
    std::vector<char> pinned(length, 0);
    if (pin_ends) pinned.front() = pinned.back() = 1;
    Options options;
    options.smoothing_time = smoothing_time;
    Options schur = options, linalg = options;
    schur.track_method = TrackMethod::schur;
    linalg.track_method = TrackMethod::linalg;
    const double h = 1.0 / 30;  // seconds between frames
    auto eliminate_solver = make_track_solver(positions, pinned, options, h);
    auto schur_solver = make_track_solver(positions, pinned, schur, h);
    auto linalg_solver = make_track_solver(positions, pinned, linalg, h);
    // (first, last, stride): the middle (vertices before and after the window), the start, the end, the whole
    // track (no vertex outside the window), a single push, neighbouring pushes (two per vertex pair).
    const int cases[][3] = {{90, 110, 3}, {0, 12, 2}, {length - 14, length - 1, 2}, {0, length - 1, 7},
                            {100, 100, 1}, {40, 60, 2}, {1, 1, 1}, {length - 2, length - 2, 1}};
    for (const auto& c : cases) {
      for (int repeat = 0; repeat < 3; ++repeat) {
        const std::vector<PointConstraint> p = pushes(pinned, c[0], c[1], c[2], rng);
        INFO((pin_ends ? "pinned ends" : "no pins") << ", smoothing_time " << smoothing_time << ", pushes " << c[0] << " .. "
                                                    << c[1] << " every " << c[2]);
        if (p.empty()) continue;
        const Displacement d = eliminate_solver->solve(p);
        // Every push met: its point moves by its target (to rounding of values ≤ 0.05 m).
        for (const PointConstraint& k : p) {
          const Eigen::Vector2d moved = k.c0 * d.row(k.v0).transpose() + k.c1 * d.row(k.v1).transpose();
          CHECK((moved - k.target).norm() <= 1e-13);
        }
        if (pin_ends) {
          CHECK(d.row(0).norm() == 0.0);
          CHECK(d.row(length - 1).norm() == 0.0);
        }
        // The same minimiser (unique: the system is SPD): apart by rounding only, far below the pushes. Rounding
        // grows with the condition number: the frame-based energy's is a few thousand (1e-10 m is ample); the
        // smoothing's is about 16 m⁴, m = 50 frames its longest smoothing (track_solver.cpp), so ε · 16 m⁴ of
        // the largest push, 0.05 m.
        const double rounding = smoothing_time > 0 ? 0.05 * 2.2e-16 * 16 * std::pow(50.0, 4) : 1e-10;
        CHECK((d - schur_solver->solve(p)).cwiseAbs().maxCoeff() <= rounding);
        CHECK((d - linalg_solver->solve(p)).cwiseAbs().maxCoeff() <= rounding);
      }
    }
  }
}

TEST_CASE("a track solver refuses two pushes on one vertex") {
  const Displacement positions = walk(30, 5);
  std::vector<char> pinned(30, 0);
  auto solver = make_track_solver(positions, pinned, Options{}, 1.0 / 30);
  const std::vector<PointConstraint> shared{{10, 11, 0.5, 0.5, {0.01, 0.0}}, {11, 12, 0.5, 0.5, {0.0, 0.01}}};
  CHECK_THROWS_AS(solver->solve(shared), std::logic_error);
}
