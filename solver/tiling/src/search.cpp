// Phase 2: Algorithm 2 of the paper. For each dangling end d (in time order), every usable patch with a
// matching end, best preference first, is placed with that end exactly on d; kept if it does not raise the
// number of dangling ends and is valid, else jittered with a growing range (§5.2: 0.6 m, ±15°, ±0.3 s up to
// 1.0 m, ±25°, ±0.5 s). When nothing fits, the patch holding d is removed (never a keyframe) and remembered, so
// that the same patch is not proposed at the same end again. Ends when no end dangles, when a sweep over the
// dangling ends changes nothing, or at SearchOptions::max_steps placements.
//
// Bridges (our addition): before those candidates, patches that would join d to another dangling end n at
// once — one end on d, the other on n — placed by the rigid fit of the two ends (rotation from the chord
// between them, or from d's heading when the chord is short; translation and time shift splitting the
// residual between both ends), kept when both ends then lie within the match thresholds; at most
// SearchOptions::bridge_attempts per end, fewest residual first, accepted only when they lower the dangling
// count. Without them a tile periodic on every axis, where no end can leave by a side, rarely closes: an end
// pushed forward by the candidates above meets another only by chance. On such a tile, after
// SearchOptions::stale_sweeps sweeps in a row that did not lower the count, the smallest group of patches
// connected to a dangling end (through every connection of every character on the way; no keyframe among
// them; at most half the tiling) is dropped whole: its dangling ends go and no partner is left dangling. The same
// holds in a window of a windowed run (problem.h), where an end just after the freeze time may have nothing that
// fits before it: removals would only move it back and forth.
#include "phases.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>
#include <tuple>

