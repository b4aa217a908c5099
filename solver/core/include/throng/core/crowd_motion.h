// CrowdMotion: the positions of N agents over T frames, the value every method reads and writes.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace throng {

/// N agents over T frames in 3-D; 2-D crowds keep z = 0. A plain value type: the members are the data.
///
///   positions   #frames by #agents by 3, contiguous row-major [T][N][3] (metres); NaN where an agent is absent
///   times       #frames, strictly increasing (seconds); not necessarily uniform (after a time warp)
///   ids         #agents, stable across edits (an agent keeps its id through every method)
///   radii       #agents (metres)
///   species     #agents, group or species index (walking group, subgroup, patch colour ...)
///   velocities  empty, or #frames by #agents by 3 like positions (m/s)
///
/// Presence: real data has agents entering and leaving; agent n is present at frame t iff its position there
/// is finite. The file writes −1 as the per-frame id where an agent is absent.
struct CrowdMotion {
  std::vector<double> times;
  std::vector<double> positions;
  std::vector<std::int64_t> ids;
  std::vector<double> radii;
  std::vector<std::int32_t> species;
  std::vector<double> velocities;

  /// Frames, agents and the given times; positions all absent (NaN), ids 0..N-1, radii `radius`, species 0.
  static CrowdMotion with_shape(std::size_t frame_count, std::size_t agent_count, double radius = 0.25);

  [[nodiscard]] std::size_t frame_count() const noexcept { return times.size(); }
  [[nodiscard]] std::size_t agent_count() const noexcept { return ids.size(); }

  /// Position of agent `agent` at frame `frame` (3 doubles, writable view into `positions`).
  [[nodiscard]] Eigen::Map<Eigen::Vector3d> position(std::size_t frame, std::size_t agent) noexcept {
    return Eigen::Map<Eigen::Vector3d>(positions.data() + index(frame, agent));
  }
  [[nodiscard]] Eigen::Map<const Eigen::Vector3d> position(std::size_t frame, std::size_t agent) const noexcept {
    return Eigen::Map<const Eigen::Vector3d>(positions.data() + index(frame, agent));
  }

  /// All agents at one frame: #agents by 3, row-major view into `positions`.
  using FrameView = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
  using ConstFrameView = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
  [[nodiscard]] FrameView frame(std::size_t frame) noexcept {
    return FrameView(positions.data() + index(frame, 0), static_cast<Eigen::Index>(agent_count()), 3);
  }
  [[nodiscard]] ConstFrameView frame(std::size_t frame) const noexcept {
    return ConstFrameView(positions.data() + index(frame, 0), static_cast<Eigen::Index>(agent_count()), 3);
  }

  /// True iff agent `agent` is present (its position is finite) at frame `frame`.
  [[nodiscard]] bool present(std::size_t frame, std::size_t agent) const noexcept {
    return std::isfinite(positions[index(frame, agent)]);
  }

  /// First and one-past-last frame where the agent is present; {0, 0} if never present.
  /// Presence need not be contiguous in general data; this is the enclosing span.
  [[nodiscard]] std::pair<std::size_t, std::size_t> presence_span(std::size_t agent) const noexcept;

  /// Flat offset of (frame, agent, x) in `positions` / `velocities`.
  [[nodiscard]] std::size_t index(std::size_t frame, std::size_t agent) const noexcept {
    return (frame * agent_count() + agent) * 3;
  }

  /// Checks every invariant above; throws InputError naming the member and the problem
  /// (sizes disagree, times not strictly increasing or not finite, a present agent with a NaN coordinate,
  /// duplicate ids, a negative or non-finite radius). `what` prefixes the message (a file name, a step).
  void validate(const std::string& what = "crowd") const;
};

/// NaN, for absent positions.
inline constexpr double absent = std::numeric_limits<double>::quiet_NaN();

}  // namespace throng
