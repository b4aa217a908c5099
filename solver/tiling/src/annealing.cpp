// Phase 1: Algorithm 1 of the paper as printed (METHODS.md §4): T starts at T_max and falls by ΔT at every
// proposal (never below 0); a proposal is accepted when e^(−ΔE / kT) > R(0, 1) and it is valid; i counts the
// proposals since the last acceptance and the phase ends at i_max.
//
// Density caps: a proposal is refused (a failure) when it would make the tiling hold more than
// Options::characters characters (on a tile periodic on every axis with a density per area: its target count),
// or raise the presence of some area in some time bin above its target
// (presence.h: the patch's paths and the projections of its ends still open). The rigid placement's paths are
// tested first, before the stitch, so a full bin costs little. In a window of a windowed run, a proposal is
// refused when an entry it leaves dangling could not be continued back to a side of the region after the
// window's freeze time (stitcher.h, entries_reachable).
#include "phases.h"

#include <algorithm>
#include <cmath>

namespace throng::tiling {
namespace {

// Options::characters; on a tile periodic on every axis with a density per area and no such cap, the region's
// mean target count: there every character is a loop present at every time, so starting more chains than
// characters only leaves ends that phase 2 must pair up.
std::size_t chain_cap(const TilingState& state) {
  const Problem& problem = state.problem();
  const Presence& presence = state.presence();
  const Region& r = problem.region;
  if (problem.options.characters > 0 || !presence.enabled() || !(r.periodic[0] && r.periodic[1] && r.periodic[2])) {
    return problem.options.characters;
  }
  double sum = 0;
  for (std::size_t b = 0; b < presence.bins(); ++b) sum += presence.target(0, b);
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(sum / static_cast<double>(presence.bins()))));
}

}  // namespace

void anneal(TilingState& state, Stitcher& stitcher, const PreferenceModel& preference, Rng& rng, ChainReport& report,
            const Tick& tick) {
  const AnnealingOptions& o = state.problem().options.annealing;
  const std::size_t target = chain_cap(state);
  double temperature = o.t_max;
  std::size_t failures = 0;
  const bool capped = state.presence().enabled();
  Presence::Delta delta;
  while (failures < o.max_failures && report.proposals < o.max_proposals) {
    ++report.proposals;
    Proposal p;
    p.type = preference.sample_type(rng);
    p.transform = preference.sample_transform(rng);
    const double r = rng.uniform();
    bool accepted = false;
    bool fits = true;
    if (capped) {
      delta.clear();
      stitcher.placement_presence(p.type, place(state.problem().library.types[p.type], p.transform), delta);
      fits = state.presence().fits(delta, 1.0);
    }
    if (fits) {
      const Attempt a = stitcher.stitch(p);
      bool too_many = target > 0 && a.delta_characters > 0 &&
                      state.characters() + static_cast<std::size_t>(a.delta_characters) > target;
      if (capped && a.feasible && !too_many) {
        delta.clear();
        stitcher.presence_delta(a, delta);
        too_many = !state.presence().fits(delta, 1.0);
      }
      if (a.feasible && !too_many && !stitcher.entries_reachable(a)) too_many = true;
      if (a.feasible && !too_many) {
        const double nd = static_cast<double>(state.dangling()), nc = static_cast<double>(state.connected_ends());
        const double dE = state.energy(nd + static_cast<double>(a.delta_dangling), nc + static_cast<double>(a.delta_connected)) -
                          state.energy(nd, nc);
        const bool metropolis = dE <= 0 || (temperature > 0 && std::exp(-dE / (o.boltzmann_k * temperature)) > r);
        if (metropolis && stitcher.valid(a)) {
          state.apply(a.change);
          ++report.accepted;
          accepted = true;
        }
      }
    }
    failures = accepted ? 1 : failures + 1;
    temperature = std::max(0.0, temperature - o.t_step);
    if ((report.proposals & 1023) == 0 && tick) tick(static_cast<double>(failures) / static_cast<double>(o.max_failures));
  }
}

}  // namespace throng::tiling
