#include <throng/core/errors.h>
#include <throng/timewarp/resample.h>
#include <throng/timewarp/schema.h>
#include <throng/timewarp/timewarp.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

namespace throng::timewarp {
namespace {

std::string number(double v) {
  std::string s = std::to_string(v);
  while (s.size() > 1 && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  return s;
}

// Per-interval sums of Eq. 12: A = Σ a², B = Σ a b, and the data for the deviation report.
struct IntervalSums {
  std::vector<double> A, B;
  std::vector<std::size_t> terms;
};

IntervalSums interval_sums(const CrowdMotion& deformed, const CrowdMotion& reference) {
  const std::size_t intervals = deformed.frame_count() - 1;
  IntervalSums s{std::vector<double>(intervals, 0.0), std::vector<double>(intervals, 0.0),
                 std::vector<std::size_t>(intervals, 0)};
  for (std::size_t i = 0; i < intervals; ++i) {
    const double dt = deformed.times[i + 1] - deformed.times[i];
    for (std::size_t j = 0; j < deformed.agent_count(); ++j) {
      if (!deformed.present(i, j) || !deformed.present(i + 1, j) || !reference.present(i, j) || !reference.present(i + 1, j)) {
        continue;
      }
      const double a = (deformed.position(i + 1, j) - deformed.position(i, j)).norm();
      const double b = (reference.position(i + 1, j) - reference.position(i, j)).norm() / dt;
      s.A[i] += a * a;
      s.B[i] += a * b;
      ++s.terms[i];
    }
  }
  return s;
}

// Σ over terms of (a s_i − b)², and of b², for the report.
void deviations(const CrowdMotion& deformed, const CrowdMotion& reference, const std::vector<double>& s_before,
                const std::vector<double>& s_after, Report& report) {
  double before = 0, after = 0, speed = 0;
  std::size_t count = 0;
  for (std::size_t i = 0; i + 1 < deformed.frame_count(); ++i) {
    const double dt = deformed.times[i + 1] - deformed.times[i];
    for (std::size_t j = 0; j < deformed.agent_count(); ++j) {
      if (!deformed.present(i, j) || !deformed.present(i + 1, j) || !reference.present(i, j) || !reference.present(i + 1, j)) {
        continue;
      }
      const double a = (deformed.position(i + 1, j) - deformed.position(i, j)).norm();
      const double b = (reference.position(i + 1, j) - reference.position(i, j)).norm() / dt;
      before += (a * s_before[i] - b) * (a * s_before[i] - b);
      after += (a * s_after[i] - b) * (a * s_after[i] - b);
      speed += b * b;
      ++count;
    }
  }
  report.terms = count;
  if (count == 0) return;
  report.speed_deviation_before = std::sqrt(before / static_cast<double>(count));
  report.speed_deviation_after = std::sqrt(after / static_cast<double>(count));
  report.reference_speed_rms = std::sqrt(speed / static_cast<double>(count));
}

// Minimises Σ P_i (r_i − target_i)² + Σ μ_i (r_{i+1} − r_i)² with lo ≤ r ≤ hi: the clamped closed form when every
// μ is 0, else a primal active-set loop over the tridiagonal system (strictly convex: it terminates).
std::vector<double> solve_ratios(const std::vector<double>& P, const std::vector<double>& target, const std::vector<double>& mu,
                                 double lo, double hi, std::vector<std::int8_t>& bound, int& iterations) {
  const std::size_t n = P.size();
  std::vector<double> r(n);
  bound.assign(n, 0);
  iterations = 0;
  const bool smooth = std::any_of(mu.begin(), mu.end(), [](double m) { return m > 0; });
  if (!smooth) {
    for (std::size_t i = 0; i < n; ++i) {
      r[i] = std::clamp(target[i], lo, hi);
      bound[i] = target[i] < lo ? -1 : target[i] > hi ? 1 : 0;
    }
    iterations = 1;
    return r;
  }
  // bound: −1 fixed at lo (r small: the interval at its longest), +1 fixed at hi, 0 free.
  const int cap = 3 * static_cast<int>(n) + 10;
  for (iterations = 1; iterations <= cap; ++iterations) {
    std::vector<double> lower(n > 0 ? n - 1 : 0, 0.0), diagonal(n, 0.0), upper(n > 0 ? n - 1 : 0, 0.0);
    RowMatrix rhs(static_cast<Eigen::Index>(n), 1);
    for (std::size_t i = 0; i < n; ++i) {
      if (bound[i] != 0) {
        diagonal[i] = 1.0;
        rhs(static_cast<Eigen::Index>(i), 0) = bound[i] < 0 ? lo : hi;
        continue;
      }
      diagonal[i] = P[i] + (i > 0 ? mu[i - 1] : 0.0) + (i + 1 < n ? mu[i] : 0.0);
      double b = P[i] * target[i];
      if (i > 0) {
        if (bound[i - 1] != 0) b += mu[i - 1] * (bound[i - 1] < 0 ? lo : hi);
        else lower[i - 1] = -mu[i - 1];
      }
      if (i + 1 < n) {
        if (bound[i + 1] != 0) b += mu[i] * (bound[i + 1] < 0 ? lo : hi);
        else upper[i] = -mu[i];
      }
      rhs(static_cast<Eigen::Index>(i), 0) = b;
    }
    solve_tridiagonal(lower, diagonal, upper, rhs);
    for (std::size_t i = 0; i < n; ++i) r[i] = rhs(static_cast<Eigen::Index>(i), 0);
    bool changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (bound[i] == 0) {
        if (r[i] < lo) bound[i] = -1, changed = true;
        else if (r[i] > hi) bound[i] = 1, changed = true;
        continue;
      }
      // Half the gradient of the objective at the bound; release when moving inward lowers the objective.
      double g = P[i] * (r[i] - target[i]);
      if (i > 0) g += mu[i - 1] * (r[i] - r[i - 1]);
      if (i + 1 < n) g += mu[i] * (r[i] - r[i + 1]);
      const double tolerance = 1e-12 * (P[i] + (i > 0 ? mu[i - 1] : 0.0) + (i + 1 < n ? mu[i] : 0.0)) * std::max(1.0, hi);
      if ((bound[i] < 0 && g < -tolerance) || (bound[i] > 0 && g > tolerance)) {
        bound[i] = 0;
        changed = true;
      }
    }
    if (!changed) {
      for (std::size_t i = 0; i < n; ++i) r[i] = std::clamp(r[i], lo, hi);
      return r;
    }
  }
  throw NumericalError("time warp: the clamped smoothing problem did not settle after " + std::to_string(cap) + " active-set passes");
}

}  // namespace

void validate(const Options& o) { check_options(describe, o, "timewarp option "); }

double Warp::map(double old_time) const {
  const std::size_t n = source_times.size();
  if (n == 0) return old_time;
  if (n == 1) return warped_times[0] + (old_time - source_times[0]);
  const auto it = std::upper_bound(source_times.begin() + 1, source_times.end() - 1, old_time);
  const auto i = static_cast<std::size_t>(it - source_times.begin()) - 1;
  const double u = (old_time - source_times[i]) / (source_times[i + 1] - source_times[i]);
  return warped_times[i] + u * (warped_times[i + 1] - warped_times[i]);
}

CrowdMotion match_reference(const CrowdMotion& deformed, const CrowdMotion& reference, double tolerance) {
  std::unordered_map<std::int64_t, std::size_t> agent_of;
  for (std::size_t a = 0; a < reference.agent_count(); ++a) agent_of.emplace(reference.ids[a], a);
  std::vector<std::size_t> agents(deformed.agent_count());
  for (std::size_t j = 0; j < deformed.agent_count(); ++j) {
    const auto it = agent_of.find(deformed.ids[j]);
    if (it == agent_of.end()) {
      throw InputError("time warp: agent " + std::to_string(deformed.ids[j]) +
                       " of the deformed crowd is not in the reference crowd (agents are matched by id)");
    }
    agents[j] = it->second;
  }
  std::vector<std::size_t> frames(deformed.frame_count());
  for (std::size_t i = 0; i < deformed.frame_count(); ++i) {
    const double t = deformed.times[i];
    const auto it = std::lower_bound(reference.times.begin(), reference.times.end(), t - tolerance);
    if (it == reference.times.end() || std::abs(*it - t) > tolerance) {
      const std::string span = reference.times.empty() ? std::string("no frames")
                                                       : "[" + number(reference.times.front()) + ", " + number(reference.times.back()) + "] s";
      throw InputError("time warp: frame " + std::to_string(i) + " of the deformed crowd (t = " + number(t) +
                       " s) has no reference frame within " + number(tolerance) + " s (the reference covers " + span +
                       "); the reference must be the crowd before the deformation, at the same frame times");
    }
    frames[i] = static_cast<std::size_t>(it - reference.times.begin());
  }
  CrowdMotion out = CrowdMotion::with_shape(deformed.frame_count(), deformed.agent_count());
  out.times = deformed.times;
  out.ids = deformed.ids;
  out.radii = deformed.radii;
  out.species = deformed.species;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    for (std::size_t j = 0; j < agents.size(); ++j) out.position(i, j) = reference.position(frames[i], agents[j]);
  }
  return out;
}

