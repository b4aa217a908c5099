// The repair loop of collide.h: detect, choose disjoint pushable contacts, push, deform each touched trajectory.
#include "track_solver.h"

#include <throng/core/timer.h>
#include <throng/collide/collide.h>
#include <throng/collide/schema.h>
#include <throng/collide/contact_tracker.h>
#include <throng/core/errors.h>
#include <throng/core/facing_carry.h>
#include <throng/core/format.h>
#include <throng/core/parallel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <tuple>

namespace throng::collide {
namespace {

using Vec = Eigen::Vector2d;
using Clock = std::chrono::steady_clock;
using Displacement = Eigen::Matrix<double, Eigen::Dynamic, 2>;

// The contact tracker's skin (contact_tracker.h), metres. A push separates a pair by a tenth of its clearance
// (0.05 m for two 0.25 m agents), so a segment leaves its registered box after a few pushes; measured on the configs (BM_Config, one
// thread): 0.1 m and 0.2 m within 10 % of 0.15 m, 0.3 m 25-45 % slower (more neighbours to examine per moved
// segment), 0.5 m 50-75 % slower.
constexpr double tracker_skin = 0.15;

// A deformation of which less than this fraction fits within the limits is dropped (collide.h "Limits"): its
// contact could only creep, and a contact that creeps never stops making progress.
constexpr double min_step = 0.05;

// One contact interval across iterations: (kind, agent or a, b or obstacle, interval).
using ContactKey = std::tuple<int, std::size_t, std::size_t, std::size_t>;

// A run of consecutive present frames of one agent, and its solver (made when first pushed, on the rank that
// solves the track).
struct Track {
  std::size_t agent = 0, first = 0, length = 0;
  double interval_s = 0;  // mean frame interval
  std::vector<char> pinned;
  std::unique_ptr<TrackSolver> solver;
  std::vector<PointConstraint> constraints;  // this iteration's
  std::vector<ContactKey> pushed_by;         // the contacts behind them
};

// How pushing one contact interval has gone.
struct ContactHistory {
  double best_deficit = std::numeric_limits<double>::infinity();
  std::size_t pushes_since_best = 0;
  bool abandoned = false;
  bool held[2] = {false, false};  // pairs: agent a's, b's deformation found no room within the limits
};

class Repair {
 public:
  Repair(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Options& options,
         const Communicator& communicator)
      : input_(crowd), crowd_(crowd), obstacles_(obstacles), options_(options), frames_(crowd.frame_count()),
        agents_(crowd.agent_count()), communicator_(communicator), ranks_(communicator.size()), rank_(communicator.rank()) {
    make_tracks();
    make_limits();
  }

  Result run(Progress& progress) {
    Result result;
    Report& report = result.report;
    report.ranks = ranks_;
    auto start = Clock::now();
    ContactTracker tracker(crowd_, obstacles_, options_.margin, tracker_skin);
    const Contacts& contacts = tracker.contacts();
    report.detect_seconds += seconds_since(start);
    report.initial_pair_contacts = contacts.pair_count();
    report.initial_obstacle_contacts = contacts.obstacle_count();
    const double initial = std::max<double>(1.0, static_cast<double>(contacts.size()));
    double fraction = 0.0;
    std::vector<char> moved_ever(agents_, 0);
    std::size_t fewest = std::numeric_limits<std::size_t>::max(), fewest_at = 0;
    report.stop_reason = "converged";
    while (contacts.size() > 0) {
      if (report.iterations >= options_.max_iterations) {
        report.stop_reason = "iteration cap reached";
        break;
      }
      std::vector<char> moved(agents_, 0);
      std::size_t pushable = 0;
      const std::size_t taken = choose(contacts, moved, pushable);
      if (taken == 0) {
        report.stop_reason = "only stuck or abandoned contacts left";
        break;
      }
      if (pushable < fewest) {
        fewest = pushable;
        fewest_at = report.iterations;
      } else if (report.iterations - fewest_at >= options_.stall_iterations) {
        for (Track& t : tracks_) {
          t.constraints.clear();
          t.pushed_by.clear();
        }
        report.stop_reason = "no progress";
        break;
      }
      report.constraints += taken;
      start = Clock::now();
      deform();
      report.solve_seconds += seconds_since(start);
      ++report.iterations;
      for (std::size_t a = 0; a < agents_; ++a) moved_ever[a] = static_cast<char>(moved_ever[a] | moved[a]);
      start = Clock::now();
      tracker.update(crowd_, moved);
      report.detect_seconds += seconds_since(start);
      report.history.push_back(contacts.size());
      fraction = std::max({fraction, static_cast<double>(report.iterations) / static_cast<double>(options_.max_iterations),
                           1.0 - static_cast<double>(contacts.size()) / initial});
      progress.update(std::min(fraction, 1.0), "collide");
    }
    // The final state: the tracker's contacts are those of the current positions (every deformation was followed
    // by an update), exactly what a full search reports (contact_tracker.h); the gaps are searched afresh.
    start = Clock::now();
    const Contacts& final_contacts = tracker.contacts();
    report.pair_contacts = final_contacts.pair_count();
    report.obstacle_contacts = final_contacts.obstacle_count();
    report.converged = final_contacts.size() == 0;
    if (report.converged) report.stop_reason = "converged";
    classify_remaining(final_contacts, report);
    const Gaps gaps = exact_gaps();
    report.min_pair_gap = gaps.pair;
    report.min_obstacle_gap = gaps.obstacle;
    report.detect_seconds += seconds_since(start);
    report.moved_agents = static_cast<std::size_t>(std::count(moved_ever.begin(), moved_ever.end(), 1));
    report.factorizations = static_cast<int>(ranks_ > 1 ? communicator_.sum(factorizations_) : factorizations_);
    report.max_displacement = largest_displacement();
    report.limited_steps = limited_steps_;
    report.held_steps = held_steps_;
    report.input_motion = motion_stats(input_);
    report.output_motion = motion_stats(crowd_);
    result.crowd = crowd_;
    if (report.moved_agents > 0) result.crowd.velocities.clear();
    // Facing and actions: carried along the repaired paths (throng/core/facing_carry.h; collide.h "Facing").
    carry_facing_same_frames(input_, result.crowd, changed_agents());
    progress.update(1.0, "collide");
    return result;
  }

