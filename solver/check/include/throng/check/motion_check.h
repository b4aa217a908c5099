// An independent judge of motion plausibility: does every agent of a crowd move as a person can?
//
// Written apart from the methods (it shares no code with them beyond throng/core's value types and obstacle
// geometry), like the tiling checker: it measures a crowd from its positions alone and compares the
// measures with limits. `throng check-motion` (docs/commands/check-motion.md) is its command.
//
// Measures (per agent and over the crowd). Each agent's present frames form runs of consecutive frames;
// nothing is measured across a gap, so the frames where an agent appears or vanishes contribute no
// acceleration or turn (both need a frame on each side), and Settings::edge_frames widens that exclusion.
// With positions p_i at times t_i of one run (3-D; 2-D crowds have z = 0):
//   speed               |v_{i+½}|, v_{i+½} = (p_{i+1} − p_i) / (t_{i+1} − t_i), one sample per interval
//   acceleration        |a_i|, a_i = (v_{i+½} − v_{i−½}) / h_i, h_i = (t_{i+1} − t_{i−1}) / 2, per interior frame
//   tangential, normal  |a_i · u|, |a_i − (a_i · u) u| with u the unit of v_{i−½} + v_{i+½} (no sample when 0)
//   turning rate        angle(v_{i−½}, v_{i+½}) / h_i, where both speeds ≥ Settings::heading_min_speed (a
//                       person standing still has no walking direction)
//   facing rate         |wrap(θ_{i+1} − θ_i)| / (t_{i+1} − t_i), per interval, when facings are given
//   displacement        |p_i − r(t_i)| against a reference crowd: the agent with the same id, r linear in time
//                       between its present frames (a time within time_tolerance_s of a reference frame uses
//                       that frame); frames outside the reference agent's runs are not measured
//   contacts            distinct pairs of agents closer than r_a + r_b + margin − contact_tolerance at some
//                       moment (exact: closest approach of two linear motions per frame interval), and distinct
//                       agent–obstacle pairs whose signed distance drops below r + margin − contact_tolerance
//                       (at the frames and obstacle_samples − 1 points between each pair of frames)
// Each measure over the crowd: sample count, 50th / 95th / 99th percentiles (nearest rank: the value with
// ⌈p·n⌉ − 1 samples below it in sorted order) and maximum, with the agent and time of the maximum.
//
// Limits (check()): the crowd's maximum speed, maximum and 99th-percentile acceleration, maximum and
// 99th-percentile turning rate, maximum facing rate, maximum displacement, and the number of pair contacts and
// of obstacle contacts. A limit of +∞ (or an unset contact limit) is not checked. Defaults for walking
// people and their sources are in docs/commands/check-motion.md; with a reference, limits_from_reference()
// bounds the output by the input's own statistics.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

