// The agent simulation of paper §5 (Eq. 14–22 as read in sketch.h): a two-buffer step, its neighbour searches over
// agents sorted by grid cell, TBB-parallel over ranges of agents. Each agent reads only the state at the step's
// start and writes only its own entries of the next state, so the result does not depend on the thread count.
#include <throng/core/errors.h>
#include <throng/core/obstacle.h>
#include <throng/core/parallel.h>
#include <throng/sketch/sketch.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <sstream>

#include "agent_repulsion.h"
#include "move_lanes.h"
#include "neighbour_grid.h"
#include "obstacle_field.h"

namespace throng::sketch {
namespace {

// Agents per parallel task.
constexpr std::size_t grain = 512;

constexpr std::uint8_t walking = static_cast<std::uint8_t>(AgentStatus::walking);
constexpr std::uint8_t arrived = static_cast<std::uint8_t>(AgentStatus::arrived);
constexpr std::uint8_t removed = static_cast<std::uint8_t>(AgentStatus::removed);

// The agents' state at one time: positions (metres), walking velocity (m/s, the direction filter's u; with the
// paper's rule the step's move over Δt), facing (a unit vector in the ground plane, sketch.h "Facing"), target
// index, status, and the side each agent goes round the obstacle it is sliding along (+1 left, −1 right, 0 none).
// Structure of arrays.
struct State {
  std::vector<double> x, y;
  std::vector<double> ux, uy;
  std::vector<double> hx, hy;
  std::vector<std::uint32_t> k;
  std::vector<std::uint8_t> status;
  std::vector<std::int8_t> side;
};

// What the next step needs to know about a state as a whole, gathered while the state is written (per task,
// merged under a lock: minima, maxima and counts are exact in any order, so the result is thread-independent).
struct Summary {
  std::size_t n_walking = 0, n_standing = 0;  // agents walking; agents arrived and still present
  double largest_avoidance = 0;               // max r over agents in the grid: the grid's cell size
  Eigen::AlignedBox2d bounds;                 // of the agents in the grid

  void add(std::uint8_t status, double x, double y, double r) {
    if (status == removed) return;
    (status == walking ? n_walking : n_standing) += 1;
    largest_avoidance = std::max(largest_avoidance, r);
    bounds.extend(Eigen::Vector2d(x, y));
  }
  void merge(const Summary& o) {
    n_walking += o.n_walking;
    n_standing += o.n_standing;
    largest_avoidance = std::max(largest_avoidance, o.largest_avoidance);
    bounds.extend(o.bounds);
  }
};

// The quaternion (x, y, z, w) of the yaw about +z that turns +x onto the ground direction (dx, dy) ≠ 0: facing_along's
// half-angle formula (no trigonometry), with a plain square root for the length (std::hypot costs more than the
// rest of the frame's work per agent).
void yaw_quaternion(double dx, double dy, double* q) {
  const double length = std::sqrt(dx * dx + dy * dy);
  const double c = dx / length, s = dy / length;
  q[0] = q[1] = 0.0;
  if (c >= 0) {
    const double norm = std::sqrt(2.0 * (1.0 + c));
    q[2] = s / norm;
    q[3] = (1.0 + c) / norm;
  } else {  // near a half turn: from u − x̂, which keeps its digits there
    const double norm = std::sqrt(2.0 * (1.0 - c));
    const double sign = s < 0 ? -1.0 : 1.0;
    q[2] = sign * (1.0 - c) / norm;
    q[3] = sign * s / norm;
  }
}

}  // namespace

struct Simulation::Impl {
  Course course;
  AgentParameters agents;
  Scene scene;
  Options options;
  std::size_t K = 0, A = 0, N = 0;

