// Collision-repair scenes as data, shared by the tests and the benchmarks (bench/collide): the paper's two
// groups bumping (Figure 8), a circular group forced through a narrow opening (Figure 9), two groups crossing,
// and random crowds for the broad phase.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>

#include <cstdint>
#include <vector>

namespace throng::collide::scenes {

struct CollideScene {
  CrowdMotion crowd;
  std::vector<Obstacle> obstacles;
};

/// Two square groups of side×side agents (radius 0.25 m, spacing 1.2 m), 2 m apart, walking head-on along x
/// through each other, each ending where the other started (Figure 8); the second group is shifted by 0.1 m in
/// y so no pair is exactly head-on. `frames` frames at 30 fps; the groups meet half way.
[[nodiscard]] CollideScene bump(std::size_t side, std::size_t frames);

/// A disc of `agents` agents (radius 0.25 m, packed on rings 0.8 m apart) walking north at 1.3 m/s through a
/// gap of `opening` metres in a 0.4 m thick wall along y = 0 (two walls from x = ±opening/2 to ±40 m);
/// `frames` frames at 30 fps; the disc starts 8 m south of the wall (Figure 9).
[[nodiscard]] CollideScene narrow_opening(std::size_t agents, double opening, std::size_t frames);

/// Two square groups of `per_group` agents each (radius 0.25 m, spacing 1.5 m) crossing at right angles, one
/// walking east and one north, both centred on the origin at mid-run; each starts 1 m before the other's lane
/// and ends 1 m past it. `frames` frames at 5 fps (a merge of two walking groups, down-sampled as edits sample;
/// 500 per group and 300 frames walk at 1.2 m/s).
[[nodiscard]] CollideScene crossing(std::size_t per_group, std::size_t frames);

/// `agents` agents on random walks (steps up to `step` m per frame) in a square of side `extent` m, radii
/// 0.2–0.35 m, some absent at the start or the end (entering and leaving); deterministic in `seed`.
[[nodiscard]] CrowdMotion random_crowd(std::size_t agents, std::size_t frames, double extent, double step, std::uint64_t seed);

/// Four obstacles among random_crowd(…, extent 15, …): a post, a triangle, a thick wall and a post moving along
/// keyframes over the first 3 s.
[[nodiscard]] std::vector<Obstacle> scattered_obstacles();

}  // namespace throng::collide::scenes