 private:
  // The agents whose positions differ from the input's at some frame (on every rank: the whole crowd is here).
  [[nodiscard]] std::vector<std::size_t> changed_agents() const {
    std::vector<std::size_t> changed;
    for (std::size_t a = 0; a < agents_; ++a) {
      for (std::size_t f = 0; f < frames_; ++f) {
        if (input_.present(f, a) && input_.position(f, a) != crowd_.position(f, a)) {
          changed.push_back(a);
          break;
        }
      }
    }
    return changed;
  }

  // --- tracks and pins ---
  void make_tracks() {
    std::vector<char> fixed(agents_, 0);
    for (std::int64_t id : options_.fixed_agents) {
      const auto it = std::find(crowd_.ids.begin(), crowd_.ids.end(), id);
      if (it == crowd_.ids.end()) {
        throw ConfigError("fixed_agents: agent " + std::to_string(id) + " is not in the crowd");
      }
      fixed[static_cast<std::size_t>(it - crowd_.ids.begin())] = 1;
    }
    track_of_.assign(agents_ * frames_, -1);
    for (std::size_t a = 0; a < agents_; ++a) {
      for (std::size_t f = 0; f < frames_;) {
        if (!crowd_.present(f, a)) {
          ++f;
          continue;
        }
        Track t;
        t.agent = a;
        t.first = f;
        while (f < frames_ && crowd_.present(f, a)) {
          track_of_[a * frames_ + f] = static_cast<int>(tracks_.size());
          ++f;
        }
        t.length = f - t.first;
        t.interval_s = t.length > 1 ? (crowd_.times[f - 1] - crowd_.times[t.first]) / static_cast<double>(t.length - 1) : 1.0;
        t.pinned.assign(t.length, fixed[a]);
        if (options_.pin_ends) {
          t.pinned.front() = 1;
          t.pinned.back() = 1;
        }
        tracks_.push_back(std::move(t));
      }
    }
  }

  // --- limits (collide.h "Limits") ---
  void make_limits() {
    speed_limit_ = options_.max_speed_ratio * motion_stats(input_).max_speed;
    if (options_.max_acceleration > 0) {
      input_acceleration_.assign(frames_ * agents_, 0.0);
      for (std::size_t a = 0; a < agents_; ++a) {
        for (std::size_t f = 1; f + 1 < frames_; ++f) {
          if (input_.present(f - 1, a) && input_.present(f, a) && input_.present(f + 1, a)) {
            input_acceleration_[a * frames_ + f] = acceleration(input_, a, f, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                                               Eigen::Vector3d::Zero()).norm();
          }
        }
      }
    }
  }
  double bound(std::size_t agent) const {
    return options_.max_displacement > 0 ? options_.max_displacement : 8.0 * input_.radii[agent];
  }
  // (p_{f+1} + d1 − p_f − d0) / Δt
  static Eigen::Vector3d velocity(const CrowdMotion& c, std::size_t a, std::size_t f, const Eigen::Vector3d& d0,
                                  const Eigen::Vector3d& d1) {
    return (c.position(f + 1, a) + d1 - c.position(f, a) - d0) / (c.times[f + 1] - c.times[f]);
  }
  // Central second difference at frame f with the three displacements added.
  static Eigen::Vector3d acceleration(const CrowdMotion& c, std::size_t a, std::size_t f, const Eigen::Vector3d& d0,
                                      const Eigen::Vector3d& d1, const Eigen::Vector3d& d2) {
    return (velocity(c, a, f, d1, d2) - velocity(c, a, f - 1, d0, d1)) / (0.5 * (c.times[f + 1] - c.times[f - 1]));
  }