  // The course and the agents' parameters, flattened for the step.
  std::vector<double> main_x, main_y;               // K
  std::vector<double> offset_x, offset_y;           // K by A: V_{i,k}
  std::vector<double> speed, standard, correction;  // K
  std::vector<double> tangent_x, tangent_y;         // K: unit direction of the main line at k (central difference)
  std::vector<double> weight;                       // N by A: o_{j,i} of the auxiliary lines
  std::vector<double> draw;                         // N: u_j
  std::vector<double> end_x, end_y;                 // N: target(j, K − 1), each agent's end point

  std::array<State, 2> states;
  int current = 0;
  std::vector<double> arrival;        // N, seconds or NaN
  std::vector<std::uint8_t> in_grid;  // N, status != removed
  std::vector<double> fastest;        // N: fastest |u|² over the steps since the last take_pose (m²/s²)
  detail::NeighbourGrid grid;
  detail::ObstacleField obstacles;
  std::size_t steps = 0;
  std::atomic<std::size_t> unresolved{0};
  Summary summary;  // of now()
  std::mutex summary_lock;

  Impl(Course course_in, AgentParameters agents_in, Scene scene_in, Options options_in);

  [[nodiscard]] State& now() { return states[static_cast<std::size_t>(current)]; }
  [[nodiscard]] const State& now() const { return states[static_cast<std::size_t>(current)]; }
  [[nodiscard]] const State& previous() const { return states[static_cast<std::size_t>(1 - current)]; }
  [[nodiscard]] double time_at(std::size_t step) const { return static_cast<double>(step) * options.time_step_s; }

  // p'_{j,k} (Eq. 4).
  [[nodiscard]] Eigen::Vector2d target(std::uint32_t j, std::uint32_t k) const {
    double x = main_x[k], y = main_y[k];
    const double* w = weight.data() + static_cast<std::size_t>(j) * A;
    const double* ox = offset_x.data() + static_cast<std::size_t>(k) * A;
    const double* oy = offset_y.data() + static_cast<std::size_t>(k) * A;
    for (std::size_t i = 0; i < A; ++i) {
      x += w[i] * ox[i];
      y += w[i] * oy[i];
    }
    return {x, y};
  }
  // r_{j,k} (Eq. 15 as read).
  [[nodiscard]] double avoidance(std::uint32_t j, std::uint32_t k) const {
    return standard[k] * (1.0 + draw[j] * correction[k]);
  }

  // True when a standing (arrived) agent is closer than r to p (state at the step's start).
  [[nodiscard]] bool touches_standing(std::size_t slot, const Eigen::Vector2d& p, double r) const;
  // Advances agents [begin, end) from `now` into `next` over [t0, t1]. Writes only those
  // agents' entries of `next`, `arrival`, `fastest` and `in_grid`; adds their obstacle contacts left unresolved
  // to `failures` and their states to `gathered`.
  void advance(std::size_t begin, std::size_t end, double t0, double t1, State& next, std::size_t& failures,
               Summary& gathered);

  // Rebuilds the neighbour grid and the obstacle lists for a step over [t0, t1].
  void rebuild(double t0, double t1);
  // The summary and in_grid of the current state, serially (the constructor; steps gather it as they go).
  void summarise();
  // Target advancement: while the agent at p is within R of its target, has passed it (is ahead of the line
  // through the target across the path), or the target lies in an obstacle at time t (where no agent can reach
  // it), the target moves on. True when that happens at the last point.
  // `goal` is target(j, k) (the step computed it for the force).
  [[nodiscard]] bool reach_targets(std::uint32_t j, const Eigen::Vector2d& p, std::uint32_t& k, double t,
                                   Eigen::Vector2d goal) const {
    const double R2 = options.follow_radius_m * options.follow_radius_m;
    for (;;) {
      const Eigen::Vector2d d = p - goal;
      const bool reached = d.squaredNorm() <= R2 || d.x() * tangent_x[k] + d.y() * tangent_y[k] > 0 ||
                           (!obstacles.empty() && obstacles.overlaps(goal, t));
      if (!reached) return false;
      if (k + 1 == K) return true;
      goal = target(j, ++k);
    }
  }

