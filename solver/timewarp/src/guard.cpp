#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/timewarp/guard.h>
#include <throng/timewarp/schema.h>
#include <throng/timewarp/resample.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <string>

namespace throng::timewarp {
namespace {

using Vec = Eigen::Vector3d;

// The warp's ramp: 1 at 0, smooth (zero slope) there, e^{−|x|}-like tails.
double kernel(double x) {
  x = std::abs(x);
  return (1 + x) * std::exp(-x);
}

// |a| at frame f of agent a (0 unless present at f − 1, f, f + 1).
double acceleration_at(const CrowdMotion& c, std::size_t a, std::size_t f) {
  if (f == 0 || f + 1 >= c.frame_count() || !c.present(f - 1, a) || !c.present(f, a) || !c.present(f + 1, a)) return 0.0;
  const Vec before = (c.position(f, a) - c.position(f - 1, a)) / (c.times[f] - c.times[f - 1]);
  const Vec after = (c.position(f + 1, a) - c.position(f, a)) / (c.times[f + 1] - c.times[f]);
  return ((after - before) / (0.5 * (c.times[f + 1] - c.times[f - 1]))).norm();
}

double largest(const std::vector<double>& v) { return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end()); }

// Replaces agent a's positions at frames [s, e] by the bridge of least Σ|Δ²x|² over the window and its two fixed
// frames each side inside the run [rs, re), keeping the pinned frames' positions; returns the largest shift.
double bridge(CrowdMotion& c, std::size_t a, std::size_t s, std::size_t e, std::size_t rs, std::size_t re,
              const std::vector<char>& pinned) {
  auto fixed_frame = [&](std::size_t f) { return f < s || f > e || pinned[f] != 0; };
  const auto n = static_cast<Eigen::Index>(e - s + 1);
  const std::size_t lo = s > rs + 2 ? s - 2 : rs, hi = std::min(re - 1, e + 2);  // frames in the energy
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  for (std::size_t k = lo + 1; k + 1 <= hi; ++k) {  // the second difference centred at k
    const std::size_t frames[3] = {k - 1, k, k + 1};
    const double coefficient[3] = {1.0, -2.0, 1.0};
    Vec fixed = Vec::Zero();
    for (int i = 0; i < 3; ++i) {
      if (fixed_frame(frames[i])) fixed += coefficient[i] * Vec(c.position(frames[i], a));
    }
    for (int i = 0; i < 3; ++i) {
      if (fixed_frame(frames[i])) continue;
      const auto u = static_cast<Eigen::Index>(frames[i] - s);
      rhs.row(u) -= coefficient[i] * fixed.transpose();
      for (int j = 0; j < 3; ++j) {
        if (!fixed_frame(frames[j])) M(u, static_cast<Eigen::Index>(frames[j] - s)) += coefficient[i] * coefficient[j];
      }
    }
  }
  // A faint tie to the current positions: fixes what the second differences leave free (a window that is the
  // whole run may move along a straight line). A pinned frame's row holds the tie alone: it stays where it is.
  constexpr double tie = 1e-6;
  for (Eigen::Index u = 0; u < n; ++u) {
    M(u, u) += tie;
    rhs.row(u) += tie * Vec(c.position(s + static_cast<std::size_t>(u), a)).transpose();
  }
  const Eigen::MatrixXd x = M.ldlt().solve(rhs);
  double shift = 0;
  for (Eigen::Index u = 0; u < n; ++u) {
    auto p = c.position(s + static_cast<std::size_t>(u), a);
    shift = std::max(shift, (x.row(u).transpose() - Vec(p)).norm());
    p = x.row(u).transpose();
  }
  return shift;
}

struct Smoothed {
  std::size_t kinks_before = 0, kinks_after = 0, windows = 0;
  double shift = 0;
};

// Step 2 of guard.h for agent a, with the per-frame limits `limit` ([T][N]).
Smoothed smooth_agent(CrowdMotion& c, std::size_t a, const std::vector<double>& limit, const std::vector<char>& pinned,
                      const GuardOptions& o) {
  Smoothed out;
  const std::size_t T = c.frame_count(), N = c.agent_count();
  for (std::size_t rs = 0; rs < T;) {
    if (!c.present(rs, a)) {
      ++rs;
      continue;
    }
    std::size_t re = rs;
    while (re < T && c.present(re, a)) ++re;
    const double h = re - rs > 1 ? (c.times[re - 1] - c.times[rs]) / static_cast<double>(re - rs - 1) : 1.0;
    auto kinks = [&] {
      std::vector<std::size_t> k;
      for (std::size_t f = rs + 1; f + 1 < re; ++f) {
        if (acceleration_at(c, a, f) > limit[f * N + a] * (1 + 1e-9)) k.push_back(f);
      }
      return k;
    };
    std::vector<std::size_t> found = kinks();
    out.kinks_before += found.size();
    auto w = static_cast<std::size_t>(std::ceil(o.smoothing_time / h));
    const auto widest = static_cast<std::size_t>(std::ceil(o.max_window_time / h));
    while (!found.empty() && w <= widest) {
      // Windows [f − w, f + w] within the run, merged where they meet.
      std::size_t s = found.front() > rs + w ? found.front() - w : rs, e = std::min(re - 1, found.front() + w);
      auto flush = [&] {
        out.shift = std::max(out.shift, bridge(c, a, s, e, rs, re, pinned));
        ++out.windows;
      };
      for (std::size_t i = 1; i < found.size(); ++i) {
        const std::size_t s2 = found[i] > rs + w ? found[i] - w : rs;
        if (s2 <= e + 1) {
          e = std::min(re - 1, found[i] + w);
        } else {
          flush();
          s = s2;
          e = std::min(re - 1, found[i] + w);
        }
      }
      flush();
      found = kinks();
      w = w + std::max<std::size_t>(1, w / 2);
    }
    out.kinks_after += found.size();
    rs = re;
  }
  return out;
}

}  // namespace

