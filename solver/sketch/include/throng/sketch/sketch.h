// Stroke-driven crowds: a few drawn strokes become per-agent crowd parameters, then an agent simulation.
//
// Paper: Ogiwara & Oshita, "Pen-based Interface for Crowd Animation" (seed 003), read with METHODS.md §3.
// Pipeline (each step is an entry point below, so tests and tools can look at the intermediate values):
//
//   strokes ──analyse_strokes──▶ Course            per main-line point k: path q_{1,k}, offsets V_{i,k} (Eq. 1, 4),
//                                                   speed v_k (Eq. 5), width W_k and standard distance s_k (Eq. 6–7),
//                                                   irregularity E_k (Eq. 8–12)
//   Course + start positions ──agent_parameters──▶ AgentParameters   weights o_{j,i} (Eq. 2–3), draws u_j (Eq. 13)
//   (no positions) ──place_agents──▶ start positions between the outermost auxiliary lines
//   Simulation: path following, agent and obstacle avoidance, step (Eq. 14–22)
//   simulate(): all of the above, sampled into a CrowdMotion at the output rate.
//
// Decisions where the paper is unclear or wrong (METHODS.md §3 "Reading" and our own):
// - Strokes live in the ground plane (x, y); the output has z = 0. Times are seconds, lengths metres.
// - Correspondence: every auxiliary stroke is resampled by normalised arc length to the main line's K points.
// - Consecutive main-line points at the same place (a pen pause) are merged into the first one: the pause time
//   then belongs to the next segment, which becomes slower (Eq. 5 would otherwise give v = 0 and stall agents).
// - Eq. 1 is a moving average over [k−δ, k+δ], the window shrunk symmetrically near the ends so the drawn end
//   points are kept. Eq. 9–10 use the window [k−δ, k+δ] over the K−1 segment values G, truncated at the ends
//   (a shrunk window would make the variance 0 there); VAR is the variance around the window's mean AVG.
// - Eq. 2–3: l_{j,i} is the distance from agent j's start to the polyline of stroke i as the targets use it
//   (main line, smoothed auxiliary line). Strokes at distance 0 share all the weight.
// - Eq. 6: "side" is the sign of the cross product of the main line's tangent with the offset; a side with no
//   auxiliary point uses the main line itself (so one auxiliary line gives W = its distance to the main line).
// - Eq. 13: e_{j,k} = u_j · min(E_k / E_MAX, 1) with u_j ~ U(0.5, 1) drawn once per agent from
//   Rng(derive_seed(seed, j)), so agent j's draw does not depend on the agent count or the thread count.
// - Eq. 15: r_{j,k} = s_k (1 + e_{j,k}) (the text's s·e would switch avoidance off for smooth strokes).
// - Eq. 16, 18: repulsion (p_j − p_l)(r/d − 1), of length r − d. Obstacles generalise the paper's circles by the
//   signed distance to the boundary b (core's distance_to) and its outward normal n: n · (r_block − b) when
//   b < r_block, which is exactly Eq. 18 for a circle of radius ρ with r_block,x = ρ + obstacle_distance_m.
//   Beyond the paper (Options::slide_around_obstacles): Eq. 18's push is radial, so an agent whose path force
//   points into an obstacle (walking head-on into it, or its target lies inside it) is held in front of it for
//   good. Then the path force is turned along the boundary of the most pressing obstacle, keeping its length:
//   forward along the course; facing the boundary square-on (within cos 0.1), round the side the course passes
//   the obstacle on when the main line runs beside it (a gate's wall: through the gate), else the side of the
//   obstacle's centre the agent is on (neighbours split the same way, so the two flows never meet), else the
//   side the pull leans to, else by agent parity — and the agent keeps that side from step to step until it
//   loses contact, so it does not dither.
// - Eq. 21: the paper's per-step v becomes v_k Δt with v_k in m/s, k the agent's current target index (v_0 = v_1).
// - Walking-direction filter (beyond the paper; Options::direction_filter_s = τ, 0 = the paper's rule). Eq. 21
//   moves a full v_k Δt along F/|F| every step, so wherever F swings from step to step — an agent held between
//   its target's pull and its neighbours' repulsion, F turning by up to 180° — the agent jumps back and forth by
//   v_k Δt: measured on the paper experiment, 11 % of agent-frames accelerated above 10 m/s² (a person cannot).
//   Instead each walking agent carries a walking velocity u (0 at the start) that relaxes toward Eq. 21's
//   v_k F/|F| (0 when F = 0): u ← u + (1 − exp(−Δt/τ)) (v_k F/|F| − u), and moves u Δt; after the obstacle
//   cut below, u is the move actually made over Δt. A steady F gives u → v_k F/|F|, the paper's motion (the
//   same paths, speeds and spacing up to a turning radius of about v_k τ); a direction that flips each step
//   averages out and the agent stands instead of vibrating. |u| never exceeds the course's fastest v_k, and
//   |Δu| per step is at most
//   2 v_k (1 − exp(−Δt/τ)): an acceleration of at most 2 v_k / τ, and about v_k Δt / τ² for a steady swing.
//   An agent that arrives keeps its u and slows down over about τ (the paper's agents stop dead: a deceleration
//   of v_k / Δt); standing agents' make-room moves (below) are filtered the same way, u relaxing toward the
//   move over Δt. With `remove`, an agent vanishes where it arrives, as before.
//   With the filter and max_acceleration > 0, agents also brake for obstacles (beyond the paper): u's speed
//   toward an obstacle whose boundary is g beyond the body radius, relative to that boundary, is held to
//   min(√(2 a g), g / Δt), a = max_acceleration, so an agent walking at a pillar slows and slides round it
//   instead of being stopped dead at the boundary by the obstacle cut, and steps aside from a moving obstacle
//   coming at it (shortening the rest of u so |u| grows only for an obstacle faster than the agent). Measured on
//   sketch-large: the largest acceleration went from 11.97 to 5.8 m/s². Braking adds at most about a to a step.
// - Target advancement: after the move, while the agent is within R of its target OR has passed it (is ahead of
//   the line through the target across the main line's direction there) OR the target lies inside an obstacle
//   (grown by the agent radius: no agent can get there), the target moves on — several points
//   in one step when points are denser than the step. The paper advances only within R; then agents pushed past
//   their target by the agents behind are pulled back to it and a dense crowd deadlocks (observed on the paper
//   experiment, which stalled mid-course). Reaching or passing the last point is arrival. The same rule places
//   given start positions on their path: an agent ahead of the first points starts from the first one ahead.
// - No agent ends a step inside an obstacle: a move is cut where it would first enter an obstacle grown by the
//   agent radius (checked at intervals of half the radius, so thin walls cannot be jumped), then the agent is
//   projected out of every obstacle it still overlaps at the step's end time (moving obstacles push agents).
//   If projections conflict (a gap narrower than the agent) the agent keeps its previous position when that is
//   clear, else the best position found is kept and counted in SimulationResult::unresolved_obstacle_contacts.
// - End of path: `stop` — the agent stops walking and stands. The crowd standing at the end covers about a disc
//   of radius ρ = √(n s² (√3/2) / π) (n standing agents, s the last standard distance); a walking agent within
//   R + ρ of its own last target joins it and stands too, and so does one within 2(R + ρ) that touches (comes
//   within its avoidance distance of) a standing agent. With the paper's rule alone a large crowd never
//   finishes: late agents push forever into those standing on their end points (2,000 agents still milled round
//   the end after 600 s). Standing agents make room: each step they move by half their summed overlap with
//   agents (Eq. 16 terms) and obstacles (Eq. 18 terms), at most v Δt, so a standing crowd settles without the
//   jitter of Eq. 21's constant step. `remove` — the agent is present at the step it arrives and absent (NaN)
//   from the next one.
// - Facing and actions (beyond the paper; issue 13). The facing is the simulated walking direction: the walking
//   velocity u above (the direction filter's, already a low-pass of Eq. 21's direction; with the paper's rule the
//   step's move), not the sampled positions' difference. The facing is a unit vector h in the ground plane. Each step,
//   where |u| ≥ facing_standing_speed_m_s, h moves toward u's direction û by c = 1 − exp(−Δt/facing_filter_s)
//   of the difference and is renormalised (a low-pass of the direction: a small difference δ turns h by about
//   c δ, and a reversal of û is damped most — with c < 1/2 it never flips h), then turns at most
//   facing_turn_rate_rad_s Δt; slower, h is kept exactly (and so it is within 1e-3 rad of û: no visible turn,
//   no work for agents walking straight on), so a standing agent — arrived, held in a jam, or
//   making room — keeps its last facing. At the start h points at the agent's first target. Frames between steps
//   blend the two steps' facings along the shorter arc (normalised). No trigonometry per agent and step. So ψ turns at most facing_turn_rate_rad_s / output_rate_hz per frame whatever
//   the avoidance does (10.8° at 25 fps), and step-to-step swings of u are damped by the low-pass. The action is
//   the speed class, with PathPoseRule's thresholds (the exports' default), of the fastest |u| over the steps
//   that overlap the interval from the previous output frame (frames need not fall on steps: 24 fps against
//   Δt = 0.04 s): stand below facing_standing_speed_m_s — the same test as the kept facing, so a frame that says
//   stand has exactly the previous frame's facing —, run from running_speed_m_s, walk between; u is filtered, so
//   the class does not flicker with the avoidance either. The table is standard_actions().
// - Determinism: every agent reads only the previous state (two buffers); neighbour sums run in a fixed order
//   (grid cells, then agent index); random draws come from per-agent streams. Same bits for any thread count.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/progress.h>
#include <throng/core/scene.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

