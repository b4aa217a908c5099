// The repair loop of collide.h: detect, choose disjoint contacts, push, deform each touched trajectory.
#include "track_solver.h"

#include <throng/collide/collide.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>
#include <tuple>

namespace throng::collide {
namespace {

using Vec = Eigen::Vector2d;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// A run of consecutive present frames of one agent, and its solver (made when first pushed).
struct Track {
  std::size_t agent = 0, first = 0, length = 0;
  std::vector<char> pinned;
  std::unique_ptr<TrackSolver> solver;
  std::vector<PointConstraint> constraints;  // this iteration's
};

class Repair {
 public:
  Repair(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Options& options)
      : crowd_(crowd), obstacles_(obstacles), options_(options), frames_(crowd.frame_count()), agents_(crowd.agent_count()) {
    make_tracks();
    factorizations_.assign(tracks_.size(), 0);
  }

  Result run(Progress& progress) {
    Result result;
    Report& report = result.report;
    auto start = Clock::now();
    Contacts contacts = find_contacts(crowd_, obstacles_, options_.margin);
    report.detect_seconds += seconds_since(start);
    report.initial_pair_contacts = contacts.pair_count();
    report.initial_obstacle_contacts = contacts.obstacle_count();
    const double initial = std::max<double>(1.0, static_cast<double>(contacts.size()));
    double fraction = 0.0;
    std::vector<char> moved_ever(agents_, 0);
    report.stop_reason = "converged";
    while (contacts.size() > 0) {
      if (report.iterations >= options_.max_iterations) {
        report.stop_reason = "iteration cap reached";
        break;
      }
      std::vector<char> moved(agents_, 0);
      const std::size_t taken = choose(contacts, moved);
      if (taken == 0) {
        report.stop_reason = "only stuck contacts left";
        break;
      }
      report.constraints += taken;
      start = Clock::now();
      deform();
      report.solve_seconds += seconds_since(start);
      ++report.iterations;
      for (std::size_t a = 0; a < agents_; ++a) moved_ever[a] = static_cast<char>(moved_ever[a] | moved[a]);
      start = Clock::now();
      contacts = redetect(contacts, moved);
      report.detect_seconds += seconds_since(start);
      report.history.push_back(contacts.size());
      fraction = std::max({fraction, static_cast<double>(report.iterations) / static_cast<double>(options_.max_iterations),
                           1.0 - static_cast<double>(contacts.size()) / initial});
      progress.update(std::min(fraction, 1.0), "collide");
    }
    // The final state, from scratch.
    start = Clock::now();
    const Contacts final_contacts = find_contacts(crowd_, obstacles_, options_.margin);
    report.detect_seconds += seconds_since(start);
    report.pair_contacts = final_contacts.pair_count();
    report.obstacle_contacts = final_contacts.obstacle_count();
    report.min_pair_gap = final_contacts.min_pair_gap;
    report.min_obstacle_gap = final_contacts.min_obstacle_gap;
    report.converged = final_contacts.size() == 0;
    if (report.converged) report.stop_reason = "converged";
    report.stuck_contacts = final_contacts.size() == 0 ? 0 : count_stuck(final_contacts);
    report.moved_agents = static_cast<std::size_t>(std::count(moved_ever.begin(), moved_ever.end(), 1));
    for (char f : factorizations_) report.factorizations += f;
    result.crowd = crowd_;
    if (report.moved_agents > 0) result.crowd.velocities.clear();
    progress.update(1.0, "collide");
    return result;
  }

