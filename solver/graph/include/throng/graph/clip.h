// A clip: the part of a crowd that a graph is built from — a frame range, a set of agents present over all of
// it, sampled at a regular step (the paper down-samples the source frames before building the graph).
#pragma once

#include <throng/core/crowd_motion.h>

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace throng {

/// Which part of a crowd to take, and how densely to sample it.
struct ClipOptions {
  std::size_t first_frame = 0;  ///< first source frame (index into the crowd's frames)
  /// last source frame, inclusive; the default (or anything past the end) means the crowd's last frame
  std::size_t last_frame = std::numeric_limits<std::size_t>::max();
  /// ids of the agents to take; empty means every agent present over the whole clip (others are left out and
  /// listed in Clip::left_out). A listed agent absent anywhere in the clip is a ConfigError.
  std::vector<std::int64_t> agents;
  /// Sample every `sample_step`-th source frame from first_frame (1 = every frame). The last frame of the clip
  /// and the frames in make_clip's `required_frames` are samples too, so the last interval may be shorter.
  std::size_t sample_step = 1;
};

/// The sampled clip.
///   frames     #samples source frame indices, increasing (the first and last frame of the clip included)
///   times      #samples (seconds)
///   agents     #agents source agent indices;  ids  #agents
///   positions  #samples*#agents by 2 (metres): row i·#agents + j is agent j at sample i
struct Clip {
  std::size_t first_frame = 0;
  std::size_t last_frame = 0;
  std::vector<std::size_t> frames;
  std::vector<double> times;
  std::vector<std::size_t> agents;
  std::vector<std::int64_t> ids;
  Eigen::Matrix<double, Eigen::Dynamic, 2> positions;
  std::vector<std::int64_t> left_out;  ///< ids not taken because they are absent somewhere in the clip

  [[nodiscard]] std::size_t sample_count() const noexcept { return frames.size(); }
  [[nodiscard]] std::size_t agent_count() const noexcept { return agents.size(); }
  /// Row of agent j at sample i in `positions` (the graph's vertex index).
  [[nodiscard]] Eigen::Index vertex(std::size_t sample, std::size_t agent) const noexcept {
    return static_cast<Eigen::Index>(sample * agents.size() + agent);
  }
  /// The sample at source frame `frame`, or −1 when that frame is not a sample.
  [[nodiscard]] long sample_of_frame(std::size_t frame) const noexcept;
  /// The graph agent with id `id`, or −1.
  [[nodiscard]] long agent_of_id(std::int64_t id) const noexcept;
};

/// Samples `crowd` as `options` say; `required_frames` (source frames inside the clip, any order) become
/// samples too, so constraints can refer to them. Throws ConfigError for a frame range outside the crowd or
/// reversed, a step of 0, an unknown agent id or a listed agent absent somewhere in the clip, fewer than two
/// samples or no agent left; the messages name the option, the value and what was expected.
[[nodiscard]] Clip make_clip(const CrowdMotion& crowd, const ClipOptions& options,
                             std::span<const std::size_t> required_frames = {});

}  // namespace throng
