// The per-interval pieces shared by the broad phase (broad_phase.cpp) and the incremental tracker
// (contact_tracker.cpp), private to solver/collide. Both decide a contact with these same functions on the same
// arguments (agents in index order), so their results are the same bits.
#pragma once

#include <throng/collide/broad_phase.h>
#include <throng/collide/narrow_phase.h>
#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace throng::collide::detail {

using Vec = Eigen::Vector2d;

inline Vec xy(const CrowdMotion& crowd, std::size_t frame, std::size_t agent) {
  const double* p = crowd.positions.data() + crowd.index(frame, agent);
  return {p[0], p[1]};
}

/// Agent `agent` moves over interval i (present at frames i and i + 1).
inline bool has_segment(const CrowdMotion& crowd, std::size_t interval, std::size_t agent) {
  return crowd.present(interval, agent) && crowd.present(interval + 1, agent);
}

/// An axis-aligned box in x, y.
struct Box {
  Vec lo{0, 0}, hi{0, 0};
  [[nodiscard]] bool overlaps(const Box& o) const {
    return !(lo.x() > o.hi.x() || o.lo.x() > hi.x() || lo.y() > o.hi.y() || o.lo.y() > hi.y());
  }
  [[nodiscard]] bool contains(const Box& o) const {
    return lo.x() <= o.lo.x() && lo.y() <= o.lo.y() && o.hi.x() <= hi.x() && o.hi.y() <= hi.y();
  }
};

/// The box of agent a's segment over interval i, widened by `widen` on every side.
inline Box segment_box(const CrowdMotion& crowd, std::size_t interval, std::size_t a, double widen) {
  const Vec p0 = xy(crowd, interval, a), p1 = xy(crowd, interval + 1, a);
  return {p0.cwiseMin(p1).array() - widen, p0.cwiseMax(p1).array() + widen};
}

/// The narrow phase of agents a < b over interval i: the contact when their clearance is violated; their gap
/// (distance − r_a − r_b) lowers `min_gap`. True when a contact was written to `out`.
inline bool examine_pair(const CrowdMotion& crowd, std::size_t interval, std::size_t a, std::size_t b, double margin,
                         PairContact& out, double& min_gap) {
  const Approach approach =
      closest_approach(xy(crowd, interval, a), xy(crowd, interval + 1, a), xy(crowd, interval, b), xy(crowd, interval + 1, b));
  const double radii = crowd.radii[a] + crowd.radii[b];
  min_gap = std::min(min_gap, approach.distance - radii);
  const double clearance = radii + margin;
  if (!(approach.distance < clearance)) return false;
  out = {a, b, interval, approach.s, approach.distance, clearance, approach.offset};
  return true;
}

/// The bounds of every obstacle over every interval: [obstacle][interval].
inline std::vector<std::vector<Eigen::AlignedBox2d>> obstacle_bounds(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles) {
  const std::size_t intervals = crowd.frame_count() > 0 ? crowd.frame_count() - 1 : 0;
  std::vector<std::vector<Eigen::AlignedBox2d>> bounds(obstacles.size(), std::vector<Eigen::AlignedBox2d>(intervals));
  for (std::size_t o = 0; o < obstacles.size(); ++o) {
    for (std::size_t i = 0; i < intervals; ++i) bounds[o][i] = bounds_over(obstacles[o], crowd.times[i], crowd.times[i + 1]);
  }
  return bounds;
}

/// Agent `agent`'s segment over interval i against obstacle o (its bounds over the interval `bound`): appends
/// the contact to `out` (when not null) if the clearance r + margin is violated; the gap lowers `min_gap`.
inline void examine_obstacle(const CrowdMotion& crowd, const Obstacle& obstacle, std::size_t o, const Eigen::AlignedBox2d& bound,
                             std::size_t agent, std::size_t interval, double margin, std::vector<ObstacleContact>* out,
                             double& min_gap) {
  const double r = crowd.radii[agent];
  const double clearance = r + margin;
  const Vec p0 = xy(crowd, interval, agent), p1 = xy(crowd, interval + 1, agent);
  const Vec lo = p0.cwiseMin(p1).array() - clearance, hi = p0.cwiseMax(p1).array() + clearance;
  if (lo.x() > bound.max().x() || bound.min().x() > hi.x() || lo.y() > bound.max().y() || bound.min().y() > hi.y()) return;
  const Penetration p = deepest_penetration(obstacle, p0, p1, crowd.times[interval], crowd.times[interval + 1]);
  min_gap = std::min(min_gap, p.signed_distance - r);
  if (out != nullptr && p.signed_distance < clearance) out->push_back({agent, o, interval, p.s, p.signed_distance, clearance});
}

/// Contacts sorted as find_contacts returns them: pairs by (a, b, interval), obstacles by (agent, obstacle, interval).
void sort_contacts(Contacts& contacts);

}  // namespace throng::collide::detail
