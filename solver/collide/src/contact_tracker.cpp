#include <throng/collide/contact_tracker.h>
#include <throng/core/parallel.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "segments.h"

namespace throng::collide {

using detail::Box;
using detail::Vec;

// One interval's registered boxes, their neighbour lists and the interval's contacts.
struct ContactTracker::Interval {
  std::vector<Box> registered;  // by agent, valid where in_grid
  std::vector<char> in_grid;    // by agent: had a segment when built
  std::size_t members = 0;
  // Neighbours: the agents whose registered boxes overlap agent a's are partners[offsets[a] .. offsets[a + 1]).
  std::vector<std::uint32_t> offsets, partners;
  std::vector<PairContact> pairs;
  std::vector<ObstacleContact> obstacles;
};

namespace {

// What the narrow phase needs, gathered once per update.
struct Setting {
  const CrowdMotion& crowd;
  const std::vector<Obstacle>& obstacles;
  const std::vector<std::vector<Eigen::AlignedBox2d>>& bounds;
  double margin, skin;
};

double half_width(const Setting& s, std::size_t a) { return s.crowd.radii[a] + 0.5 * s.margin; }

void examine_obstacles(ContactTracker::Interval& I, std::size_t i, std::size_t a, const Setting& s) {
  double gap = 0.0;
  for (std::size_t o = 0; o < s.obstacles.size(); ++o) {
    detail::examine_obstacle(s.crowd, s.obstacles[o], o, s.bounds[o][i], a, i, s.margin, &I.obstacles, gap);
  }
}

// The interval's registered boxes and neighbour lists from the current positions, and all its contacts afresh.
// The neighbours are found with the broad phase's grid (broad_phase.h): cell = the largest registered box, so a
// box covers at most 2×2 cells, and a pair is taken in the cell of its overlap's lower-left corner only.
void build(ContactTracker::Interval& I, std::size_t i, const Setting& s) {
  const CrowdMotion& crowd = s.crowd;
  const std::size_t n = crowd.agent_count();
  I.registered.assign(n, Box{});
  I.in_grid.assign(n, 0);
  I.offsets.assign(n + 1, 0);
  I.partners.clear();
  I.pairs.clear();
  I.obstacles.clear();
  I.members = 0;
  double cell = 0.0;
  Vec origin = Vec::Constant(std::numeric_limits<double>::infinity());
  for (std::size_t a = 0; a < n; ++a) {
    if (!detail::has_segment(crowd, i, a)) continue;
    const Box box = detail::segment_box(crowd, i, a, half_width(s, a) + 0.5 * s.skin);
    I.registered[a] = box;
    I.in_grid[a] = 1;
    ++I.members;
    cell = std::max(cell, (box.hi - box.lo).maxCoeff());
    origin = origin.cwiseMin(box.lo);
    examine_obstacles(I, i, a, s);
  }
  if (I.members < 2) return;
  cell = std::max(cell, 1e-9);
  auto cell_of = [&](double v, double o) { return static_cast<std::int64_t>(std::floor((v - o) / cell)); };
  auto key_of = [](std::int64_t ix, std::int64_t iy) {
    return (static_cast<std::uint64_t>(ix) << 32) | static_cast<std::uint64_t>(static_cast<std::uint32_t>(iy));
  };
  thread_local std::vector<std::pair<std::uint64_t, std::uint32_t>> entries;  // (cell key, agent)
  thread_local std::vector<std::array<std::int64_t, 2>> low_cell;            // lower-left cell by agent
  thread_local std::vector<std::pair<std::uint32_t, std::uint32_t>> found;   // neighbour pairs a < b
  entries.clear();
  found.clear();
  low_cell.resize(n);
  for (std::size_t a = 0; a < n; ++a) {
    if (I.in_grid[a] == 0) continue;
    const Box& b = I.registered[a];
    const std::int64_t x0 = cell_of(b.lo.x(), origin.x()), y0 = cell_of(b.lo.y(), origin.y());
    low_cell[a] = {x0, y0};
    for (std::int64_t ix = x0; ix <= cell_of(b.hi.x(), origin.x()); ++ix) {
      for (std::int64_t iy = y0; iy <= cell_of(b.hi.y(), origin.y()); ++iy) entries.emplace_back(key_of(ix, iy), static_cast<std::uint32_t>(a));
    }
  }
  std::sort(entries.begin(), entries.end());
  double gap = 0.0;
  PairContact contact;
  for (std::size_t begin = 0; begin < entries.size();) {
    std::size_t end = begin;
    while (end < entries.size() && entries[end].first == entries[begin].first) ++end;
    for (std::size_t j = begin; j < end; ++j) {
      for (std::size_t k = j + 1; k < end; ++k) {
        const std::uint32_t a = entries[j].second, b = entries[k].second;  // a < b: sorted within a cell
        if (!I.registered[a].overlaps(I.registered[b])) continue;
        // Once: in the cell of the overlap's lower-left corner (cell_of is monotone: the larger lower-left cells).
        if (key_of(std::max(low_cell[a][0], low_cell[b][0]), std::max(low_cell[a][1], low_cell[b][1])) != entries[begin].first) continue;
        found.emplace_back(a, b);
        if (detail::examine_pair(crowd, i, a, b, s.margin, contact, gap)) I.pairs.push_back(contact);
      }
    }
    begin = end;
  }
  for (const auto& [a, b] : found) {
    ++I.offsets[a + 1];
    ++I.offsets[b + 1];
  }
  for (std::size_t a = 0; a < n; ++a) I.offsets[a + 1] += I.offsets[a];
  I.partners.resize(I.offsets[n]);
  thread_local std::vector<std::uint32_t> fill;
  fill.assign(I.offsets.begin(), I.offsets.end() - 1);
  for (const auto& [a, b] : found) {
    I.partners[fill[a]++] = b;
    I.partners[fill[b]++] = a;
  }
}

// Re-examines the moved segments `moved` (ascending agents) of an interval whose registered boxes still hold them.
void refresh(ContactTracker::Interval& I, std::size_t i, const std::vector<std::uint32_t>& moved, const Setting& s) {
  thread_local std::vector<char> is_moved;
  is_moved.assign(s.crowd.agent_count(), 0);
  for (std::uint32_t a : moved) is_moved[a] = 1;
  std::erase_if(I.pairs, [&](const PairContact& c) { return is_moved[c.a] != 0 || is_moved[c.b] != 0; });
  std::erase_if(I.obstacles, [&](const ObstacleContact& c) { return is_moved[c.agent] != 0; });
  double gap = 0.0;
  PairContact contact;
  for (std::uint32_t a : moved) {
    examine_obstacles(I, i, a, s);
    for (std::uint32_t k = I.offsets[a]; k < I.offsets[a + 1]; ++k) {
      const std::uint32_t b = I.partners[k];
      if (is_moved[b] != 0 && b < a) continue;  // a pair of moved segments is examined from its lower agent
      if (detail::examine_pair(s.crowd, i, std::min(a, b), std::max(a, b), s.margin, contact, gap)) I.pairs.push_back(contact);
    }
  }
}

// True when a moved segment left its registered box (or its presence changed): the neighbour lists no longer
// hold every pair that could touch.
bool needs_rebuild(const ContactTracker::Interval& I, std::size_t i, const std::vector<std::uint32_t>& moved, const Setting& s) {
  for (std::uint32_t a : moved) {
    if (!detail::has_segment(s.crowd, i, a) || I.in_grid[a] == 0) return true;  // presence changed
    if (!I.registered[a].contains(detail::segment_box(s.crowd, i, a, half_width(s, a)))) return true;
  }
  return false;
}

std::uint64_t bits_of(double v) { return std::bit_cast<std::uint64_t>(v); }

}  // namespace

ContactTracker::ContactTracker(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double margin, double skin)
    : obstacles_(obstacles), margin_(margin), skin_(skin), frames_(crowd.frame_count()), agents_(crowd.agent_count()),
      obstacle_bounds_(detail::obstacle_bounds(crowd, obstacles)) {
  bits_.resize(2 * frames_ * agents_);
  for (std::size_t f = 0; f < frames_; ++f) {
    for (std::size_t a = 0; a < agents_; ++a) {
      const double* p = crowd.positions.data() + crowd.index(f, a);
      bits_[2 * (f * agents_ + a)] = bits_of(p[0]);
      bits_[2 * (f * agents_ + a) + 1] = bits_of(p[1]);
    }
  }
  intervals_.resize(frames_ > 0 ? frames_ - 1 : 0);
  const Setting s{crowd, obstacles_, obstacle_bounds_, margin_, skin_};
  parallel_for(intervals_.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) build(intervals_[i], i, s);
  });
  gather(crowd);
}