namespace throng::sketch {

/// Facing (see the header comment). Below this walking speed (m/s) an agent stands: it keeps its facing and its
/// action is stand. PathPoseRule's standing speed, the exports' default rule, so both agree on who stands.
inline constexpr double facing_standing_speed_m_s = PathPoseRule{}.standing_speed;
/// From this walking speed (m/s) on the action is run (PathPoseRule's running speed: the walk–run transition).
inline constexpr double running_speed_m_s = PathPoseRule{}.running_speed;
/// τ (s) of the facing's low-pass toward the walking direction: short against the walking velocity's own τ
/// (direction_filter_s, 0.5 s) so that the facing lags a turn by little, long against Δt so that a swing of u
/// over a step or two (avoidance with the paper's rule) moves the facing by a fraction of it (0.18 at Δt = 0.04 s).
inline constexpr double facing_filter_s = 0.2;
/// Fastest turn of the facing (rad/s): 270°/s, an about-turn in 2/3 s, a brisk turn on the spot and below the
/// checker's plausibility limit (throng/check, 360°/s); bounds the facing's change per frame whatever the forces do.
inline constexpr double facing_turn_rate_rad_s = 1.5 * std::numbers::pi;

/// A drawn stroke: a polyline in the ground plane and the time each point was drawn.
///   points  #points, metres
///   times   #points, seconds; strictly increasing on the main stroke (its timing sets the crowd's speed);
///           may be empty on auxiliary strokes (not used there)
struct Stroke {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> times;
};

/// What the user drew, and optionally where the agents start.
///   strokes            stroke 0 is the main line; strokes 1.. are auxiliary lines (at least one)
///   initial_positions  #agents start positions (metres); empty: Options::agent_count agents are placed
///                      automatically between the outermost auxiliary lines (place_agents)
struct Drawing {
  std::vector<Stroke> strokes;
  std::vector<Eigen::Vector2d> initial_positions;
};

/// What an agent does when it reaches the last point of its path.
enum class EndOfPath { stop, remove };

/// Every parameter of the method, with the defaults used when a job does not set it.
struct Options {
  // --- Strokes to parameters (paper §4) ---
  /// δ of Eq. 1, 9, 10: the moving windows span δ main-line points on each side.
  int smoothing_window = 5;
  /// > 0: resample the main line to this arc-length spacing (metres) before anything else, times linear in arc
  /// length (speeds are kept), so δ means the same on strokes drawn at any sampling rate. 0: use points as drawn.
  double resample_spacing_m = 0.0;
  /// Multiplies the drawing speed of Eq. 5 (a drawing made at a different pace than the crowd should walk).
  double speed_scale = 1.0;
  /// Eq. 7: at widths W ≤ narrow_width_m the standard distance is narrow_distance_m, at W ≥ wide_width_m it is
  /// wide_distance_m, linear in between (metres).
  double narrow_width_m = 2.0;
  double wide_width_m = 20.0;
  double narrow_distance_m = 0.7;
  double wide_distance_m = 2.0;
  /// α of Eq. 12 (E_k = α VAR_k; VAR is dimensionless: a variance of distance change per metre).
  double irregularity_gain = 1.0;
  /// E_MAX of Eq. 13: irregularity at which the correction is full (e_{j,k} = u_j).
  double irregularity_max = 0.2;

