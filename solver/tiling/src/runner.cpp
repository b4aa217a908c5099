#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/tiling/runner.h>
#include <throng/tiling/schema.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <sstream>
#include <type_traits>
#include <variant>

namespace throng::tiling {
namespace {

// The resources tile() would need (tile.h), named by the keys that set them.
void check_resources(const Job& job, const Prepared& p) {
  std::size_t largest = 0;
  double bytes = 0;
  for (std::size_t k = 0; k < p.library.types.size(); ++k) {
    bytes += deformation_bytes(p.library.types[k]);
    if (p.library.types[k].sample_count() > p.library.types[largest].sample_count()) largest = k;
  }
  if (bytes > max_deformation_bytes) {
    const PatchType& big = p.library.types[largest];
    const bool real_patch = largest >= p.library.types.size() - p.recorded_types;
    std::ostringstream m;
    m << (real_patch ? "library.real.sample_rate" : "library.builtin_options.sample_rate") << " = "
      << (real_patch ? job.library.real_options.sample_rate_hz : job.library.builtin_options.sample_rate_hz)
      << " Hz: the patch deformation systems would take " << bytes / 1e9 << " GB ('" << big.name << "' alone has "
      << big.sample_count() << " samples), more than the " << max_deformation_bytes / 1e9 << " GB allowed; lower the sample rate";
    throw ConfigError(m.str());
  }
  // A windowed run indexes one window and its look-ahead (at most another window) at a time, not the horizon.
  Region r = *job.environment.scene.region;
  if (job.window_s > 0) r.t1 = std::min(r.t1, r.t0 + 2 * job.window_s);
  const double cells = index_cells(p.library, r, job.options);
  if (cells > max_index_cells) {
    std::ostringstream m;
    m << "index.cell = " << job.options.index.cell_m << " m, index.cell_time = " << job.options.index.cell_s
      << " s: the space-time index would have " << cells << " cells over the region and its margins, more than "
      << max_index_cells << "; use larger cells or a smaller region";
    throw ConfigError(m.str());
  }
}

}  // namespace

void describe(OptionBinder& b, Job& job) {
  describe(b, job.options);
  b.section("output", [&](OptionBinder& o) { describe(o, job.layout); });
  b.field({.key = "window", .unit = "s", .range = Range::non_negative(),
           .help = "tile the horizon window by window and stream it to the output (throng tile; 0: all at once)"},
          job.window_s);
  b.section("library", [&](OptionBinder& l) {  // each block only with its kind of patches
    if (l.present({.key = "builtin_options"}, !job.library.builtin.empty())) {
      l.section("builtin_options", [&](OptionBinder& o) { describe(o, job.library.builtin_options); });
    }
    if (l.present({.key = "real"}, job.library.real)) {
      l.section("real", [&](OptionBinder& o) { describe(o, job.library.real_options); });
    }
  });
}

std::vector<std::string> builtin_names(const std::vector<std::string>& names_or_groups) {
  std::vector<std::string> names;
  const std::vector<std::string> all = builtin_patch_names();
  for (const std::string& n : names_or_groups) {
    std::vector<std::string> members;
    try {
      members = std::find(all.begin(), all.end(), n) != all.end() ? std::vector<std::string>{n} : builtin_patch_group(n);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string(e.what()) + " (built-in patch names are listed in throng/tiling/library.h)");
    }
    for (const std::string& m : members) {
      if (std::find(names.begin(), names.end(), m) == names.end()) names.push_back(m);
    }
  }
  return names;
}

Prepared prepare(const Job& job, const CrowdMotion* recorded) {
  Prepared p;
  if (job.library.saved) p.library = *job.library.saved;
  if (!job.library.builtin.empty()) {
    PatchLibrary builtin;
    try {
      builtin = builtin_library(builtin_names(job.library.builtin), job.library.builtin_options);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string("library.builtin_options: ") + e.what());
    }
    try {
      merge_into(p.library, builtin);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string("library.builtin: ") + e.what() + " (library.file holds it already: leave it out of builtin)");
    }
  }
  if (job.library.real) {
    if (recorded == nullptr) throw ConfigError("library.real: no recorded crowd to make patches from");
    PatchLibrary made;
    try {
      made = patches_from_trajectories(*recorded, job.library.real_options);
    } catch (const InputError& e) {
      throw ConfigError(std::string("library.real: ") + e.what());
    }
    p.recorded_types = made.types.size();
    try {
      merge_into(p.library, made);
    } catch (const ConfigError& e) {
      throw ConfigError(std::string("library.real.prefix: ") + e.what());
    }
  }
  if (p.library.types.empty()) throw ConfigError("library: give `builtin` patches, `real` patches, a saved library `file`, or several");
  for (const auto& [name, weight] : job.library.preferences) {
    try {
      p.library.types[p.library.find(name)].preference = weight;
    } catch (const ConfigError& e) {
      throw ConfigError("library.preferences." + name + ": " + e.what());
    }
  }
  for (std::size_t k = 0; k < job.keyframes.size(); ++k) {
    Keyframe key;
    try {
      key.type = p.library.find(job.keyframes[k].patch);
    } catch (const ConfigError& e) {
      throw ConfigError("keyframes[" + std::to_string(k) + "].patch: " + e.what());
    }
    key.transform = job.keyframes[k].transform;
    p.keyframes.push_back(key);
  }
  check_resources(job, p);
  return p;
}

CheckOptions check_options_for(const Options& options) {
  CheckOptions c;
  c.limits = options.limits;
  c.match = options.match;
  c.obstacle_step_m = options.obstacle_step_m;
  c.obstacle_step_s = options.obstacle_step_s;
  return c;
}