  // The largest α in [0, 1] such that moving track t by α·d keeps every vertex within its displacement bound,
  // every speed within speed_limit_ and every acceleration within max(max_acceleration, the input's there): each
  // condition is |x + α y| ≤ L with x, y vectors of the current state and of d, a quadratic in α that holds at
  // α = 0, so its larger root bounds α.
  double admissible_step(const Track& t, const Displacement& d) const {
    double alpha = 1.0;
    auto keep = [&alpha](const Eigen::Vector3d& x, const Eigen::Vector3d& y, double limit) {
      const double yy = y.squaredNorm(), c = x.squaredNorm() - limit * limit;
      if (yy == 0.0) return;
      if (c > 1e-12 * limit * limit) {  // already at the limit (rounding): no room
        alpha = 0.0;
        return;
      }
      const double xy = x.dot(y);
      alpha = std::min(alpha, (-xy + std::sqrt(std::max(0.0, xy * xy - yy * std::min(c, 0.0)))) / yy);
    };
    auto move = [&](std::size_t j) {
      return Eigen::Vector3d(d(static_cast<Eigen::Index>(j), 0), d(static_cast<Eigen::Index>(j), 1), 0.0);
    };
    const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
    const double limit = bound(t.agent);
    for (std::size_t j = 0; j < t.length; ++j) {
      const Vec o = offset_from_input(t.first + j, t.agent);
      keep(Eigen::Vector3d(o.x(), o.y(), 0.0), move(j), limit);
    }
    if (speed_limit_ > 0) {
      for (std::size_t j = 0; j + 1 < t.length; ++j) {
        const std::size_t f = t.first + j;
        const Eigen::Vector3d now = velocity(crowd_, t.agent, f, zero, zero);
        keep(now, velocity(crowd_, t.agent, f, move(j), move(j + 1)) - now, (1 - 1e-6) * speed_limit_);  // strictly within
      }
    }
    if (!input_acceleration_.empty()) {
      for (std::size_t j = 1; j + 1 < t.length; ++j) {
        const std::size_t f = t.first + j;
        const Eigen::Vector3d now = acceleration(crowd_, t.agent, f, zero, zero, zero);
        const Eigen::Vector3d change = acceleration(crowd_, t.agent, f, move(j - 1), move(j), move(j + 1)) - now;
        // A rounding-sized slack: a push changes every frame of the track a little, and a frame already at the
        // limit (the input's own, beyond max_acceleration) would otherwise hold the whole track.
        const double own = input_acceleration_[t.agent * frames_ + f];
        keep(now, change, (1 + 1e-3) * std::max(options_.max_acceleration, own));
      }
    }
    return std::max(alpha, 0.0);
  }

  Vec at(std::size_t frame, std::size_t agent) const {
    const double* p = crowd_.positions.data() + crowd_.index(frame, agent);
    return {p[0], p[1]};
  }
  Vec offset_from_input(std::size_t frame, std::size_t agent) const {
    const double *p = crowd_.positions.data() + crowd_.index(frame, agent), *q = input_.positions.data() + input_.index(frame, agent);
    return {p[0] - q[0], p[1] - q[1]};
  }

  bool pinned(std::size_t agent, std::size_t frame) const {
    const Track& t = tracks_[static_cast<std::size_t>(track_of_[agent * frames_ + frame])];
    return t.pinned[frame - t.first] != 0;
  }

  // How the point at fraction s of interval i of an agent moves: the constraint's vertices and coefficients, and
  // the factor its displacement is scaled by; movable = false when no free vertex carries it.
  struct Mover {
    bool movable = false;
    int track = -1;
    PointConstraint constraint;
    double scale = 1.0;
  };

  Mover mover(std::size_t agent, std::size_t interval, double s) const {
    Mover m;
    m.track = track_of_[agent * frames_ + interval];
    const Track& t = tracks_[static_cast<std::size_t>(m.track)];
    const auto k = static_cast<int>(interval - t.first);
    const bool pinned0 = t.pinned[static_cast<std::size_t>(k)] != 0, pinned1 = t.pinned[static_cast<std::size_t>(k) + 1] != 0;
    const double w0 = 1.0 - s, w1 = s;
    constexpr double tiny = 1e-9, least_share = 0.25;  // a lone free vertex moves at most 1/0.25 = 4 pushes
    if (!pinned0 && !pinned1) {
      m.movable = true;
      m.constraint = {k, k + 1, w0, w1, Vec::Zero()};
    } else if (!pinned0 && w0 > tiny) {
      m.movable = true;
      m.constraint = {k, k, 1.0, 0.0, Vec::Zero()};
      m.scale = 1.0 / std::max(w0, least_share);
    } else if (!pinned1 && w1 > tiny) {
      m.movable = true;
      m.constraint = {k + 1, k + 1, 1.0, 0.0, Vec::Zero()};
      m.scale = 1.0 / std::max(w1, least_share);
    }
    return m;
  }

