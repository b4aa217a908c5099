// The two clips bench_stitch and bench_methods stitch: G, a block of `rows` × `cols` agents marching along a
// gentle arc; G′, another block (wider spacing, other jitter, turning the other way) that starts near G's end —
// clips made apart, as stitching meets them. 25 × 40 × 300 frames is bench_stitch's 1,000-agent case.
#pragma once

#include "../../tests/graph/synthetic_crowd.h"

namespace throng::bench {

struct TwoClips {
  CrowdMotion first, second;
};

inline TwoClips two_clips(int rows, int cols, std::size_t frames) {
  TwoClips k{test::marching_grid(rows, cols, frames, 1.0, 1.2, 0.1, 0.05, 0.2, 5),
             test::marching_grid(rows, cols, frames, 1.2, 1.3, 0.1, -0.05, 0.2, 7)};
  for (std::size_t f = 0; f < k.second.frame_count(); ++f) {
    for (std::size_t a = 0; a < k.second.agent_count(); ++a) k.second.position(f, a).head<2>() += Eigen::Vector2d(35.0, 8.0);
  }
  return k;
}

}  // namespace throng::bench
