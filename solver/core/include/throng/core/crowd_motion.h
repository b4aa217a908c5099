// CrowdMotion: the positions of N agents over T frames, the value every method reads and writes.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace throng {

/// One entry of a crowd's action table: what an agent is doing (`name`: "walk", "stand", "run", a tiled patch's
/// label such as "bow") and what it carries (`prop`, empty for nothing). Per-frame actions index the table.
struct ActionKind {
  std::string name;
  std::string prop;
  friend bool operator==(const ActionKind& a, const ActionKind& b) { return a.name == b.name && a.prop == b.prop; }
};

/// N agents over T frames in 3-D; 2-D crowds keep z = 0. A plain value type: the members are the data.
///
///   positions   #frames by #agents by 3, contiguous row-major [T][N][3] (metres); NaN where an agent is absent
///   times       #frames, strictly increasing (seconds); not necessarily uniform (after a time warp)
///   ids         #agents, stable across edits (an agent keeps its id through every method)
///   radii       #agents (metres)
///   species     #agents, group or species index (walking group, subgroup, patch colour ...)
///   velocities  empty, or #frames by #agents by 3 like positions (m/s)
///   orientations  empty (not given), or #frames by #agents by 4: unit quaternions (x, y, z, w), scalar last as
///               in glTF and Eigen's storage, turning the agent's body frame (forward +x, left +y, up +z) into the
///               world. A 2-D crowd's facing is a yaw about +z (w = cos(yaw/2), z = sin(yaw/2)); a 3-D motion
///               (the airshow) may use any orientation. Values at absent frames are ignored (the file stores NaN).
///   actions     empty (not given), or #frames by #agents: an index into action_table (≥ 0 where present; values
///               at absent frames are ignored, the file stores −1)
///   action_table  the names the actions index, stored once (standard_actions() when a method has no own table)
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
  std::vector<double> orientations;
  std::vector<std::int32_t> actions;
  std::vector<ActionKind> action_table;

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

  /// Orientation of agent `agent` at frame `frame` (a view into `orientations`, which must not be empty).
  [[nodiscard]] Eigen::Map<Eigen::Quaterniond> orientation(std::size_t frame, std::size_t agent) noexcept {
    return Eigen::Map<Eigen::Quaterniond>(orientations.data() + (frame * agent_count() + agent) * 4);
  }
  [[nodiscard]] Eigen::Map<const Eigen::Quaterniond> orientation(std::size_t frame, std::size_t agent) const noexcept {
    return Eigen::Map<const Eigen::Quaterniond>(orientations.data() + (frame * agent_count() + agent) * 4);
  }

  /// Action of agent `agent` at frame `frame` (`actions` must not be empty).
  [[nodiscard]] std::int32_t& action(std::size_t frame, std::size_t agent) noexcept { return actions[frame * agent_count() + agent]; }
  [[nodiscard]] std::int32_t action(std::size_t frame, std::size_t agent) const noexcept { return actions[frame * agent_count() + agent]; }

  /// Flat offset of (frame, agent, x) in `positions` / `velocities`.
  [[nodiscard]] std::size_t index(std::size_t frame, std::size_t agent) const noexcept {
    return (frame * agent_count() + agent) * 3;
  }

  /// Checks every invariant above; throws InputError naming the member and the problem
  /// (sizes disagree, times not strictly increasing or not finite, a present agent with a NaN coordinate,
  /// duplicate ids, a negative or non-finite radius; orientations or actions of the wrong size, a present
  /// agent's orientation not a finite unit quaternion within orientation_tolerance, a present agent's action
  /// outside action_table, actions without a table, an action table with an empty name or a repeated entry).
  /// `what` prefixes the message (a file name, a step).
  void validate(const std::string& what = "crowd") const;
};

/// NaN, for absent positions.
inline constexpr double absent = std::numeric_limits<double>::quiet_NaN();

/// How far |q| may be from 1 for a stored orientation: single-precision data (another tool's file) is accepted.
inline constexpr double orientation_tolerance = 1e-6;

// ---- Facing and action derived from the path: the documented default for a crowd that carries none ----------

/// The standard action table, indices given by StandardAction: walk, stand, run (no prop). A method's own table
/// starts with these and appends its own entries (a tiled patch's label and prop).
[[nodiscard]] const std::vector<ActionKind>& standard_actions();
enum StandardAction : std::int32_t { action_walk = 0, action_stand = 1, action_run = 2 };

/// Thresholds of the default facing and action.
struct PathPoseRule {
  double standing_speed = 0.3;  ///< m/s: slower is standing (keeps the last facing); above the annotation noise
                                ///< of recorded crowds (a few cm per frame) and below a slow walk (~0.5 m/s)
  double running_speed = 2.0;   ///< m/s: from here on running (the walk–run transition of adults, ~2 m/s)
};

/// The agent's velocity at a frame from its path (m/s): `velocities` where given and finite, else the central
/// difference of its positions over the neighbouring frames where it is present (one-sided at the ends of its
/// presence). nullopt where the agent is absent or present at this frame alone.
[[nodiscard]] std::optional<Eigen::Vector3d> path_velocity(const CrowdMotion& motion, std::size_t frame, std::size_t agent);

/// The orientation whose forward (+x) points along `direction` with no roll: a yaw about +z, then a pitch
/// (none for a direction in the ground plane). Identity for a zero direction.
[[nodiscard]] Eigen::Quaterniond facing_along(const Eigen::Vector3d& direction);

/// The default action from the path: stand below rule.standing_speed (or without a velocity), run from
/// rule.running_speed, walk between (indices into standard_actions()).
[[nodiscard]] std::int32_t path_action(const CrowdMotion& motion, std::size_t frame, std::size_t agent, const PathPoseRule& rule = {});

/// The default facing, derived from the path (the standing rule): where the agent moves at least
/// rule.standing_speed it faces along its velocity (facing_along); where it is slower or absent it keeps its last
/// facing; before its first such frame it faces where it will first move, and an agent that never moves faces +x.
/// Stateful so that a stream costs O(1) per value: frames of one agent asked in order (t after t − 1) continue
/// its state; any other order replays the agent from frame 0. Holds a reference to `motion`.
class PathFacing {
 public:
  explicit PathFacing(const CrowdMotion& motion, PathPoseRule rule = {});
  [[nodiscard]] Eigen::Quaterniond at(std::size_t frame, std::size_t agent);
  /// at(frame, n) for every agent n in [first, last), in order, into out[0 .. last − first): the same values and
  /// state, computed a range at a time so that the agents' square roots and divisions overlap (one value at a time
  /// they wait on each other: 23 ns a value on this machine, most of a glTF export's CPU).
  void at_frame(std::size_t frame, std::size_t first, std::size_t last, Eigen::Quaterniond* out);

 private:
  [[nodiscard]] std::optional<Eigen::Quaterniond> moving_facing(std::size_t frame, std::size_t agent) const;
  const CrowdMotion& motion_;
  PathPoseRule rule_;
  std::vector<Eigen::Quaterniond> last_;  // per agent: the facing at next_[agent] − 1
  std::vector<std::size_t> next_;         // per agent: the frame the state continues at (npos: not started)
};

}  // namespace throng