  // --- stuck contacts: the clearance is violated at an end frame where every agent involved is pinned ---
  bool stuck(const PairContact& c) const {
    if (!mover(c.a, c.interval, c.s).movable && !mover(c.b, c.interval, c.s).movable) return true;
    for (std::size_t f : {c.interval, c.interval + 1}) {
      if (pinned(c.a, f) && pinned(c.b, f) && (at(f, c.a) - at(f, c.b)).norm() < c.clearance) return true;
    }
    return false;
  }
  bool stuck(const ObstacleContact& c) const {
    if (!mover(c.agent, c.interval, c.s).movable) return true;
    for (std::size_t f : {c.interval, c.interval + 1}) {
      if (pinned(c.agent, f) &&
          distance_to(obstacles_[c.obstacle], at(f, c.agent), crowd_.times[f]).signed_distance < c.clearance) {
        return true;
      }
    }
    return false;
  }
  static ContactKey key(const PairContact& c) { return {0, c.a, c.b, c.interval}; }
  static ContactKey key(const ObstacleContact& c) { return {1, c.agent, c.obstacle, c.interval}; }
  bool abandoned(const ContactKey& k) const {
    const auto it = history_.find(k);
    return it != history_.end() && it->second.abandoned;
  }

  // --- choosing this iteration's pushes ---
  struct Candidate {
    double deficit;
    int kind;  // 0 pair, 1 obstacle
    std::size_t index;
  };

  // The interval's two vertices are not used by a push taken this iteration, and — with smoothing in time —
  // no push on the same track this iteration is within smoothing_time of it: exact pushes a few frames apart
  // pull the track to different places frame by frame (a kink at every one), while one push per smoothing_time
  // moves the whole stretch smoothly and clears its neighbouring intervals with it (collide.h "Iteration").
  bool claimable(std::size_t agent, std::size_t interval) const {
    const std::size_t v0 = agent * frames_ + interval;
    if (used_[v0] != 0 || used_[v0 + 1] != 0) return false;
    if (options_.smoothing_time <= 0) return true;
    const Track& t = tracks_[static_cast<std::size_t>(track_of_[v0])];
    const double k = static_cast<double>(interval - t.first), apart = options_.smoothing_time / t.interval_s;
    for (const PointConstraint& c : t.constraints) {
      if (std::abs(static_cast<double>(c.v0) - k) < apart) return false;
    }
    return true;
  }
  void mark(std::size_t agent, std::size_t interval) {
    const std::size_t v0 = agent * frames_ + interval;
    used_[v0] = used_[v0 + 1] = 1;
    touched_.push_back(v0);
  }

  // False when the push would carry a vertex of the mover more than max_displacement from its input.
  bool within_bound(const Mover& m, std::size_t agent, const Vec& displacement) const {
    const Track& t = tracks_[static_cast<std::size_t>(m.track)];
    const Vec step = m.scale * displacement;
    for (int v : {m.constraint.v0, m.constraint.v1}) {
      if ((offset_from_input(t.first + static_cast<std::size_t>(v), agent) + step).norm() > bound(agent)) return false;
    }
    return true;
  }

  void push(const Mover& m, const Vec& displacement, const ContactKey& by, std::vector<char>& moved) {
    PointConstraint c = m.constraint;
    c.target = m.scale * displacement;
    Track& t = tracks_[static_cast<std::size_t>(m.track)];
    t.constraints.push_back(c);
    t.pushed_by.push_back(by);
    moved[t.agent] = 1;
  }

  // Records a push of contact `k` at `deficit`; false (and the contact abandoned) when it has had
  // contact_patience pushes without a new smallest deficit.
  bool progressing(const ContactKey& k, double deficit, double clearance) {
    ContactHistory& h = history_[k];
    if (deficit < h.best_deficit - 1e-9 * clearance) {
      h.best_deficit = deficit;
      h.pushes_since_best = 0;
      return true;
    }
    if (++h.pushes_since_best >= options_.contact_patience) {
      h.abandoned = true;
      return false;
    }
    return true;
  }
  void abandon(const ContactKey& k) { history_[k].abandoned = true; }
  // The limits left no room for `agent`'s side of contact k: a pair goes on pushing its other side alone (and is
  // abandoned when both are held), an obstacle contact is abandoned.
  void hold(const ContactKey& k, std::size_t agent) {
    ContactHistory& h = history_[k];
    if (std::get<0>(k) != 0) {
      h.abandoned = true;
      return;
    }
    h.held[agent == std::get<1>(k) ? 0 : 1] = true;
    if (h.held[0] && h.held[1]) h.abandoned = true;
  }

