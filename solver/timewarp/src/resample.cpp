#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/timewarp/resample.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace throng::timewarp {
namespace {

using Index = Eigen::Index;

// Output times within [first, last] (with `slack` either side), as a range of indices into `times`.
std::pair<std::size_t, std::size_t> times_within(const std::vector<double>& times, double first, double last, double slack) {
  const auto begin = std::lower_bound(times.begin(), times.end(), first - slack);
  const auto end = std::upper_bound(begin, times.end(), last + slack);
  return {static_cast<std::size_t>(begin - times.begin()), static_cast<std::size_t>(end - times.begin())};
}

// Writes the spline's values (and slopes) at times[begin, end) into the output's columns of `agents` (three
// columns per agent, in the spline's column order), clamping each time into the spline's knot span.
void write_samples(const CubicSpline& spline, const std::vector<std::size_t>& agents, const std::vector<double>& times,
                   std::size_t begin, std::size_t end, bool with_velocities, CrowdMotion& out) {
  const double lo = spline.knots().front(), hi = spline.knots().back();
  Eigen::RowVectorXd value(spline.columns()), slope(spline.columns());
  for (std::size_t k = begin; k < end; ++k) {
    const double t = std::clamp(times[k], lo, hi);
    spline.evaluate(t, 0, value);
    if (with_velocities) spline.evaluate(t, 1, slope);
    for (std::size_t a = 0; a < agents.size(); ++a) {
      const std::size_t at = out.index(k, agents[a]);
      for (int d = 0; d < 3; ++d) {
        out.positions[at + static_cast<std::size_t>(d)] = value[static_cast<Index>(3 * a) + d];
        if (with_velocities) out.velocities[at + static_cast<std::size_t>(d)] = slope[static_cast<Index>(3 * a) + d];
      }
    }
  }
}

// Facing and action of agent `a` at output times[begin, end) from its run of frames first..last (knots clamped
// as for the positions): orientations slerp between the two frames around each time, the action is the one of the
// frame at or before it.
void write_pose(const CrowdMotion& crowd, std::size_t a, std::size_t first, std::size_t last, const std::vector<double>& knot_times,
                const std::vector<double>& times, std::size_t begin, std::size_t end, CrowdMotion& out) {
  const auto knots_begin = knot_times.begin() + static_cast<std::ptrdiff_t>(first);
  const auto knots_end = knot_times.begin() + static_cast<std::ptrdiff_t>(last) + 1;
  for (std::size_t k = begin; k < end; ++k) {
    const double t = std::clamp(times[k], knot_times[first], knot_times[last]);
    // The frame at or before t within the run, and the one after it (the same at the run's last frame).
    const std::size_t at = first + static_cast<std::size_t>(std::upper_bound(knots_begin, knots_end, t) - knots_begin) - 1;
    const std::size_t next = std::min(at + 1, last);
    if (!crowd.orientations.empty()) {
      const double u = next == at ? 0.0 : (t - knot_times[at]) / (knot_times[next] - knot_times[at]);
      out.orientation(k, a) = crowd.orientation(at, a).slerp(u, Eigen::Quaterniond(crowd.orientation(next, a))).normalized();
    }
    if (!crowd.actions.empty()) out.action(k, a) = crowd.action(at, a);
  }
}


}  // namespace

std::vector<double> uniform_times(double start, double end, double rate_hz) {
  if (!(std::isfinite(rate_hz) && rate_hz > 0)) {
    throw ConfigError("output frame rate " + std::to_string(rate_hz) + " Hz: expected a finite rate > 0");
  }
  if (!(end >= start)) {
    throw InputError("resampling: end time " + std::to_string(end) + " s is before the start " + std::to_string(start) + " s");
  }
  const double duration = end - start;
  const auto count = static_cast<std::size_t>(std::floor(duration * rate_hz * (1.0 + 1e-9) + 1e-9)) + 1;
  std::vector<double> times(count);
  for (std::size_t k = 0; k < count; ++k) times[k] = start + static_cast<double>(k) / rate_hz;
  times.back() = std::min(times.back(), end);
  return times;
}

double frame_rate(const CrowdMotion& crowd) {
  if (crowd.frame_count() < 2) {
    throw InputError("a frame rate needs at least 2 frames, the crowd has " + std::to_string(crowd.frame_count()));
  }
  std::vector<double> intervals(crowd.frame_count() - 1);
  for (std::size_t i = 0; i + 1 < crowd.frame_count(); ++i) intervals[i] = crowd.times[i + 1] - crowd.times[i];
  const auto middle = intervals.begin() + static_cast<std::ptrdiff_t>(intervals.size() / 2);
  std::nth_element(intervals.begin(), middle, intervals.end());
  const double rate = 1.0 / *middle;
  // Frame times k/24 stored as doubles give intervals off by ~1e-13 relative, so the median says 23.99999999999983
  // Hz and every output time would drift off the k/24 grid. Rates are set by people in whole mHz (24, 29.97, 2.5):
  // a rate within 1e-9 relative of one is that rate.
  const double snapped = std::round(rate * 1000.0) / 1000.0;
  return std::abs(snapped - rate) <= 1e-9 * rate ? snapped : rate;
}

