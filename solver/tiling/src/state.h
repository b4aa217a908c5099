// The incremental state of one chain: live instances, their connections and end statuses, the space-time index
// of their paths, the index of dangling ends, the counts E_tiling needs (Eq. 6) and the presence of characters
// per area and time (presence.h, when a density is asked for). Adding or removing an instance updates all of it
// locally; nothing is ever rebuilt.
//
// A windowed run (windowed.h) starts each window's chains from the instances it carries over (restore()):
// instances of earlier windows that lie entirely before the window's start are `fixed` (never deformed, never
// removed, like keyframes), and their ends may name partners no longer carried (`gone`: connected, but not to
// anything in this state).
#pragma once

#include <throng/tiling/tiling.h>

#include "end_index.h"
#include "presence.h"
#include "problem.h"
#include "segment_index.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace throng::tiling {

/// What a character end is doing. Props have no ends (none).
enum class EndStatus : std::uint8_t { none, dangling, connected, free };

/// The instance a connected end names when its partner is not in this state (a windowed run's earlier window).
inline constexpr std::uint32_t gone = 0xFFFFFFFFu;

struct EndLink {
  EndStatus status = EndStatus::none;
  FragmentRef partner{};  ///< partner.instance == gone: connected to an instance outside this state
  std::array<int, 3> image{0, 0, 0};  ///< the connection's image (entry + image ⊙ period = exit)
};

struct LiveInstance {
  bool alive = false;
  std::uint32_t type = 0;
  Transform transform;
  bool keyframed = false;
  bool fixed = false;       ///< carried from an earlier window and lying before this one: never changed
  std::vector<Path> paths;
  std::vector<std::array<EndLink, 2>> ends;  ///< per fragment: [0] entry, [1] exit

  /// Neither deformed nor removed by this chain.
  [[nodiscard]] bool pinned() const noexcept { return keyframed || fixed; }
};

/// A stitch of a new end to an existing dangling end.
struct NewLink {
  std::uint32_t new_fragment = 0;
  bool new_is_exit = false;
  FragmentRef existing;
  std::array<int, 3> image{0, 0, 0};  ///< the connection's image (entry + image ⊙ period = exit)
};

/// A new instance with the deformation it causes: what a stitch proposes and the state applies at once.
struct Change {
  std::uint32_t type = 0;
  Transform transform;
  bool keyframed = false;
  std::vector<Path> paths;                                           ///< the new instance's (deformed) paths
  std::vector<std::pair<std::uint32_t, std::vector<Path>>> modified;  ///< re-deformed neighbours
  std::vector<NewLink> links;
};

class TilingState {
 public:
  explicit TilingState(const Problem& problem);

  [[nodiscard]] const Problem& problem() const noexcept { return problem_; }
  [[nodiscard]] std::size_t slots() const noexcept { return instances_.size(); }
  [[nodiscard]] const LiveInstance& at(std::uint32_t id) const { return instances_[id]; }
  /// The id the next add() will use.
  [[nodiscard]] std::uint32_t next_id() const noexcept;

  [[nodiscard]] std::size_t dangling() const noexcept { return dangling_; }
  [[nodiscard]] std::size_t connected_ends() const noexcept { return 2 * connections_; }
  [[nodiscard]] std::size_t connections() const noexcept { return connections_; }
  [[nodiscard]] std::size_t instances() const noexcept { return live_; }
  /// Chains of character fragments: fragments − connections (loops on a periodic time axis aside).
  [[nodiscard]] std::size_t characters() const noexcept { return character_fragments_ - connections_; }
  /// E_tiling of Eq. 6 for the given counts: (N_d + α) / (N_c + N_d), with N_c + N_d taken as 1 when 0.
  [[nodiscard]] double energy(double dangling, double connected) const noexcept;

  [[nodiscard]] const SegmentIndex& segments() const noexcept { return segments_; }
  [[nodiscard]] const EndIndex& dangling_ends() const noexcept { return ends_; }
  [[nodiscard]] const Presence& presence() const noexcept { return presence_; }
  /// Adds sign × the presence of instance `id` as it stands (its character paths and the projections of its
  /// unconnected ends, presence.h) to `delta`.
  void presence_of(std::uint32_t id, double sign, Presence::Delta& delta) const;

  /// dangling or free for an unconnected end at this place (tiling.h, the region rule).
  [[nodiscard]] EndStatus classify(const EndPoint& end, bool is_exit) const;

  /// Applies a change; returns the new instance's id.
  std::uint32_t apply(const Change& change);
  /// Removes an instance; its partners' ends become unconnected again.
  void remove(std::uint32_t id);

  /// Fills an empty state with `instances` (ids = positions; links name positions or `gone`): the state a windowed
  /// run carries into a window. Unconnected ends are classified again (the window's region is not the one they
  /// were classified in); connected ones keep their links. Connections to `gone` count as connections.
  void restore(std::vector<LiveInstance> instances);

  /// The live tiling, instances renumbered in id order.
  [[nodiscard]] Tiling snapshot() const;

 private:
  void index_ends(std::uint32_t id, bool insert);  // (un)indexes the instance's dangling ends
  void set_unconnected(std::uint32_t id, std::uint32_t fragment, int side);
  void track_presence(std::uint32_t id, double sign);  // applies presence_of(id, sign)

  const Problem& problem_;
  std::vector<LiveInstance> instances_;
  std::vector<std::uint32_t> free_ids_;
  SegmentIndex segments_;
  EndIndex ends_;
  Presence presence_;
  Presence::Delta scratch_;
  std::size_t dangling_ = 0;
  std::size_t connections_ = 0;
  std::size_t character_fragments_ = 0;
  std::size_t live_ = 0;
};

}  // namespace throng::tiling