void validate(const GuardOptions& o, const std::string& what) {
  check_options(describe, o, what.empty() ? what : what + ".");  // the ranges: schema.cpp
  if (!(o.max_window_time >= o.smoothing_time)) {
    throw ConfigError(what + ".max_window_time " + std::to_string(o.max_window_time) + ": expected a duration ≥ smoothing_time");
  }
}

double fastest_speed(const CrowdMotion& c) {
  double fastest = 0;
  for (std::size_t f = 0; f + 1 < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) {
      if (c.present(f, a) && c.present(f + 1, a)) {
        fastest = std::max(fastest, (c.position(f + 1, a) - c.position(f, a)).norm() / (c.times[f + 1] - c.times[f]));
      }
    }
  }
  return fastest;
}

std::vector<double> accelerations(const CrowdMotion& c) {
  std::vector<double> out(c.frame_count() * c.agent_count(), 0.0);
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) out[f * c.agent_count() + a] = acceleration_at(c, a, f);
  }
  return out;
}

Source source_of(const CrowdMotion& output, const CrowdMotion& reference, double time_tolerance_s) {
  return {fastest_speed(reference), accelerations(match_reference(output, reference, time_tolerance_s))};
}

void describe(ReportWriter& w, const GuardReport& g) {
  w.flag("guard_warped", g.warped);
  w.number("guard_largest_stretch", g.largest_stretch);
  w.count("guard_kinks_before", g.kinks_before);
  w.count("guard_kinks_after", g.kinks_after);
  w.number("guard_max_speed_m_s", g.max_speed_after);
  w.number("guard_max_acceleration_m_s2", g.max_acceleration_after);
}