  // The direction agent a is pushed (b the opposite way). `apart`: along their offset at the moment of closest
  // approach. `sideways`: the part of that offset across their relative motion over the interval — for an
  // interval that ends before (or starts after) their closest moment, the offset also points along the motion,
  // and pushing along it would only shift the two in time (one held back, then rushed past); across it, they
  // sidestep. Relative motion (nearly) nil or offset (nearly) along it: the offset, or when that is zero, the
  // left of a's relative motion (else +x).
  Vec pair_direction(const PairContact& c) const {
    const Vec relative = (at(c.interval + 1, c.a) - at(c.interval + 1, c.b)) - (at(c.interval, c.a) - at(c.interval, c.b));
    const double speed = relative.norm();
    if (options_.pair_push == PairPush::sideways && speed > 1e-9 && c.distance > 1e-12) {
      const Vec along = relative / speed;
      const Vec across = c.offset - c.offset.dot(along) * along;
      if (across.norm() > 1e-6 * c.distance) return across.normalized();
      return Vec(-along.y(), along.x());
    }
    if (c.distance > 1e-12) return c.offset / c.distance;
    if (speed > 1e-12) return Vec(-relative.y(), relative.x()) / speed;
    return {1.0, 0.0};
  }

  // The pushes of a pair contact's two points for a separation `separation` (metres) along pair_direction,
  // half each; a side that cannot move (`a_moves` / `b_moves` false) takes none and the other the whole.
  std::pair<Vec, Vec> pair_pushes(const PairContact& c, double separation, bool a_moves, bool b_moves) const {
    const Vec n = pair_direction(c);
    const double half = 0.5 * separation;
    return {(b_moves ? half : 2 * half) * n, -(a_moves ? half : 2 * half) * n};
  }

  // Distance along `direction` from p until the obstacle's signed distance reaches `clearance` (convex: one exit).
  double exit_distance(const Obstacle& o, const Vec& p, double time, const Vec& direction, double clearance) const {
    auto outside = [&](double lambda) { return distance_to(o, p + lambda * direction, time).signed_distance >= clearance; };
    double lo = 0.0, hi = std::max(1e-3, clearance - distance_to(o, p, time).signed_distance);
    for (int k = 0; k < 64 && !outside(hi); ++k) {
      lo = hi;
      hi *= 2.0;
    }
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (outside(mid) ? hi : lo) = mid;
    }
    return hi;
  }

  // Walking from contact `c` backward (step −1: from the interval's first frame) or forward (+1: from its
  // second) along the agent's run of present frames, the outward normal of the obstacle at the first frame where
  // the agent keeps its clearance; none when it never does.
  std::optional<Vec> clear_side(const ObstacleContact& c, int step) const {
    const Obstacle& o = obstacles_[c.obstacle];
    for (std::ptrdiff_t f = static_cast<std::ptrdiff_t>(c.interval) + (step > 0 ? 1 : 0);
         f >= 0 && f < static_cast<std::ptrdiff_t>(frames_) && crowd_.present(static_cast<std::size_t>(f), c.agent); f += step) {
      const auto frame = static_cast<std::size_t>(f);
      const ObstacleDistance d = distance_to(o, at(frame, c.agent), crowd_.times[frame]);
      if (d.signed_distance >= c.clearance) return d.normal;
    }
    return std::nullopt;
  }

  Vec obstacle_displacement(const ObstacleContact& c) const {
    const Obstacle& o = obstacles_[c.obstacle];
    const double t0 = crowd_.times[c.interval], t1 = crowd_.times[c.interval + 1];
    const double time = t0 + c.s * (t1 - t0);
    const Vec p0 = at(c.interval, c.agent), p1 = at(c.interval + 1, c.agent);
    const Vec p = p0 + c.s * (p1 - p0);
    const double extra = 0.5 * options_.push_fraction * c.clearance;
    Vec relative = (p1 - p0) / (t1 - t0);
    if (o.is_moving()) relative -= (pose_at(o, t1).translation() - pose_at(o, t0).translation()) / (t1 - t0);
    ObstaclePull rule = options_.obstacle_pull;
    if (rule == ObstaclePull::back) {
      // The side it came from (collide.h "Iteration"): the outward normal where the track was last clear
      // before the contact, when it is clear again later on that same side (within 60°) or never; past or
      // through the obstacle (clear again on another side): sideways.
      const std::optional<Vec> entry = clear_side(c, -1), exit = clear_side(c, +1);
      if (entry && !(exit && entry->dot(*exit) < 0.5)) {
        return (exit_distance(o, p, time, *entry, c.clearance) + extra) * *entry;
      }
      if (!entry && exit) return (exit_distance(o, p, time, *exit, c.clearance) + extra) * *exit;
      rule = entry ? ObstaclePull::sideways : ObstaclePull::nearest;
    }
    if (rule == ObstaclePull::sideways && relative.norm() > 1e-9) {
      const Vec side = Vec(-relative.y(), relative.x()).normalized();
      const double left = exit_distance(o, p, time, side, c.clearance);
      const double right = exit_distance(o, p, time, -side, c.clearance);
      return left <= right ? Vec((left + extra) * side) : Vec(-(right + extra) * side);
    }
    const ObstacleDistance d = distance_to(o, p, time);
    return (c.clearance - d.signed_distance + extra) * d.normal;
  }

