// tile(): input checks, the impossibility test, and multi-start over threads and MPI ranks.
//
// Chain c runs on rank c mod size; a rank runs its chains in parallel (TBB). Each chain depends only on
// (problem, seed, c), so its result is the same bits wherever it runs. The best chain is chosen by every rank
// from the all-gathered scores (fewest dangling, density rule, mean preference cost, chain index) and sent by
// the rank that ran it to all others.
#include <throng/tiling/tile.h>

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/linalg/mpi.h>
#include <throng/tiling/characters.h>

#include "phases.h"
#include "serialize.h"
#include "viability.h"

#include <atomic>
#include <chrono>
#include <cstring>
#include <cmath>
#include <memory>
#include <sstream>
#include <thread>
#include <tuple>

namespace throng::tiling {
namespace {

void check_inputs(const PatchLibrary& library, const Environment& environment, const std::vector<Keyframe>& keyframes,
                  const Options& options) {
  validate(options);
  library.validate();
  if (!environment.scene.region) {
    throw ConfigError("tile: no region: the tiler fills a space-time box (give `region: {min, max, time}`)");
  }
  const Region& r = *environment.scene.region;
  if (!(r.max.x() > r.min.x() && r.max.y() > r.min.y() && r.t1 > r.t0)) {
    throw ConfigError("tile: the region must have max > min on x and y and t1 > t0");
  }
  environment.scene.validate("tile scene");
  const auto check_zones = [](const std::vector<Zone>& zones, const char* what) {
    for (std::size_t i = 0; i < zones.size(); ++i) {
      const Zone& z = zones[i];
      if (!(z.radius_m > 0) || !z.center.allFinite() || !(z.t1 >= z.t0)) {
        throw ConfigError(std::string("tile: ") + what + " " + std::to_string(i) +
                          ": expected a finite centre, radius > 0 and t1 ≥ t0");
      }
    }
  };
  check_zones(environment.sources, "source");
  check_zones(environment.sinks, "sink");
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const Keyframe& k = keyframes[i];
    if (k.type >= library.types.size()) {
      throw ConfigError("tile: keyframe " + std::to_string(i) + " names patch type " + std::to_string(k.type) + " of " +
                        std::to_string(library.types.size()));
    }
    if (!k.transform.translation.allFinite() || !std::isfinite(k.transform.angle) || !std::isfinite(k.transform.time_shift)) {
      throw ConfigError("tile: keyframe " + std::to_string(i) + " has a non-finite placement");
    }
  }
}

// Keyframes must not overlap each other or an obstacle: the user placed them, the tiler cannot move them.
void check_keyframes(const Problem& problem, const std::vector<Keyframe>& keyframes) {
  TilingState state(problem);
  Stitcher stitcher(state);
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    Attempt a;
    a.change.type = static_cast<std::uint32_t>(keyframes[i].type);
    a.change.transform = keyframes[i].transform;
    canonicalise(problem, a.change.transform);
    a.change.keyframed = true;
    a.change.paths = place(problem.library.types[keyframes[i].type], a.change.transform);
    a.feasible = true;
    if (!stitcher.valid(a)) {
      std::ostringstream m;
      m << "tile: keyframe " << i << " ('" << problem.library.types[keyframes[i].type].name << "' at ("
        << keyframes[i].transform.translation.x() << ", " << keyframes[i].transform.translation.y() << ") m, "
        << keyframes[i].transform.time_shift << " s) overlaps an earlier keyframe or an obstacle";
      throw ConfigError(m.str());
    }
    state.apply(a.change);
  }
}

// The ranking key of a chain: smaller is better.
std::tuple<double, double, double, double> score(const ChainReport& r, const Options& options) {
  const double characters = static_cast<double>(r.characters);
  const double density = options.characters > 0 ? std::abs(characters - static_cast<double>(options.characters)) : -characters;
  return {static_cast<double>(r.dangling), density, r.mean_preference_cost, static_cast<double>(r.chain)};
}

std::vector<double> as_doubles(const ChainReport& r) {
  std::vector<double> d((sizeof(ChainReport) + sizeof(double) - 1) / sizeof(double), 0.0);
  std::memcpy(d.data(), &r, sizeof(ChainReport));
  return d;
}