GuardResult guard(const CrowdMotion& output, const Source& source, const GuardOptions& o) {
  validate(o);
  const std::size_t T = output.frame_count(), N = output.agent_count();
  if (!source.acceleration.empty() && source.acceleration.size() != T * N) {
    throw InputError("guard: the source's accelerations have " + std::to_string(source.acceleration.size()) +
                     " values, expected " + std::to_string(T) + " frames × " + std::to_string(N) + " agents");
  }
  GuardResult r;
  r.crowd = output;
  r.warp.source_times = r.warp.warped_times = output.times;
  GuardReport& report = r.report;
  report.max_speed_before = fastest_speed(output);
  report.duration_before = report.duration_after = T > 0 ? output.times.back() - output.times.front() : 0.0;
  report.max_acceleration_before = largest(accelerations(output));
  if (!o.enabled || T < 2) {
    report.max_speed_after = report.max_speed_before;
    report.max_acceleration_after = report.max_acceleration_before;
    return r;
  }
  // 1. Speed: the stretch each interval needs, ramped (guard.h); aimed 2 % under the limit, for the splines'
  // overshoot, and repeated (at most 3 rounds) while some agent is still beyond it.
  report.speed_limit = source.max_speed > 0 ? o.max_speed_ratio * source.max_speed : 0.0;
  std::vector<double> limit(T * N, o.max_acceleration);
  for (std::size_t k = 0; k < source.acceleration.size(); ++k) {
    if (std::isfinite(source.acceleration[k])) limit[k] = std::max(limit[k], source.acceleration[k]);
  }
  for (int round = 0; round < 3 && report.speed_limit > 0; ++round) {
    const CrowdMotion& c = r.crowd;
    const std::size_t frames = c.frame_count();
    if (fastest_speed(c) <= report.speed_limit) break;
    std::vector<double> need(frames - 1, 1.0), mid(frames - 1), stretch(frames - 1, 1.0);
    for (std::size_t i = 0; i + 1 < frames; ++i) {
      mid[i] = 0.5 * (c.times[i] + c.times[i + 1]);
      for (std::size_t a = 0; a < N; ++a) {
        if (!c.present(i, a) || !c.present(i + 1, a)) continue;
        const double v = (c.position(i + 1, a) - c.position(i, a)).norm() / (c.times[i + 1] - c.times[i]);
        need[i] = std::max(need[i], v / (0.98 * report.speed_limit));
      }
    }
    for (std::size_t k = 0; k + 1 < frames; ++k) {
      if (need[k] <= 1) continue;
      for (std::size_t i = 0; i + 1 < frames; ++i) {
        stretch[i] = std::max(stretch[i], 1 + (need[k] - 1) * kernel((mid[i] - mid[k]) / o.ramp_time));
      }
    }
    std::vector<double> knots(frames);
    knots[0] = c.times[0];
    for (std::size_t i = 0; i + 1 < frames; ++i) knots[i + 1] = knots[i] + stretch[i] * (c.times[i + 1] - c.times[i]);
    const std::vector<double> times = uniform_times(knots.front(), knots.back(), frame_rate(output));
    // Each new frame's limit: the larger of the two frames around its unwarped time.
    std::vector<double> resampled(times.size() * N);
    for (std::size_t f = 0; f < times.size(); ++f) {
      const auto it = std::upper_bound(knots.begin(), knots.end(), times[f]);
      const std::size_t hi = std::min<std::size_t>(static_cast<std::size_t>(it - knots.begin()), frames - 1);
      const std::size_t lo = hi > 0 ? hi - 1 : 0;
      for (std::size_t a = 0; a < N; ++a) resampled[f * N + a] = std::max(limit[lo * N + a], limit[hi * N + a]);
    }
    limit = std::move(resampled);
    // The warp of the output's own frames: this round's knots composed with the earlier rounds'.
    Warp round_warp;
    round_warp.source_times = c.times;
    round_warp.warped_times = knots;
    for (double& t : r.warp.warped_times) t = round_warp.map(t);
    for (std::size_t i = 0; i + 1 < frames; ++i) report.stretched_intervals += round == 0 && stretch[i] > 1 ? 1 : 0;
    report.largest_stretch *= *std::max_element(stretch.begin(), stretch.end());
    r.crowd = resample_crowd(c, knots, times);
    report.warped = true;
  }
  if (report.warped) {
    Warp& w = r.warp;
    w.inverse_intervals.resize(T - 1);
    w.bound.assign(T - 1, 0);
    for (std::size_t i = 0; i + 1 < T; ++i) w.inverse_intervals[i] = 1.0 / (w.warped_times[i + 1] - w.warped_times[i]);
    report.duration_after = r.crowd.times.back() - r.crowd.times.front();
  }
  // 2. Kinks, agent by agent (each writes only its own positions), the pinned times kept at the frames nearest
  // their warped times.
  const std::vector<double>& times = r.crowd.times;
  std::vector<char> pinned(times.size(), 0);
  for (double t : source.pinned_times) {
    const double warped = report.warped ? r.warp.map(t) : t;
    const auto after = std::lower_bound(times.begin(), times.end(), warped);
    auto f = static_cast<std::size_t>(std::min<std::ptrdiff_t>(after - times.begin(), static_cast<std::ptrdiff_t>(times.size()) - 1));
    if (f > 0 && std::abs(times[f - 1] - warped) <= std::abs(times[f] - warped)) --f;
    pinned[f] = 1;
  }
  std::vector<Smoothed> per_agent(N);
  parallel_for(N, 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t a = begin; a < end; ++a) per_agent[a] = smooth_agent(r.crowd, a, limit, pinned, o);
  });
  for (const Smoothed& s : per_agent) {
    report.kinks_before += s.kinks_before;
    report.kinks_after += s.kinks_after;
    report.windows += s.windows;
    report.largest_shift = std::max(report.largest_shift, s.shift);
  }
  if (report.warped || report.windows > 0) r.crowd.velocities.clear();
  report.max_speed_after = fastest_speed(r.crowd);
  report.max_acceleration_after = largest(accelerations(r.crowd));
  return r;
}

}  // namespace throng::timewarp
