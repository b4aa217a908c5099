// Collision repair of a crowd animation (Kwon, Lee, Lee, Takahashi, SIGGRAPH 2008, §6.1;
// ../shared/design/METHODS.md §1.3): push trajectories apart, and out of obstacles, by small linear deformations
// of the colliding trajectories until every clearance holds.
//
// Iteration. Find every contact (broad_phase.h: exact, every pair, every obstacle, one contact per colliding frame
// interval, so a pair too close over many frames has many, and the deepest that can move is always among
// them). Order them deepest first
// (deficit = clearance − distance; ties by kind, then indices) and take each one whose trajectory vertices are
// not yet used by a taken contact this iteration ("every disjoint collision in one solve", beyond the paper).
// For each taken contact the point of closest approach p(s) = (1 − s) v_i + s v_{i+1} of each trajectory gets
// a prescribed displacement — a linear constraint on two temporally adjacent vertices, as in the paper:
//  * two agents: each moves push_fraction·clearance/2 along ±(p_a − p_b), so their separation grows by
//    push_fraction (10 % in the paper) of the clearance; when one of them cannot move there (pinned), the other
//    takes the whole push; when their offset is zero the direction is across their relative motion (else +x);
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
// energy (throng/graph/features.h Eq. 6, features and weights measured once on the input trajectory) plus an
// anchor (mean temporal weight)/spread⁴ · |d|², with the pins fixed (d = 0) and the pushes met (to ~1e-7 of a
// push, src/track_solver.h). The temporal term bends (it penalises second differences of d); against the anchor
// a push fades over about `spread` frames each side. The anchor keeps a trajectory without pins determined, and
// locality matters: with a tiny anchor (a push bending the whole trajectory between its pins) pushes at
// different moments undo each other and hard scenes cycle (measured on two 2×2 groups bumping with two agents
// fixed, push 10 %: spread 8 frames converged in 1,371 iterations, 15 in more than 3,000, 30 and 100 had not
// converged after 3,000). The default 15 frames (half a second at 30 fps) keeps sidesteps human-sized. Each
// trajectory's system is assembled once (features of the input trajectory, not re-measured per iteration) and
// each iteration adds its pushes and solves (see src/track_solver.h for why these small banded systems do not
// go to throng/linalg's general solver); the deformation of each iteration is added to the current positions.
//
// Pins. With pin_ends, every trajectory's first and last present frame is pinned (for a crowd present throughout,
// the clip's first and last frames: paper Figure 8); `fixed_agents` pins whole trajectories. A pushed point
// between a pinned and a free vertex moves through the free vertex alone (its displacement is capped at four
// times the push); a point on a pinned vertex, or between two, cannot move. A contact where neither side can move
// is "stuck": it stays, and the run ends when only stuck contacts are left.
//
// End. The run stops when no contact is left (converged), when only stuck contacts are left, or after
// max_iterations solves. It never throws for a result that still collides: the caller reads the report (and
// `throng collide` writes the output, then exits 5). Agents move only in x and y; absent frames stay absent.
// Presence: a trajectory is a run of consecutive present frames (real data has agents entering and leaving).
#pragma once

#include <throng/collide/broad_phase.h>
#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>
#include <throng/core/progress.h>

#include <cstdint>
#include <string>
#include <vector>

namespace throng::collide {

enum class ObstaclePull { sideways, nearest };

struct Options {
  double margin = 0.0;            ///< metres added to r_a + r_b (pairs) and to r (obstacles), ≥ 0
  double push_fraction = 0.1;     ///< separation added per push, as a fraction of the clearance, in (0, 1]
  ObstaclePull obstacle_pull = ObstaclePull::sideways;
  std::size_t max_iterations = 10000;  ///< solves at most, ≥ 1
  bool pin_ends = true;                ///< pin every trajectory's first and last present frame
  std::vector<std::int64_t> fixed_agents;  ///< ids of agents that must not move at all
  double spread = 15.0;               ///< frames over which a push fades along a trajectory (each side), ≥ 1
  double min_feature_length = 0.05;   ///< ℓ of the temporal feature weights (metres, throng/graph/features.h)
};

/// What the run did and what is left. Gaps are distance − radii (pairs) or signed distance − r (obstacles).
struct Report {
  std::size_t iterations = 0;          ///< solves
  std::size_t initial_pair_contacts = 0, initial_obstacle_contacts = 0;
  std::size_t pair_contacts = 0;       ///< remaining pairs closer than their clearance
  std::size_t obstacle_contacts = 0;   ///< remaining agent–obstacle contacts
  std::size_t stuck_contacts = 0;      ///< remaining contacts that no pin-free vertex can resolve
  std::size_t constraints = 0;         ///< pushed points over the whole run
  std::size_t moved_agents = 0;        ///< agents whose trajectory changed
  double min_pair_gap = 0;             ///< metres, smallest over the result (+∞ if no pair came near, see Contacts)
  double min_obstacle_gap = 0;         ///< metres, idem for obstacles
  bool converged = false;              ///< no contact left
  std::string stop_reason;             ///< "converged", "only stuck contacts left", "iteration cap reached"
  double detect_seconds = 0, solve_seconds = 0;
  std::vector<std::size_t> history;    ///< contacts (one per colliding frame interval) after each iteration
  int factorizations = 0;              ///< trajectories factorised (one factorisation each for the whole run)

  [[nodiscard]] std::size_t remaining() const noexcept { return pair_contacts + obstacle_contacts; }
};

struct Result {
  CrowdMotion crowd;  ///< the repaired crowd: same frames, agents, ids, radii, species; velocities dropped if anything moved
  Report report;
};

/// Repairs `crowd` among `obstacles`. Throws ConfigError for bad options (naming the option) or an unknown fixed
/// agent id, InputError for an invalid crowd. Does not throw when contacts remain (see the report).
[[nodiscard]] Result resolve_collisions(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Options& options,
                                        Progress& progress);

/// Checks option values; throws ConfigError naming the option.
void validate(const Options& options);

/// One line for logs and errors: "3 pairs and 1 obstacle contact remain after 200 iterations (iteration cap
/// reached); smallest pair gap -0.12 m".
[[nodiscard]] std::string summary(const Report& report);

}  // namespace throng::collide
