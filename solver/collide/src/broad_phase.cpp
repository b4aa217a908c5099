#include <throng/collide/broad_phase.h>

#include "segments.h"

#include <throng/core/parallel.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tuple>
#include <utility>

namespace throng::collide {
namespace {

using detail::Box;
using detail::has_segment;
using detail::Vec;
using detail::xy;

// What one interval found: its contacts and its smallest gap.
struct IntervalPairs {
  std::vector<PairContact> contacts;
  double min_gap = std::numeric_limits<double>::infinity();
  bool record = true;  // false: only the smallest gap (smallest_gaps)
};

// The narrow phase of one pair over one interval, recording a contact when the clearance is violated.
void examine(const CrowdMotion& crowd, std::size_t interval, std::size_t a, std::size_t b, double margin, IntervalPairs& out) {
  PairContact contact;
  if (detail::examine_pair(crowd, interval, a, b, margin, contact, out.min_gap) && out.record) out.contacts.push_back(contact);
}

bool wanted(const std::vector<char>& agents, std::size_t a, std::size_t b) {
  return agents.empty() || agents[a] != 0 || agents[b] != 0;
}

void all_pairs_interval(const CrowdMotion& crowd, std::size_t interval, double margin, const std::vector<char>& agents,
                        IntervalPairs& out) {
  const std::size_t n = crowd.agent_count();
  for (std::size_t a = 0; a < n; ++a) {
    if (!has_segment(crowd, interval, a)) continue;
    for (std::size_t b = a + 1; b < n; ++b) {
      if (has_segment(crowd, interval, b) && wanted(agents, a, b)) examine(crowd, interval, a, b, margin, out);
    }
  }
}

void grid_interval(const CrowdMotion& crowd, std::size_t interval, double margin, const std::vector<char>& agents,
                   IntervalPairs& out) {
  const std::size_t n = crowd.agent_count();
  std::vector<Box> boxes(n);
  std::vector<std::size_t> members;
  members.reserve(n);
  double cell = 0.0;
  Vec origin(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity());
  for (std::size_t a = 0; a < n; ++a) {
    if (!has_segment(crowd, interval, a)) continue;
    boxes[a] = detail::segment_box(crowd, interval, a, crowd.radii[a] + 0.5 * margin);
    cell = std::max(cell, (boxes[a].hi - boxes[a].lo).maxCoeff());
    origin = origin.cwiseMin(boxes[a].lo);
    members.push_back(a);
  }
  if (members.size() < 2) return;
  cell = std::max(cell, 1e-9);
  auto cell_of = [&](double v, double o) { return static_cast<std::int64_t>(std::floor((v - o) / cell)); };
  auto key_of = [](std::int64_t ix, std::int64_t iy) { return (static_cast<std::uint64_t>(ix) << 32) | static_cast<std::uint64_t>(iy); };
  // Each box covers at most 2×2 cells (its extent is at most one cell).
  std::vector<std::pair<std::uint64_t, std::size_t>> entries;
  entries.reserve(4 * members.size());
  for (std::size_t a : members) {
    const std::int64_t x0 = cell_of(boxes[a].lo.x(), origin.x()), x1 = cell_of(boxes[a].hi.x(), origin.x());
    const std::int64_t y0 = cell_of(boxes[a].lo.y(), origin.y()), y1 = cell_of(boxes[a].hi.y(), origin.y());
    for (std::int64_t ix = x0; ix <= x1; ++ix) {
      for (std::int64_t iy = y0; iy <= y1; ++iy) entries.emplace_back(key_of(ix, iy), a);
    }
  }
  std::sort(entries.begin(), entries.end());
  for (std::size_t begin = 0; begin < entries.size();) {
    std::size_t end = begin;
    while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
    for (std::size_t j = begin; j < end; ++j) {
      for (std::size_t k = j + 1; k < end; ++k) {
        const std::size_t a = entries[j].second, b = entries[k].second;  // a < b: sorted within a cell
        const Box &A = boxes[a], &B = boxes[b];
        if (!A.overlaps(B)) continue;
        // Examine the pair once: in the cell holding the lower-left corner of the overlap.
        const Vec corner = A.lo.cwiseMax(B.lo);
        if (key_of(cell_of(corner.x(), origin.x()), cell_of(corner.y(), origin.y())) != entries[begin].first) continue;
        if (wanted(agents, a, b)) examine(crowd, interval, a, b, margin, out);
      }
    }
    begin = end;
  }
}

// Every interval's contacts, sorted by (a, b, interval).
std::vector<PairContact> gather_pairs(std::vector<IntervalPairs>& per_interval) {
  std::vector<PairContact> all;
  for (auto& found : per_interval) all.insert(all.end(), found.contacts.begin(), found.contacts.end());
  std::sort(all.begin(), all.end(), [](const PairContact& x, const PairContact& y) {
    return std::tie(x.a, x.b, x.interval) < std::tie(y.a, y.b, y.interval);
  });
  return all;
}

// Obstacle contacts of one agent, by (obstacle, interval), and its smallest gap.
void agent_obstacles(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles,
                     const std::vector<std::vector<Eigen::AlignedBox2d>>& obstacle_bounds, std::size_t agent, double margin,
                     std::vector<ObstacleContact>* out, double& min_gap) {
  for (std::size_t o = 0; o < obstacles.size(); ++o) {
    for (std::size_t i = 0; i + 1 < crowd.frame_count(); ++i) {
      if (has_segment(crowd, i, agent)) {
        detail::examine_obstacle(crowd, obstacles[o], o, obstacle_bounds[o][i], agent, i, margin, out, min_gap);
      }
    }
  }
}

}  // namespace

Contacts find_contacts(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double margin, BroadPhase method,
                       const std::vector<char>& agents) {
  Contacts out;
  const std::size_t intervals = crowd.frame_count() > 0 ? crowd.frame_count() - 1 : 0;
  std::vector<IntervalPairs> per_interval(intervals);
  parallel_for(intervals, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (method == BroadPhase::grid) {
        grid_interval(crowd, i, margin, agents, per_interval[i]);
      } else {
        all_pairs_interval(crowd, i, margin, agents, per_interval[i]);
      }
    }
  });
  for (const auto& found : per_interval) out.min_pair_gap = std::min(out.min_pair_gap, found.min_gap);
  out.pairs = gather_pairs(per_interval);

  if (!obstacles.empty()) {
    const auto bounds = detail::obstacle_bounds(crowd, obstacles);
    const std::size_t n = crowd.agent_count();
    std::vector<std::vector<ObstacleContact>> per_agent(n);
    std::vector<double> gaps(n, std::numeric_limits<double>::infinity());
    parallel_for(n, 8, [&](std::size_t begin, std::size_t end) {
      for (std::size_t a = begin; a < end; ++a) {
        if (agents.empty() || agents[a] != 0) agent_obstacles(crowd, obstacles, bounds, a, margin, &per_agent[a], gaps[a]);
      }
    });
    for (std::size_t a = 0; a < n; ++a) {
      out.obstacles.insert(out.obstacles.end(), per_agent[a].begin(), per_agent[a].end());
      out.min_obstacle_gap = std::min(out.min_obstacle_gap, gaps[a]);
    }
  }
  return out;
}

