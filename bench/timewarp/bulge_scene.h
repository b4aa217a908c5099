// The walkers bench_timewarp and bench_methods warp: `rows` × `cols` walkers 1 m apart walking +x at 1.4 m/s for
// `frames` frames of 0.1 s; the deformed copy bulges 3 m sideways between x = 20 and 60 m (the same scene as
// tests/timewarp, larger). 25 × 40 × 600 is bench_timewarp's 1,000-agent case.
#pragma once

#include <throng/core/crowd_motion.h>

#include <cmath>
#include <numbers>

namespace throng::bench {

struct BulgeScene {
  CrowdMotion original, deformed;
};

inline BulgeScene bulge_scene(int rows, int cols, std::size_t frames) {
  CrowdMotion c = CrowdMotion::with_shape(frames, static_cast<std::size_t>(rows * cols));
  for (std::size_t f = 0; f < frames; ++f) {
    c.times[f] = 0.1 * static_cast<double>(f);
    for (int r = 0; r < rows; ++r) {
      for (int k = 0; k < cols; ++k) c.position(f, static_cast<std::size_t>(r * cols + k)) << 1.4 * c.times[f] - r, k - 0.5 * (cols - 1), 0.0;
    }
  }
  CrowdMotion d = c;
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t a = 0; a < d.agent_count(); ++a) {
      auto p = d.position(f, a);
      if (p.x() > 20 && p.x() < 60) p.y() += 3.0 * std::sin(std::numbers::pi * (p.x() - 20) / 40);
    }
  }
  return BulgeScene{std::move(c), std::move(d)};
}

}  // namespace throng::bench