ChainReport from_doubles(const double* d) {
  ChainReport r;
  std::memcpy(static_cast<void*>(&r), d, sizeof(ChainReport));
  return r;
}

}  // namespace

TilingResult tile(const PatchLibrary& library, const Environment& environment, const std::vector<Keyframe>& keyframes,
                  const Options& options, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  check_inputs(library, environment, keyframes, options);
  progress.update(0.0, "precomputing patch systems");
  const Problem problem(library, environment, options);
  if (problem.usable_types.empty()) {
    std::ostringstream m;
    m << "tile: no patch type can ever be placed inside the region without leaving an end that nothing can continue:";
    const Viability v = find_usable_types(library);
    for (std::size_t k = 0; k < library.types.size(); ++k) m << (k ? ";" : "") << " '" << library.types[k].name << "': " << v.why[k];
    m << ". Add patches whose entries take the exits' pose classes (and the other way round)";
    throw NumericalError(m.str());
  }
  check_keyframes(problem, keyframes);

  const int rank = mpi::rank(), size = mpi::size();
  std::vector<std::size_t> mine;
  for (std::size_t c = 0; c < options.chains; ++c) {
    if (static_cast<int>(c % static_cast<std::size_t>(size)) == rank) mine.push_back(c);
  }
  std::vector<ChainResult> results(mine.size());
  const auto fractions = std::make_unique<std::atomic<double>[]>(std::max<std::size_t>(1, mine.size()));
  for (std::size_t i = 0; i < mine.size(); ++i) fractions[i] = 0.0;
  const std::thread::id caller = std::this_thread::get_id();
  parallel_for(mine.size(), 1, [&](std::size_t a, std::size_t b) {
    for (std::size_t i = a; i < b; ++i) {
      results[i] = run_chain(problem, keyframes, mine[i], [&, i](double f) {
        fractions[i] = f;
        if (std::this_thread::get_id() != caller) return;
        double sum = 0;
        for (std::size_t j = 0; j < mine.size(); ++j) sum += fractions[j];
        progress.update(std::min(1.0, sum / static_cast<double>(mine.size())), "tiling");
      });
      results[i].report.characters = count_characters(library, results[i].tiling);
    }
  });

  // Every chain's report on every rank, in chain order.
  std::vector<double> local;
  for (const ChainResult& r : results) {
    const std::vector<double> d = as_doubles(r.report);
    local.insert(local.end(), d.begin(), d.end());
  }
  const std::size_t per = as_doubles(ChainReport{}).size();
  std::vector<ChainReport> reports(options.chains);
  if (size > 1) {
    for (const std::vector<double>& from : mpi::all_gather(local)) {
      for (std::size_t k = 0; k + per <= from.size(); k += per) {
        const ChainReport r = from_doubles(from.data() + k);
        reports[r.chain] = r;
      }
    }
  } else {
    for (const ChainResult& r : results) reports[r.report.chain] = r.report;
  }
  std::size_t best = 0;
  for (std::size_t c = 1; c < reports.size(); ++c) {
    if (score(reports[c], options) < score(reports[best], options)) best = c;
  }

  TilingResult out;
  const int owner = static_cast<int>(best % static_cast<std::size_t>(size));
  if (size > 1) {
    std::vector<std::byte> bytes;
    if (rank == owner) {
      for (const ChainResult& r : results) {
        if (r.report.chain == best) bytes = to_bytes(r);
      }
    }
    mpi::broadcast(bytes, owner);
    out.tiling = from_bytes(bytes).tiling;
  } else {
    for (ChainResult& r : results) {
      if (r.report.chain == best) out.tiling = std::move(r.tiling);
    }
  }
  out.report.chains = reports;
  out.report.best_chain = best;
  out.report.dangling = reports[best].dangling;
  out.report.instances = out.tiling.instances.size();
  out.report.characters = reports[best].characters;
  out.report.connections = out.tiling.connections.size();
  for (std::size_t k = 0; k < library.types.size(); ++k) {
    if (!problem.usable[k]) out.report.unusable_types.push_back(k);
  }
  out.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  progress.update(1.0, "tiling");
  return out;
}

}  // namespace throng::tiling