Gaps smallest_gaps(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double reach) {
  Gaps out;
  const std::size_t intervals = crowd.frame_count() > 0 ? crowd.frame_count() - 1 : 0;
  std::vector<IntervalPairs> per_interval(intervals);
  parallel_for(intervals, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      per_interval[i].record = false;
      grid_interval(crowd, i, reach, {}, per_interval[i]);
    }
  });
  for (const auto& found : per_interval) out.pair = std::min(out.pair, found.min_gap);
  if (!obstacles.empty()) {
    const auto bounds = detail::obstacle_bounds(crowd, obstacles);
    std::vector<double> gaps(crowd.agent_count(), std::numeric_limits<double>::infinity());
    parallel_for(crowd.agent_count(), 8, [&](std::size_t begin, std::size_t end) {
      for (std::size_t a = begin; a < end; ++a) agent_obstacles(crowd, obstacles, bounds, a, reach, nullptr, gaps[a]);
    });
    for (double g : gaps) out.obstacle = std::min(out.obstacle, g);
  }
  return out;
}

}  // namespace throng::collide

namespace throng::collide {

void detail::sort_contacts(Contacts& contacts) {
  std::sort(contacts.pairs.begin(), contacts.pairs.end(), [](const PairContact& x, const PairContact& y) {
    return std::tie(x.a, x.b, x.interval) < std::tie(y.a, y.b, y.interval);
  });
  std::sort(contacts.obstacles.begin(), contacts.obstacles.end(), [](const ObstacleContact& x, const ObstacleContact& y) {
    return std::tie(x.agent, x.obstacle, x.interval) < std::tie(y.agent, y.obstacle, y.interval);
  });
}

std::size_t Contacts::pair_count() const noexcept {
  std::size_t n = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    n += k == 0 || pairs[k].a != pairs[k - 1].a || pairs[k].b != pairs[k - 1].b;
  }
  return n;
}

std::size_t Contacts::obstacle_count() const noexcept {
  std::size_t n = 0;
  for (std::size_t k = 0; k < obstacles.size(); ++k) {
    n += k == 0 || obstacles[k].agent != obstacles[k - 1].agent || obstacles[k].obstacle != obstacles[k - 1].obstacle;
  }
  return n;
}

}  // namespace throng::collide