  // Takes the pushable contacts deepest first, each whose vertices no taken contact uses; `pushable` counts the
  // contacts neither stuck nor abandoned. Returns how many were taken.
  std::size_t choose(const Contacts& contacts, std::vector<char>& moved, std::size_t& pushable) {
    std::vector<Candidate> order;
    order.reserve(contacts.size());
    for (std::size_t k = 0; k < contacts.pairs.size(); ++k) {
      const PairContact& c = contacts.pairs[k];
      if (!abandoned(key(c)) && !stuck(c)) order.push_back({c.clearance - c.distance, 0, k});
    }
    for (std::size_t k = 0; k < contacts.obstacles.size(); ++k) {
      const ObstacleContact& c = contacts.obstacles[k];
      if (!abandoned(key(c)) && !stuck(c)) order.push_back({c.clearance - c.signed_distance, 1, k});
    }
    pushable = order.size();
    std::sort(order.begin(), order.end(), [](const Candidate& x, const Candidate& y) {
      return std::tie(y.deficit, x.kind, x.index) < std::tie(x.deficit, y.kind, y.index);
    });
    used_.resize(agents_ * frames_, 0);
    std::size_t taken = 0;
    for (const Candidate& candidate : order) {
      if (candidate.kind == 0) {
        const PairContact& c = contacts.pairs[candidate.index];
        if (!claimable(c.a, c.interval) || !claimable(c.b, c.interval)) continue;
        Mover ma = mover(c.a, c.interval, c.s), mb = mover(c.b, c.interval, c.s);
        // A side the limits held before takes no push: the other one takes it whole, as for a pinned side.
        if (const auto h = history_.find(key(c)); h != history_.end()) {
          ma.movable = ma.movable && !h->second.held[0];
          mb.movable = mb.movable && !h->second.held[1];
        }
        if (!ma.movable && !mb.movable) {
          abandon(key(c));
          continue;
        }
        const double separation = options_.push_size == PushSize::full ? candidate.deficit + options_.push_fraction * c.clearance
                                                                        : options_.push_fraction * c.clearance;
        const auto [push_a, push_b] = pair_pushes(c, separation, ma.movable, mb.movable);
        if ((ma.movable && !within_bound(ma, c.a, push_a)) || (mb.movable && !within_bound(mb, c.b, push_b))) {
          abandon(key(c));
          continue;
        }
        if (!progressing(key(c), candidate.deficit, c.clearance)) continue;
        mark(c.a, c.interval);
        mark(c.b, c.interval);
        if (ma.movable) push(ma, push_a, key(c), moved);
        if (mb.movable) push(mb, push_b, key(c), moved);
      } else {
        const ObstacleContact& c = contacts.obstacles[candidate.index];
        if (!claimable(c.agent, c.interval)) continue;
        const Mover m = mover(c.agent, c.interval, c.s);
        const Vec displacement = obstacle_displacement(c);
        if (!within_bound(m, c.agent, displacement)) {
          abandon(key(c));
          continue;
        }
        if (!progressing(key(c), candidate.deficit, c.clearance)) continue;
        mark(c.agent, c.interval);
        push(m, displacement, key(c), moved);
      }
      ++taken;
    }
    for (std::size_t v : touched_) used_[v] = used_[v + 1] = 0;
    touched_.clear();
    return taken;
  }

  // Distinct pairs (and agent–obstacle pairs) left: stuck when every contact of theirs is stuck, abandoned when
  // none is pushable and one was abandoned.
  void classify_remaining(const Contacts& contacts, Report& report) const {
    auto classify = [&](bool all_stuck, bool any_pushable) {
      if (all_stuck) {
        ++report.stuck_contacts;
      } else if (!any_pushable) {
        ++report.abandoned_contacts;
      }
    };
    for (std::size_t k = 0; k < contacts.pairs.size();) {
      const PairContact& first = contacts.pairs[k];
      bool all_stuck = true, any_pushable = false;
      for (; k < contacts.pairs.size() && contacts.pairs[k].a == first.a && contacts.pairs[k].b == first.b; ++k) {
        const PairContact& c = contacts.pairs[k];
        const bool is_stuck = stuck(c);
        all_stuck = all_stuck && is_stuck;
        any_pushable = any_pushable || (!is_stuck && !abandoned(key(c)));
      }
      classify(all_stuck, any_pushable);
    }
    for (std::size_t k = 0; k < contacts.obstacles.size();) {
      const ObstacleContact& first = contacts.obstacles[k];
      bool all_stuck = true, any_pushable = false;
      for (; k < contacts.obstacles.size() && contacts.obstacles[k].agent == first.agent &&
             contacts.obstacles[k].obstacle == first.obstacle;
           ++k) {
        const ObstacleContact& c = contacts.obstacles[k];
        const bool is_stuck = stuck(c);
        all_stuck = all_stuck && is_stuck;
        any_pushable = any_pushable || (!is_stuck && !abandoned(key(c)));
      }
      classify(all_stuck, any_pushable);
    }
  }

