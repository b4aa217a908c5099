#include "problem.h"

#include <throng/core/parallel.h>

#include "viability.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace throng::tiling {

PatchPrecompute::PatchPrecompute(const PatchLibrary& library, const DeformationOptions& options) {
  // Deformation systems, one per type (independent: built in parallel, each the same whatever the threads).
  std::vector<std::optional<PatchSystem>> built(library.types.size());
  parallel_for(library.types.size(), 1, [&](std::size_t a, std::size_t b) {
    for (std::size_t k = a; k < b; ++k) built[k].emplace(library.types[k], options);
  });
  systems.reserve(built.size());
  for (auto& s : built) systems.push_back(std::move(*s));

  const Viability v = find_usable_types(library);
  usable = v.usable;
  for (std::size_t k = 0; k < usable.size(); ++k) {
    if (usable[k]) usable_types.push_back(k);
  }
  for (const PatchType& type : library.types) {
    const auto contact = contact_pairs(type);
    std::vector<std::pair<std::size_t, std::size_t>> clear;
    for (std::size_t a = 0; a < type.fragments.size(); ++a) {
      for (std::size_t b = a + 1; b < type.fragments.size(); ++b) {
        if (std::find(contact.begin(), contact.end(), std::pair(a, b)) == contact.end()) clear.emplace_back(a, b);
      }
    }
    clear_pairs.push_back(std::move(clear));
  }
  max_extent_m = max_extent_of(library);
  max_half_duration_s = max_half_duration_of(library);
}

Problem::Problem(const PatchLibrary& lib, const Environment& env, const Options& opts)
    : Problem(std::make_shared<const PatchPrecompute>(lib, opts.deformation), lib, env, opts,
              TimeWindow{env.scene.region->t0, env.scene.region->t1, -std::numeric_limits<double>::infinity(),
                         env.scene.region->t0, env.scene.region->t1}) {}

Problem::Problem(std::shared_ptr<const PatchPrecompute> shared, const PatchLibrary& lib, const Environment& env,
                 const Options& opts, const TimeWindow& span)
    : precompute(std::move(shared)), library(lib), environment(env), options(opts), region(*env.scene.region),
      index_region(region), systems(precompute->systems), usable(precompute->usable),
      usable_types(precompute->usable_types), clear_pairs(precompute->clear_pairs),
      max_extent_m(precompute->max_extent_m), max_half_duration_s(precompute->max_half_duration_s),
      sample_t0(span.sample_t0), sample_t1(span.sample_t1), freeze(span.freeze), window(span) {
  const Eigen::Vector3d p = tiling::periods(region);
  periods.p = {p.x(), p.y(), p.z()};
  if (std::isfinite(freeze)) index_region.t0 = freeze;
  if (std::isfinite(freeze)) {
    const double bin = options.density.bin_s;
    const double first = span.horizon_t0 + std::floor((freeze - span.horizon_t0) / bin) * bin;
    presence_span = {first, span.horizon_t1, freeze, span.horizon_t1};
  } else {
    presence_span = {span.horizon_t0, span.horizon_t1, span.horizon_t0, span.horizon_t1};
  }
  max_speed_m_s = speed_limit(library, options.limits.speed_ratio);
  const double margin_s = 2 * max_half_duration_s + options.search.jitter_time_end_s + options.match.time_s;
  for (const Obstacle& o : environment.scene.obstacles) {
    obstacle_bounds.push_back(bounds_over(o, index_region.t0 - margin_s, index_region.t1 + margin_s));
  }
}

double max_extent_of(const PatchLibrary& library) {
  double extent = 0;
  for (const PatchType& type : library.types) {
    for (const Fragment& f : type.fragments) {
      for (const Eigen::Vector2d& q : f.positions) extent = std::max(extent, q.norm() + f.radius_m);
    }
  }
  return extent;
}

double max_half_duration_of(const PatchLibrary& library) {
  double half = 0;
  for (const PatchType& type : library.types) half = std::max(half, 0.5 * (type.end_time() - type.start_time()));
  return half;
}

double index_margin_m(const Options& options, double max_extent_m) {
  return 2 * max_extent_m + options.search.jitter_distance_end_m + options.match.distance_m;
}

double index_margin_s(const Options& options, double max_half_duration_s) {
  return 2 * max_half_duration_s + options.search.jitter_time_end_s + options.match.time_s;
}

EndPoint Problem::end_point(std::size_t type, const std::vector<Path>& paths, std::size_t f, bool is_exit) const {
  const Path& p = paths[f];
  const std::size_t s = is_exit ? p.times.size() - 1 : 0;
  const Fragment& fr = library.types[type].fragments[f];
  return {p.positions[s], p.headings[s], p.times[s], is_exit ? fr.exit_class : fr.entry_class};
}

}  // namespace throng::tiling
