// Bridges (our addition to Algorithm 2, search.cpp): joining a dangling end d to another dangling end n of the
// opposite kind at once.
//
//   one  a patch fitted between d and n: one end on d, the other on n, placed by the rigid fit of the two ends
//        (rotation from the chord between them, or from d's heading when the chord is short; translation and
//        time shift splitting the residual between both ends), kept when both ends then lie within the match
//        thresholds; at most SearchOptions::bridge_attempts per end, fewest residual first, accepted only when
//        it lowers the dangling count.
//   two  a patch placed on d (the given candidates in order, unjittered), then `one` from its other end; the
//        first patch is removed again when no bridge follows. Patches last about the same time (2 s for the
//        built-in walks), so an exit and an entry a little more than one patch apart in time are joined by no
//        single patch, and continuing both steps over the gap.
//
//   close  from a dangling exit to a dangling entry: single-character patches placed end to end (each one's entry
//        exactly on the previous exit, as Algorithm 2 places its candidates), then `one`. The sequence is planned
//        on the undeformed patches by a beam search (closure.cpp) toward the entry, in space on the torus and in
//        time one period at most ahead, then applied one patch at a time, each placed again on the actual
//        (deformed) exit, and undone when a step does not fit.
//
// Guidance on a tile periodic on every axis, where no end can leave by a side and every open chain must meet
// another: schedule_cost(), how far off schedule a candidate's open end would be for the dangling end of the
// opposite kind it could best walk to — the time gap to it (forward, at least the shortest patch, within one
// period) against the straight walk there at DensityOptions::projection_speed_mps, over the nearest images.
#pragma once

#include "phases.h"

#include <functional>
#include <optional>
#include <vector>

namespace throng::tiling {

/// A placement of fragment `fragment` of type `type` tried at a dangling end, in order of `cost`.
struct Placement {
  double cost = 0;
  std::uint32_t type = 0;
  std::uint32_t fragment = 0;
  Transform transform;
};

/// The fit of `one` (see the file comment) of fragment `fr`, whose end `new_is_exit` goes on d and the other on n
/// (n's position and time on its image nearest d); none when an end would lie outside the match thresholds.
[[nodiscard]] std::optional<std::pair<Transform, double>> bridge_fit(const Fragment& fr, bool new_is_exit, const EndPoint& d,
                                                                     const Eigen::Vector2d& n_position, double n_time,
                                                                     double n_heading, const MatchThresholds& match);

class Bridger {
 public:
  /// `refused(type, fragment, side, at)`: the search's history; `admissible(attempt)`: its density cap.
  Bridger(TilingState& state, Stitcher& stitcher, ChainReport& report,
          std::function<bool(std::uint32_t, std::uint32_t, int, const EndPoint&)> refused,
          std::function<bool(const Attempt&)> admissible);

  /// `one` at the dangling end (ref, side: 0 entry, 1 exit); true when a bridge was placed.
  bool one(FragmentRef ref, int side);
  /// `two` at the dangling end with these first patches (at most bridge_attempts of them are tried).
  bool two(FragmentRef ref, int side, const std::vector<Placement>& first);

  /// `close` from the dangling exit `exit` toward the dangling entries `entries` (tried in order); true when
  /// the exit was joined to one.
  bool close(FragmentRef exit, const std::vector<EndPoint>& entries);

  /// The guidance cost of an open end at (position, time) of a patch placed at an end of side `side` (see the
  /// file comment), against `partners`, the dangling ends of the kind the open end needs.
  [[nodiscard]] double schedule_cost(const Eigen::Vector2d& position, double time, int side,
                                     const std::vector<EndPoint>& partners) const;

 private:
  bool place(const Placement& p, FragmentRef ref, int side, bool must_lower, std::uint32_t* id);

  TilingState& state_;
  Stitcher& stitcher_;
  ChainReport& report_;
  std::function<bool(std::uint32_t, std::uint32_t, int, const EndPoint&)> refused_;
  std::function<bool(const Attempt&)> admissible_;
  double reach_m_ = 0;
  double span_s_ = 0;
  double shortest_s_ = 0;
  std::vector<EndMatch> near_;
};

}  // namespace throng::tiling
