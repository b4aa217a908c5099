// Stitch (P ∪ P_new) and IsValid of Algorithms 1 and 2: place a patch, stitch its ends to matching dangling
// ends, deform it and its neighbours together (deformation.h), count what changes, and test the result.
#pragma once

#include "state.h"

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

namespace throng::tiling {

/// A patch to try: a type, a placement, and (phase 2) one end that must be stitched to a given dangling end.
struct Proposal {
  std::uint32_t type = 0;
  Transform transform;
  bool keyframed = false;
  std::optional<NewLink> forced;
};

/// A stitched proposal: the change it would make and what it does to the counts of Eq. 6.
struct Attempt {
  Change change;
  bool feasible = false;        ///< the joint solve met every stitching constraint
  long delta_dangling = 0;      ///< N_d after − before
  long delta_connected = 0;     ///< N_c after − before (2 per link)
  long delta_characters = 0;    ///< chains after − before
};

class Stitcher {
 public:
  explicit Stitcher(const TilingState& state) : state_(state), problem_(state.problem()) {}

  /// Places the proposal, stitches every end that matches a dangling end (greedily by normalised distance,
  /// ties by ids), and deforms. Infeasible attempts (contradictory constraints) have feasible = false.
  [[nodiscard]] Attempt stitch(const Proposal& proposal);

  /// IsValid: deformation within limits, headings matched at every connection of a deformed instance, no
  /// interpenetration with other instances or obstacles, and (in a window) no sample before its freeze time.
  [[nodiscard]] bool valid(const Attempt& attempt);

  /// What applying the attempt would change in the state's presence (presence.h): the instances it touches as
  /// they are, subtracted, and as they would become, added.
  void presence_delta(const Attempt& attempt, Presence::Delta& delta) const;
  /// In a window (problem.h: a finite freeze time): whether every entry the attempt leaves dangling can be
  /// reached by a character walking straight in from a side of the region after the freeze time (at
  /// DensityOptions::projection_speed_mps). Nothing before the freeze may change, so a new character can only
  /// come in from a side; phase 1 refuses seeds whose entries could not be continued back to one. Always true
  /// outside a window.
  [[nodiscard]] bool entries_reachable(const Attempt& attempt) const;
  /// The presence of a rigid placement's character paths alone (no projection): phase 1's quick test.
  void placement_presence(std::uint32_t type, const std::vector<Path>& paths, Presence::Delta& delta) const;

 private:
  bool deform(const Proposal& proposal, Attempt& attempt);
  [[nodiscard]] bool connected(FragmentRef a, FragmentRef b, const Attempt& attempt) const;
  [[nodiscard]] bool hits_obstacle(const Fragment& fragment, const Path& path) const;

  const TilingState& state_;
  const Problem& problem_;
  std::vector<EndMatch> matches_;  // scratch
};

}  // namespace throng::tiling
