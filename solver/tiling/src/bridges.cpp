#include "bridges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace throng::tiling {

std::optional<std::pair<Transform, double>> bridge_fit(const Fragment& fr, bool new_is_exit, const EndPoint& d,
                                                       const Eigen::Vector2d& n_position, double n_time, double n_heading,
                                                       const MatchThresholds& match) {
  const std::size_t on_d = new_is_exit ? fr.sample_count() - 1 : 0;
  const std::size_t on_n = new_is_exit ? 0 : fr.sample_count() - 1;
  const Eigen::Vector2d chord_patch = fr.positions[on_n] - fr.positions[on_d];
  const Eigen::Vector2d chord_world = n_position - d.position;
  Transform t;
  t.angle = chord_patch.norm() > 0.3 && chord_world.norm() > 0.3
                ? wrap_angle(std::atan2(chord_world.y(), chord_world.x()) - std::atan2(chord_patch.y(), chord_patch.x()))
                : wrap_angle(d.heading - fr.headings[on_d]);
  t.translation = 0.5 * ((d.position + n_position) - rotate(fr.positions[on_d] + fr.positions[on_n], t.angle));
  t.time_shift = 0.5 * ((d.time + n_time) - (fr.times[on_d] + fr.times[on_n]));
  double score = 0;
  const auto end = [&](std::size_t s, const Eigen::Vector2d& p, double time, double heading) {
    const double dist = (t.apply(fr.positions[s]) - p).norm();
    const double dt = std::abs(fr.times[s] + t.time_shift - time);
    const double da = std::abs(wrap_angle(fr.headings[s] + t.angle - heading));
    score += (dist / match.distance_m) * (dist / match.distance_m) + (dt / match.time_s) * (dt / match.time_s) +
             (da / match.angle_rad) * (da / match.angle_rad);
    return dist <= match.distance_m && dt <= match.time_s && da <= match.angle_rad;
  };
  if (!end(on_d, d.position, d.time, d.heading) || !end(on_n, n_position, n_time, n_heading)) return std::nullopt;
  return std::pair(t, score);
}

Bridger::Bridger(TilingState& state, Stitcher& stitcher, ChainReport& report,
                 std::function<bool(std::uint32_t, std::uint32_t, int, const EndPoint&)> refused,
                 std::function<bool(const Attempt&)> admissible)
    : state_(state), stitcher_(stitcher), report_(report), refused_(std::move(refused)), admissible_(std::move(admissible)) {
  const Problem& problem = state.problem();
  // How far a bridge may reach: a patch's end-to-end chord (at most twice its extent) and its duration, plus the
  // match thresholds at both ends.
  reach_m_ = 2 * problem.max_extent_m + 2 * problem.options.match.distance_m;
  span_s_ = 2 * problem.max_half_duration_s + 2 * problem.options.match.time_s;
  shortest_s_ = std::numeric_limits<double>::infinity();
  for (std::uint32_t k : problem.usable_types) {
    shortest_s_ = std::min(shortest_s_, problem.library.types[k].end_time() - problem.library.types[k].start_time());
  }
}

bool Bridger::place(const Placement& c, FragmentRef ref, int side, bool must_lower, std::uint32_t* id) {
  const Problem& problem = state_.problem();
  const bool new_is_exit = side == 0;
  ++report_.search_steps;
  Transform t = c.transform;
  const std::array<int, 3> k = canonicalise(problem, t);
  const std::array<int, 3> image = new_is_exit ? std::array<int, 3>{-k[0], -k[1], -k[2]} : k;
  const Attempt a = stitcher_.stitch({c.type, t, false, NewLink{c.fragment, new_is_exit, ref, image}});
  if (!a.feasible || (must_lower ? a.delta_dangling >= 0 : a.delta_dangling > 0)) return false;
  if (!admissible_(a) || !stitcher_.valid(a)) return false;
  const std::uint32_t placed = state_.apply(a.change);
  if (id) *id = placed;
  return true;
}

