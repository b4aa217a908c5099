// Strokes → Course: correspondence, smoothing (Eq. 1), speed (Eq. 5), width and standard distance (Eq. 6–7),
// irregularity (Eq. 8–12). See sketch.h for how the garbled equations are read.
#include <throng/core/errors.h>
#include <throng/sketch/sketch.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "polyline.h"

namespace throng::sketch {
namespace {

using detail::arc_lengths;
using detail::cross;

// Below this distance (metres) two consecutive main-line points are the same place (a pen pause).
constexpr double same_place_m = 1e-9;

std::string stroke_name(std::size_t i) {
  return i == 0 ? std::string("stroke 0 (main line)") : "stroke " + std::to_string(i) + " (auxiliary line)";
}

std::string format_point(const Eigen::Vector2d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ")";
  return s.str();
}

void check_stroke(const Stroke& stroke, std::size_t i) {
  const std::string name = stroke_name(i);
  if (stroke.points.size() < 2) {
    throw InputError("sketch: " + name + " has " + std::to_string(stroke.points.size()) +
                     " point(s), expected at least 2");
  }
  for (std::size_t k = 0; k < stroke.points.size(); ++k) {
    if (!stroke.points[k].allFinite()) {
      throw InputError("sketch: " + name + " point " + std::to_string(k) + " is " + format_point(stroke.points[k]) +
                       ", expected finite coordinates");
    }
  }
  const bool main = i == 0;
  if (main || !stroke.times.empty()) {
    if (stroke.times.size() != stroke.points.size()) {
      throw InputError("sketch: " + name + " has " + std::to_string(stroke.times.size()) + " time stamps for " +
                       std::to_string(stroke.points.size()) + " points, expected one per point");
    }
    for (std::size_t k = 0; k < stroke.times.size(); ++k) {
      if (!std::isfinite(stroke.times[k])) {
        throw InputError("sketch: " + name + " time stamp " + std::to_string(k) + " is " +
                         std::to_string(stroke.times[k]) + ", expected a finite time in seconds");
      }
      if (main && k > 0 && !(stroke.times[k] > stroke.times[k - 1])) {
        std::ostringstream m;
        m << "sketch: " << name << " time stamp " << k << " is " << stroke.times[k] << " s, not after "
          << stroke.times[k - 1] << " s at point " << k - 1
          << "; the main line's time stamps must increase strictly (they set the crowd's speed)";
        throw InputError(m.str());
      }
    }
  }
  if (arc_lengths(stroke.points).back() <= same_place_m) {
    throw InputError("sketch: " + name + " has zero length (all its points are at " +
                     format_point(stroke.points.front()) + ")");
  }
}

// The main line with pen pauses merged (the first point and time of each run of coinciding points is kept).
void merge_pauses(const Stroke& stroke, std::vector<Eigen::Vector2d>& points, std::vector<double>& times) {
  points.clear();
  times.clear();
  for (std::size_t k = 0; k < stroke.points.size(); ++k) {
    if (!points.empty() && (stroke.points[k] - points.back()).norm() <= same_place_m) continue;
    points.push_back(stroke.points[k]);
    times.push_back(stroke.times[k]);
  }
}

// Uniform arc-length resampling at about `spacing` metres; times linear in arc length (keeps Eq. 5 speeds).
void resample_uniform(std::vector<Eigen::Vector2d>& points, std::vector<double>& times, double spacing) {
  const std::vector<double> cumulative = arc_lengths(points);
  const double length = cumulative.back();
  const auto segments = static_cast<std::size_t>(std::max(1.0, std::round(length / spacing)));
  std::vector<Eigen::Vector2d> p;
  std::vector<double> t;
  p.reserve(segments + 1);
  t.reserve(segments + 1);
  for (std::size_t m = 0; m <= segments; ++m) {
    const double s = length * static_cast<double>(m) / static_cast<double>(segments);
    p.push_back(detail::point_at(points, cumulative, s));
    t.push_back(detail::value_at(times, cumulative, s));
  }
  points = std::move(p);
  times = std::move(t);
}

// Eq. 1 (read): moving average over [k−w, k+w], w = min(δ, k, K−1−k) so the end points are kept.
std::vector<Eigen::Vector2d> smooth(const std::vector<Eigen::Vector2d>& q, int delta) {
  const auto K = static_cast<std::ptrdiff_t>(q.size());
  std::vector<Eigen::Vector2d> out(q.size());
  for (std::ptrdiff_t k = 0; k < K; ++k) {
    const std::ptrdiff_t w = std::min<std::ptrdiff_t>({delta, k, K - 1 - k});
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    for (std::ptrdiff_t d = -w; d <= w; ++d) sum += q[static_cast<std::size_t>(k + d)];
    out[static_cast<std::size_t>(k)] = sum / static_cast<double>(2 * w + 1);
  }
  return out;
}

// Unit-free tangent of the main line at k (central difference; one-sided where that vanishes).
Eigen::Vector2d tangent(const std::vector<Eigen::Vector2d>& main, std::size_t k) {
  const std::size_t K = main.size();
  Eigen::Vector2d t = main[std::min(k + 1, K - 1)] - main[k > 0 ? k - 1 : 0];
  if (t.squaredNorm() > 0) return t;
  if (k + 1 < K) return main[k + 1] - main[k];
  return main[k] - main[k - 1];
}

}  // namespace

Course analyse_strokes(const std::vector<Stroke>& strokes, const Options& options) {
  validate(options);
  if (strokes.size() < 2) {
    throw InputError("sketch: " + std::to_string(strokes.size()) +
                     " stroke(s) given, expected a main line and at least one auxiliary line");
  }
  for (std::size_t i = 0; i < strokes.size(); ++i) check_stroke(strokes[i], i);

  Course c;
  merge_pauses(strokes[0], c.main, c.main_times);
  if (options.resample_spacing_m > 0) resample_uniform(c.main, c.main_times, options.resample_spacing_m);
  const std::size_t K = c.main.size();
  const std::size_t A = strokes.size() - 1;

  // Correspondence: auxiliary lines resampled at the main line's normalised arc lengths.
  const std::vector<double> cumulative = arc_lengths(c.main);
  std::vector<double> fractions(K);
  for (std::size_t k = 0; k < K; ++k) fractions[k] = cumulative[k] / cumulative.back();
  for (std::size_t i = 0; i < A; ++i) {
    c.auxiliary.push_back(detail::resample_at_fractions(strokes[i + 1].points, fractions));
    c.smoothed.push_back(smooth(c.auxiliary.back(), options.smoothing_window));
  }

  // Eq. 5: speed of the segment ending at k.
  c.speed.resize(K);
  for (std::size_t k = 1; k < K; ++k) {
    c.speed[k] = options.speed_scale * (c.main[k] - c.main[k - 1]).norm() / (c.main_times[k] - c.main_times[k - 1]);
  }
  c.speed[0] = c.speed[1];

  // Eq. 6–7: width between the farthest smoothed auxiliary points on either side, then standard distance.
  c.width.resize(K);
  c.standard_distance.resize(K);
  const double slope =
      (options.wide_distance_m - options.narrow_distance_m) / (options.wide_width_m - options.narrow_width_m);
  for (std::size_t k = 0; k < K; ++k) {
    const Eigen::Vector2d t = tangent(c.main, k);
    Eigen::Vector2d left = c.main[k], right = c.main[k];
    double left_distance = 0, right_distance = 0;
    for (std::size_t i = 0; i < A; ++i) {
      const Eigen::Vector2d v = c.smoothed[i][k] - c.main[k];
      const double d = v.norm();
      const bool on_left = cross(t, v) >= 0;
      double& farthest = on_left ? left_distance : right_distance;
      if (d > farthest) {
        farthest = d;
        (on_left ? left : right) = c.smoothed[i][k];
      }
    }
    const double W = (left - right).norm();
    c.width[k] = W;
    c.standard_distance[k] = W <= options.narrow_width_m ? options.narrow_distance_m
                             : W >= options.wide_width_m
                                 ? options.wide_distance_m
                                 : options.narrow_distance_m + slope * (W - options.narrow_width_m);
  }

  // Eq. 8: change of the main-to-auxiliary distance per metre of main line, on the raw (resampled) auxiliaries.
  c.distance_change.assign(A, std::vector<double>(K - 1));
  for (std::size_t i = 0; i < A; ++i) {
    for (std::size_t k = 0; k + 1 < K; ++k) {
      const double here = (c.main[k] - c.auxiliary[i][k]).norm();
      const double next = (c.main[k + 1] - c.auxiliary[i][k + 1]).norm();
      c.distance_change[i][k] = (here - next) / (c.main[k] - c.main[k + 1]).norm();
    }
  }

  // Eq. 9–12: windowed mean and variance of G per auxiliary line, mean over lines, gain; Eq. 13's scale.
  c.irregularity.resize(K);
  c.correction_scale.resize(K);
  const auto delta = static_cast<std::ptrdiff_t>(options.smoothing_window);
  const auto last_segment = static_cast<std::ptrdiff_t>(K) - 2;
  for (std::size_t k = 0; k < K; ++k) {
    const std::ptrdiff_t lo = std::max<std::ptrdiff_t>(0, static_cast<std::ptrdiff_t>(k) - delta);
    const std::ptrdiff_t hi = std::min<std::ptrdiff_t>(last_segment, static_cast<std::ptrdiff_t>(k) + delta);
    const auto n = static_cast<double>(hi - lo + 1);
    double variance_sum = 0;
    for (std::size_t i = 0; i < A; ++i) {
      const std::vector<double>& G = c.distance_change[i];
      double mean = 0;
      for (std::ptrdiff_t m = lo; m <= hi; ++m) mean += G[static_cast<std::size_t>(m)];
      mean /= n;
      double var = 0;
      for (std::ptrdiff_t m = lo; m <= hi; ++m) {
        const double d = G[static_cast<std::size_t>(m)] - mean;
        var += d * d;
      }
      variance_sum += var / n;
    }
    c.irregularity[k] = options.irregularity_gain * variance_sum / static_cast<double>(A);
    c.correction_scale[k] = std::min(c.irregularity[k] / options.irregularity_max, 1.0);
  }
  return c;
}

}  // namespace throng::sketch
