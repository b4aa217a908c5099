// Collision repair of a crowd animation (Kwon, Lee, Lee, Takahashi, SIGGRAPH 2008, §6.1;
// docs/METHODS.md §1.3): push trajectories apart, and out of obstacles, by small linear deformations
// of the colliding trajectories until every clearance holds.
//
// Iteration. Find every contact (broad_phase.h: exact, every pair, every obstacle, one contact per colliding frame
// interval, so a pair too close over many frames has many, and the deepest that can move is always among
// them; after the first search incrementally, contact_tracker.h: only segments that moved are examined again,
// with exactly the full search's result). Order them deepest first
// (deficit = clearance − distance; ties by kind, then indices) and take each one whose trajectory vertices are
// not yet used by a taken contact this iteration ("every disjoint collision in one solve", beyond the paper).
// For each taken contact the point of closest approach p(s) = (1 − s) v_i + s v_{i+1} of each trajectory gets
// a prescribed displacement — a linear constraint on two temporally adjacent vertices, as in the paper:
//  * two agents: each moves push_fraction·clearance/2 along ±n, so their separation grows by push_fraction
//    (10 % in the paper) of the clearance; when one of them cannot move there (pinned), the other takes the
//    whole push. Direction (`pair_push`): `apart` is their offset p_a − p_b (the paper's rule); `sideways`
//    (default) is the part of the offset across their relative motion over the interval. Most contact intervals
//    of a pair end before or start after its closest moment, where the offset points along the motion; pushing
//    along it holds one agent back and then rushes it past the other (measured on the bump config: 1.75 → 8.6
//    m/s at most with `apart`, 99th percentile 3.8; 6.5 m/s with `sideways`, 99th percentile 2.9). Zero offset:
//    across their relative motion;
//  * agent and obstacle: the point moves out to the clearance plus push_fraction·clearance/2. Direction
//    (`obstacle_pull`): `nearest` moves it toward the nearest boundary point (the paper's rule); `sideways`
//    (default) moves it across its own motion relative to the obstacle, to the nearer of the two sides — for a
//    trajectory crossing a wall or a post this is the way round it (the paper's Figure 9 pulls "toward the
//    opening"), and for a trajectory grazing an obstacle it equals `nearest`; an agent at rest relative to
//    the obstacle uses `nearest`.
// Then each trajectory with constraints is deformed on its own (the paper's "subgraph containing only the
// vertices and motion edges of colliding trajectories": with only motion edges the subgraph falls apart into one
// chain per trajectory, so the pushes, being prescribed per point, decouple by trajectory and solve in parallel).
//
// Deformation of one trajectory: the displacement d of its vertices minimises the temporal term of the editing
// energy (throng/graph/features.h Eq. 6, features and weights measured once on the input trajectory), plus a
// velocity term velocity_weight·w̄·Σ|d_{k+1} − d_k|² (w̄ the mean temporal weight; beyond the paper), plus an
// anchor velocity_weight·w̄/spread² · |d|², with the pins fixed (d = 0) and the pushes met exactly (linear
// equality constraints). Velocity and anchor balance at `spread` frames: a push fades as exp(−|k|/spread) each
// side. Why the velocity term: the temporal features alone only penalise second differences of d, so a linear
// ramp is free; two nearby pushes in opposite directions then start a ramp that only the anchor stops, far
// away — measured without it (velocity_weight 0, anchor w̄/spread⁴): spread 30 on Figure 9 abandoned a contact
// after a 10 m drift, spread 60 moved vertices 115 m at 1,400 m/s; with it, every spread stays within 0.5 m
// (bump) and 2.2 m (Figure 9). Locality still matters: pushes at different moments undo each other when each
// bends a whole trajectory. Spreads above 1,000 frames count as 1,000 (the anchor stays ≥ 1e-6 of the velocity
// weight, so a trajectory without pins stays well conditioned; a push then moves it almost rigidly).
//
// Plausibility (report: input and output max speed and acceleration; the measurements on the shipped configs and
// real data are in docs/commands/collide.md). Pushes are met exactly at contact points only, so a contact cleared
// at the last iteration can leave a sharp turn; a speed limit is not a constraint of this method.
//
// Solver (src/track_solver.h). Each touched trajectory's system Q (features of its input shape, its pins) is
// assembled and factorised once, when it is first pushed, and cached for the run; each iteration's pushes are
// met exactly (no penalty, so every spread works). Three implementations of that one method (TrackMethod, for
// benchmarks and tests; they agree to 1e-10 m):
//  * `eliminate` (the default): each push row is solved for one of its two unknowns, so the rest is an
//    unconstrained band system that differs from Q only in a window around the pushed vertices; the unknowns
//    before and after the window are eliminated through Q's top-down and reversed band Cholesky factors (made
//    once), and only the window is factorised per solve: O(window · 9² + length · 5). The pushes of one
//    trajectory in one iteration span about 5 % of it in the shipped configs.
//  * `schur`: the band factor of Q once, the pushes through the Schur complement on it: m back substitutions and
//    an m × m dense factorisation for m pushed rows (hundreds per trajectory in the first iterations).
//  * `linalg`: throng/linalg's ConstrainedLeastSquares (CHOLMOD, its Schur complement over added constraints).
// How fast each is, and the configs' and real data's speeds, are measured in docs/commands/collide.md
// (bench_collide).
//
// Pins. With pin_ends, every trajectory's first and last present frame is pinned (for a crowd present throughout,
// the clip's first and last frames: paper Figure 8); `fixed_agents` pins whole trajectories. A pushed point
// between a pinned and a free vertex moves through the free vertex alone (its displacement scaled by 1/weight,
// at most four times the push); a point between two pinned vertices cannot move.
//
// Stuck and abandoned contacts. A contact is stuck when no push can clear it: its clearance is already violated
// at an end frame of its interval where every agent involved is pinned (two pinned agents overlapping at a
// pinned frame; an agent whose pinned frame is inside an obstacle — real data has pedestrians tracked inside
// pillars), or no side can move. Stuck contacts are never pushed (pushing the free vertex of such an interval
// cannot clear it and only drags the trajectory away). A contact is abandoned when pushing it makes no
// progress: `contact_patience` pushes without its deficit (clearance − distance) reaching a new smallest value,
// or a push whose deformation would carry any vertex more than `max_displacement` from its input (that
// trajectory's deformation is then dropped for the iteration). Neither kind is pushed again.
//
// End. The run stops when no contact is left (converged), when only stuck or abandoned contacts are left, when
// `stall_iterations` iterations in a row did not reduce the smallest number of pushable contacts seen ("no
// progress"), or after max_iterations solves. It never throws for a result that still collides: the caller reads
// the report (and `throng collide` writes the output, then exits 5). Agents move only in x and y; absent frames
// stay absent. Presence: a trajectory is a run of consecutive present frames (real data has agents entering
// and leaving).
//
// Ranks. Under mpiexec with several ranks, each iteration's touched trajectories are solved round-robin over the
// ranks (the systems are small and independent) and the displacements are gathered so every rank holds the
// same positions; contact detection runs on every rank (it is the same on each, and gathering contacts would
// cost more than the grid). Each trajectory's solve is the same computation on whichever rank, so 1 and n ranks
// give the same bits. No `solver.backend` option: the distributed (petsc) backend solves one system across all
// ranks, which for these ~1,000-unknown systems is pure communication.
#pragma once

