// Episode detection: Eq. 4, Eq. 5, events and their merging (episodes.h, construct.h steps 2–4).
#include "episodes.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace throng::tiling {

// The velocity stands for the paper's full-body pose "ignoring horizontal translation and rotation about the
// vertical axis": a common rotation of all velocities leaves every ‖v_{i+j} − v_{i+k}‖ unchanged, so world
// velocities give the rotation-free value, and velocities carry no translation.
std::vector<double> motion_variation(const std::vector<Eigen::Vector2d>& velocities, std::size_t w) {
  const auto n = static_cast<long>(velocities.size());
  const auto half = static_cast<long>(w);
  std::vector<double> out(velocities.size(), 0.0);
  for (long i = 0; i < n; ++i) {
    const long lo = std::max(0L, i - half), hi = std::min(n - 1, i + half);
    double sum = 0;
    for (long j = lo; j <= hi; ++j) {
      for (long k = j + 1; k <= hi; ++k) {
        sum += (velocities[static_cast<std::size_t>(j)] - velocities[static_cast<std::size_t>(k)]).squaredNorm();
      }
    }
    out[static_cast<std::size_t>(i)] = sum;
  }
  return out;
}

namespace {

// g(A, B) of Eq. 5: the angle between A's heading and the direction from A to B, in [0, π].
double gaze_angle(const Eigen::Vector2d& from, double heading, const Eigen::Vector2d& to) {
  const Eigen::Vector2d d = to - from;
  if (d.norm() < 1e-12) return 0;
  const Eigen::Vector2d facing(std::cos(heading), std::sin(heading));
  return std::acos(std::clamp(facing.dot(d.normalized()), -1.0, 1.0));
}

}  // namespace

double synchronicity(double variation_a, double variation_b, const Eigen::Vector2d& position_a, double heading_a,
                     const Eigen::Vector2d& position_b, double heading_b) {
  return variation_a * variation_b * std::exp(-gaze_angle(position_a, heading_a, position_b)) *
         std::exp(-gaze_angle(position_b, heading_b, position_a));
}

namespace {

// Whether tracks A and B (both present at global sample g) have an event there (construct.h step 3).
bool event_at(const Track& A, const Track& B, long g, const RealPatchOptions& o) {
  const std::size_t sa = A.local(g), sb = B.local(g);
  const double d = (A.p[sa] - B.p[sb]).norm();
  if (d < o.contact_m) return true;
  if (d < o.near_m && (A.variation[sa] >= o.reaction_min_m2ps2 || B.variation[sb] >= o.reaction_min_m2ps2)) return true;
  return d < o.sync_range_m &&
         synchronicity(A.variation[sa], B.variation[sb], A.p[sa], A.heading[sa], B.p[sb], B.heading[sb]) >= o.synchronicity_min;
}

double distance_at(const Track& A, const Track& B, long g) { return (A.p[A.local(g)] - B.p[B.local(g)]).norm(); }

// The events of one pair of tracks, appended to `out`.
void pair_events(const std::vector<Track>& tracks, std::size_t a, std::size_t b, const RealPatchOptions& o,
                 std::vector<Event>& out) {
  const Track& A = tracks[a];
  const Track& B = tracks[b];
  const long lo = std::max(A.start, B.start), hi = std::min(A.end(), B.end());
  const double dt = 1.0 / o.sample_rate_hz;
  long g = lo;
  while (g < hi) {
    if (!event_at(A, B, g, o)) {
      ++g;
      continue;
    }
    Event e{a, b, g, g, g};
    while (e.last + 1 < hi && event_at(A, B, e.last + 1, o)) {
      ++e.last;
      if (distance_at(A, B, e.last) < distance_at(A, B, e.closest)) e.closest = e.last;
    }
    g = e.last + 1;
    if (static_cast<double>(e.last - e.first) * dt >= o.min_contact_s) out.push_back(e);
  }
}

}  // namespace

std::vector<Event> detect_events(const std::vector<Track>& tracks, const RealPatchOptions& o) {
  std::vector<Event> events;
  for (std::size_t a = 0; a < tracks.size(); ++a) {
    for (std::size_t b = a + 1; b < tracks.size(); ++b) {
      if (tracks[a].agent != tracks[b].agent) pair_events(tracks, a, b, o, events);
    }
  }
  return events;
}

namespace {

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t{0}); }
  std::size_t root(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t i, std::size_t j) { parent[root(i)] = root(j); }
};

// Whether events e and f are "nearby spatially and temporally" (construct.h step 4).
bool nearby(const Event& e, const Event& f, const std::vector<Track>& tracks, const RealPatchOptions& o) {
  const long overlap_from = std::max(e.first, f.first), overlap_to = std::min(e.last, f.last);
  const auto gap = static_cast<long>(std::lround(o.merge_gap_s * o.sample_rate_hz));
  if (overlap_from - overlap_to > gap) return false;
  if (e.a == f.a || e.a == f.b || e.b == f.a || e.b == f.b) return true;
  // The overlap, or the gap between them when they do not overlap.
  const long from = std::min(overlap_from, overlap_to), to = std::max(overlap_from, overlap_to);
  for (std::size_t x : {e.a, e.b}) {
    for (std::size_t y : {f.a, f.b}) {
      const Track& X = tracks[x];
      const Track& Y = tracks[y];
      for (long g = std::max({from, X.start, Y.start}); g <= std::min({to, X.end() - 1, Y.end() - 1}); ++g) {
        if (distance_at(X, Y, g) < o.merge_distance_m) return true;
      }
    }
  }
  return false;
}

}  // namespace

std::vector<Episode> merge_events(const std::vector<Event>& events, const std::vector<Track>& tracks, const RealPatchOptions& o) {
  UnionFind sets(events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    for (std::size_t j = i + 1; j < events.size(); ++j) {
      if (sets.root(i) != sets.root(j) && nearby(events[i], events[j], tracks, o)) sets.join(i, j);
    }
  }
  std::vector<Episode> episodes;
  std::vector<long> index_of_root(events.size(), -1);
  for (std::size_t i = 0; i < events.size(); ++i) {
    long& k = index_of_root[sets.root(i)];
    if (k < 0) {
      k = static_cast<long>(episodes.size());
      episodes.push_back({{}, events[i].first, events[i].last, {}});
    }
    Episode& ep = episodes[static_cast<std::size_t>(k)];
    ep.events.push_back(events[i]);
    ep.first = std::min(ep.first, events[i].first);
    ep.last = std::max(ep.last, events[i].last);
    ep.tracks.push_back(events[i].a);
    ep.tracks.push_back(events[i].b);
  }
  for (Episode& ep : episodes) {
    std::sort(ep.tracks.begin(), ep.tracks.end());
    ep.tracks.erase(std::unique(ep.tracks.begin(), ep.tracks.end()), ep.tracks.end());
  }
  std::stable_sort(episodes.begin(), episodes.end(), [](const Episode& x, const Episode& y) { return x.first < y.first; });
  return episodes;
}

}  // namespace throng::tiling
