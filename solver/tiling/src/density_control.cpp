// Density per area after phase 2 (options.h DensityOptions, presence.h). Phase 1 fills each time bin up to its
// target, counting what its seed patches will become (the projections of their open ends); phase 2 then
// continues the chains, and removals and chains that do not run straight leave some bins above or below.
// Each round (at most DensityOptions::rounds):
//   over   bins above (1 + tolerance) × target lose whole groups of patches: the connected groups (every
//          instance reachable through connections; none pinned, none joined to an instance outside the state)
//          whose removal lowers the total distance of the bins to their band the most, one at a time, while one
//          lowers it. A whole group leaves no end dangling.
//   under  bins below (1 − tolerance) × target get phase 1 again (its cap stops at the target) and phase 2.
// Only the bins the problem's sample span overlaps are controlled (a window's own); the rounds stop when every
// one lies in its band or a round changed nothing.
#include "phases.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace throng::tiling {
namespace {

struct Band {
  std::size_t first_bin = 0, last_bin = 0;  // controlled bins [first, last)
  double tolerance = 0.1;
};

Band band_of(const TilingState& state) {
  const Presence& p = state.presence();
  const Problem& problem = state.problem();
  Band b;
  b.tolerance = problem.options.density.tolerance;
  if (problem.region.periodic[2]) {
    b.last_bin = p.bins();
    return b;
  }
  b.first_bin = p.bin_of(problem.sample_t0);
  const std::size_t last = p.bin_of(std::nextafter(problem.sample_t1, -1e300));
  b.last_bin = last == p.bins() ? p.bins() : last + 1;
  if (b.first_bin == p.bins()) b.first_bin = 0;
  return b;
}

// How far a bin's occupancy lies outside its band.
double distance(double occupancy, double target, double tolerance) {
  return std::max({0.0, occupancy - (1 + tolerance) * target, (1 - tolerance) * target - occupancy});
}

// Σ distance over the controlled bins, and whether any bin lies above or below.
struct Status {
  double distance = 0;
  double target = 0;
  bool over = false;
  bool under = false;
};

Status status_of(const TilingState& state, const Band& band) {
  const Presence& p = state.presence();
  Status s;
  for (std::size_t a = 0; a < p.areas(); ++a) {
    for (std::size_t b = band.first_bin; b < band.last_bin; ++b) {
      const double o = p.occupancy(a, b), t = p.target(a, b);
      s.distance += distance(o, t, band.tolerance);
      s.target += t;
      s.over = s.over || o > (1 + band.tolerance) * t;
      s.under = s.under || o < (1 - band.tolerance) * t;
    }
  }
  return s;
}

// The connected groups of live instances that may be removed whole (see the file comment), in order of their
// lowest id; each sorted.
std::vector<std::vector<std::uint32_t>> removable_groups(const TilingState& state) {
  std::vector<std::vector<std::uint32_t>> groups;
  std::vector<char> seen(state.slots(), 0);
  for (std::uint32_t start = 0; start < state.slots(); ++start) {
    if (seen[start] || !state.at(start).alive) continue;
    std::vector<std::uint32_t> group{start};
    seen[start] = 1;
    bool removable = true;
    for (std::size_t k = 0; k < group.size(); ++k) {
      const LiveInstance& inst = state.at(group[k]);
      removable = removable && !inst.pinned();
      for (const auto& sides : inst.ends) {
        for (const EndLink& e : sides) {
          if (e.status != EndStatus::connected) continue;
          if (e.partner.instance == gone) {
            removable = false;
            continue;
          }
          if (!seen[e.partner.instance]) {
            seen[e.partner.instance] = 1;
            group.push_back(e.partner.instance);
          }
        }
      }
    }
    if (!removable) continue;
    std::sort(group.begin(), group.end());
    groups.push_back(std::move(group));
  }
  return groups;
}

// Drops groups from over-full bins while that brings the bins closer to their bands; returns how many instances.
std::size_t drop_over(TilingState& state, const Band& band) {
  const Presence& p = state.presence();
  std::size_t dropped = 0;
  Presence::Delta delta;
  for (;;) {
    const std::vector<std::vector<std::uint32_t>> groups = removable_groups(state);
    double best_gain = 1e-9;
    std::size_t best = groups.size();
    for (std::size_t g = 0; g < groups.size(); ++g) {
      delta.clear();
      for (std::uint32_t id : groups[g]) state.presence_of(id, -1.0, delta);
      // Net change per controlled bin, then the change of distance.
      std::vector<std::pair<std::size_t, double>> net(delta.terms);
      std::sort(net.begin(), net.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      double gain = 0;
      bool touches_over = false;
      for (std::size_t i = 0; i < net.size();) {
        double sum = 0;
        std::size_t j = i;
        for (; j < net.size() && net[j].first == net[i].first; ++j) sum += net[j].second;
        const std::size_t area = net[i].first / p.bins(), bin = net[i].first % p.bins();
        if (bin >= band.first_bin && bin < band.last_bin) {
          const double o = p.occupancy(area, bin), t = p.target(area, bin);
          touches_over = touches_over || o > (1 + band.tolerance) * t;
          gain += distance(o, t, band.tolerance) - distance(o + sum, t, band.tolerance);
        }
        i = j;
      }
      if (touches_over && gain > best_gain) {
        best_gain = gain;
        best = g;
      }
    }
    if (best == groups.size()) return dropped;
    for (std::uint32_t id : groups[best]) state.remove(id);
    dropped += groups[best].size();
  }
}

}  // namespace

void meet_density(TilingState& state, Stitcher& stitcher, const PreferenceModel& preference, Rng& rng,
                  ChainReport& report, const Tick& tick) {
  if (!state.presence().enabled()) return;
  const Band band = band_of(state);
  const std::size_t rounds = state.problem().options.density.rounds;
  for (std::size_t round = 0; round < rounds; ++round) {
    const Status before = status_of(state, band);
    if (!before.over && !before.under) break;
    ++report.density_rounds;
    if (before.over) report.density_removed += drop_over(state, band);
    if (status_of(state, band).under) {
      anneal(state, stitcher, preference, rng, report, {});
      search(state, stitcher, preference, rng, report, {});
    }
    if (tick) tick(static_cast<double>(round + 1) / static_cast<double>(rounds));
    if (status_of(state, band).distance >= before.distance) break;  // the round made nothing better
  }
  const Status after = status_of(state, band);
  report.density_distance = after.target > 0 ? after.distance / after.target : 0.0;
}

}  // namespace throng::tiling
