#include "spline.h"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace throng::formation {

SplineWeights catmull_rom_weights(double t, double tension) noexcept {
  const double t2 = t * t, t3 = t2 * t;
  SplineWeights w;
  w.c[0] = tension * (-t + 2 * t2 - t3);
  w.c[1] = (1 - 3 * t2 + 2 * t3) + tension * (t2 - t3);
  w.c[2] = (3 * t2 - 2 * t3) + tension * (t - 2 * t2 + t3);
  w.c[3] = tension * (-t2 + t3);
  return w;
}

ControlKeys control_keys(int segment, int keyframe_count, const std::vector<bool>& sharp) noexcept {
  assert(segment >= 0 && segment + 1 < keyframe_count);
  assert(sharp.empty() || static_cast<int>(sharp.size()) == keyframe_count);
  auto is_sharp = [&](int k) { return !sharp.empty() && sharp[static_cast<std::size_t>(k)]; };
  const int before = is_sharp(segment) ? segment : std::max(segment - 1, 0);
  const int after = is_sharp(segment + 1) ? segment + 1 : std::min(segment + 2, keyframe_count - 1);
  return ControlKeys{{before, segment, segment + 1, after}};
}

Timeline make_timeline(const std::vector<double>& keyframe_times, double frame_rate_hz) {
  assert(keyframe_times.size() >= 2);
  Timeline out;
  const std::size_t segments = keyframe_times.size() - 1;
  for (std::size_t s = 0; s < segments; ++s) {
    const double t0 = keyframe_times[s], t1 = keyframe_times[s + 1];
    const auto steps = static_cast<std::size_t>(std::max(1.0, std::round((t1 - t0) * frame_rate_hz)));
    out.keyframe_frame.push_back(out.times.size());
    for (std::size_t i = 0; i < steps; ++i) {
      const double u = static_cast<double>(i) / static_cast<double>(steps);
      out.times.push_back(i == 0 ? t0 : t0 + (t1 - t0) * u);
      out.segment.push_back(static_cast<int>(s));
      out.local.push_back(u);
    }
  }
  out.keyframe_frame.push_back(out.times.size());
  out.times.push_back(keyframe_times.back());
  out.segment.push_back(static_cast<int>(segments - 1));
  out.local.push_back(1.0);
  return out;
}

}  // namespace throng::formation