  void step();
};

Simulation::Impl::Impl(Course course_in, AgentParameters agents_in, Scene scene_in, Options options_in)
    : course(std::move(course_in)),
      agents(std::move(agents_in)),
      scene(std::move(scene_in)),
      options(options_in),
      obstacles(scene, options.agent_radius_m, options.obstacle_distance_m, options.slide_around_obstacles) {
  validate(options);
  scene.validate("sketch scene");
  K = course.point_count();
  A = course.auxiliary_count();
  N = agents.agent_count();
  if (K < 2 || A < 1 || course.speed.size() != K || course.standard_distance.size() != K ||
      course.correction_scale.size() != K) {
    throw InputError(
        "sketch: the course is incomplete (expected at least 2 points, one auxiliary line and one "
        "speed, standard distance and correction per point; build it with analyse_strokes)");
  }
  if (static_cast<std::size_t>(agents.weights.rows()) != N ||
      static_cast<std::size_t>(agents.weights.cols()) != A + 1 || agents.correction_draw.size() != N ||
      agents.first_target.size() != N) {
    throw InputError("sketch: agent parameters disagree with " + std::to_string(N) + " agents and " +
                     std::to_string(A + 1) + " strokes (build them with agent_parameters or place_agents)");
  }
  // The neighbour grid's slots, and its searches' reads a few past them, are 32-bit.
  if (N >= std::numeric_limits<std::uint32_t>::max() - 16) throw InputError("sketch: too many agents");

  main_x.resize(K);
  main_y.resize(K);
  offset_x.resize(K * A);
  offset_y.resize(K * A);
  for (std::size_t k = 0; k < K; ++k) {
    main_x[k] = course.main[k].x();
    main_y[k] = course.main[k].y();
    for (std::size_t i = 0; i < A; ++i) {
      const Eigen::Vector2d v = course.offset(i, k);
      offset_x[k * A + i] = v.x();
      offset_y[k * A + i] = v.y();
    }
  }
  speed = course.speed;
  // Filtered, with an acceleration bound: agents brake for obstacles from the stopping distance at the fastest
  // closing speed (walking plus the fastest obstacle), plus one step's move (see the braking in advance()).
  if (options.direction_filter_s > 0 && options.max_acceleration_m_s2 > 0 && !scene.obstacles.empty()) {
    const double v = *std::max_element(speed.begin(), speed.end()) + obstacles.fastest_boundary_speed();
    obstacles.look_ahead(v * v / (2.0 * options.max_acceleration_m_s2) + v * options.time_step_s);
  }
  tangent_x.resize(K);
  tangent_y.resize(K);
  for (std::size_t k = 0; k < K; ++k) {
    Eigen::Vector2d t = course.main[std::min(k + 1, K - 1)] - course.main[k > 0 ? k - 1 : 0];
    if (t.squaredNorm() == 0) t = k + 1 < K ? course.main[k + 1] - course.main[k] : course.main[k] - course.main[k - 1];
    t.normalize();
    tangent_x[k] = t.x();
    tangent_y[k] = t.y();
  }
  standard = course.standard_distance;
  correction = course.correction_scale;
  weight.resize(N * A);
  for (std::size_t j = 0; j < N; ++j) {
    for (std::size_t i = 0; i < A; ++i) {
      weight[j * A + i] = agents.weights(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i + 1));
    }
  }
  draw = agents.correction_draw;
  end_x.resize(N);
  end_y.resize(N);
  for (std::uint32_t j = 0; j < N; ++j) {
    const Eigen::Vector2d end = target(j, static_cast<std::uint32_t>(K - 1));
    end_x[j] = end.x();
    end_y[j] = end.y();
  }