bool Bridger::one(FragmentRef ref, int side) {
  const Problem& problem = state_.problem();
  const SearchOptions& o = problem.options.search;
  if (o.bridge_attempts == 0) return false;
  const LiveInstance& holder = state_.at(ref.instance);
  const EndPoint at = problem.end_point(holder.type, holder.paths, ref.fragment, side == 1);
  const bool new_is_exit = side == 0;  // a dangling entry takes an exit, and the other way round
  std::vector<Placement> bridges;
  near_.clear();
  state_.dangling_ends().near(at, new_is_exit, reach_m_, new_is_exit ? -span_s_ : 0.0, new_is_exit ? 0.0 : span_s_, near_);
  for (const EndMatch& m : near_) {
    const LiveInstance& other = state_.at(m.end.instance);
    const EndPoint n = problem.end_point(other.type, other.paths, m.end.fragment, new_is_exit);
    const Eigen::Vector2d n_position =
        n.position + Eigen::Vector2d(m.image[0] * problem.periods.p[0], m.image[1] * problem.periods.p[1]);
    const double n_time = n.time + m.image[2] * problem.periods.p[2];
    for (std::uint32_t k : problem.usable_types) {
      const PatchType& type = problem.library.types[k];
      for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
        const Fragment& fr = type.fragments[f];
        if (!fr.is_character()) continue;
        if ((new_is_exit ? fr.exit_class : fr.entry_class) != at.pose_class) continue;
        if ((new_is_exit ? fr.entry_class : fr.exit_class) != n.pose_class) continue;
        if (refused_(k, f, new_is_exit ? 1 : 0, at)) continue;
        const auto fit = bridge_fit(fr, new_is_exit, at, n_position, n_time, n.heading, problem.options.match);
        if (fit) bridges.push_back({fit->second, k, f, fit->first});
      }
    }
  }
  std::sort(bridges.begin(), bridges.end(), [](const Placement& a, const Placement& b) {
    return std::tie(a.cost, a.type, a.fragment, a.transform.time_shift, a.transform.translation.x(),
                    a.transform.translation.y()) < std::tie(b.cost, b.type, b.fragment, b.transform.time_shift,
                                                             b.transform.translation.x(), b.transform.translation.y());
  });
  if (bridges.size() > o.bridge_attempts) bridges.resize(o.bridge_attempts);
  for (const Placement& c : bridges) {
    if (report_.search_steps >= o.max_steps) return false;
    if (place(c, ref, side, true, nullptr)) return true;
  }
  return false;
}

bool Bridger::two(FragmentRef ref, int side, const std::vector<Placement>& first) {
  const SearchOptions& o = state_.problem().options.search;
  std::size_t tried = 0;
  for (const Placement& c : first) {
    if (tried++ >= o.bridge_attempts || report_.search_steps >= o.max_steps) return false;
    std::uint32_t id = 0;
    if (!place(c, ref, side, false, &id)) continue;
    if (one({id, c.fragment}, side)) return true;
    state_.remove(id);
  }
  return false;
}

double Bridger::schedule_cost(const Eigen::Vector2d& position, double time, int side,
                              const std::vector<EndPoint>& partners) const {
  const Periods& periods = state_.problem().periods;
  const double speed = state_.problem().options.density.projection_speed_mps;
  const double P = periods.p[2];
  double best = std::numeric_limits<double>::infinity();
  for (const EndPoint& n : partners) {
    // Forward in time from the open exit to the partner's entry (or from the partner's exit to the open entry).
    const double gap = side == 1 ? n.time - time : time - n.time;
    const double dt = P > 0 ? shortest_s_ + std::fmod(std::fmod(gap - shortest_s_, P) + P, P) : gap;
    if (!(dt >= shortest_s_)) continue;
    for (int ix = -1; ix <= 1; ++ix) {
      for (int iy = -1; iy <= 1; ++iy) {
        const Eigen::Vector2d q = n.position + Eigen::Vector2d(ix * periods.p[0], iy * periods.p[1]) - position;
        best = std::min(best, std::abs(dt - q.norm() / speed));
      }
    }
  }
  return best;
}

}  // namespace throng::tiling