 private:
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
        t.pinned.assign(t.length, fixed[a]);
        if (options_.pin_ends) {
          t.pinned.front() = 1;
          t.pinned.back() = 1;
        }
        tracks_.push_back(std::move(t));
      }
    }
  }

  Vec at(std::size_t frame, std::size_t agent) const {
    const double* p = crowd_.positions.data() + crowd_.index(frame, agent);
    return {p[0], p[1]};
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

  // --- choosing this iteration's pushes ---
  struct Candidate {
    double deficit;
    int kind;  // 0 pair, 1 obstacle
    std::size_t index;
  };

  bool claim(std::size_t agent, std::size_t interval) {
    const std::size_t v0 = agent * frames_ + interval;
    if (used_[v0] != 0 || used_[v0 + 1] != 0) return false;
    return true;
  }
  void mark(std::size_t agent, std::size_t interval) {
    const std::size_t v0 = agent * frames_ + interval;
    used_[v0] = used_[v0 + 1] = 1;
    touched_.push_back(v0);
  }

  void push(const Mover& m, const Vec& displacement, std::vector<char>& moved) {
    PointConstraint c = m.constraint;
    c.target = m.scale * displacement;
    Track& t = tracks_[static_cast<std::size_t>(m.track)];
    t.constraints.push_back(c);
    moved[t.agent] = 1;
  }

  Vec pair_direction(const PairContact& c) const {
    if (c.distance > 1e-12) return c.offset / c.distance;
    const Vec relative = (at(c.interval + 1, c.a) - at(c.interval + 1, c.b)) - (at(c.interval, c.a) - at(c.interval, c.b));
    if (relative.norm() > 1e-12) return Vec(-relative.y(), relative.x()) / relative.norm();
    return {1.0, 0.0};
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

  Vec obstacle_displacement(const ObstacleContact& c) const {
    const Obstacle& o = obstacles_[c.obstacle];
    const double t0 = crowd_.times[c.interval], t1 = crowd_.times[c.interval + 1];
    const double time = t0 + c.s * (t1 - t0);
    const Vec p0 = at(c.interval, c.agent), p1 = at(c.interval + 1, c.agent);
    const Vec p = p0 + c.s * (p1 - p0);
    const double extra = 0.5 * options_.push_fraction * c.clearance;
    Vec relative = (p1 - p0) / (t1 - t0);
    if (o.is_moving()) relative -= (pose_at(o, t1).translation() - pose_at(o, t0).translation()) / (t1 - t0);
    if (options_.obstacle_pull == ObstaclePull::sideways && relative.norm() > 1e-9) {
      const Vec side = Vec(-relative.y(), relative.x()).normalized();
      const double left = exit_distance(o, p, time, side, c.clearance);
      const double right = exit_distance(o, p, time, -side, c.clearance);
      return left <= right ? Vec((left + extra) * side) : Vec(-(right + extra) * side);
    }
    const ObstacleDistance d = distance_to(o, p, time);
    return (c.clearance - d.signed_distance + extra) * d.normal;
  }

  std::size_t choose(const Contacts& contacts, std::vector<char>& moved) {
    std::vector<Candidate> order;
    order.reserve(contacts.size());
    for (std::size_t k = 0; k < contacts.pairs.size(); ++k) {
      order.push_back({contacts.pairs[k].clearance - contacts.pairs[k].distance, 0, k});
    }
    for (std::size_t k = 0; k < contacts.obstacles.size(); ++k) {
      order.push_back({contacts.obstacles[k].clearance - contacts.obstacles[k].signed_distance, 1, k});
    }
    std::sort(order.begin(), order.end(), [](const Candidate& x, const Candidate& y) {
      return std::tie(y.deficit, x.kind, x.index) < std::tie(x.deficit, y.kind, y.index);
    });
    used_.resize(agents_ * frames_, 0);
    std::size_t taken = 0;
    for (const Candidate& candidate : order) {
      if (candidate.kind == 0) {
        const PairContact& c = contacts.pairs[candidate.index];
        const Mover ma = mover(c.a, c.interval, c.s), mb = mover(c.b, c.interval, c.s);
        if (!ma.movable && !mb.movable) continue;
        if (!claim(c.a, c.interval) || !claim(c.b, c.interval)) continue;
        mark(c.a, c.interval);
        mark(c.b, c.interval);
        const Vec n = pair_direction(c);
        const double half = 0.5 * options_.push_fraction * c.clearance;
        const double share_a = mb.movable ? half : 2 * half, share_b = ma.movable ? half : 2 * half;
        if (ma.movable) push(ma, share_a * n, moved);
        if (mb.movable) push(mb, -share_b * n, moved);
      } else {
        const ObstacleContact& c = contacts.obstacles[candidate.index];
        const Mover m = mover(c.agent, c.interval, c.s);
        if (!m.movable || !claim(c.agent, c.interval)) continue;
        mark(c.agent, c.interval);
        push(m, obstacle_displacement(c), moved);
      }
      ++taken;
    }
    for (std::size_t v : touched_) used_[v] = used_[v + 1] = 0;
    touched_.clear();
    return taken;
  }

  // Distinct pairs (and agent–obstacle pairs) none of whose contacts has a free vertex to move.
  std::size_t count_stuck(const Contacts& contacts) const {
    std::size_t stuck = 0;
    for (std::size_t k = 0; k < contacts.pairs.size();) {
      const PairContact& first = contacts.pairs[k];
      bool movable = false;
      for (; k < contacts.pairs.size() && contacts.pairs[k].a == first.a && contacts.pairs[k].b == first.b; ++k) {
        const PairContact& c = contacts.pairs[k];
        movable = movable || mover(c.a, c.interval, c.s).movable || mover(c.b, c.interval, c.s).movable;
      }
      stuck += !movable;
    }
    for (std::size_t k = 0; k < contacts.obstacles.size();) {
      const ObstacleContact& first = contacts.obstacles[k];
      bool movable = false;
      for (; k < contacts.obstacles.size() && contacts.obstacles[k].agent == first.agent &&
             contacts.obstacles[k].obstacle == first.obstacle;
           ++k) {
        const ObstacleContact& c = contacts.obstacles[k];
        movable = movable || mover(c.agent, c.interval, c.s).movable;
      }
      stuck += !movable;
    }
    return stuck;
  }

  // --- deforming ---
  void deform() {
    std::vector<std::size_t> busy;
    for (std::size_t t = 0; t < tracks_.size(); ++t) {
      if (!tracks_[t].constraints.empty()) busy.push_back(t);
    }
    std::vector<std::string> failures(busy.size());
    parallel_for(busy.size(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t k = begin; k < end; ++k) {
        Track& t = tracks_[busy[k]];
        if (!t.solver) {
          Eigen::Matrix<double, Eigen::Dynamic, 2> original(static_cast<Eigen::Index>(t.length), 2);
          for (std::size_t j = 0; j < t.length; ++j) original.row(static_cast<Eigen::Index>(j)) = at(t.first + j, t.agent).transpose();
          t.solver = std::make_unique<TrackSolver>(original, t.pinned, options_.spread, options_.min_feature_length);
          ++factorizations_[busy[k]];
        }
        const Eigen::Matrix<double, Eigen::Dynamic, 2> d = t.solver->solve(t.constraints);
        for (std::size_t j = 0; j < t.length; ++j) {
          double* p = crowd_.positions.data() + crowd_.index(t.first + j, t.agent);
          p[0] += d(static_cast<Eigen::Index>(j), 0);
          p[1] += d(static_cast<Eigen::Index>(j), 1);
        }
        t.constraints.clear();
      }
    });
  }

  // Contacts after a deformation: those of unmoved agents stay as they were; the moved agents are searched again.
  Contacts redetect(const Contacts& before, const std::vector<char>& moved) const {
    Contacts fresh = find_contacts(crowd_, obstacles_, options_.margin, BroadPhase::grid, moved);
    for (const PairContact& c : before.pairs) {
      if (moved[c.a] == 0 && moved[c.b] == 0) fresh.pairs.push_back(c);
    }
    for (const ObstacleContact& c : before.obstacles) {
      if (moved[c.agent] == 0) fresh.obstacles.push_back(c);
    }
    std::sort(fresh.pairs.begin(), fresh.pairs.end(),
              [](const PairContact& x, const PairContact& y) {
                return std::tie(x.a, x.b, x.interval) < std::tie(y.a, y.b, y.interval);
              });
    std::sort(fresh.obstacles.begin(), fresh.obstacles.end(), [](const ObstacleContact& x, const ObstacleContact& y) {
      return std::tie(x.agent, x.obstacle, x.interval) < std::tie(y.agent, y.obstacle, y.interval);
    });
    return fresh;
  }

  CrowdMotion crowd_;
  const std::vector<Obstacle>& obstacles_;
  Options options_;
  std::size_t frames_, agents_;
  std::vector<Track> tracks_;
  std::vector<int> track_of_;  // agent * frames + frame → track, −1 when absent
  std::vector<char> used_;     // agent * frames + frame → vertex claimed this iteration
  std::vector<std::size_t> touched_;
  std::vector<char> factorizations_;  // per track: 1 once its solver exists
};

