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

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <cmath>
#include <memory>
#include <set>
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
    const Eigen::Vector2d& p = k.transform.translation;
    const bool inside = (r.periodic[0] || (p.x() >= r.min.x() && p.x() <= r.max.x())) &&
                        (r.periodic[1] || (p.y() >= r.min.y() && p.y() <= r.max.y())) &&
                        (r.periodic[2] || (k.transform.time_shift >= r.t0 && k.transform.time_shift <= r.t1));
    if (!inside) {
      std::ostringstream m;
      m << "tile: keyframe " << i << " ('" << library.types[k.type].name << "' at (" << p.x() << ", " << p.y() << ") m, "
        << k.transform.time_shift << " s) lies outside the region [" << r.min.x() << ", " << r.max.x() << "] × ["
        << r.min.y() << ", " << r.max.y() << "] m × [" << r.t0 << ", " << r.t1
        << "] s: a keyframe's centroid and middle time must lie inside";
      throw ConfigError(m.str());
    }
  }
}

// What the run would allocate, before it does (tile.h: max_deformation_bytes, max_index_cells).
void check_resources(const PatchLibrary& library, const Region& region, const Options& options) {
  double bytes = 0;
  std::size_t largest = 0;
  for (std::size_t k = 0; k < library.types.size(); ++k) {
    bytes += deformation_bytes(library.types[k]);
    if (library.types[k].sample_count() > library.types[largest].sample_count()) largest = k;
  }
  if (bytes > max_deformation_bytes) {
    std::ostringstream m;
    m << "tile: the patch deformation systems would take " << bytes / 1e9 << " GB (the largest, '"
      << library.types[largest].name << "', has " << library.types[largest].sample_count()
      << " samples), more than the " << max_deformation_bytes / 1e9
      << " GB allowed: sample the patches more coarsely or use shorter ones";
    throw ConfigError(m.str());
  }
  const double cells = index_cells(library, region, options);
  if (cells > max_index_cells) {
    std::ostringstream m;
    m << "tile: the space-time index would have " << cells << " cells over the region and its margins, more than "
      << max_index_cells << ": raise index.cell (" << options.index.cell_m << " m) or index.cell_time ("
      << options.index.cell_s << " s), or tile a smaller region";
    throw ConfigError(m.str());
  }
}

// A keyframe is kept as placed and never removed: an end of it inside the region (one that needs a partner)
// whose pose class no usable type continues could never be connected, so the run could never be perfect.
void check_keyframe_ends(const PatchLibrary& library, const Environment& environment, const Viability& viability,
                         const std::vector<Keyframe>& keyframes) {
  std::set<std::size_t> entries, exits;  // pose classes of the usable types' entries and exits
  for (std::size_t k = 0; k < library.types.size(); ++k) {
    if (!viability.usable[k]) continue;
    for (const Fragment& f : library.types[k].fragments) {
      if (!f.is_character()) continue;
      entries.insert(f.entry_class);
      exits.insert(f.exit_class);
    }
  }
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    const PatchType& type = library.types[keyframes[i].type];
    const std::vector<Path> paths = place(type, keyframes[i].transform);
    for (std::size_t f = 0; f < type.fragments.size(); ++f) {
      const Fragment& fr = type.fragments[f];
      if (!fr.is_character()) continue;
      for (const bool exit : {false, true}) {
        const Path& p = paths[f];
        const std::size_t s = exit ? p.times.size() - 1 : 0;
        if (end_needs_no_partner(environment, p.positions[s], p.times[s], exit)) continue;
        const std::size_t c = exit ? fr.exit_class : fr.entry_class;
        if ((exit ? entries : exits).contains(c)) continue;
        std::ostringstream m;
        m << "tile: keyframe " << i << " ('" << type.name << "'): the " << (exit ? "exit" : "entry") << " of fragment " << f
          << " at (" << p.positions[s].x() << ", " << p.positions[s].y() << ") m, " << p.times[s] << " s has pose class '"
          << library.pose_classes[c] << "', which no usable patch " << (exit ? "enters" : "leaves")
          << " with: it could never be connected";
        if (!viability.usable[keyframes[i].type]) m << " (the patch itself is never used: " << viability.why[keyframes[i].type] << ")";
        m << ". Add patches " << (exit ? "entering" : "leaving") << " with that class, or place the keyframe so this end "
          << "lies outside the region";
        throw ConfigError(m.str());
      }
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
std::tuple<double, double, double, double, double> score(const ChainReport& r, const Options& options) {
  const double characters = static_cast<double>(r.characters);
  const double density = options.characters > 0 ? std::abs(characters - static_cast<double>(options.characters)) : -characters;
  return {static_cast<double>(r.dangling), r.density_distance, density, r.mean_preference_cost, static_cast<double>(r.chain)};
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

double deformation_bytes(const PatchType& type) {
  const auto n = static_cast<double>(type.sample_count());
  return 8.0 * ((2 * n) * (2 * n) + n * n);
}

double index_cells(const PatchLibrary& library, const Region& region, const Options& options) {
  const double segments = Grid3::cells(region, options.index.cell_m, options.index.cell_s,
                                       index_margin_m(options, max_extent_of(library)),
                                       index_margin_s(options, max_half_duration_of(library)));
  const MatchThresholds& m = options.match;
  const double ends = Grid3::cells(region, EndIndex::cell_m(m), EndIndex::cell_s(m), EndIndex::margin_m(m), EndIndex::margin_s(m));
  return std::max(segments, ends);
}

TilingResult tile(const PatchLibrary& library, const Environment& environment, const std::vector<Keyframe>& keyframes,
                  const Options& options, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  check_inputs(library, environment, keyframes, options);
  const Viability viability = find_usable_types(library);
  if (std::none_of(viability.usable.begin(), viability.usable.end(), [](bool u) { return u; })) {
    std::ostringstream m;
    m << "tile: no patch type can ever be placed inside the region without leaving an end that nothing can continue:";
    for (std::size_t k = 0; k < library.types.size(); ++k) m << (k ? ";" : "") << " '" << library.types[k].name << "': " << viability.why[k];
    m << ". Add patches whose entries take the exits' pose classes (and the other way round)";
    throw NumericalError(m.str());
  }
  check_keyframe_ends(library, environment, viability, keyframes);
  check_resources(library, *environment.scene.region, options);
  progress.update(0.0, "precomputing patch systems");
  const Problem problem(library, environment, options);
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
