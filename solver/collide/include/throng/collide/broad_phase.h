// Broad phase of collision repair: which agents come closer than their clearance, and which trajectories come
// closer to an obstacle than the agent's clearance, over a whole crowd (METHODS.md §1.3 "Beyond").
//
// Clearance: two agents a, b need r_a + r_b + margin between their centres; an agent needs r + margin between
// its centre and an obstacle's boundary. A contact is a clearance strictly violated at some moment.
//
// Method (grid). Every agent moves linearly between two frames, so over frame interval i its positions lie in
// the bounding box of its two end positions. Boxes are widened by r + margin/2 (agents) and, for obstacles, by
// r + margin against the obstacle's bounds over the interval: two agents whose widened boxes do not overlap
// cannot be closer than their clearance in that interval. Each interval is processed on its own (TBB, in
// parallel): its boxes go into a uniform grid whose cell is the largest box, so a box covers at most 2×2 cells;
// a pair is examined only in the cell holding the lower-left corner of the two boxes' overlap, so once; the exact
// narrow phase (narrow_phase.h) then decides. The result is exactly the all-pairs result (`all_pairs` runs every
// pair of every interval through the same narrow phase, for tests and benchmarks) and does not depend on the
// thread count: per-interval results are merged in interval order and sorted.
//
// An agent's segment over interval i exists when it is present at frames i and i + 1 (real data has agents
// entering and leaving); z is ignored.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>

#include <Eigen/Core>

#include <cstddef>
#include <limits>
#include <vector>

namespace throng::collide {

/// Two agents closer than their clearance in one frame interval, at the moment of their smallest distance there.
struct PairContact {
  std::size_t a = 0, b = 0;    ///< agent indices, a < b
  std::size_t interval = 0;    ///< frame interval [interval, interval + 1]
  double s = 0.0;              ///< fraction of the interval where the distance is smallest
  double distance = 0.0;       ///< metres between the centres
  double clearance = 0.0;      ///< r_a + r_b + margin
  Eigen::Vector2d offset{0, 0};  ///< p_a − p_b at that moment
};

/// A trajectory closer to an obstacle than the agent's clearance in one frame interval, at its deepest point there.
struct ObstacleContact {
  std::size_t agent = 0, obstacle = 0;  ///< agent index, obstacle index
  std::size_t interval = 0;             ///< frame interval
  double s = 0.0;                       ///< fraction of the interval where the signed distance is smallest
  double signed_distance = 0.0;         ///< metres from the obstacle's boundary (negative inside)
  double clearance = 0.0;               ///< r + margin
};

/// Every contact, one per colliding interval, sorted by (a, b, interval) and by (agent, obstacle, interval), and
/// the smallest gaps seen.
struct Contacts {
  std::vector<PairContact> pairs;
  std::vector<ObstacleContact> obstacles;
  /// Smallest distance − r_a − r_b over the pairs the broad phase examined (+∞ if none): exact whenever it is
  /// below the margin (every pair that close is examined).
  double min_pair_gap = std::numeric_limits<double>::infinity();
  /// Smallest signed distance − r over the agent–obstacle intervals examined (+∞ if none), exact below the margin.
  double min_obstacle_gap = std::numeric_limits<double>::infinity();

  [[nodiscard]] std::size_t size() const noexcept { return pairs.size() + obstacles.size(); }
  /// Distinct colliding agent pairs.
  [[nodiscard]] std::size_t pair_count() const noexcept;
  /// Distinct (agent, obstacle) pairs in contact.
  [[nodiscard]] std::size_t obstacle_count() const noexcept;
};

enum class BroadPhase {
  grid,       ///< per-interval uniform grid (the product)
  all_pairs,  ///< every pair of every interval (reference for tests and benchmarks)
};

/// Smallest gaps of a crowd (metres): distance − r_a − r_b over pairs, signed distance − r over agents and
/// obstacles.
struct Gaps {
  double pair = std::numeric_limits<double>::infinity();
  double obstacle = std::numeric_limits<double>::infinity();
};

/// The smallest gaps of `crowd`, exact whenever they are at most `reach` metres: the grid runs with boxes widened
/// by `reach` (as for a margin), so every pair and agent–obstacle interval within `reach` of touching is examined.
/// A value above `reach` is only an upper bound; +∞ when nothing was examined.
[[nodiscard]] Gaps smallest_gaps(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double reach);

/// Finds every contact of `crowd` (and with `obstacles`) for clearance margin `margin` (metres, ≥ 0).
/// `agents`, when not empty, restricts the search to pairs with at least one agent flagged (and obstacle contacts
/// to flagged agents), for callers that know which agents moved; flags are by agent index. (The repair loop
/// searches incrementally with contact_tracker.h, which re-examines only the moved segments.)
[[nodiscard]] Contacts find_contacts(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, double margin,
                                     BroadPhase method = BroadPhase::grid, const std::vector<char>& agents = {});

}  // namespace throng::collide