namespace throng::tiling {
namespace {

struct DanglingEnd {
  double time;
  FragmentRef ref;
  int side;  // 0 entry, 1 exit
  friend bool operator<(const DanglingEnd& a, const DanglingEnd& b) {
    return std::tie(a.time, a.ref, a.side) < std::tie(b.time, b.ref, b.side);
  }
};

// What history remembers of a removed instance: its type, which of its ends was attached, and where.
using HistoryKey = std::tuple<std::uint32_t, std::uint32_t, int, long, long, long, long>;

HistoryKey history_key(std::uint32_t type, std::uint32_t fragment, int side, const EndPoint& at) {
  return {type, fragment, side, std::lround(at.position.x() * 100), std::lround(at.position.y() * 100),
          std::lround(at.time * 100), std::lround(wrap_angle(at.heading) * 180 / std::numbers::pi)};
}

struct Candidate {
  double cost;
  std::uint32_t type;
  std::uint32_t fragment;
  Transform transform;
};

// The placement of fragment `fr` of a type that puts its end `mine` (entry when !exit_on_d) on d and its other
// end on n (world, n on its nearest image), and the normalised residual of both ends; none when an end would
// then lie outside the match thresholds.
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

}  // namespace

std::array<int, 3> canonicalise(const Problem& problem, Transform& t) {
  const Region& r = problem.region;
  std::array<int, 3> k{0, 0, 0};
  const auto wrap = [](double& v, double lo, double period) {
    if (period <= 0) return 0;
    const auto n = static_cast<int>(std::floor((v - lo) / period));
    v -= n * period;
    return n;
  };
  k[0] = wrap(t.translation.x(), r.min.x(), problem.periods.p[0]);
  k[1] = wrap(t.translation.y(), r.min.y(), problem.periods.p[1]);
  k[2] = wrap(t.time_shift, r.t0, problem.periods.p[2]);
  return k;
}

void search(TilingState& state, Stitcher& stitcher, const PreferenceModel& preference, Rng& rng, ChainReport& report,
            const Tick& tick) {
  const Problem& problem = state.problem();
  const SearchOptions& o = problem.options.search;
  std::set<HistoryKey> history;
  const std::size_t start_dangling = std::max<std::size_t>(1, state.dangling());
  // How far a bridge may reach: a patch's end-to-end chord (at most twice its extent) and its duration, plus the
  // match thresholds at both ends.
  const double bridge_reach_m = 2 * problem.max_extent_m + 2 * problem.options.match.distance_m;
  const double bridge_span_s = 2 * problem.max_half_duration_s + 2 * problem.options.match.time_s;
  std::vector<EndMatch> near;
  // Where no end can leave by a side (every axis periodic) bridges are the only way the count falls: try them
  // first; elsewhere they are the last resort before a removal.
  const bool bridges_first = problem.region.periodic[0] && problem.region.periodic[1] && problem.region.periodic[2];
  // In a window of a windowed run an end may sit where nothing can continue it (a patch would reach back before
  // the freeze time): removing patch after patch then only moves the end back and forth; its whole group goes.
  const bool windowed = std::isfinite(problem.freeze);

  const auto still_dangling = [&](const DanglingEnd& d) {
    if (d.ref.instance >= state.slots()) return false;
    // An id removed in this sweep may have been reused by an instance of another type: check the fragment.
    const LiveInstance& inst = state.at(d.ref.instance);
    return inst.alive && d.ref.fragment < inst.ends.size() &&
           inst.ends[d.ref.fragment][static_cast<std::size_t>(d.side)].status == EndStatus::dangling;
  };

  std::size_t fewest = state.dangling(), stale = 0;
  // The instances connected to `start`'s instance through connections, transitively (every character of every
  // patch on the way): dropping them all leaves no partner dangling. Empty when a keyframe is among them.
  const auto component = [&](std::uint32_t start) {
    std::vector<std::uint32_t> out{start};
    std::set<std::uint32_t> seen{start};
    for (std::size_t k = 0; k < out.size(); ++k) {
      const LiveInstance& inst = state.at(out[k]);
      if (inst.pinned()) return std::vector<std::uint32_t>{};
      for (const auto& sides : inst.ends) {
        for (const EndLink& e : sides) {
          if (e.status == EndStatus::connected && seen.insert(e.partner.instance).second) out.push_back(e.partner.instance);
        }
      }
    }
    std::sort(out.begin(), out.end());
    return out;
  };
  // The dangling ends in sweep order (time, then instance, fragment, entry before exit).
  const auto dangling_ends = [&]() {
    std::vector<DanglingEnd> ends;
    for (std::uint32_t id = 0; id < state.slots(); ++id) {
      const LiveInstance& inst = state.at(id);
      if (!inst.alive) continue;
      for (std::uint32_t f = 0; f < inst.ends.size(); ++f) {
        for (int side = 0; side < 2; ++side) {
          if (inst.ends[f][static_cast<std::size_t>(side)].status != EndStatus::dangling) continue;
          ends.push_back({side == 1 ? inst.paths[f].times.back() : inst.paths[f].times.front(), {id, f}, side});
        }
      }
    }
    std::sort(ends.begin(), ends.end());
    return ends;
  };
  while (state.dangling() > 0 && report.search_steps < o.max_steps) {
    const std::vector<DanglingEnd> ends = dangling_ends();
    bool changed = false;
    for (const DanglingEnd& d : ends) {
      if (report.search_steps >= o.max_steps) break;
      if (!still_dangling(d)) continue;
      const LiveInstance& holder = state.at(d.ref.instance);
      const EndPoint at = problem.end_point(holder.type, holder.paths, d.ref.fragment, d.side == 1);
      const bool new_is_exit = d.side == 0;  // a dangling entry takes an exit, and the other way round

      // Bridges: patches joining d to another dangling end n at once (see the file comment).
      const auto try_bridges = [&]() {
      std::vector<Candidate> bridges;
      if (o.bridge_attempts > 0) {
        near.clear();
        state.dangling_ends().near(at, new_is_exit, bridge_reach_m, new_is_exit ? -bridge_span_s : 0.0,
                                   new_is_exit ? 0.0 : bridge_span_s, near);
        for (const EndMatch& m : near) {
          const LiveInstance& other = state.at(m.end.instance);
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
              if (history.contains(history_key(k, f, new_is_exit ? 1 : 0, at))) continue;
              const auto fit = bridge_fit(fr, new_is_exit, at, n_position, n_time, n.heading, problem.options.match);
              if (fit) bridges.push_back({fit->second, k, f, fit->first});
            }
          }
        }
        std::sort(bridges.begin(), bridges.end(), [](const Candidate& a, const Candidate& b) {
          return std::tie(a.cost, a.type, a.fragment, a.transform.time_shift, a.transform.translation.x(),
                          a.transform.translation.y()) < std::tie(b.cost, b.type, b.fragment, b.transform.time_shift,
                                                                   b.transform.translation.x(), b.transform.translation.y());
        });
        if (bridges.size() > o.bridge_attempts) bridges.resize(o.bridge_attempts);
      }
      for (const Candidate& c : bridges) {
        if (report.search_steps >= o.max_steps) break;
        ++report.search_steps;
        Transform t = c.transform;
        const std::array<int, 3> k = canonicalise(problem, t);
        const std::array<int, 3> image = new_is_exit ? std::array<int, 3>{-k[0], -k[1], -k[2]} : k;
        const Attempt a = stitcher.stitch({c.type, t, false, NewLink{c.fragment, new_is_exit, d.ref, image}});
        if (!a.feasible || a.delta_dangling >= 0 || !stitcher.valid(a)) continue;
        state.apply(a.change);
        changed = true;
        return true;
      }
      return false;
      };
      if (bridges_first && try_bridges()) continue;

      // Every usable patch end that matches d, placed exactly on it, best preference first.
      std::vector<Candidate> candidates;
      for (std::uint32_t k : problem.usable_types) {
        const PatchType& type = problem.library.types[k];
        for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
          const Fragment& fr = type.fragments[f];
          if (!fr.is_character() || (new_is_exit ? fr.exit_class : fr.entry_class) != at.pose_class) continue;
          if (history.contains(history_key(k, f, new_is_exit ? 1 : 0, at))) continue;
          const std::size_t s = new_is_exit ? fr.sample_count() - 1 : 0;
          Transform t;
          t.angle = wrap_angle(at.heading - fr.headings[s]);
          t.translation = at.position - rotate(fr.positions[s], t.angle);
          t.time_shift = at.time - fr.times[s];
          candidates.push_back({preference.cost(k, t), k, f, t});
        }
      }
      std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        return std::tie(a.cost, a.type, a.fragment) < std::tie(b.cost, b.type, b.fragment);
      });

      bool placed = false;
      for (const Candidate& c : candidates) {
        for (std::size_t i = 0; i < o.jitter_attempts && report.search_steps < o.max_steps; ++i) {
          ++report.search_steps;
          Transform t = c.transform;
          if (i > 0) {
            const double u = o.jitter_attempts > 2 ? static_cast<double>(i - 1) / static_cast<double>(o.jitter_attempts - 2) : 1.0;
            const double radius = o.jitter_distance_start_m + u * (o.jitter_distance_end_m - o.jitter_distance_start_m);
            const double angle = o.jitter_angle_start_rad + u * (o.jitter_angle_end_rad - o.jitter_angle_start_rad);
            const double time = o.jitter_time_start_s + u * (o.jitter_time_end_s - o.jitter_time_start_s);
            const double rho = radius * std::sqrt(rng.uniform()), phi = rng.uniform(-std::numbers::pi, std::numbers::pi);
            t.translation += rho * Eigen::Vector2d(std::cos(phi), std::sin(phi));
            t.angle = wrap_angle(t.angle + rng.uniform(-angle, angle));
            t.time_shift += rng.uniform(-time, time);
          }
          // Keep the instance in the tile; the stitch to d then crosses a seam: exit = entry + image ⊙ period.
          const std::array<int, 3> k = canonicalise(problem, t);
          const std::array<int, 3> image = new_is_exit ? std::array<int, 3>{-k[0], -k[1], -k[2]} : k;
          Proposal p{c.type, t, false, NewLink{c.fragment, new_is_exit, d.ref, image}};
          const Attempt a = stitcher.stitch(p);
          if (!a.feasible || a.delta_dangling > 0) {
            if (i == 0 && a.feasible) break;  // Algorithm 2 line 5: this patch would add dangling ends
            continue;
          }
          if (stitcher.valid(a)) {
            state.apply(a.change);
            placed = changed = true;
            break;
          }
        }
        if (placed) break;
      }
      if (placed || !still_dangling(d)) continue;
      if (!bridges_first && try_bridges()) continue;
      if (holder.pinned()) continue;  // nothing was applied since `holder` was taken: still valid
      // Nothing fits d: remove its patch (Algorithm 2 line 15) and remember where it was attached.
      for (std::uint32_t f = 0; f < holder.ends.size(); ++f) {
        for (int side = 0; side < 2; ++side) {
          const EndLink& e = holder.ends[f][static_cast<std::size_t>(side)];
          if (e.status != EndStatus::connected) continue;
          const LiveInstance& partner = state.at(e.partner.instance);
          history.insert(history_key(holder.type, f, side,
                                     problem.end_point(partner.type, partner.paths, e.partner.fragment, side == 0)));
        }
      }
      state.remove(d.ref.instance);
      ++report.removals;
      changed = true;
      if (tick) tick(1.0 - std::min(1.0, static_cast<double>(state.dangling()) / static_cast<double>(start_dangling)));
    }
    if (state.dangling() < fewest) {
      fewest = state.dangling();
      stale = 0;
    } else {
      ++stale;
    }
    if ((bridges_first || windowed) && stale >= o.stale_sweeps) {
      // The smallest component holding a dangling end (ties: the first in sweep order), if it is at most half
      // of the tiling: dropping more would trade the tiling for an empty one.
      std::vector<std::uint32_t> drop;
      for (const DanglingEnd& d : dangling_ends()) {
        std::vector<std::uint32_t> c = component(d.ref.instance);
        if (!c.empty() && (drop.empty() || c.size() < drop.size())) drop = std::move(c);
      }
      if (!drop.empty() && 2 * drop.size() <= state.instances()) {
        for (std::uint32_t id : drop) state.remove(id);
        report.removals += drop.size();
        changed = true;
        stale = 0;
        fewest = state.dangling();
      }
    }
    if (!changed) break;
  }
  report.search_capped = state.dangling() > 0 && report.search_steps >= o.max_steps;
}

}  // namespace throng::tiling