  State& s0 = now();
  s0.x.resize(N);
  s0.y.resize(N);
  s0.ux.assign(N, 0.0);
  s0.uy.assign(N, 0.0);
  s0.hx.assign(N, 1.0);
  s0.hy.assign(N, 0.0);
  s0.k.resize(N);
  s0.status.assign(N, walking);
  s0.side.assign(N, 0);
  arrival.assign(N, std::numeric_limits<double>::quiet_NaN());
  fastest.assign(N, 0.0);
  in_grid.assign(N, 1);
  for (std::size_t j = 0; j < N; ++j) {
    s0.x[j] = agents.start[j].x();
    s0.y[j] = agents.start[j].y();
    if (agents.first_target[j] >= K) {
      throw InputError("sketch: agent " + std::to_string(j) + " first target " +
                       std::to_string(agents.first_target[j]) + " is past the course's " + std::to_string(K) +
                       " points");
    }
    s0.k[j] = static_cast<std::uint32_t>(agents.first_target[j]);
  }

  // Starting positions: a centre inside an obstacle is an input error; an overlapping body is pushed out.
  summarise();
  rebuild(0.0, 0.0);
  for (std::uint32_t j = 0; j < N; ++j) {
    Eigen::Vector2d p(s0.x[j], s0.y[j]);
    for (std::size_t o = 0; o < scene.obstacles.size(); ++o) {
      const double d = distance_to(scene.obstacles[o], p, 0.0).signed_distance;
      if (d < 0) {
        std::ostringstream m;
        m << "sketch: agent " << j << " starts at (" << p.x() << ", " << p.y() << ") inside obstacle " << o;
        if (!scene.obstacles[o].name.empty()) m << " ('" << scene.obstacles[o].name << "')";
        m << ", " << -d << " m from its boundary; start agents outside obstacles";
        throw InputError(m.str());
      }
    }
    if (!obstacles.empty() && !obstacles.keep_clear(p, p, 0.0)) ++unresolved;
    s0.x[j] = p.x();
    s0.y[j] = p.y();
    if (reach_targets(j, p, s0.k[j], 0.0, target(j, s0.k[j]))) {
      s0.status[j] = arrived;
      arrival[j] = 0.0;
    }
    // The first facing: toward the first target (where the agent is about to walk), along the course at it.
    const Eigen::Vector2d ahead = target(j, s0.k[j]) - p;
    const Eigen::Vector2d facing =
        ahead.squaredNorm() > 1e-18 ? ahead.normalized() : Eigen::Vector2d(tangent_x[s0.k[j]], tangent_y[s0.k[j]]);
    s0.hx[j] = facing.x();
    s0.hy[j] = facing.y();
  }
  summarise();
  states[1] = s0;
}

void Simulation::Impl::summarise() {
  const State& s = now();
  summary = Summary{};
  for (std::uint32_t j = 0; j < N; ++j) {
    in_grid[j] = s.status[j] != removed;
    summary.add(s.status[j], s.x[j], s.y[j], avoidance(j, s.k[j]));
  }
}

void Simulation::Impl::rebuild(double t0, double t1) {
  const State& s = now();
  // With avoidance off, cells only serve the obstacle lists: any size works, use the follow radius.
  const double cell =
      options.avoid_weight > 0 && summary.largest_avoidance > 0 ? summary.largest_avoidance : options.follow_radius_m;
  grid.build(s.x, s.y, in_grid, summary.n_walking + summary.n_standing, summary.bounds, cell);
  obstacles.rebuild(grid, t0, t1);
}

bool Simulation::Impl::touches_standing(std::size_t slot, const Eigen::Vector2d& p, double r) const {
  const State& s = now();
  const std::uint32_t* order = grid.order().data();
  const double* sx = grid.sorted_x().data();
  const double* sy = grid.sorted_y().data();
  const std::size_t nx = grid.columns(), ny = grid.rows();
  const std::size_t cx = grid.column(p.x()), cy = grid.row(p.y());
  const std::size_t c0 = cx > 0 ? cx - 1 : 0, c1 = std::min(cx + 1, nx - 1);
  for (std::size_t row = cy > 0 ? cy - 1 : 0; row <= std::min(cy + 1, ny - 1); ++row) {
    const std::uint32_t from = grid.cell_start(row * nx + c0), to = grid.cell_start(row * nx + c1 + 1);
    for (std::uint32_t l = from; l < to; ++l) {
      if (l == slot || s.status[order[l]] != arrived) continue;
      const double dx = p.x() - sx[l], dy = p.y() - sy[l];
      if (dx * dx + dy * dy < r * r) return true;
    }
  }
  return false;
}