Warp solve_warp(const CrowdMotion& deformed, const CrowdMotion& reference, const Options& options, Report* report) {
  validate(options);
  const std::size_t frames = deformed.frame_count();
  if (frames < 2) throw InputError("time warp: the crowd has " + std::to_string(frames) + " frames; a warp needs at least 2");
  if (reference.frame_count() != frames || reference.agent_count() != deformed.agent_count()) {
    throw InputError("time warp: the reference has " + std::to_string(reference.frame_count()) + " frames × " +
                     std::to_string(reference.agent_count()) + " agents, the deformed crowd " + std::to_string(frames) +
                     " × " + std::to_string(deformed.agent_count()) + " (use match_reference)");
  }
  const std::size_t n = frames - 1;
  const IntervalSums sums = interval_sums(deformed, reference);
  std::vector<double> dt(n), P(n), target(n, 1.0), mu(n > 0 ? n - 1 : 0, 0.0);
  double mean_P = 0;
  std::size_t moving = 0;
  for (std::size_t i = 0; i < n; ++i) {
    dt[i] = deformed.times[i + 1] - deformed.times[i];
    if (sums.A[i] > 0) {
      P[i] = sums.A[i] / (dt[i] * dt[i]);
      target[i] = sums.B[i] * dt[i] / sums.A[i];
      mean_P += P[i];
      ++moving;
    }
  }
  mean_P = moving > 0 ? mean_P / static_cast<double>(moving) : 1.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (sums.A[i] <= 0) P[i] = 1e-3 * mean_P;  // still interval: keep its length, weakly
  }
  if (options.smoothing_time > 0) {
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double tau = 0.5 * (dt[i] + dt[i + 1]);
      mu[i] = 0.5 * (P[i] + P[i + 1]) * (options.smoothing_time / tau) * (options.smoothing_time / tau);
    }
  }
  // r = Δt / Δt' ∈ [1 / max_ratio, 1 / min_ratio].
  Warp warp;
  int iterations = 0;
  std::vector<std::int8_t> r_bound;
  const std::vector<double> r = moving > 0 ? solve_ratios(P, target, mu, 1.0 / options.max_interval_ratio,
                                                         1.0 / options.min_interval_ratio, r_bound, iterations)
                                           : std::vector<double>(n, 1.0);
  if (moving == 0) r_bound.assign(n, 0);
  warp.source_times = deformed.times;
  warp.warped_times.resize(frames);
  warp.inverse_intervals.resize(n);
  warp.bound.resize(n);
  warp.warped_times[0] = deformed.times[0];
  for (std::size_t i = 0; i < n; ++i) {
    warp.inverse_intervals[i] = r[i] / dt[i];
    warp.warped_times[i + 1] = warp.warped_times[i] + dt[i] / r[i];
    // r at its upper bound means the interval at its shortest.
    warp.bound[i] = static_cast<std::int8_t>(-r_bound[i]);
  }
  if (report) {
    report->frames_in = frames;
    report->agents = deformed.agent_count();
    report->still_intervals = n - moving;
    report->active_set_iterations = iterations;
    report->clamped_short = static_cast<std::size_t>(std::count(warp.bound.begin(), warp.bound.end(), std::int8_t{-1}));
    report->clamped_long = static_cast<std::size_t>(std::count(warp.bound.begin(), warp.bound.end(), std::int8_t{1}));
    std::vector<double> s_before(n);
    for (std::size_t i = 0; i < n; ++i) s_before[i] = 1.0 / dt[i];
    deviations(deformed, reference, s_before, warp.inverse_intervals, *report);
    report->duration_in_s = deformed.times.back() - deformed.times.front();
    report->warped_duration_s = warp.warped_times.back() - warp.warped_times.front();
  }
  return warp;
}

Result time_warp(const CrowdMotion& deformed, const CrowdMotion& reference, const Options& options) {
  validate(options);
  Result result;
  const CrowdMotion matched = match_reference(deformed, reference, options.time_tolerance_s);
  result.warp = solve_warp(deformed, matched, options, &result.report);
  const double rate = options.output_rate_hz > 0 ? options.output_rate_hz : frame_rate(deformed);
  // The output frames run to the one nearest the warped end, and every agent's first and last samples land on the
  // output frames nearest them (half an output interval of slack): a warp that moves the end by less than half a
  // frame keeps every sample instead of dropping the last one.
  const double half_frame = 0.5 / rate;
  const std::vector<double> times =
      uniform_times(result.warp.warped_times.front(), result.warp.warped_times.back() + half_frame, rate);
  result.crowd = resample_crowd(deformed, result.warp.warped_times, times, options.spline_end, true, half_frame);
  result.report.frames_out = result.crowd.frame_count();
  result.report.duration_out_s = times.back() - times.front();
  result.report.output_rate_hz = rate;
  return result;
}

}  // namespace throng::timewarp