CrowdMotion resample_crowd(const CrowdMotion& crowd, const std::vector<double>& knot_times, const std::vector<double>& times,
                           SplineEnd end, bool with_velocities, double end_slack_s) {
  const std::size_t frames = crowd.frame_count();
  const std::size_t agents = crowd.agent_count();
  if (knot_times.size() != frames) {
    throw InputError("resampling: " + std::to_string(knot_times.size()) + " knot times for " + std::to_string(frames) + " frames");
  }
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (!(times[k] > times[k - 1])) throw InputError("resampling: output times are not strictly increasing at " + std::to_string(k));
  }
  CrowdMotion out = CrowdMotion::with_shape(times.size(), agents);
  out.times = times;
  out.ids = crowd.ids;
  out.radii = crowd.radii;
  out.species = crowd.species;
  if (with_velocities) out.velocities.assign(out.positions.size(), absent);
  if (!crowd.orientations.empty()) out.orientations.assign(times.size() * agents * 4, absent);
  if (!crowd.actions.empty()) out.actions.assign(times.size() * agents, -1);
  out.action_table = crowd.action_table;
  if (!(std::isfinite(end_slack_s) && end_slack_s >= 0)) {
    throw ConfigError("resampling: end slack " + std::to_string(end_slack_s) + " s: expected a finite time ≥ 0");
  }
  if (frames == 0 || agents == 0 || times.empty()) return out;
  const double slack = 1e-9 * std::max(1.0, std::abs(knot_times.back() - knot_times.front()));

  // Agents present at every frame share one spline (3 columns each).
  std::vector<std::size_t> whole, partial;
  for (std::size_t a = 0; a < agents; ++a) {
    bool throughout = true;
    for (std::size_t f = 0; f < frames && throughout; ++f) throughout = crowd.present(f, a);
    (throughout ? whole : partial).push_back(a);
  }
  if (!whole.empty() && frames >= 2) {
    RowMatrix values(static_cast<Index>(frames), static_cast<Index>(3 * whole.size()));
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t a = 0; a < whole.size(); ++a) {
        values.block<1, 3>(static_cast<Index>(f), static_cast<Index>(3 * a)) = crowd.position(f, whole[a]).transpose();
      }
    }
    const CubicSpline spline(knot_times, std::move(values), end);
    // Named, not a structured binding: clang 14 (the asan preset) cannot capture a binding in a lambda.
    const auto within = times_within(times, knot_times.front() - end_slack_s, knot_times.back() + end_slack_s, slack);
    const std::size_t begin = within.first, stop = within.second;
    parallel_for(stop - begin, 16, [&](std::size_t b, std::size_t e) {
      write_samples(spline, whole, times, begin + b, begin + e, with_velocities, out);
    });
    if (!crowd.orientations.empty() || !crowd.actions.empty()) {
      parallel_for(whole.size(), 16, [&](std::size_t b, std::size_t e) {
        for (std::size_t w = b; w < e; ++w) write_pose(crowd, whole[w], 0, frames - 1, knot_times, times, begin, stop, out);
      });
    }
  } else {
    partial.insert(partial.end(), whole.begin(), whole.end());
    std::sort(partial.begin(), partial.end());
  }

  // The others: one spline per run of consecutive present frames.
  parallel_for(partial.size(), 4, [&](std::size_t b, std::size_t e) {
    for (std::size_t p = b; p < e; ++p) {
      const std::size_t a = partial[p];
      for (std::size_t f = 0; f < frames;) {
        if (!crowd.present(f, a)) {
          ++f;
          continue;
        }
        std::size_t last = f;
        while (last + 1 < frames && crowd.present(last + 1, a)) ++last;
        // The slack, but less than half the way to a neighbouring frame where the agent is absent.
        const double before = f > 0 ? std::min(end_slack_s, 0.5 * (knot_times[f] - knot_times[f - 1])) : end_slack_s;
        const double after = last + 1 < frames ? std::min(end_slack_s, 0.5 * (knot_times[last + 1] - knot_times[last])) : end_slack_s;
        const auto [begin, stop] = times_within(times, knot_times[f] - before, knot_times[last] + after, slack);
        if (last == f) {
          for (std::size_t k = begin; k < stop; ++k) {
            const std::size_t at = out.index(k, a);
            for (int d = 0; d < 3; ++d) out.positions[at + static_cast<std::size_t>(d)] = crowd.position(f, a)[d];
            if (with_velocities) std::fill_n(out.velocities.begin() + static_cast<std::ptrdiff_t>(at), 3, 0.0);
          }
        } else {
          RowMatrix values(static_cast<Index>(last - f + 1), 3);
          for (std::size_t g = f; g <= last; ++g) values.row(static_cast<Index>(g - f)) = crowd.position(g, a).transpose();
          const CubicSpline spline(std::vector<double>(knot_times.begin() + static_cast<std::ptrdiff_t>(f),
                                                       knot_times.begin() + static_cast<std::ptrdiff_t>(last) + 1),
                                   std::move(values), end);
          write_samples(spline, {a}, times, begin, stop, with_velocities, out);
        }
        if (!crowd.orientations.empty() || !crowd.actions.empty()) write_pose(crowd, a, f, last, knot_times, times, begin, stop, out);
        f = last + 1;
      }
    }
  });
  return out;
}

}  // namespace throng::timewarp
