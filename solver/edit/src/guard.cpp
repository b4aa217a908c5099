#include <throng/edit/guard.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace throng::edit {
namespace {

// The clip's frames as the editor reads a request's (residual.cpp does the same): negative counts back from last.
struct ClipFrames {
  std::size_t first = 0, last = 0;
  [[nodiscard]] long absolute(Frame f) const { return f < 0 ? static_cast<long>(last) + 1 + f : f; }
  void add_range(Frame a, Frame b, std::vector<std::size_t>& out) const {
    const long from = std::max(absolute(a), static_cast<long>(first)), to = std::min(absolute(b), static_cast<long>(last));
    for (long f = from; f <= to; ++f) out.push_back(static_cast<std::size_t>(f));
  }
};

}  // namespace

std::vector<std::size_t> constrained_frames(const Request& request, std::size_t first_frame, std::size_t last_frame) {
  const ClipFrames clip{first_frame, last_frame};
  std::vector<std::size_t> out;
  for (const Pin& p : request.pins) clip.add_range(p.frame, p.frame, out);
  for (const Drag& d : request.drags) clip.add_range(d.selection.first_frame, d.selection.last_frame, out);
  for (const Constraint& constraint : request.constraints) {
    std::visit(
        [&](const auto& k) {
          using T = std::decay_t<decltype(k)>;
          if constexpr (std::is_same_v<T, Velocity>) {
            // (p(f + 1) − p(f)) / Δt, the backward difference at the clip's last frame: both frames hold.
            const long f = clip.absolute(k.frame), f0 = f < static_cast<long>(clip.last) ? f : f - 1;
            clip.add_range(f0, f0 + 1, out);
          } else if constexpr (std::is_same_v<T, Acceleration>) {
            // The three frames of its second difference: f − 1, f, f + 1, or the three nearest at the clip's ends.
            if (clip.last >= clip.first + 2) {  // (the editor refuses an acceleration in a shorter clip)
              const long f = std::clamp(clip.absolute(k.frame), static_cast<long>(clip.first) + 1, static_cast<long>(clip.last) - 1);
              clip.add_range(f - 1, f + 1, out);
            }
          } else if constexpr (std::is_same_v<T, Row>) {
            for (const RowTerm& t : k.terms) clip.add_range(t.frame, t.frame, out);
          } else {
            clip.add_range(k.first_frame, k.last_frame, out);
          }
        },
        constraint);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

// Index of the frame of `times` (sorted) nearest t.
std::size_t nearest_frame(const std::vector<double>& times, double t) {
  const auto after = std::lower_bound(times.begin(), times.end(), t);
  auto f = static_cast<std::size_t>(std::min<std::ptrdiff_t>(after - times.begin(), static_cast<std::ptrdiff_t>(times.size()) - 1));
  if (f > 0 && std::abs(times[f - 1] - t) <= std::abs(times[f] - t)) --f;
  return f;
}

// The time in `before`'s frames (fractional index, linear) of a time `t` of the warp's output: the inverse of
// `warp` (source_times = before's times), then the original time of that place by `original` (one per frame).
double unwarped(const timewarp::Warp& warp, const std::vector<double>& original, double t) {
  const std::vector<double>& w = warp.warped_times;
  const auto after = std::upper_bound(w.begin(), w.end(), t);
  const std::size_t i = std::min<std::size_t>(static_cast<std::size_t>(std::max<std::ptrdiff_t>(after - w.begin(), 1)) - 1, w.size() - 2);
  const double x = std::clamp((t - w[i]) / (w[i + 1] - w[i]), 0.0, 1.0);
  return original[i] + x * (original[i + 1] - original[i]);
}

// One report for passes run one after the other: the first's before, the last's after, the stretches multiplied.
void merge(timewarp::GuardReport& total, const timewarp::GuardReport& next) {
  total.warped = total.warped || next.warped;
  total.stretched_intervals = std::max(total.stretched_intervals, next.stretched_intervals);
  total.largest_stretch *= next.largest_stretch;
  total.max_speed_after = next.max_speed_after;
  total.duration_after = next.duration_after;
  total.kinks_after = next.kinks_after;
  total.windows += next.windows;
  total.largest_shift = std::max(total.largest_shift, next.largest_shift);
  total.max_acceleration_after = next.max_acceleration_after;
}

}  // namespace

timewarp::GuardResult guard_edit(const CrowdMotion& written, std::size_t written_first_frame, const CrowdMotion& input,
                                 const Request& request, std::size_t first_frame, std::size_t last_frame,
                                 const timewarp::GuardOptions& options) {
  if (!options.enabled) return timewarp::guard(written, timewarp::Source{}, options);
  const timewarp::Source source = timewarp::source_of(written, input);
  timewarp::Source pass = source;
  for (std::size_t f : constrained_frames(request, first_frame, last_frame)) {
    if (f >= written_first_frame && f - written_first_frame < written.frame_count()) {
      pass.pinned_times.push_back(written.times[f - written_first_frame]);
    }
  }
  // Facings: a warp resamples them with the positions (timewarp/resample.h) and only lengthens intervals, so they
  // turn no faster than in the edit's output; the smoothing moves positions and keeps them.
  timewarp::GuardResult result = timewarp::guard(written, pass, options);
  // The smoothing next to pinned frames (a drag's range is held on one side of its kink) can make a step faster
  // than the warp allowed: another pass warps that away (and smooths what its warp bends), at most two more.
  // Each pass's source is the input at the original time of each frame (the warps inverted, nearest input frame).
  const std::size_t N = written.agent_count();
  std::vector<double> original(result.crowd.frame_count());  // per frame of result.crowd: its time in `written`
  for (std::size_t f = 0; f < original.size(); ++f) {
    original[f] = result.report.warped ? unwarped(result.warp, written.times, result.crowd.times[f]) : written.times[f];
  }
  std::vector<double> pinned = pass.pinned_times;  // at result.crowd's times
  for (double& t : pinned) t = result.warp.map(t);
  for (int round = 0; round < 2 && result.report.speed_limit > 0 &&
                      result.report.max_speed_after > result.report.speed_limit * (1 + 1e-9);
       ++round) {
    const std::size_t T = result.crowd.frame_count();
    timewarp::Source next;
    next.max_speed = source.max_speed;
    next.pinned_times = pinned;
    next.acceleration.assign(T * N, 0.0);
    for (std::size_t f = 0; f < T; ++f) {
      const std::size_t g = nearest_frame(written.times, original[f]);
      std::copy_n(source.acceleration.begin() + static_cast<std::ptrdiff_t>(g * N), N,
                  next.acceleration.begin() + static_cast<std::ptrdiff_t>(f * N));
    }
    timewarp::GuardResult again = timewarp::guard(result.crowd, next, options);
    std::vector<double> again_original(again.crowd.frame_count());
    for (std::size_t f = 0; f < again_original.size(); ++f) {
      again_original[f] = again.report.warped ? unwarped(again.warp, original, again.crowd.times[f]) : original[f];
    }
    for (double& t : pinned) t = again.warp.map(t);
    for (double& t : result.warp.warped_times) t = again.warp.map(t);
    merge(result.report, again.report);
    result.crowd = std::move(again.crowd);
    original = std::move(again_original);
  }
  if (result.report.warped) {
    timewarp::Warp& w = result.warp;
    for (std::size_t i = 0; i + 1 < w.warped_times.size(); ++i) w.inverse_intervals[i] = 1.0 / (w.warped_times[i + 1] - w.warped_times[i]);
  }
  return result;
}

CrowdMotion clip_of(const CrowdMotion& written, std::size_t written_first_frame, std::size_t first_frame,
                    std::size_t last_frame, const std::vector<std::int64_t>& clip_ids) {
  if (first_frame < written_first_frame || last_frame < first_frame ||
      last_frame - written_first_frame >= written.frame_count()) {
    throw std::invalid_argument("clip_of: frames " + std::to_string(first_frame) + ".." + std::to_string(last_frame) +
                                " are not in the written crowd");
  }
  std::unordered_map<std::int64_t, std::size_t> index;
  for (std::size_t a = 0; a < written.agent_count(); ++a) index.emplace(written.ids[a], a);
  CrowdMotion out = CrowdMotion::with_shape(last_frame - first_frame + 1, clip_ids.size());
  for (std::size_t f = first_frame; f <= last_frame; ++f) out.times[f - first_frame] = written.times[f - written_first_frame];
  for (std::size_t j = 0; j < clip_ids.size(); ++j) {
    const auto it = index.find(clip_ids[j]);
    if (it == index.end()) throw std::invalid_argument("clip_of: agent " + std::to_string(clip_ids[j]) + " is not written");
    out.ids[j] = clip_ids[j];
    for (std::size_t f = first_frame; f <= last_frame; ++f) {
      out.position(f - first_frame, j) = written.position(f - written_first_frame, it->second);
    }
  }
  return out;
}

}  // namespace throng::edit
