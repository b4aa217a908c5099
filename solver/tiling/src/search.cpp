// Phase 2: Algorithm 2 of the paper. For each dangling end d (in time order), every usable patch with a
// matching end, best preference first, is placed with that end exactly on d; kept if it does not raise the
// number of dangling ends and is valid, else jittered with a growing range (§5.2: 0.6 m, ±15°, ±0.3 s up to
// 1.0 m, ±25°, ±0.5 s). When nothing fits, the patch holding d is removed (never a keyframe) and remembered, so
// that the same patch is not proposed at the same end again. Ends when no end dangles, when a sweep over the
// dangling ends changes nothing, or at SearchOptions::max_steps placements.
#include "phases.h"

#include <algorithm>
#include <cmath>
#include <numbers>
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

  const auto still_dangling = [&](const DanglingEnd& d) {
    if (d.ref.instance >= state.slots()) return false;
    // An id removed in this sweep may have been reused by an instance of another type: check the fragment.
    const LiveInstance& inst = state.at(d.ref.instance);
    return inst.alive && d.ref.fragment < inst.ends.size() &&
           inst.ends[d.ref.fragment][static_cast<std::size_t>(d.side)].status == EndStatus::dangling;
  };

  while (state.dangling() > 0 && report.search_steps < o.max_steps) {
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
    bool changed = false;
    for (const DanglingEnd& d : ends) {
      if (report.search_steps >= o.max_steps) break;
      if (!still_dangling(d)) continue;
      const LiveInstance& holder = state.at(d.ref.instance);
      const EndPoint at = problem.end_point(holder.type, holder.paths, d.ref.fragment, d.side == 1);
      const bool new_is_exit = d.side == 0;  // a dangling entry takes an exit, and the other way round

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
      if (placed || holder.keyframed || !still_dangling(d)) continue;
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
    if (!changed) break;
  }
  report.search_capped = state.dangling() > 0 && report.search_steps >= o.max_steps;
}

}  // namespace throng::tiling