  // The true smallest gaps: widened passes until the smallest is within the pass's reach (at most 16 m).
  Gaps exact_gaps() const {
    Gaps out;
    bool pair_done = false, obstacle_done = obstacles_.empty();
    for (double reach : {std::max(1.0, options_.margin), 4.0, 16.0}) {
      if (pair_done && obstacle_done) break;
      if (reach < options_.margin) continue;
      const Gaps g = smallest_gaps(crowd_, obstacle_done ? std::vector<Obstacle>{} : obstacles_, reach);
      if (!pair_done && g.pair <= reach) {
        out.pair = g.pair;
        pair_done = true;
      }
      if (!obstacle_done && g.obstacle <= reach) {
        out.obstacle = g.obstacle;
        obstacle_done = true;
      }
    }
    return out;
  }

  double largest_displacement() const {
    double largest = 0.0;
    for (std::size_t f = 0; f < frames_; ++f) {
      for (std::size_t a = 0; a < agents_; ++a) {
        if (crowd_.present(f, a)) largest = std::max(largest, offset_from_input(f, a).norm());
      }
    }
    return largest;
  }

  // --- deforming ---
  // Each touched track is solved on rank (track index) mod ranks, which keeps its factorisation for the run; the
  // displacements are then gathered, so every rank applies every track's displacement, in track order.
  void deform() {
    std::vector<std::size_t> busy;
    for (std::size_t t = 0; t < tracks_.size(); ++t) {
      if (!tracks_[t].constraints.empty()) busy.push_back(t);
    }
    std::vector<std::size_t> mine;  // positions in `busy` of the tracks this rank solves: track index mod ranks
    for (std::size_t k = 0; k < busy.size(); ++k) {
      if (static_cast<int>(busy[k] % static_cast<std::size_t>(ranks_)) == rank_) mine.push_back(k);
    }
    std::vector<Displacement> displacement(busy.size());
    std::vector<std::string> failures(mine.size());
    std::vector<char> made(mine.size(), 0);
    parallel_for(mine.size(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t j = begin; j < end; ++j) {
        const std::size_t k = mine[j];
        Track& t = tracks_[busy[k]];
        try {
          if (!t.solver) {
            Displacement original(static_cast<Eigen::Index>(t.length), 2);
            for (std::size_t v = 0; v < t.length; ++v) {
              original.row(static_cast<Eigen::Index>(v)) = input_.position(t.first + v, t.agent).head<2>().transpose();
            }
            t.solver = make_track_solver(original, t.pinned, options_, t.interval_s);
            made[j] = 1;
          }
          displacement[k] = t.solver->solve(t.constraints);
        } catch (const std::exception& e) {
          failures[j] = e.what();
        }
      }
    });
    for (char m : made) factorizations_ += m;
    std::string failure;
    for (const std::string& f : failures) {
      if (!f.empty()) {
        failure = f;
        break;
      }
    }
    if (ranks_ > 1) gather(busy, mine, displacement, failure);
    if (!failure.empty()) throw NumericalError(failure);
    // Each deformation is taken as far as the limits allow (collide.h "Limits"): whole, shortened, or — with
    // less than min_step of it admissible — dropped, and the contacts that asked for it abandoned. The bounds
    // hold for every vertex, not only the pushed ones.
    for (std::size_t k = 0; k < busy.size(); ++k) {
      Track& t = tracks_[busy[k]];
      const Displacement& d = displacement[k];
      const double alpha = std::min(1.0, admissible_step(t, d));
      if (alpha >= min_step) {
        if (alpha < 1.0) ++limited_steps_;
        for (std::size_t j = 0; j < t.length; ++j) {
          double* p = crowd_.positions.data() + crowd_.index(t.first + j, t.agent);
          p[0] += alpha * d(static_cast<Eigen::Index>(j), 0);
          p[1] += alpha * d(static_cast<Eigen::Index>(j), 1);
        }
      } else {
        ++held_steps_;
        for (const ContactKey& by : t.pushed_by) hold(by, t.agent);
      }
      t.constraints.clear();
      t.pushed_by.clear();
    }
  }

