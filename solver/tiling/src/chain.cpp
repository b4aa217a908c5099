#include "phases.h"

#include <chrono>
#include <tuple>

namespace throng::tiling {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The counts and the mean preference cost of a chain's final state.
void describe(const TilingState& state, const PreferenceModel& preference, ChainReport& report) {
  report.dangling = state.dangling();
  report.instances = state.instances();
  report.characters = state.characters();
  double cost = 0;
  for (std::uint32_t id = 0; id < state.slots(); ++id) {
    const LiveInstance& inst = state.at(id);
    if (inst.alive) cost += preference.cost(inst.type, inst.transform);
  }
  report.mean_preference_cost = state.instances() == 0 ? 0.0 : cost / static_cast<double>(state.instances());
}

}  // namespace

namespace {

// One attempt of a chain: keyframes, phase 1, phase 2, density rounds, drawing from `rng`.
ChainResult attempt(const Problem& problem, const std::vector<Keyframe>& keyframes, std::size_t chain, Rng& rng,
                    const Tick& tick) {
  ChainResult out;
  ChainReport& report = out.report;
  report.chain = chain;
  TilingState state(problem);
  Stitcher stitcher(state);
  const PreferenceModel preference(problem);

  for (const Keyframe& k : keyframes) {
    Change c;
    c.type = static_cast<std::uint32_t>(k.type);
    c.transform = k.transform;
    canonicalise(problem, c.transform);
    c.keyframed = true;
    c.paths = place(problem.library.types[k.type], c.transform);
    state.apply(c);
  }

  const auto start = std::chrono::steady_clock::now();
  // Keyframes first get their characters continued by the deterministic search while the space around them is
  // still empty: phase 1 would otherwise crowd their ends, and phase 2 may not remove a keyframe to free them.
  if (!keyframes.empty()) search(state, stitcher, preference, rng, report, {});
  anneal(state, stitcher, preference, rng, report, [&](double f) { if (tick) tick(0.5 * f); });
  report.phase1_seconds = seconds_since(start);
  report.phase1_instances = state.instances();
  report.phase1_dangling = state.dangling();

  const auto start2 = std::chrono::steady_clock::now();
  search(state, stitcher, preference, rng, report, [&](double f) { if (tick) tick(0.5 + 0.5 * f); });
  meet_density(state, stitcher, preference, rng, report, {});
  report.phase2_seconds = seconds_since(start2);

  out.tiling = state.snapshot();
  describe(state, preference, report);
  if (tick) tick(1.0);
  return out;
}

}  // namespace

ChainResult run_chain(const Problem& problem, const std::vector<Keyframe>& keyframes, std::size_t chain, const Tick& tick) {
  const Region& region = problem.region;
  const SearchOptions& o = problem.options.search;
  Rng rng(derive_seed(problem.options.seed, chain));
  if (!(region.periodic[0] && region.periodic[1] && region.periodic[2]) || o.restarts == 0) return attempt(problem, keyframes, chain, rng, tick);
  // A tile periodic on every axis: attempts of restart_steps placements, the first from the chain's own stream
  // (options.h SearchOptions::restarts).
  Options options = problem.options;
  options.search.max_steps = std::min(o.max_steps, o.restart_steps);
  const Problem limited(problem.precompute, problem.library, problem.environment, options, problem.window);
  ChainResult best;
  double seconds[2] = {0, 0};
  for (std::size_t a = 0; a <= o.restarts; ++a) {
    Rng attempt_rng(a == 0 ? derive_seed(problem.options.seed, chain) : derive_seed(derive_seed(problem.options.seed, chain), a));
    ChainResult r = attempt(a == o.restarts ? problem : limited, keyframes, chain, attempt_rng, a == 0 ? tick : Tick{});
    seconds[0] += r.report.phase1_seconds;
    seconds[1] += r.report.phase2_seconds;
    const bool better = a == 0 || std::tie(r.report.dangling, r.report.density_distance) <
                                      std::tie(best.report.dangling, best.report.density_distance);
    if (better) best = std::move(r);
    best.report.attempts = a + 1;
    if (best.report.dangling == 0) break;
  }
  best.report.phase1_seconds = seconds[0];
  best.report.phase2_seconds = seconds[1];
  return best;
}

WindowChain run_window_chain(const Problem& problem, std::vector<LiveInstance> carried, std::size_t chain,
                             std::uint64_t seed, const Tick& tick) {
  WindowChain out;
  ChainReport& report = out.report;
  report.chain = chain;
  Rng rng(seed);
  out.state = std::make_unique<TilingState>(problem);
  TilingState& state = *out.state;
  state.restore(std::move(carried));
  Stitcher stitcher(state);
  const PreferenceModel preference(problem);

  const auto start = std::chrono::steady_clock::now();
  anneal(state, stitcher, preference, rng, report, [&](double f) { if (tick) tick(0.5 * f); });
  report.phase1_seconds = seconds_since(start);
  report.phase1_instances = state.instances();
  report.phase1_dangling = state.dangling();
  const auto start2 = std::chrono::steady_clock::now();
  search(state, stitcher, preference, rng, report, [&](double f) { if (tick) tick(0.5 + 0.5 * f); });
  meet_density(state, stitcher, preference, rng, report, {});
  report.phase2_seconds = seconds_since(start2);
  describe(state, preference, report);
  if (tick) tick(1.0);
  return out;
}

}  // namespace throng::tiling
