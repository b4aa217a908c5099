// The two phases of the tiling algorithm (§5) and one chain that runs them.
#pragma once

#include <throng/core/random.h>
#include <throng/tiling/tile.h>

#include "preference.h"
#include "state.h"
#include "stitcher.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace throng::tiling {

/// Called now and then with the chain's own progress in [0, 1].
using Tick = std::function<void(double)>;

/// Phase 1, Algorithm 1: stochastic sampling by simulated annealing with E_tiling (Eq. 6).
void anneal(TilingState& state, Stitcher& stitcher, const PreferenceModel& preference, Rng& rng, ChainReport& report,
            const Tick& tick);

/// Phase 2, Algorithm 2: deterministic search with jittering and removal, until no end dangles or the cap.
void search(TilingState& state, Stitcher& stitcher, const PreferenceModel& preference, Rng& rng, ChainReport& report,
            const Tick& tick);

/// Density per area after phase 2 (density_control.cpp): correction rounds that drop whole groups of patches
/// from over-full bins and sample under-full ones again; sets report.density_*.
void meet_density(TilingState& state, Stitcher& stitcher, const PreferenceModel& preference, Rng& rng,
                  ChainReport& report, const Tick& tick);

/// Moves a transform by whole periods into the tile on the periodic axes; returns the periods subtracted.
std::array<int, 3> canonicalise(const Problem& problem, Transform& transform);

struct ChainResult {
  Tiling tiling;
  ChainReport report;
};

/// One chain: keyframes, phase 1, phase 2, density rounds, from Rng(derive_seed(seed, chain)).
[[nodiscard]] ChainResult run_chain(const Problem& problem, const std::vector<Keyframe>& keyframes, std::size_t chain,
                                    const Tick& tick);

/// One chain of a window of a windowed run (windowed.h): from the carried instances, phase 1, phase 2, density
/// rounds, drawing from Rng(seed). The state is returned as it ends; report.characters, .instances, .dangling
/// and .mean_preference_cost describe it.
struct WindowChain {
  std::unique_ptr<TilingState> state;
  ChainReport report;
};
[[nodiscard]] WindowChain run_window_chain(const Problem& problem, std::vector<LiveInstance> carried, std::size_t chain,
                                           std::uint64_t seed, const Tick& tick);

}  // namespace throng::tiling