ContactTracker::~ContactTracker() = default;
ContactTracker::ContactTracker(ContactTracker&&) noexcept = default;
ContactTracker& ContactTracker::operator=(ContactTracker&&) noexcept = default;

void ContactTracker::update(const CrowdMotion& crowd, const std::vector<char>& candidates) {
  ++stats_.updates;
  // Which vertices changed (bit for bit), frame by frame in parallel (the positions are stored by frame).
  changed_.resize(frames_ * agents_);
  parallel_for(frames_, 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t f = begin; f < end; ++f) {
      const double* p = crowd.positions.data() + crowd.index(f, 0);
      std::uint64_t* stored = bits_.data() + 2 * f * agents_;
      char* changed = changed_.data() + f * agents_;
      for (std::size_t a = 0; a < agents_; ++a, p += 3, stored += 2) {
        changed[a] = 0;
        if (!candidates.empty() && candidates[a] == 0) continue;
        const std::uint64_t x = bits_of(p[0]), y = bits_of(p[1]);
        if (x != stored[0] || y != stored[1]) {
          changed[a] = 1;
          stored[0] = x;
          stored[1] = y;
        }
      }
    }
  });
  // Each interval on its own: its moved segments (an end changed) re-examined, or the interval rebuilt.
  moved_.resize(intervals_.size());
  std::vector<char> rebuilt(intervals_.size(), 0);
  const Setting s{crowd, obstacles_, obstacle_bounds_, margin_, skin_};
  parallel_for(intervals_.size(), 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      std::vector<std::uint32_t>& moved = moved_[i];
      moved.clear();
      const char *c0 = changed_.data() + i * agents_, *c1 = c0 + agents_;
      for (std::size_t a = 0; a < agents_; ++a) {
        // A vertex next to an absent one changes no segment of this interval (absent before and after).
        if ((c0[a] != 0 || c1[a] != 0) && (intervals_[i].in_grid[a] != 0 || detail::has_segment(crowd, i, a))) {
          moved.push_back(static_cast<std::uint32_t>(a));
        }
      }
      if (moved.empty()) continue;
      if (needs_rebuild(intervals_[i], i, moved, s)) {
        build(intervals_[i], i, s);
        rebuilt[i] = 1;
      } else {
        refresh(intervals_[i], i, moved, s);
      }
    }
  });
  for (std::size_t i = 0; i < intervals_.size(); ++i) {
    stats_.moved_segments += moved_[i].size();
    stats_.rebuilt_intervals += rebuilt[i];
    stats_.refreshed_intervals += !moved_[i].empty() && rebuilt[i] == 0;
  }
  gather(crowd);
}

void ContactTracker::gather(const CrowdMotion& crowd) {
  contacts_.pairs.clear();
  contacts_.obstacles.clear();
  contacts_.min_pair_gap = contacts_.min_obstacle_gap = std::numeric_limits<double>::infinity();
  for (const Interval& I : intervals_) {
    contacts_.pairs.insert(contacts_.pairs.end(), I.pairs.begin(), I.pairs.end());
    contacts_.obstacles.insert(contacts_.obstacles.end(), I.obstacles.begin(), I.obstacles.end());
  }
  detail::sort_contacts(contacts_);
  for (const PairContact& c : contacts_.pairs) {
    contacts_.min_pair_gap = std::min(contacts_.min_pair_gap, c.distance - (crowd.radii[c.a] + crowd.radii[c.b]));
  }
  for (const ObstacleContact& c : contacts_.obstacles) {
    contacts_.min_obstacle_gap = std::min(contacts_.min_obstacle_gap, c.signed_distance - crowd.radii[c.agent]);
  }
}

}  // namespace throng::collide