std::string number(double v) {
  if (!std::isfinite(v)) return "none";
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

}  // namespace

void validate(const Options& o) {
  auto fail = [](const std::string& m) { throw ConfigError(m); };
  if (!(std::isfinite(o.margin) && o.margin >= 0)) fail("margin " + number(o.margin) + ": expected a length ≥ 0");
  if (!(o.push_fraction > 0 && o.push_fraction <= 1)) fail("push_fraction " + number(o.push_fraction) + ": expected 0 < value ≤ 1");
  if (o.max_iterations < 1) fail("max_iterations 0: expected at least 1");
  if (!(std::isfinite(o.spread) && o.spread >= 1)) fail("spread " + number(o.spread) + ": expected a frame count ≥ 1");
  if (!(std::isfinite(o.min_feature_length) && o.min_feature_length > 0)) {
    fail("min_feature_length " + number(o.min_feature_length) + ": expected > 0");
  }
}

Result resolve_collisions(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, const Options& options,
                          Progress& progress) {
  validate(options);
  crowd.validate("collide input");
  for (std::size_t o = 0; o < obstacles.size(); ++o) validate(obstacles[o], "obstacle " + std::to_string(o));
  Repair repair(crowd, obstacles, options);
  return repair.run(progress);
}

std::string summary(const Report& r) {
  std::ostringstream s;
  if (r.converged) {
    s << "no collision left after " << r.iterations << " iterations";
  } else {
    s << r.pair_contacts << " colliding pair(s) and " << r.obstacle_contacts << " obstacle contact(s) remain ("
      << r.stuck_contacts << " stuck at pinned frames) after " << r.iterations << " iterations (" << r.stop_reason << ")";
  }
  s << "; smallest pair gap " << number(r.min_pair_gap) << " m, smallest obstacle gap " << number(r.min_obstacle_gap) << " m";
  return s.str();
}

}  // namespace throng::collide