  // --- Agents ---
  /// Agents placed automatically when the drawing gives no initial positions.
  std::size_t agent_count = 50;
  /// Agent body radius (metres): written to the output, kept clear of obstacles.
  double agent_radius_m = 0.25;
  /// Seed of the per-agent draws u_j (Eq. 13).
  std::uint64_t seed = 1;

  // --- Simulation (paper §5) ---
  /// R of Eq. 14 (metres): no pull within R of the target; the target advances when the agent is within R.
  double follow_radius_m = 1.0;
  /// Distance from an obstacle's boundary (metres) inside which an agent is pushed away (r_block − ρ, Eq. 18).
  double obstacle_distance_m = 0.5;
  /// Slide around obstacles: when the path force (Eq. 14) points into an obstacle within obstacle_distance_m, it
  /// is turned along the obstacle's boundary, forward along the course (see the header comment). false is the
  /// paper's model, in which an agent walking into an obstacle, or whose target lies inside one, stops there.
  bool slide_around_obstacles = true;
  /// Weights of Eq. 20 (paper: 1 : 2 : 2). avoid_weight = 0 switches agent avoidance off.
  double trajectory_weight = 1.0;
  double avoid_weight = 2.0;
  double obstacle_weight = 2.0;
  /// Simulation time step Δt (seconds). Eq. 21 moves every walking agent a full v Δt each step, so with the
  /// paper's rule (direction_filter_s = 0) agents held in balance jitter by about v Δt: 0.04 s keeps that near
  /// 5 cm at walking speed.
  double time_step_s = 0.04;
  /// τ (seconds) of the walking-direction filter (beyond the paper; see the header comment): each step the
  /// agent's walking velocity relaxes toward Eq. 21's v_k F/|F| by 1 − exp(−Δt/τ) of the difference. 0: the
  /// paper's rule, a full v_k Δt along F/|F| every step.
  double direction_filter_s = 0.5;
  /// m/s² ≥ 0, with the filter only: the walking velocity changes by at most this × Δt per step, and agents brake
  /// for obstacles at this deceleration (see the header comment); 0: no bound, no braking.
  double max_acceleration_m_s2 = 2.5;
  /// Output frames per second (frames are exact positions on the piecewise-linear simulated motion).
  double output_rate_hz = 25.0;
  /// Seconds to simulate; 0: until every agent has finished its path, at most max_duration_s.
  double duration_s = 0.0;
  double max_duration_s = 600.0;
  EndOfPath end_of_path = EndOfPath::stop;
};

/// Throws ConfigError naming the first field with an impossible value, its value and what is expected.
void validate(const Options& options);

/// The shared parameters along the course, one entry per main-line point k = 0..K−1 (after merging pen pauses
/// and the optional resampling).
///   main          K points q_{1,k}; main_times K seconds (as drawn, strictly increasing)
///   auxiliary     #aux by K: auxiliary strokes resampled to the main line's points (raw, for Eq. 8)
///   smoothed      #aux by K: the same after Eq. 1 (q̄_{i,k})
///   speed         K, v_k of Eq. 5 in m/s (speed_scale applied; v_0 = v_1)
///   width         K, W_k of Eq. 6 (metres);  standard_distance  K, s_k of Eq. 7 (metres)
///   distance_change  #aux by K−1, G_{i,k} of Eq. 8 (dimensionless)
///   irregularity  K, E_k of Eq. 12;  correction_scale  K, min(E_k / E_MAX, 1) (Eq. 13 without u_j)
struct Course {
  std::vector<Eigen::Vector2d> main;
  std::vector<double> main_times;
  std::vector<std::vector<Eigen::Vector2d>> auxiliary;
  std::vector<std::vector<Eigen::Vector2d>> smoothed;
  std::vector<double> speed;
  std::vector<double> width;
  std::vector<double> standard_distance;
  std::vector<std::vector<double>> distance_change;
  std::vector<double> irregularity;
  std::vector<double> correction_scale;

