#include <throng/formation/plausibility.h>

#include <algorithm>
#include <cmath>

namespace throng::formation {
namespace {

// The fastest speed of any individual over the frame intervals of keyframe interval k.
double interval_speed(const CrowdMotion& m, const std::vector<std::size_t>& keyframe_frames, std::size_t k) {
  double fastest = 0;
  for (std::size_t f = keyframe_frames[k]; f < keyframe_frames[k + 1]; ++f) {
    const double dt = m.times[f + 1] - m.times[f];
    for (std::size_t n = 0; n < m.agent_count(); ++n)
      fastest = std::max(fastest, (m.position(f + 1, n) - m.position(f, n)).norm() / dt);
  }
  return fastest;
}

}  // namespace

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

void guard_formation(Problem& problem, Result& result, const Options& options, Progress& progress) {
  if (!options.guard.enabled) return;
  timewarp::GuardReport report;  // result.guard at the end (remaking the formation resets result)
  const std::size_t K = problem.keyframes.size();
  const double stated = options.max_speed_mps > 0 ? options.max_speed_mps : keyframe_speed(result.motion, result.keyframe_frames);
  report.speed_limit = options.guard.max_speed_ratio * stated;
  report.max_speed_before = timewarp::fastest_speed(result.motion);
  report.duration_before = problem.keyframes.back().time_s - problem.keyframes.front().time_s;
  std::vector<double> original(K);
  for (std::size_t k = 0; k < K; ++k) original[k] = problem.keyframes[k].time_s;

  // 1. Re-timing: each interval lengthened by its own need (aimed 2 % under the limit, for the change of the
  // neighbouring tangents), to whole frames; repeated while the remade formation is still too fast.
  const double frame = 1.0 / options.frame_rate_hz;
  for (int round = 0; round < 4 && report.speed_limit > 0; ++round) {
    bool stretched = false;
    std::vector<double> times(K);
    times[0] = problem.keyframes[0].time_s;
    for (std::size_t k = 0; k + 1 < K; ++k) {
      const double length = problem.keyframes[k + 1].time_s - problem.keyframes[k].time_s;
      const double need = interval_speed(result.motion, result.keyframe_frames, k) / report.speed_limit;
      double next = length;
      if (need > 1) {
        next = std::ceil(length * need / 0.98 / frame - 1e-9) * frame;
        stretched = true;
      }
      times[k + 1] = times[k] + next;
    }
    if (!stretched) break;
    for (std::size_t k = 0; k < K; ++k) problem.keyframes[k].time_s = times[k];
    progress.update(0.0, "formation guard: re-timed keyframes");
    result = animate_formation(problem, options, progress);
    report.warped = true;
  }
  for (std::size_t k = 0; k + 1 < K; ++k) {
    report.largest_stretch = std::max(report.largest_stretch, (problem.keyframes[k + 1].time_s - problem.keyframes[k].time_s) /
                                                                  (original[k + 1] - original[k]));
    report.stretched_intervals += problem.keyframes[k + 1].time_s - problem.keyframes[k].time_s > original[k + 1] - original[k] ? 1 : 0;
  }
  report.duration_after = problem.keyframes.back().time_s - problem.keyframes.front().time_s;

  // 2. Kinks, with the keyframe frames pinned (no further warp: max_speed 0).
  timewarp::Source source;
  for (std::size_t f : result.keyframe_frames) source.pinned_times.push_back(result.motion.times[f]);
  timewarp::GuardResult smoothed = timewarp::guard(result.motion, source, options.guard);
  result.motion = std::move(smoothed.crowd);
  report.kinks_before = smoothed.report.kinks_before;
  report.kinks_after = smoothed.report.kinks_after;
  report.windows = smoothed.report.windows;
  report.largest_shift = smoothed.report.largest_shift;
  report.max_acceleration_before = smoothed.report.max_acceleration_before;
  report.max_acceleration_after = smoothed.report.max_acceleration_after;
  report.max_speed_after = timewarp::fastest_speed(result.motion);
  result.guard = report;
}

}  // namespace throng::formation
