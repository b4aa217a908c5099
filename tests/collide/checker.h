// An independent brute-force check of a repaired crowd: every pair of agents and every agent–obstacle pair,
// every frame interval, sampled finely in time (no broad phase, no closed forms; obstacle distances from
// throng/core's distance_to). Piecewise-linear motion makes sampled distances upper bounds of the exact ones,
// within (step·relative speed)²-small errors for fine sampling.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>

#include <vector>

namespace throng::collide::check {

/// min over pairs and sampled moments of |p_a − p_b| − (r_a + r_b + margin) (metres; ≥ 0 when no pair collides).
[[nodiscard]] double min_pair_slack(const CrowdMotion& crowd, double margin, int samples_per_interval = 16);

/// min over agents, obstacles and sampled moments of signed distance − (r + margin) (≥ 0: no contact).
[[nodiscard]] double min_obstacle_slack(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double margin,
                                        int samples_per_interval = 16);

/// Number of vertices (agent, frame) whose x or y differs between the crowds, among `frames` (every frame when
/// empty) and agents flagged in `agents` (every agent when empty).
[[nodiscard]] std::size_t changed_vertices(const CrowdMotion& before, const CrowdMotion& after,
                                           const std::vector<std::size_t>& frames = {}, const std::vector<char>& agents = {});

}  // namespace throng::collide::check