  [[nodiscard]] std::size_t point_count() const noexcept { return main.size(); }
  [[nodiscard]] std::size_t auxiliary_count() const noexcept { return smoothed.size(); }
  /// V_{i,k} of Eq. 4 for auxiliary line `aux` (0-based among auxiliaries): q̄_{i,k} − q_{1,k}.
  [[nodiscard]] Eigen::Vector2d offset(std::size_t aux, std::size_t k) const { return smoothed[aux][k] - main[k]; }
};

/// Checks the strokes (at least a main and one auxiliary; ≥ 2 points; finite values; main times strictly
/// increasing; no zero-length stroke) and computes the Course. Throws InputError naming the stroke, the point
/// and the value; ConfigError for bad options.
[[nodiscard]] Course analyse_strokes(const std::vector<Stroke>& strokes, const Options& options);

/// Per-agent parameters.
///   start          #agents start positions p_{j,0}
///   weights        #agents by #strokes, o_{j,i} of Eq. 2–3 (column 0: the main line); rows sum to 1
///   correction_draw  #agents, u_j in [0.5, 1) of Eq. 13
///   first_target   #agents, the target index each agent starts from (0 for given positions; the placement row's
///                  point for automatic placement, so agents placed along the course do not walk back)
struct AgentParameters {
  std::vector<Eigen::Vector2d> start;
  Eigen::MatrixXd weights;
  std::vector<double> correction_draw;
  std::vector<std::size_t> first_target;

