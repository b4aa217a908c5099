#include <throng/formation/plausibility.h>

#include <algorithm>
#include <cmath>

namespace throng::formation {

double keyframe_speed(const CrowdMotion& motion, const std::vector<std::size_t>& keyframe_frames) {
  double fastest = 0;
  for (std::size_t k = 1; k < keyframe_frames.size(); ++k) {
    const std::size_t a = keyframe_frames[k - 1], b = keyframe_frames[k];
    const double dt = motion.times[b] - motion.times[a];
    if (!(dt > 0)) continue;
    for (std::size_t n = 0; n < motion.agent_count(); ++n)
      fastest = std::max(fastest, (motion.position(b, n) - motion.position(a, n)).norm() / dt);
  }
  return fastest;
}

void guard_formation(Result& result, const Options& options) {
  if (!options.guard.enabled) return;
  timewarp::Source source;
  source.max_speed = options.max_speed_mps > 0 ? options.max_speed_mps : keyframe_speed(result.motion, result.keyframe_frames);
  std::vector<double> old_times;
  for (std::size_t f : result.keyframe_frames) old_times.push_back(result.motion.times[f]);
  source.pinned_times = old_times;  // the smoothing keeps the keyframes
  timewarp::GuardResult guarded = timewarp::guard(result.motion, source, options.guard);
  result.motion = std::move(guarded.crowd);
  result.guard = guarded.report;
  if (!guarded.report.warped) return;
  // Each keyframe's frame: the one nearest its warped time.
  const std::vector<double>& times = result.motion.times;
  for (std::size_t k = 0; k < old_times.size(); ++k) {
    const double t = guarded.warp.map(old_times[k]);
    const auto after = std::lower_bound(times.begin(), times.end(), t);
    std::size_t f = static_cast<std::size_t>(std::min<std::ptrdiff_t>(after - times.begin(), static_cast<std::ptrdiff_t>(times.size()) - 1));
    if (f > 0 && std::abs(times[f - 1] - t) <= std::abs(times[f] - t)) --f;
    result.keyframe_frames[k] = f;
  }
}

}  // namespace throng::formation
