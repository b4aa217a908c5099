// Incremental contact detection for the repair loop (collide.h): after each deformation only the segments that
// moved are tested again, and the contacts of everything else are kept. The contacts are always exactly what
// find_contacts (broad_phase.h) reports for the current positions — the same contacts, in the same order, with
// the same bits (tests/collide: equal to a full search after every iteration of a repair, on random scenes).
//
// Why it is exact. A contact is decided by the narrow phase alone (clearance strictly violated at the closest
// moment); a broad phase only has to hand it every pair that could be in contact. A segment (agent a, interval
// i) whose two end positions did not change (bit for bit) keeps every narrow-phase result with every other
// segment that did not change, so only pairs with a moved segment are examined again — with the same function
// on the same arguments as the full search (lower agent index first), so with the same bits.
//
// Finding those pairs (neighbour lists with a skin, as Verlet lists). Each interval keeps its segments' boxes
// (widened by r + margin/2 as in the broad phase) plus a skin of `skin`/2 on every side, as they were when the
// interval was last built ("registered" boxes), and for each segment the list of segments whose registered boxes
// overlap its own, found with the broad phase's grid when the interval is built. While a segment's current box
// stays inside its registered box, every segment that could touch it is in its list, so a moved segment is
// examined against its list alone. When a moved segment leaves its registered box (or its presence changed),
// the interval is rebuilt from the current positions and all its pairs examined afresh. Obstacle contacts of a
// moved segment are recomputed against every obstacle (with the obstacles' bounds over the interval, as in the
// broad phase). Measured on a random crowd of 1,000 agents × 300 frames (bench_collide BM_TrackerUpdate against
// BM_BroadPhase): an update after 10 % of the agents moved costs 10–15 % of a full search, after all of them
// moved (within the skin) 15–30 %.
//
// Memory: about 60 bytes per agent and frame interval (registered box, neighbour list, the positions' bits),
// some 2.5 times the crowd's own positions, for as long as the tracker lives (the repair's run).
//
// Presence may change between updates (the repair does not change it; an agent that appears or disappears at a
// frame rebuilds the intervals next to it). Deterministic: each interval is processed on its own (TBB) and the
// results are merged and sorted, whatever the thread count.
#pragma once

#include <throng/collide/broad_phase.h>
#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>

#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <vector>

namespace throng::collide {

/// What an update did (for benchmarks and tests).
struct TrackerStats {
  std::size_t updates = 0;            ///< update() calls
  std::size_t moved_segments = 0;     ///< segments found moved, over all updates
  std::size_t rebuilt_intervals = 0;  ///< interval grids rebuilt after the first build
  std::size_t refreshed_intervals = 0;  ///< intervals whose moved segments were examined through their neighbour lists
};

class ContactTracker {
 public:
  /// Full search of `crowd` (equal to find_contacts(crowd, obstacles, margin)); builds every interval's grid.
  /// `skin` (metres, ≥ 0): extra widening of the registered boxes. Keeps references to nothing: update() takes
  /// the crowd again.
  ContactTracker(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double margin, double skin);
  ~ContactTracker();
  ContactTracker(ContactTracker&&) noexcept;
  ContactTracker& operator=(ContactTracker&&) noexcept;

  /// The contacts after `crowd` moved since the last call (same agents and frames). `candidates`, when
  /// not empty, flags by agent index the only agents that may have moved (others are not compared); empty: every
  /// agent is compared. Afterwards contacts() equals find_contacts(crowd, obstacles, margin) in pairs and
  /// obstacles; its min_pair_gap and min_obstacle_gap are the smallest over the contacts (+∞ without contacts),
  /// so exact below the margin, as find_contacts promises.
  void update(const CrowdMotion& crowd, const std::vector<char>& candidates = {});

  [[nodiscard]] const Contacts& contacts() const noexcept { return contacts_; }
  [[nodiscard]] const TrackerStats& stats() const noexcept { return stats_; }

  /// One interval's grid and contacts (defined in contact_tracker.cpp, where its helpers name it).
  struct Interval;

 private:
  void gather(const CrowdMotion& crowd);

  std::vector<Obstacle> obstacles_;
  double margin_ = 0.0, skin_ = 0.0;
  std::size_t frames_ = 0, agents_ = 0;
  std::vector<std::uint64_t> bits_;  // x, y bit patterns per (frame, agent), as last seen
  std::vector<char> changed_;        // update()'s changed vertices per (frame, agent) (kept to reuse)
  std::vector<Interval> intervals_;
  std::vector<std::vector<std::uint32_t>> moved_;  // update()'s moved agents by interval (kept to reuse)
  std::vector<std::vector<Eigen::AlignedBox2d>> obstacle_bounds_;  // [obstacle][interval]
  Contacts contacts_;
  TrackerStats stats_;
};

}  // namespace throng::collide