  [[nodiscard]] std::size_t agent_count() const noexcept { return start.size(); }
};

/// Weights and draws for agents starting at `start` (first_target 0). Throws InputError for a non-finite start.
[[nodiscard]] AgentParameters agent_parameters(const Course& course, const std::vector<Eigen::Vector2d>& start,
                                               const Options& options);

/// `count` agents placed between the outermost (smoothed) auxiliary lines, in rows across the course starting at
/// its first point and going forward along it. In each row the agents are s_k apart (s_k at that point, Eq. 7),
/// rows s_k·√3/2 apart and staggered (a hexagonal packing); a slot is skipped when it is closer than s to an agent
/// already placed or within max(obstacle_distance_m, agent_radius_m) of an obstacle at time 0. Deterministic.
/// first_target is the row's main-line point. Throws ConfigError (agent_count) when the course cannot hold them.
[[nodiscard]] AgentParameters place_agents(const Course& course, std::size_t count, const Scene& scene,
                                           const Options& options);

/// p'_{j,k} of Eq. 4: q_{1,k} + Σ_i o_{j,i} V_{i,k}.
[[nodiscard]] Eigen::Vector2d target_point(const Course& course, const AgentParameters& agents, std::size_t agent,
                                           std::size_t k);
/// r_{j,k} of Eq. 15 (read): s_k (1 + u_j · min(E_k / E_MAX, 1)).
[[nodiscard]] double avoidance_distance(const Course& course, const AgentParameters& agents, std::size_t agent,
                                        std::size_t k);

/// Where an agent is in its life.
enum class AgentStatus : std::uint8_t { walking, arrived, removed };

/// The agent simulation of paper §5, one time step at a time (two buffers, TBB-parallel, same bits for any
/// thread count; the thread count is set by the caller, e.g. with throng::ThreadLimit).
class Simulation {
 public:
  /// Validates the options and the scene (InputError) and checks that no agent starts with its centre inside an
  /// obstacle (InputError naming the agent and obstacle); agents overlapping an obstacle are projected out.
  Simulation(Course course, AgentParameters agents, Scene scene, Options options);
  ~Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;

  /// Advances by Options::time_step_s.
  void step();

  [[nodiscard]] std::size_t agent_count() const noexcept;
  [[nodiscard]] std::size_t step_count() const noexcept;
  /// Seconds since the start (step_count · Δt).
  [[nodiscard]] double time() const noexcept;
  /// True when no agent is walking any more (and, with EndOfPath::remove, every one has been removed).
  [[nodiscard]] bool finished() const noexcept;