void Simulation::Impl::advance(std::size_t begin, std::size_t end, double t0, double t1, State& next,
                               std::size_t& failures, Summary& gathered) {
  const State& s = now();
  const std::uint32_t* slot_of = grid.slot_of().data();
  const double R = options.follow_radius_m;
  const double w_traj = options.trajectory_weight, w_avoid = options.avoid_weight, w_block = options.obstacle_weight;
  const double dt = options.time_step_s;
  const bool filtered = options.direction_filter_s > 0;
  // A change of the walking velocity over one step is at most max_acceleration Δt long (sketch.h).
  const detail::MoveConstants constants{dt,
                                        filtered,
                                        filtered ? -std::expm1(-dt / options.direction_filter_s) : 1.0,
                                        options.max_acceleration_m_s2 > 0 ? options.max_acceleration_m_s2 * dt : 0.0,
                                        -std::expm1(-dt / facing_filter_s),
                                        std::cos(facing_turn_rate_rad_s * dt),
                                        std::sin(facing_turn_rate_rad_s * dt),
                                        facing_standing_speed_m_s};
  const detail::MoveLanes& lanes = detail::move_lanes();
  const bool has_obstacles = !obstacles.empty();
  // Filtered, with an acceleration bound: the walking velocity wanted is slowed toward obstacles ahead so the agent
  // can stop short of them at max_acceleration, and steps aside for moving ones: without it, an agent walking at
  // an obstacle turns only within obstacle_distance of it and keep_clear stops it dead at the boundary (10.7 m/s²
  // measured on sketch-large at its pillars), and a cart shoves it.
  const bool braking = filtered && constants.largest_change > 0 && has_obstacles;
  const bool remove_at_end = options.end_of_path == EndOfPath::remove;
  // The crowd standing at the end covers about a disc of this radius around the end (hexagonal packing at the
  // last standard distance): walking agents that reach it, R beyond, join it (EndOfPath::stop).
  const double standing_area = static_cast<double>(summary.n_standing) * standard[K - 1] * standard[K - 1] * 0.8660254;
  const double end_reach = remove_at_end ? 0.0 : R + std::sqrt(standing_area / std::numbers::pi);

  // Agents go by index, not by grid slot: a task's writes to the next state are then one run of each array, where
  // in slot order (the grid's, which follows the agents' places, not their indices) both cores wrote into the same
  // cache lines wherever indices and places disagree (bench/sketch BM_LargeCrowd, 2,000 agents entering over time,
  // on 2 threads: 254-267 -> 193-201 ms, 1.4 times one thread's speed instead of 1.1; the same bits).
  // They go in blocks of 64 through four passes: the forces (neighbour and obstacle searches, branchy),
  // the moves, the facings, then the targets. A move and a facing are each a chain of square roots and divisions
  // per agent: in short loops of their own the processor overlaps several agents' chains, where in one loop with
  // the searches it could not (bench/sketch BM_Step, 10,000 agents on 1 thread: 293 → 209 ms), and four agents
  // share each vector operation (move_lanes.h). Each pass does for an agent the same operations in the same order
  // as one loop over the agents would (each pass reads only the state at the step's start, the grid and the
  // block's own entries), so the bits do not depend on how the agents are cut into tasks.
  using detail::MoveKind;
  detail::MoveBlock block;
  constexpr std::size_t block_size = detail::MoveBlock::size;
  std::array<double, block_size> gx{}, gy{};    // the target (walking), pass 1
  std::array<std::int8_t, block_size> sides{};  // the side round an obstacle (walking), pass 1
  for (std::size_t first = begin; first < end; first += block_size) {
    const std::size_t count = std::min(block_size, end - first);

    // 1. The force on each walking agent (Eq. 14–20) and the overlap of each standing one.
    for (std::size_t i = 0; i < count; ++i) {
      const auto j = static_cast<std::uint32_t>(first + i);
      const std::size_t slot = slot_of[j];
      const Eigen::Vector2d p(s.x[j], s.y[j]);
      const std::uint32_t k = s.k[j];
      Eigen::Vector2d force = Eigen::Vector2d::Zero();
      sides[i] = 0;
      MoveKind kind = MoveKind::stay;  // removed, or arrived with EndOfPath::remove (removed in pass 4)
      if (s.status[j] == walking) {
        kind = MoveKind::along_force;
        // Eq. 14: pull toward the target beyond R.
        const Eigen::Vector2d goal = target(j, k);
        gx[i] = goal.x();
        gy[i] = goal.y();
        const Eigen::Vector2d to_goal = goal - p;
        const double dist = to_goal.norm();
        Eigen::Vector2d pull = Eigen::Vector2d::Zero();
        if (dist > R) pull = (w_traj * (1.0 - R / dist)) * to_goal;
        // Eq. 18–19 generalised, with the pull slid along obstacles it points into.
        Eigen::Vector2d block_push = Eigen::Vector2d::Zero();
        if (has_obstacles && w_block > 0) {
          const detail::ObstacleResponse r = obstacles.respond(p, t0, pull, Eigen::Vector2d(tangent_x[k], tangent_y[k]),
                                                               Eigen::Vector2d(main_x[k], main_y[k]), s.side[j], j);
          pull = r.pull;
          block_push = r.push;
          sides[i] = r.side;
        }
        // Eq. 16–17 (repulsion sign as read) and Eq. 20.
        force = pull + w_block * block_push;
        if (w_avoid > 0) force += w_avoid * detail::agent_repulsion(grid, slot, p, avoidance(j, k));
      } else if (s.status[j] == arrived && !remove_at_end) {
        kind = MoveKind::make_room;
        // Standing agents make room: half their overlap with agents and obstacles, at most v Δt (see sketch.h).
        if (w_avoid > 0) force += detail::agent_repulsion(grid, slot, p, avoidance(j, k));
        if (has_obstacles && w_block > 0) force += obstacles.push(p, t0);
      }
      block.kind[i] = static_cast<std::int64_t>(kind);
      block.fx[i] = force.x();
      block.fy[i] = force.y();
      block.speed[i] = speed[k];
      block.px[i] = p.x();
      block.py[i] = p.y();
      block.ux[i] = s.ux[j];
      block.uy[i] = s.uy[j];
      block.hx[i] = s.hx[j];
      block.hy[i] = s.hy[j];
      block.fastest[i] = fastest[j];
    }

    // 2. The move (Eq. 21–22, filtered as in sketch.h), kept clear of obstacles.
    lanes.wanted_velocities(constants, block, count);
    if (braking) {
      for (std::size_t i = 0; i < count; ++i) {
        if (block.kind[i] == static_cast<std::int64_t>(MoveKind::stay)) continue;
        const Eigen::Vector2d u = obstacles.brake(Eigen::Vector2d(block.px[i], block.py[i]), t0, t1,
                                                  Eigen::Vector2d(block.wx[i], block.wy[i]), options.max_acceleration_m_s2);
        block.wx[i] = u.x();
        block.wy[i] = u.y();
      }
    }
    lanes.moved_places(constants, block, count);
    if (has_obstacles) {
      for (std::size_t i = 0; i < count; ++i) {
        if (block.kind[i] == static_cast<std::int64_t>(MoveKind::stay)) continue;
        Eigen::Vector2d q(block.qx[i], block.qy[i]);
        if (!obstacles.keep_clear(Eigen::Vector2d(block.px[i], block.py[i]), q, t1)) ++failures;
        block.qx[i] = q.x();
        block.qy[i] = q.y();
      }
    }

    // 3. The step's velocity (filtered: the walking velocity; the paper's rule: the move over Δt) and facing.
    lanes.velocities_and_facings(constants, block, count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t j = first + i;
      next.x[j] = block.qx[i];
      next.y[j] = block.qy[i];
      next.ux[j] = block.vx[i];
      next.uy[j] = block.vy[i];
      next.hx[j] = block.nx[i];
      next.hy[j] = block.ny[i];
      fastest[j] = block.fastest[i];  // agent j's own entry: no other task writes it
    }

    // 4. Target advancement (after the move, as in the paper; plus "passed", see sketch.h). With
    // EndOfPath::stop, an agent also stops on reaching the crowd standing at the end (see sketch.h).
    for (std::size_t i = 0; i < count; ++i) {
      const auto j = static_cast<std::uint32_t>(first + i);
      const std::size_t slot = slot_of[j];
      std::uint32_t k = s.k[j];
      std::uint8_t status = s.status[j];
      const Eigen::Vector2d q(block.qx[i], block.qy[i]);
      if (status == walking) {
        bool joins = false;
        if (end_reach > R) {
          const double to_end = (Eigen::Vector2d(end_x[j], end_y[j]) - q).norm();
          joins = to_end <= end_reach ||
                  (to_end <= 2 * end_reach && touches_standing(slot, Eigen::Vector2d(s.x[j], s.y[j]), avoidance(j, k)));
        }
        if (reach_targets(j, q, k, t1, Eigen::Vector2d(gx[i], gy[i])) || joins) {
          k = static_cast<std::uint32_t>(K - 1);
          status = arrived;
          arrival[j] = t1;  // agent j's own entry: no other task writes it
        }
      } else if (status == arrived && remove_at_end) {
        status = removed;
      }
      next.k[j] = k;
      next.status[j] = status;
      next.side[j] = sides[i];
      in_grid[j] = status != removed;
      gathered.add(status, q.x(), q.y(), avoidance(j, k));
    }
  }
}