Scene laid_scene(const Environment& environment, const LayoutOptions& layout) {
  Scene out = environment.scene;
  if (!out.region) return out;
  Region& r = *out.region;
  const Eigen::Vector3d L = periods(r);
  r.max.x() = r.min.x() + layout.repeat[0] * (r.max.x() - r.min.x());
  r.max.y() = r.min.y() + layout.repeat[1] * (r.max.y() - r.min.y());
  r.t1 = r.t0 + layout.repeat[2] * (r.t1 - r.t0);
  for (int cx = 0; cx < layout.repeat[0]; ++cx) {
    for (int cy = 0; cy < layout.repeat[1]; ++cy) {
      if (cx == 0 && cy == 0) continue;
      for (Obstacle o : environment.scene.obstacles) {
        move_rigidly(o, Eigen::Isometry2d(Eigen::Translation2d(cx * L.x(), cy * L.y())), 0.0);
        if (!o.name.empty()) o.name += " (copy " + std::to_string(cx) + ", " + std::to_string(cy) + ")";
        out.obstacles.push_back(std::move(o));
      }
    }
  }
  return out;
}

WindowOptions window_options(const Job& job) {
  WindowOptions w;
  w.window_s = job.window_s;
  w.frame_rate_hz = job.layout.frame_rate_hz;
  w.max_facing_rate_rad_s = job.layout.max_facing_rate_rad_s;
  return w;
}

Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator) {
  if (job.window_s > 0) {
    throw ConfigError("window: a windowed tiling streams its crowd to a file as it goes; run it with `throng tile` "
                      "(a step of `throng run` holds its whole crowd in memory): remove `window` here");
  }
  const CrowdMotion* recorded = inputs.empty() ? nullptr : &inputs.front()->motion;
  Run out;
  const Region& region = *job.environment.scene.region;
  if (region.periodic[0] && region.periodic[1] && region.periodic[2] && job.environment.sources.empty() &&
      job.environment.sinks.empty()) {
    out.warnings.push_back("the region is periodic in x, y and t and has no source or sink: no character can leave it, so "
                           "every one must close a loop; the search closes most (bridges, dropping open groups) but may "
                           "stop with dangling ends. More chains, fewer characters, or one axis left open make it reliable");
  }
  Prepared p = prepare(job, recorded);
  out.result = tile(p.library, job.environment, p.keyframes, job.options, progress, communicator);
  out.characters = lay_out(p.library, out.result.tiling, region, job.layout);
  out.crowd.motion = std::move(out.characters.motion);
  out.characters.motion = CrowdMotion{};
  out.crowd.scene = laid_scene(job.environment, job.layout);
  out.library = std::move(p.library);
  out.environment = job.environment;
  out.check = check_options_for(job.options);
  out.layout = job.layout;
  out.max_steps = job.options.search.max_steps;
  out.ranks = communicator.size();
  out.density = measure_density(out.library, out.result.tiling, job.environment, job.options.density, region.t0, region.t1);
  if (!out.density.windows.empty() && !out.density.met()) {
    std::ostringstream m;
    m << "the density per area is off its target by up to " << 100 * out.density.worst_error() << " % in a report window (tolerance "
      << 100 * out.density.tolerance << " %): raise density.rounds or chains, or lower density.per_m2";
    out.warnings.push_back(m.str());
  }
  const TilingReport& r = out.result.report;
  if (r.dangling > 0) {
    const ChainReport& best = r.chains[r.best_chain];
    out.shortfall = std::to_string(r.dangling) + " dangling " + (r.dangling == 1 ? "end remains" : "ends remain");
    // Worded by how the search stopped: at its cap, or because a whole sweep over the dangling ends placed and
    // removed nothing (every candidate at every end was tried and remembered).
    if (best.search_capped) {
      out.shortfall += " (the search stopped at search.max_steps = " + std::to_string(out.max_steps) +
                       " placements: raise it, allow more chains, or loosen match/limits)";
    } else {
      out.shortfall += " (the search stopped after " + std::to_string(best.search_steps) +
                       " placements because a sweep over the dangling ends changed nothing: no patch fits them; allow "
                       "more chains, add patches whose ends match theirs, or loosen match/limits)";
    }
  }
  return out;
}

void describe(ReportWriter& w, const Run& run) {
  const TilingReport& r = run.result.report;
  const ChainReport& best = r.chains[r.best_chain];
  w.count("instances", r.instances);
  w.count("characters", r.characters);
  w.count("connections", r.connections);
  w.count("dangling", r.dangling);
  w.count("agents", run.crowd.motion.agent_count());
  w.count("frames", run.crowd.motion.frame_count());
  w.count("patch_types", run.library.types.size());
  w.count("unusable_types", r.unusable_types.size());
  w.count("chains", r.chains.size());
  w.count("best_chain", r.best_chain);
  w.count("phase1_instances", best.phase1_instances);
  w.count("phase1_dangling", best.phase1_dangling);
  w.seconds("phase1_s", best.phase1_seconds);
  w.seconds("phase2_s", best.phase2_seconds);
  w.count("removals", best.removals);
  w.count("search_steps", best.search_steps);
  w.flag("search_capped", best.search_capped);
  if (!run.density.windows.empty()) {  // a density per area was asked for: each report window's mean per area
    w.number("density_worst", run.density.worst_error());
    w.flag("density_met", run.density.met());
    std::vector<double> means;
    for (const DensityWindow& d : run.density.windows) {
      for (const AreaDensity& a : d.areas) means.push_back(a.mean);
    }
    w.numbers("density_window_means", means);
  }
  w.seconds("seconds", r.seconds);
  w.ranks("ranks", run.ranks);
}

}  // namespace throng::tiling
