// Phase 2: Algorithm 2 of the paper. For each dangling end d (in time order), every usable patch with a
// matching end, best preference first, is placed with that end exactly on d; kept if it does not raise the
// number of dangling ends and is valid, else jittered with a growing range (§5.2: 0.6 m, ±15°, ±0.3 s up to
// 1.0 m, ±25°, ±0.5 s). When nothing fits, the patch holding d is removed (never a keyframe) and remembered, so
// that the same patch is not proposed at the same end again. Ends when no end dangles, when a sweep over the
// dangling ends changes nothing, or at SearchOptions::max_steps placements.
//
// Bridges (our addition, bridges.h): patches joining d to another dangling end at once, tried before removing d's
// patch; on a tile periodic on every axis, where no end can leave by a side, before the candidates, and there
// also pairs of patches (one on d, a bridge from its other end), the candidates in order of bridges.h's
// schedule_cost instead of the preference, and only exits continued: an entry waits for an exit to be walked to
// it (continuing both, they pass each other in time between two sweeps). Without them such a tile rarely closes:
// an end pushed forward meets another only by chance. On such a tile, after SearchOptions::stale_sweeps sweeps in
// a row that did not lower the count, the smallest group of patches connected to a dangling end (through every
// connection of every character on the way; nothing pinned among them; at most half the tiling) is dropped whole:
// its dangling ends go and no partner is left dangling. The same holds in a window of a windowed run (problem.h),
// where an end just after the freeze time may have nothing that fits before it: removals would only move it back
// and forth. On a tile periodic on every axis with a density per area (options.h), a candidate may not raise a
// time bin above (1 + tolerance) × its target: with no side to leave by, a chain pushed on would fill the tile.
#include "bridges.h"
#include "phases.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
  // Where no end can leave by a side (every axis periodic) bridges are the only way the count falls: try them
  // first; elsewhere they are the last resort before a removal.
  const bool bridges_first = problem.region.periodic[0] && problem.region.periodic[1] && problem.region.periodic[2];
  // In a window of a windowed run an end may sit where nothing can continue it (a patch would reach back before
  // the freeze time): removing patch after patch then only moves the end back and forth; its whole group goes.
  const bool windowed = std::isfinite(problem.freeze);
  // On a tile periodic on every axis with a density, a chain pushed on and on would fill the tile (no side to
  // leave by): candidates may not raise a bin above (1 + tolerance) × its target.
  const bool growth_capped = bridges_first && state.presence().enabled();
  const double growth_factor = 1 + problem.options.density.tolerance;
  Presence::Delta growth;
  const auto within_density = [&](const Attempt& a) {
    if (!growth_capped) return true;
    growth.clear();
    stitcher.presence_delta(a, growth);
    return state.presence().fits(growth, growth_factor);
  };
  Bridger bridger(
      state, stitcher, report,
      [&](std::uint32_t type, std::uint32_t fragment, int side, const EndPoint& at) {
        return history.contains(history_key(type, fragment, side, at));
      },
      within_density);

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

      if (bridges_first && bridger.one(d.ref, d.side)) {
        changed = true;
        continue;
      }
      // On a tile periodic on every axis only exits are continued (see the file comment).
      if (bridges_first && d.side == 0) continue;
      // There, the dangling ends the candidates' open ends could walk to.
      std::vector<EndPoint> partners;
      if (bridges_first) {
        for (const DanglingEnd& e : ends) {
          if (e.side == d.side || !still_dangling(e)) continue;
          const LiveInstance& other = state.at(e.ref.instance);
          partners.push_back(problem.end_point(other.type, other.paths, e.ref.fragment, e.side == 1));
        }
      }

      // Every usable patch end that matches d, placed exactly on it, best preference first.
      std::vector<Placement> candidates;
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
          double cost = preference.cost(k, t);
          if (bridges_first) {
            const std::size_t open = new_is_exit ? 0 : fr.sample_count() - 1;  // the candidate's other end
            cost = bridger.schedule_cost(t.apply(fr.positions[open]), fr.times[open] + t.time_shift, d.side, partners);
          }
          candidates.push_back({cost, k, f, t});
        }
      }
      std::sort(candidates.begin(), candidates.end(), [](const Placement& a, const Placement& b) {
        return std::tie(a.cost, a.type, a.fragment) < std::tie(b.cost, b.type, b.fragment);
      });

      bool placed = false;
      if (bridges_first && d.side == 1) {
        // A planned way to the nearest entries first (bridges.h, close).
        std::vector<EndPoint> nearest = partners;
        const auto distance = [&](const EndPoint& n) {
          Eigen::Vector2d v = n.position - at.position;
          for (int axis = 0; axis < 2; ++axis) {
            const double p = problem.periods.p[static_cast<std::size_t>(axis)];
            v[axis] -= std::round(v[axis] / p) * p;
          }
          return v.norm();
        };
        std::stable_sort(nearest.begin(), nearest.end(),
                         [&](const EndPoint& a, const EndPoint& b) { return distance(a) < distance(b); });
        if (nearest.size() > 3) nearest.resize(3);
        if (bridger.close(d.ref, nearest)) {
          changed = true;
          continue;
        }
      }
      if (bridges_first && bridger.two(d.ref, d.side, candidates)) {
        changed = true;
        continue;
      }
      for (const Placement& c : candidates) {
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
          if (within_density(a) && stitcher.valid(a)) {
            state.apply(a.change);
            placed = changed = true;
            break;
          }
        }
        if (placed) break;
      }
      if (placed || !still_dangling(d)) continue;
      if (!bridges_first && bridger.one(d.ref, d.side)) {
        changed = true;
        continue;
      }
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
