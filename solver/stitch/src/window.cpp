#include "window.h"

#include <throng/stitch/stitch.h>

#include <algorithm>
#include <cassert>

namespace throng::stitch::detail {
namespace {

constexpr double rounding = 1e-9;

// The regular samples of one side, as (distance in seconds from the joint, stitched frame), the joint excluded:
// every step-th frame outwards and the outer frame.
struct Side {
  std::vector<double> distance;  // increasing
  std::vector<std::size_t> frame;
  double duration = 0;           // to the outer frame
  [[nodiscard]] std::size_t inside(double window) const {
    std::size_t n = 0;
    for (double d : distance) n += inside_window(d, window) ? 1 : 0;
    return n;
  }
};

Side side(const std::vector<double>& times, std::size_t J, std::size_t step, bool before) {
  Side s;
  const std::size_t last = before ? J : times.size() - 1 - J;  // frames from the joint to the outer frame
  for (std::size_t d = step; d < last; d += step) s.frame.push_back(before ? J - d : J + d);
  s.frame.push_back(before ? 0 : times.size() - 1);
  for (std::size_t F : s.frame) s.distance.push_back(before ? times[J] - times[F] : times[F] - times[J]);
  s.duration = s.distance.back();
  return s;
}

// The frame nearest the joint whose distance is at or beyond the window (the outer frame at the latest).
std::size_t edge(const std::vector<double>& times, std::size_t J, double window, bool before) {
  if (before) {
    std::size_t F = J - 1;
    while (F > 0 && inside_window(times[J] - times[F], window)) --F;
    return F;
  }
  std::size_t F = J + 1;
  while (F + 1 < times.size() && inside_window(times[F] - times[J], window)) ++F;
  return F;
}

}  // namespace

bool inside_window(double distance, double window) noexcept { return distance < window * (1 - rounding); }

SampledWindow sample_window(const std::vector<double>& times, std::size_t J, std::size_t step, double requested_s,
                            std::size_t agents, std::size_t max_vertices) {
  assert(J >= 1 && J + 1 < times.size() && step >= 1);
  const Side before = side(times, J, step, true), after = side(times, J, step, false);
  SampledWindow w;
  if (requested_s > 0) {
    w.first_s = std::min(requested_s, before.duration);
    w.second_s = std::min(requested_s, after.duration);
  } else {
    w.first_s = before.duration;
    w.second_s = after.duration;
    // Solved samples: the free ones inside the window, the joint, and the two pinned edges.
    auto vertices = [&](double a, double b) { return agents * (before.inside(a) + after.inside(b) + 3); };
    w.whole_vertices = vertices(w.first_s, w.second_s);
    if (max_vertices > 0 && w.whole_vertices > max_vertices) {
      // The longest common window that fits: candidate lengths are the samples' distances (a sample exactly at
      // the window's length is its pinned edge); the shortest, one step, always stays.
      std::vector<double> candidates = before.distance;
      candidates.insert(candidates.end(), after.distance.begin(), after.distance.end());
      std::sort(candidates.begin(), candidates.end());
      double best = candidates.front();
      for (double c : candidates) {
        if (vertices(std::min(c, before.duration), std::min(c, after.duration)) <= max_vertices) best = c;
        else break;  // the count only grows with the window
      }
      w.first_s = std::min(best, before.duration);
      w.second_s = std::min(best, after.duration);
      w.limited = true;
    }
  }
  const std::size_t edge_before = edge(times, J, w.first_s, true), edge_after = edge(times, J, w.second_s, false);
  w.first_frames = J - edge_before;
  w.second_frames = edge_after - J;

  w.samples = before.frame;
  w.samples.push_back(J);
  w.samples.insert(w.samples.end(), after.frame.begin(), after.frame.end());
  w.samples.push_back(edge_before);
  w.samples.push_back(edge_after);
  std::sort(w.samples.begin(), w.samples.end());
  w.samples.erase(std::unique(w.samples.begin(), w.samples.end()), w.samples.end());
  auto index_of = [&](std::size_t F) {
    return static_cast<std::size_t>(std::lower_bound(w.samples.begin(), w.samples.end(), F) - w.samples.begin());
  };
  w.joint_sample = index_of(J);
  w.first_solved = index_of(edge_before);
  w.last_solved = index_of(edge_after);
  return w;
}

}  // namespace throng::stitch::detail
