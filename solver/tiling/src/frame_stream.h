// The frames of a windowed run, made window by window from the instances as they become final (windowed.h):
// what lay_out (characters.cpp) makes from the whole tiling with repeat 1, streamed.
//
// lay_out walks every chain from its head (a fragment copy with no predecessor among the laid copies: copies
// −1, 0, 1 on a periodic axis, 0 elsewhere), concatenating the samples of its fragment copies (a sample no later
// than the last one taken is skipped: the shared sample at a join), and samples the concatenation at every frame;
// a frame is present when the position lies in the laid box on the periodic axes; each maximal present run is an
// agent, ordered by (first frame, head copy, run). Here a `Walk` is that chain walk in progress: the samples not
// yet passed, the last fragment copy taken, the run it is in. A walk is started when its head is delivered and
// advanced frame by frame; it takes a fragment's successor when its samples run out and the successor, which
// starts before the frame that needs it, has been delivered by then (a window's frames are only made once every
// instance starting before its end is final). Facings and actions as lay_out makes them.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <map>
#include <vector>

namespace throng::tiling {

class FrameStream {
 public:
  /// Frames t0 + f / frame_rate over the horizon region's [t0, t1] (the last at t1).
  /// `max_turn`: the largest turn of a facing per frame (max_turn_per_frame(), characters.h).
  FrameStream(const PatchLibrary& library, const Region& region, double frame_rate_hz, double max_turn);

  [[nodiscard]] std::size_t frame_count() const noexcept { return frames_; }
  [[nodiscard]] double frame_time(std::size_t f) const noexcept;
  [[nodiscard]] std::size_t next_frame() const noexcept { return next_frame_; }

  /// Final instances with their delivered ids (`first`, first + 1, ...) and the connections into their entries.
  void deliver(std::size_t first, const std::vector<Instance>& instances, const std::vector<Connection>& connections);

  /// The frames [next_frame(), end) (end ≤ frame_count()): agents present in at least one, with their ids, and
  /// per agent the fragment copies it walks there. Instances that no later frame needs are dropped.
  void emit(std::size_t end, CrowdMotion& frames, std::vector<std::vector<AgentPiece>>& pieces);

  /// The delivered instances still held, by id (what the next frames may need).
  [[nodiscard]] const std::map<std::uint32_t, Instance>& held() const noexcept { return held_; }

  /// The whole state as bytes (host order), and back.
  void save(std::vector<std::byte>& out) const;
  void load(const std::vector<std::byte>& in, std::size_t& at);

 private:
  using Copy = std::array<int, 3>;
  struct Node {
    FragmentRef fragment;
    Copy copy{0, 0, 0};
    friend auto operator<=>(const Node&, const Node&) = default;
  };
  struct Sample {
    Eigen::Vector2d position;
    double time;
    double heading;
    std::int32_t action;  // of the segment that ends here (lay_out's rule)
  };
  struct Walk {
    Node head;
    Node last;                   // the last fragment copy whose samples were taken
    std::vector<Sample> samples; // samples from the one before the current frame on
    double radius = 0;
    std::size_t runs = 0;        // present runs closed so far
    std::int64_t agent = -1;     // the agent of the present run, −1 when absent
    double facing = 0;           // the facing shown at the last present frame (lay_out's rate limit)
    std::vector<std::pair<Node, std::array<double, 2>>> spans;  // fragment copies taken, with their time spans
    bool ended = false;          // the chain has no successor left: once past its samples, the walk is over
  };

  [[nodiscard]] bool in_range(const Copy& c) const noexcept;
  void take(Walk& walk, const Node& node);     // appends a fragment copy's samples
  bool extend(Walk& walk, double time);        // takes successors until the samples reach `time`; false: over
  // Walks for the heads among an instance's fragment copies (`previous`: the images of the connections into the
  // entries delivered with it).
  void start_walks(std::uint32_t id, const std::map<FragmentRef, Copy>& previous);

  const PatchLibrary& library_;
  PatchActions actions_;
  Region region_;
  Eigen::Vector3d period_;
  double rate_;
  double max_turn_;
  std::size_t frames_ = 0;
  std::size_t next_frame_ = 0;
  std::int64_t next_agent_ = 0;
  Copy lo_{0, 0, 0}, hi_{0, 0, 0};
  std::map<std::uint32_t, Instance> held_;
  std::map<FragmentRef, std::pair<FragmentRef, Copy>> next_;  // exit → (entry, image)
  std::vector<Walk> walks_;  // in order of their heads
};

}  // namespace throng::tiling