#include <throng/collide/broad_phase.h>
#include <throng/core/communicator.h>
#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>
#include <throng/core/progress.h>

#include <cstdint>
#include <string>
#include <vector>

namespace throng::collide {

enum class ObstaclePull { sideways, nearest };

/// Which way two colliding agents are pushed (see "Iteration" above).
enum class PairPush { sideways, apart };

/// How each trajectory's constrained system is solved (the same method, see "Solver" above; for benchmarks and
/// tests).
enum class TrackMethod { eliminate, schur, linalg };

struct Options {
  double margin = 0.0;            ///< metres added to r_a + r_b (pairs) and to r (obstacles), ≥ 0
  double push_fraction = 0.1;     ///< separation added per push, as a fraction of the clearance, in (0, 1]
  ObstaclePull obstacle_pull = ObstaclePull::sideways;
  PairPush pair_push = PairPush::sideways;
  std::size_t max_iterations = 10000;  ///< solves at most, ≥ 1
  bool pin_ends = true;                ///< pin every trajectory's first and last present frame
  std::vector<std::int64_t> fixed_agents;  ///< ids of agents that must not move at all
  double spread = 15.0;               ///< frames over which a push fades along a trajectory (each side), ≥ 1
  double velocity_weight = 1.0;       ///< weight of velocity changes against the temporal features, ≥ 0
  double min_feature_length = 0.05;   ///< ℓ of the temporal feature weights (metres, throng/graph/features.h)
  double max_displacement = 10.0;     ///< metres any vertex may move from its input (a push beyond: abandoned), > 0
  std::size_t contact_patience = 1000;  ///< pushes of one contact without a new smallest deficit before it is abandoned
  std::size_t stall_iterations = 5000;  ///< iterations without fewer pushable contacts than ever before: stop
  TrackMethod track_method = TrackMethod::eliminate;
};

/// Speeds and accelerations of a crowd (m/s, m/s²): the largest over every agent's present frames (finite
/// differences between consecutive present frames) and the 99th percentile.
struct MotionStats {
  double max_speed = 0, speed_p99 = 0;
  double max_acceleration = 0, acceleration_p99 = 0;
};

/// The statistics of `crowd`'s x, y motion.
[[nodiscard]] MotionStats motion_stats(const CrowdMotion& crowd);

/// What the run did and what is left. Gaps are distance − radii (pairs) or signed distance − r (obstacles).
struct Report {
  std::size_t iterations = 0;          ///< solves
  std::size_t initial_pair_contacts = 0, initial_obstacle_contacts = 0;
  std::size_t pair_contacts = 0;       ///< remaining distinct pairs closer than their clearance
  std::size_t obstacle_contacts = 0;   ///< remaining distinct agent–obstacle pairs in contact
  std::size_t stuck_contacts = 0;      ///< of the remaining, those whose every contact is stuck (see above)
  std::size_t abandoned_contacts = 0;  ///< of the remaining, those with an abandoned contact and no pushable one
  std::size_t constraints = 0;         ///< pushed points over the whole run
  std::size_t moved_agents = 0;        ///< agents whose trajectory changed
  /// Smallest gap over the result (metres), exact: every pair within 16 m of its clearance is examined; +∞ when
  /// no pair comes that close (or no two agents are present together).
  double min_pair_gap = 0;
  double min_obstacle_gap = 0;         ///< idem for agents and obstacles
  double max_displacement = 0;         ///< metres, the largest move of a vertex from its input
  MotionStats input_motion, output_motion;
  bool converged = false;              ///< no contact left
  /// "converged", "only stuck or abandoned contacts left", "no progress", "iteration cap reached"
  std::string stop_reason;
  double detect_seconds = 0, solve_seconds = 0;
  std::vector<std::size_t> history;    ///< contacts (one per colliding frame interval) after each iteration
  int factorizations = 0;              ///< trajectories assembled and factorised (once each for the whole run)
  int ranks = 1;                       ///< MPI ranks the solves were spread over

  [[nodiscard]] std::size_t remaining() const noexcept { return pair_contacts + obstacle_contacts; }
};

struct Result {
  CrowdMotion crowd;  ///< the repaired crowd: same frames, agents, ids, radii, species; velocities dropped if anything moved
  Report report;
};

/// Repairs `crowd` among `obstacles`, spreading the trajectories' solves over `communicator`'s ranks (every rank
/// calls it with the same arguments and gets the same result). Throws ConfigError for bad options (naming the
/// option) or an unknown fixed agent id, InputError for an invalid crowd. Does not throw when contacts remain
/// (see the report).
[[nodiscard]] Result resolve_collisions(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Options& options,
                                        Progress& progress, const Communicator& communicator = Communicator::single());

/// Checks option values; throws ConfigError naming the option.
void validate(const Options& options);

/// One line for logs and errors: "3 colliding pair(s) and 1 obstacle contact(s) remain (2 stuck at pinned
/// frames, 1 abandoned) after 200 iterations (iteration cap reached); smallest pair gap -0.12 m, ...".
[[nodiscard]] std::string summary(const Report& report);

}  // namespace throng::collide
