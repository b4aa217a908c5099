// Pairs: per frame interval, every agent's segment (its positions at the two frames; a point when it is absent
// at the second) in a sweep over x of the segments' boxes grown by the radii, pairs whose boxes are apart in y
// skipped, then the exact closest approach of each candidate pair: the offset of two linear motions is linear,
// |d0 + s (d1 − d0)| is least at s* = clamp(−d0·e / |e|², 0, 1). A pair of which one is only a point is tested at the first frame only.
// Obstacles: per agent and interval, obstacle_samples + 1 points (both frames included) against every
// obstacle whose box over the interval, grown by r + margin, meets the segment's box.
#include "contacts.h"

#include <throng/core/parallel.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

namespace throng::check::detail {
namespace {

using Vec3 = Eigen::Vector3d;

struct Segment {
  std::size_t agent;
  Vec3 from, to;
  bool moves;  // present at the next frame too
  double lo, hi;  // x extent grown by the radius + margin / 2
  double y_lo, y_hi;  // the same in y
};

// Overlap (clearance − closest distance) of each pair in contact at interval f, appended to `out`.
void pairs_at(const CrowdMotion& crowd, std::size_t f, const Settings& settings,
              std::vector<std::pair<std::pair<std::size_t, std::size_t>, double>>& out) {
  const std::size_t N = crowd.agent_count();
  const bool last = f + 1 >= crowd.frame_count();
  std::vector<Segment> segments;
  for (std::size_t a = 0; a < N; ++a) {
    if (!crowd.present(f, a)) continue;
    Segment s{a, crowd.position(f, a), crowd.position(f, a), false, 0, 0, 0, 0};
    if (!last && crowd.present(f + 1, a)) {
      s.to = crowd.position(f + 1, a);
      s.moves = true;
    }
    const double grow = crowd.radii[a] + 0.5 * settings.margin;
    s.lo = std::min(s.from.x(), s.to.x()) - grow;
    s.hi = std::max(s.from.x(), s.to.x()) + grow;
    s.y_lo = std::min(s.from.y(), s.to.y()) - grow;
    s.y_hi = std::max(s.from.y(), s.to.y()) + grow;
    segments.push_back(s);
  }
  std::sort(segments.begin(), segments.end(), [](const Segment& x, const Segment& y) {
    return x.lo < y.lo || (x.lo == y.lo && x.agent < y.agent);
  });
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const Segment& a = segments[i];
    for (std::size_t j = i + 1; j < segments.size() && segments[j].lo <= a.hi; ++j) {
      const Segment& b = segments[j];
      // Grown boxes apart in y: every point of one is more than the clearance (the two growths) from every point
      // of the other, so the overlap is negative, below any tolerance (≥ 0). Most pairs of the x sweep end here.
      if (b.y_lo > a.y_hi || a.y_lo > b.y_hi) continue;
      const double clearance = crowd.radii[a.agent] + crowd.radii[b.agent] + settings.margin;
      const Vec3 d0 = a.from - b.from;
      double closest = d0.norm();
      if (a.moves && b.moves) {
        const Vec3 e = (a.to - b.to) - d0;
        const double ee = e.squaredNorm();
        const double s = ee > 0 ? std::clamp(-d0.dot(e) / ee, 0.0, 1.0) : 0.0;
        closest = (d0 + s * e).norm();
      }
      const double overlap = clearance - closest;
      if (overlap > settings.contact_tolerance) {
        out.push_back({{std::min(a.agent, b.agent), std::max(a.agent, b.agent)}, overlap});
      }
    }
  }
}

// Deepest overlap of agent `a` with each obstacle it touches, as (obstacle, overlap).
std::vector<std::pair<std::size_t, double>> obstacle_overlaps(const CrowdMotion& crowd, std::size_t a,
                                                              const std::vector<Obstacle>& obstacles,
                                                              const Settings& settings) {
  std::vector<double> deepest(obstacles.size(), 0.0);
  const std::size_t T = crowd.frame_count();
  const double clearance = crowd.radii[a] + settings.margin;
  for (std::size_t f = 0; f < T; ++f) {
    if (!crowd.present(f, a)) continue;
    const bool moves = f + 1 < T && crowd.present(f + 1, a);
    const Eigen::Vector2d p0 = crowd.position(f, a).head<2>();
    const Eigen::Vector2d p1 = moves ? Eigen::Vector2d(crowd.position(f + 1, a).head<2>()) : p0;
    const double t0 = crowd.times[f], t1 = moves ? crowd.times[f + 1] : t0;
    Eigen::AlignedBox2d box(p0.cwiseMin(p1), p0.cwiseMax(p1));
    box.min().array() -= clearance;
    box.max().array() += clearance;
    const int n = moves ? settings.obstacle_samples : 0;
    for (std::size_t o = 0; o < obstacles.size(); ++o) {
      if (!bounds_over(obstacles[o], t0, t1).intersects(box)) continue;
      for (int k = 0; k <= n; ++k) {
        const double s = n > 0 ? static_cast<double>(k) / n : 0.0;
        const double overlap = clearance - distance_to(obstacles[o], p0 + s * (p1 - p0), t0 + s * (t1 - t0)).signed_distance;
        deepest[o] = std::max(deepest[o], overlap);
      }
    }
  }
  std::vector<std::pair<std::size_t, double>> out;
  for (std::size_t o = 0; o < obstacles.size(); ++o) {
    if (deepest[o] > settings.contact_tolerance) out.emplace_back(o, deepest[o]);
  }
  return out;
}

}  // namespace

Contacts find_contacts(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Settings& settings) {
  Contacts c;
  const std::size_t T = crowd.frame_count(), N = crowd.agent_count();
  std::vector<std::vector<std::pair<std::pair<std::size_t, std::size_t>, double>>> per_frame(T);
  parallel_for(T, 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) pairs_at(crowd, f, settings, per_frame[f]);
  });
  std::map<std::pair<std::size_t, std::size_t>, double> pairs;
  for (const auto& frame : per_frame) {
    for (const auto& [pair, overlap] : frame) {
      double& deepest = pairs[pair];
      deepest = std::max(deepest, overlap);
    }
  }
  c.pairs = pairs.size();
  for (const auto& [pair, overlap] : pairs) c.deepest_pair = std::max(c.deepest_pair, overlap);
  if (obstacles.empty()) return c;
  std::vector<std::vector<std::pair<std::size_t, double>>> per_agent(N);
  parallel_for(N, 16, [&](std::size_t begin, std::size_t end) {
    for (std::size_t a = begin; a < end; ++a) per_agent[a] = obstacle_overlaps(crowd, a, obstacles, settings);
  });
  for (const auto& agent : per_agent) {
    c.obstacle += agent.size();
    for (const auto& [o, overlap] : agent) c.deepest_obstacle = std::max(c.deepest_obstacle, overlap);
  }
  return c;
}

}  // namespace throng::check::detail