namespace throng::check {

inline constexpr double unlimited = std::numeric_limits<double>::infinity();

/// The facing (yaw about +z, radians) of every agent at every frame of a crowd, laid out [T][N] like its
/// positions; NaN where the agent is absent or its facing unknown. Optional everywhere: crowds without
/// facings are checked without the facing rate.
struct FacingSeries {
  std::vector<double> yaw;
};

/// The facings a crowd carries (CrowdMotion::orientations): the yaw of each present agent's forward axis (+x
/// rotated by its orientation), NaN where absent; none when the crowd carries no orientations.
[[nodiscard]] std::optional<FacingSeries> facings_of(const CrowdMotion& crowd);

/// How to measure.
struct Settings {
  double heading_min_speed = 0.5;    ///< m/s: turning rate only where both neighbouring speeds reach this
  double contact_tolerance = 1e-3;   ///< m: overlaps shallower than this are rounding, not contacts
  double margin = 0.0;               ///< m added to the clearances (r_a + r_b, r)
  std::size_t edge_frames = 0;       ///< frames at each end of a run also left out of every measure
  int obstacle_samples = 8;          ///< points per frame interval tested against obstacles, ≥ 1
  double time_tolerance_s = 1e-6;    ///< a crowd frame and a reference frame within this are the same
};

/// Throws ConfigError naming the setting.
void validate(const Settings& settings);

/// The upper limits of check(). Defaults: walking people (docs/commands/check-motion.md gives the sources).
struct Limits {
  double max_speed = 2.5;                             ///< m/s
  double max_acceleration = 8.0;                      ///< m/s²
  double acceleration_p99 = 3.0;                      ///< m/s²
  double max_turning_rate = 2 * std::numbers::pi;     ///< rad/s
  double turning_rate_p99 = std::numbers::pi;         ///< rad/s
  double max_facing_rate = 2 * std::numbers::pi;      ///< rad/s (only with facings)
  double max_displacement = unlimited;                ///< m (only with a reference)
  std::optional<std::size_t> max_pair_contacts;       ///< distinct pairs; unset: reported, not checked
  std::optional<std::size_t> max_obstacle_contacts;   ///< distinct agent–obstacle pairs; unset: not checked
};

/// Throws ConfigError naming the limit (a limit must be > 0, or +∞).
void validate(const Limits& limits);

/// One measure over the crowd. Empty (samples = 0): every value 0, agent −1.
struct Distribution {
  std::size_t samples = 0;
  double p50 = 0, p95 = 0, p99 = 0, max = 0;
  std::int64_t max_agent = -1;  ///< id of the agent where the maximum is
  double max_time = 0;          ///< seconds: the frame (or interval start) of the maximum
};

/// One agent's largest values (0 where it has no sample).
struct AgentMaxima {
  std::int64_t id = 0;
  double speed = 0, acceleration = 0, tangential_acceleration = 0, normal_acceleration = 0, turning_rate = 0,
         facing_rate = 0, displacement = 0;
};

/// Contacts left in the crowd (see the header comment).
struct Contacts {
  std::size_t pairs = 0, obstacle = 0;              ///< distinct agent pairs, distinct agent–obstacle pairs
  double deepest_pair = 0, deepest_obstacle = 0;    ///< m: the largest overlap beyond the clearance (0: none)
};

struct Statistics {
  std::size_t agents = 0, frames = 0;
  Distribution speed, acceleration, tangential_acceleration, normal_acceleration, turning_rate, facing_rate,
      displacement;
  std::vector<AgentMaxima> agent_maxima;  ///< one per agent, in the crowd's order
  Contacts contacts;
  bool has_facing = false, has_reference = false;
  std::size_t reference_unmatched = 0;    ///< agents whose id the reference lacks (no displacement for them)
};

/// Measures `crowd` among `obstacles`; `reference` (displacement) and `facing` (#frames × #agents yaw) are
/// optional. Throws InputError for an invalid crowd, reference or facing series (shape), ConfigError for bad
/// settings. Same result whatever the thread count.
[[nodiscard]] Statistics measure(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Settings& settings,
                                 const CrowdMotion* reference = nullptr, const FacingSeries* facing = nullptr);

/// Limits for an output judged against the input it was made from (its `reference` statistics):
///  speed ≤ speed_ratio × the reference's maximum speed; each acceleration, turning and facing limit the larger
///  of `base`'s and the reference's own value (a method is not blamed for what its input already does); contact
///  limits: the reference's counts unless `base` sets them; the displacement bound is `base`'s.
[[nodiscard]] Limits limits_from_reference(const Statistics& reference, const Limits& base, double speed_ratio = 1.25);

/// A broken limit: which, the measured value, the limit, where the worst sample is, and how many agents have a
/// sample beyond the limit (for contact limits: the contacts).
struct Violation {
  std::string limit;        ///< "max_speed", "max_acceleration", "acceleration_p99", "max_turning_rate",
                            ///< "turning_rate_p99", "max_facing_rate", "max_displacement", "max_pair_contacts",
                            ///< "max_obstacle_contacts"
  double value = 0, bound = 0;
  std::int64_t agent = -1;  ///< −1 for crowd-wide counts
  double time = 0;
  std::size_t count = 0;
};

struct Verdict {
  std::vector<Violation> violations;  ///< in the order of the list above
  [[nodiscard]] bool passed() const noexcept { return violations.empty(); }
};

/// Compares `statistics` with `limits` (validated: ConfigError).
[[nodiscard]] Verdict check(const Statistics& statistics, const Limits& limits);

/// One line: "max_speed 3.1 > 2.5 m/s (agent 7 at 4.2 s; 3 agents beyond)".
[[nodiscard]] std::string describe(const Violation& violation);

}  // namespace throng::check