  // Every rank's displacements to every rank. Message: [failed (0/1), then per solved track its position k
  // among the busy tracks and its 2·length values]. A failure on any rank is raised on every rank.
  void gather(const std::vector<std::size_t>& busy, const std::vector<std::size_t>& mine,
              std::vector<Displacement>& displacement, std::string& failure) const {
    std::vector<double> message{failure.empty() ? 0.0 : 1.0};
    if (failure.empty()) {
      for (std::size_t k : mine) {
        message.push_back(static_cast<double>(k));
        const Displacement& d = displacement[k];
        for (Eigen::Index j = 0; j < d.rows(); ++j) message.insert(message.end(), {d(j, 0), d(j, 1)});
      }
    }
    const std::vector<std::vector<double>> all = communicator_.all_gather(message);
    for (std::size_t r = 0; r < all.size(); ++r) {
      const std::vector<double>& m = all[r];
      if (m.at(0) != 0.0) {
        if (failure.empty()) failure = "collide: a trajectory's solve failed on MPI rank " + std::to_string(r);
        continue;
      }
      for (std::size_t pos = 1; pos < m.size();) {
        const auto k = static_cast<std::size_t>(m[pos++]);
        const auto length = static_cast<Eigen::Index>(tracks_[busy.at(k)].length);
        Displacement d(length, 2);
        for (Eigen::Index j = 0; j < length; ++j, pos += 2) d.row(j) << m.at(pos), m.at(pos + 1);
        displacement[k] = std::move(d);
      }
    }
  }

  const CrowdMotion& input_;
  CrowdMotion crowd_;
  const std::vector<Obstacle>& obstacles_;
  Options options_;
  std::size_t frames_, agents_;
  const Communicator& communicator_;
  int ranks_, rank_;
  std::vector<Track> tracks_;
  std::vector<int> track_of_;  // agent * frames + frame → track, −1 when absent
  std::vector<char> used_;     // agent * frames + frame → vertex claimed this iteration
  std::vector<std::size_t> touched_;
  std::map<ContactKey, ContactHistory> history_;
  double factorizations_ = 0;  // tracks factorised on this rank
  double speed_limit_ = 0;     // m/s, 0: none
  std::vector<double> input_acceleration_;  // agent * frames + frame → |a| of the input (m/s²); empty: no limit
  std::size_t limited_steps_ = 0, held_steps_ = 0;
};

std::string gap(double v) { return std::isfinite(v) ? with_digits(v, 4) + " m" : "none within 16 m"; }

}  // namespace

MotionStats motion_stats(const CrowdMotion& crowd) {
  std::vector<double> speeds, accelerations;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
    bool have_velocity = false;
    Vec velocity = Vec::Zero();
    for (std::size_t f = 0; f + 1 < crowd.frame_count(); ++f) {
      if (!crowd.present(f, a) || !crowd.present(f + 1, a)) {
        have_velocity = false;
        continue;
      }
      const double dt = crowd.times[f + 1] - crowd.times[f];
      const Vec v = (crowd.position(f + 1, a).head<2>() - crowd.position(f, a).head<2>()) / dt;
      speeds.push_back(v.norm());
      if (have_velocity) {
        const double mid = 0.5 * (crowd.times[f + 1] - crowd.times[f - 1]);
        accelerations.push_back((v - velocity).norm() / mid);
      }
      velocity = v;
      have_velocity = true;
    }
  }
  auto high = [](std::vector<double>& values, double& largest, double& p99) {
    if (values.empty()) return;
    const auto k = static_cast<std::ptrdiff_t>(std::floor(0.99 * static_cast<double>(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    p99 = values[static_cast<std::size_t>(k)];
    largest = *std::max_element(values.begin(), values.end());
  };
  MotionStats out;
  high(speeds, out.max_speed, out.speed_p99);
  high(accelerations, out.max_acceleration, out.acceleration_p99);
  return out;
}

void validate(const Options& o) { check_options(describe, o, "collide option "); }

Result resolve_collisions(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Options& options,
                          Progress& progress, const Communicator& communicator) {
  validate(options);
  crowd.validate("collide input");
  for (std::size_t o = 0; o < obstacles.size(); ++o) validate(obstacles[o], "obstacle " + std::to_string(o));
  Repair repair(crowd, obstacles, options, communicator);
  return repair.run(progress);
}

std::string summary(const Report& r) {
  std::ostringstream s;
  if (r.converged) {
    s << "no collision left after " << r.iterations << " iterations";
  } else {
    s << r.pair_contacts << " colliding pair(s) and " << r.obstacle_contacts << " obstacle contact(s) remain ("
      << r.stuck_contacts << " stuck at pinned frames, " << r.abandoned_contacts << " abandoned) after " << r.iterations
      << " iterations (" << r.stop_reason << ")";
  }
  s << "; smallest pair gap " << gap(r.min_pair_gap) << ", smallest obstacle gap " << gap(r.min_obstacle_gap);
  return s.str();
}

}  // namespace throng::collide
