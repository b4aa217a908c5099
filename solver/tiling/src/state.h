// The incremental state of one chain: live instances, their connections and end statuses, the space-time index
// of their paths, the index of dangling ends, and the counts E_tiling needs (Eq. 6). Adding or removing an
// instance updates all of it locally; nothing is ever rebuilt.
#pragma once

#include <throng/tiling/tiling.h>

#include "end_index.h"
#include "problem.h"
#include "segment_index.h"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace throng::tiling {

/// What a character end is doing. Props have no ends (none).
enum class EndStatus : std::uint8_t { none, dangling, connected, free };

struct EndLink {
  EndStatus status = EndStatus::none;
  FragmentRef partner{};
  std::array<int, 3> image{0, 0, 0};  ///< the connection's image (entry + image ⊙ period = exit)
};

struct LiveInstance {
  bool alive = false;
  std::uint32_t type = 0;
  Transform transform;
  bool keyframed = false;
  std::vector<Path> paths;
  std::vector<std::array<EndLink, 2>> ends;  ///< per fragment: [0] entry, [1] exit
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

  /// dangling or free for an unconnected end at this place (tiling.h, the region rule).
  [[nodiscard]] EndStatus classify(const EndPoint& end, bool is_exit) const;

  /// Applies a change; returns the new instance's id.
  std::uint32_t apply(const Change& change);
  /// Removes an instance; its partners' ends become unconnected again.
  void remove(std::uint32_t id);

  /// The live tiling, instances renumbered in id order.
  [[nodiscard]] Tiling snapshot() const;

 private:
  void index_ends(std::uint32_t id, bool insert);  // (un)indexes the instance's dangling ends
  void set_unconnected(std::uint32_t id, std::uint32_t fragment, int side);

  const Problem& problem_;
  std::vector<LiveInstance> instances_;
  std::vector<std::uint32_t> free_ids_;
  SegmentIndex segments_;
  EndIndex ends_;
  std::size_t dangling_ = 0;
  std::size_t connections_ = 0;
  std::size_t character_fragments_ = 0;
  std::size_t live_ = 0;
};

}  // namespace throng::tiling