void Simulation::Impl::step() {
  const double t0 = time_at(steps), t1 = time_at(steps + 1);
  rebuild(t0, t1);
  State& next = states[static_cast<std::size_t>(1 - current)];
  Summary merged;
  parallel_for(N, grain, [&](std::size_t begin, std::size_t end) {
    std::size_t failures = 0;
    Summary gathered;
    advance(begin, end, t0, t1, next, failures, gathered);
    if (failures > 0) unresolved += failures;
    const std::lock_guard<std::mutex> hold(summary_lock);
    merged.merge(gathered);
  });
  summary = merged;
  current = 1 - current;
  ++steps;
}

// --- Simulation ---

Simulation::Simulation(Course course, AgentParameters agents, Scene scene, Options options)
    : impl_(std::make_unique<Impl>(std::move(course), std::move(agents), std::move(scene), options)) {}
Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

void Simulation::step() { impl_->step(); }
std::size_t Simulation::agent_count() const noexcept { return impl_->N; }
std::size_t Simulation::step_count() const noexcept { return impl_->steps; }
double Simulation::time() const noexcept { return impl_->time_at(impl_->steps); }
bool Simulation::finished() const noexcept {
  return impl_->summary.n_walking == 0 &&
         (impl_->options.end_of_path == EndOfPath::stop || impl_->summary.n_standing == 0);
}
Eigen::Vector2d Simulation::position(std::size_t agent) const {
  assert(agent < impl_->N);
  return {impl_->now().x[agent], impl_->now().y[agent]};
}
AgentStatus Simulation::status(std::size_t agent) const {
  assert(agent < impl_->N);
  return static_cast<AgentStatus>(impl_->now().status[agent]);
}
std::size_t Simulation::target_index(std::size_t agent) const {
  assert(agent < impl_->N);
  return impl_->now().k[agent];
}
double Simulation::arrival_time(std::size_t agent) const {
  assert(agent < impl_->N);
  return impl_->arrival[agent];
}
double Simulation::path_fraction() const {
  const Impl& m = *impl_;
  if (m.N == 0) return 1.0;
  const State& s = m.now();
  const double last = static_cast<double>(m.K - 1);
  double sum = 0;
  for (std::size_t j = 0; j < m.N; ++j) sum += s.status[j] == walking ? static_cast<double>(s.k[j]) / last : 1.0;
  return sum / static_cast<double>(m.N);
}
std::size_t Simulation::unresolved_obstacle_contacts() const noexcept { return impl_->unresolved.load(); }
const Course& Simulation::course() const noexcept { return impl_->course; }
const AgentParameters& Simulation::agents() const noexcept { return impl_->agents; }

