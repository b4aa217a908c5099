// Phase 1: Algorithm 1 of the paper as printed (METHODS.md §4): T starts at T_max and falls by ΔT at every
// proposal (never below 0); a proposal is accepted when e^(−ΔE / kT) > R(0, 1) and it is valid; i counts the
// proposals since the last acceptance and the phase ends at i_max.
#include "phases.h"

#include <algorithm>
#include <cmath>

namespace throng::tiling {

void anneal(TilingState& state, Stitcher& stitcher, const PreferenceModel& preference, Rng& rng, ChainReport& report,
            const Tick& tick) {
  const AnnealingOptions& o = state.problem().options.annealing;
  const std::size_t target = state.problem().options.characters;
  double temperature = o.t_max;
  std::size_t failures = 0;
  while (failures < o.max_failures && report.proposals < o.max_proposals) {
    ++report.proposals;
    Proposal p;
    p.type = preference.sample_type(rng);
    p.transform = preference.sample_transform(rng);
    const double r = rng.uniform();
    const Attempt a = stitcher.stitch(p);
    bool accepted = false;
    const bool too_many = target > 0 && a.delta_characters > 0 &&
                          state.characters() + static_cast<std::size_t>(a.delta_characters) > target;
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
    failures = accepted ? 1 : failures + 1;
    temperature = std::max(0.0, temperature - o.t_step);
    if ((report.proposals & 1023) == 0 && tick) tick(static_cast<double>(failures) / static_cast<double>(o.max_failures));
  }
}

}  // namespace throng::tiling