  [[nodiscard]] Eigen::Vector2d position(std::size_t agent) const;
  [[nodiscard]] AgentStatus status(std::size_t agent) const;
  [[nodiscard]] std::size_t target_index(std::size_t agent) const;
  /// Time the agent reached the end of its path (seconds), NaN if it has not.
  [[nodiscard]] double arrival_time(std::size_t agent) const;
  /// Mean fraction of the path done over all agents, in [0, 1], non-decreasing.
  [[nodiscard]] double path_fraction() const;
  /// Agent-steps so far that ended overlapping an obstacle because projections conflicted (see header).
  [[nodiscard]] std::size_t unresolved_obstacle_contacts() const noexcept;

  /// Writes the positions at time `time` into `frame` (#agents by 3, z = 0; NaN for absent agents), linear
  /// between the previous step and the current one (the simulated motion is linear within a step).
  /// Requires time() − Δt ≤ `time` ≤ time() (or `time` = 0 before the first step). The obstacle guarantee holds
  /// at step times; a frame between steps lies on the straight move, which can cut a convex corner of the grown
  /// obstacle by at most (v Δt)² / (8 agent_radius_m) (1.6 mm at 1.4 m/s, Δt = 0.04 s, 0.25 m).
  void sample(double time, std::span<double> frame) const;
  /// Facing and action of an output frame at `time` (same range as sample()), frames taken in time order:
  /// `orientations` #agents by 4 (x, y, z, w), the yaw about +z interpolated along the shorter arc between the
  /// steps; `actions` #agents, standard_actions() indices from the fastest walking speed over the steps since
  /// the previous frame taken (the step holding that frame included; see the header comment). NaN and −1 where
  /// the agent is absent. Not const: it starts the next frame's speed maximum.
  void take_pose(double time, std::span<double> orientations, std::span<std::int32_t> actions);

  [[nodiscard]] const Course& course() const noexcept;
  [[nodiscard]] const AgentParameters& agents() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// What simulate() returns.
///   motion          frames at Options::output_rate_hz from time 0; ids 0..N−1, radii agent_radius_m, species 0;
///                   orientations and actions (standard_actions() table) from the simulation (see "Facing")
///   course, agents  the parameters the strokes gave (for inspection, pictures and the output file)
///   arrival_time_s  #agents, when each agent reached its path's end (NaN: it did not within the duration)
struct SimulationResult {
  CrowdMotion motion;
  Course course;
  AgentParameters agents;
  std::vector<double> arrival_time_s;
  std::size_t step_count = 0;
  std::size_t unresolved_obstacle_contacts = 0;
  bool finished = false;  ///< every agent finished its path before the duration ran out
};

/// Where simulate() puts the output frames as it makes them (frame 0, 1, ... in order): in memory (simulate()
/// without a sink: SimulationResult::motion), or a file written as the simulation goes (`throng sketch`).
class FrameSink {
 public:
  /// Where one frame goes: positions #agents × 3, orientations #agents × 4, actions #agents (see sample() and
  /// take_pose()).
  struct Frame {
    std::span<double> positions;
    std::span<double> orientations;
    std::span<std::int32_t> actions;
  };
  virtual ~FrameSink() = default;
  /// Once, before the first frame: the agent count and the frame count when `known` (a duration), else the most
  /// frames there can be (max_duration's).
  virtual void start(std::size_t agents, std::size_t frames, bool known) = 0;
  /// Where the next frame goes, valid until commit().
  [[nodiscard]] virtual Frame next_frame() = 0;
  /// The frame from next_frame() is filled.
  virtual void commit() = 0;
};

/// The whole method: analyse the strokes, place or take the agents, simulate, sample. Reports progress.
[[nodiscard]] SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options,
                                        Progress& progress);
[[nodiscard]] SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options);
/// The same with the frames handed to `sink` as they are made: the result's motion has the ids, radii, species,
/// action table and times (one per frame), and no per-frame arrays (positions, orientations, actions). The same
/// frames, bit for bit, as the in-memory simulate()'s.
[[nodiscard]] SimulationResult simulate(const Drawing& drawing, const Scene& scene, const Options& options,
                                        FrameSink& sink, Progress& progress);

}  // namespace throng::sketch