void Simulation::sample(double time, std::span<double> frame) const {
  const Impl& m = *impl_;
  assert(frame.size() == 3 * m.N);
  const State& a = m.previous();
  const State& b = m.now();
  const double t1 = this->time();
  const double alpha =
      m.steps == 0 ? 1.0 : std::clamp((time - (t1 - m.options.time_step_s)) / m.options.time_step_s, 0.0, 1.0);
  parallel_for(m.N, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j) {
      double* out = frame.data() + 3 * j;
      if (b.status[j] != removed) {
        out[0] = (1 - alpha) * a.x[j] + alpha * b.x[j];
        out[1] = (1 - alpha) * a.y[j] + alpha * b.y[j];
        out[2] = 0.0;
      } else if (alpha == 0.0 && a.status[j] != removed) {
        out[0] = a.x[j];
        out[1] = a.y[j];
        out[2] = 0.0;
      } else {
        out[0] = out[1] = out[2] = std::numeric_limits<double>::quiet_NaN();
      }
    }
  });
}

}  // namespace throng::sketch

namespace throng::sketch {

void Simulation::take_pose(double time, std::span<double> orientations, std::span<std::int32_t> actions) {
  Impl& m = *impl_;
  assert(orientations.size() == 4 * m.N && actions.size() == m.N);
  const State& a = m.previous();
  const State& b = m.now();
  const double t1 = this->time();
  const double alpha =
      m.steps == 0 ? 1.0 : std::clamp((time - (t1 - m.options.time_step_s)) / m.options.time_step_s, 0.0, 1.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto pose = [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j) {
      double* q = orientations.data() + 4 * j;
      const bool present = b.status[j] != removed || (alpha == 0.0 && a.status[j] != removed);
      if (!present) {
        q[0] = q[1] = q[2] = q[3] = nan;
        actions[j] = -1;
        m.fastest[j] = 0.0;
        continue;
      }
      // Between the step's facings (at most the largest turn apart) along the shorter arc, as the normalised
      // blend; the same facing at both ends is kept exactly.
      const bool same = a.hx[j] == b.hx[j] && a.hy[j] == b.hy[j];
      const double dx = same ? b.hx[j] : (1 - alpha) * a.hx[j] + alpha * b.hx[j];
      const double dy = same ? b.hy[j] : (1 - alpha) * a.hy[j] + alpha * b.hy[j];
      yaw_quaternion(dx, dy, q);
      // The fastest walking speed over the steps since the previous frame taken (sketch.h "Facing and actions");
      // the next frame's interval starts within the current step, so its speed starts the next maximum.
      const double speed2 = m.fastest[j];
      const double stand2 = facing_standing_speed_m_s * facing_standing_speed_m_s, run2 = running_speed_m_s * running_speed_m_s;
      actions[j] = speed2 < stand2 ? action_stand : speed2 >= run2 ? action_run : action_walk;
      m.fastest[j] = b.ux[j] * b.ux[j] + b.uy[j] * b.uy[j];
    }
  };
  // One task's worth is done here: a small crowd's frames would otherwise pay a parallel launch each.
  if (m.N <= 4096) {
    pose(0, m.N);
  } else {
    parallel_for(m.N, 4096, pose);
  }
}

}  // namespace throng::sketch
