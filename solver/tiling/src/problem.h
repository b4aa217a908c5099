// What every chain of a tiling run reads and nobody writes: the library with its precomputed deformation
// systems, the environment, the options, and values derived once from them.
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include "deformation.h"
#include "end_index.h"
#include "geometry.h"

#include <Eigen/Geometry>

#include <utility>
#include <vector>

namespace throng::tiling {

/// The largest distance of a sample (plus its radius) from its patch's centroid, over the library.
[[nodiscard]] double max_extent_of(const PatchLibrary& library);
/// The largest half time span of a patch of the library.
[[nodiscard]] double max_half_duration_of(const PatchLibrary& library);
/// How far beyond the region the segment index reaches (a placed patch's paths, jittered, matched).
[[nodiscard]] double index_margin_m(const Options& options, double max_extent_m);
[[nodiscard]] double index_margin_s(const Options& options, double max_half_duration_s);

struct Problem {
  Problem(const PatchLibrary& library, const Environment& environment, const Options& options);

  const PatchLibrary& library;
  const Environment& environment;
  const Options& options;
  Region region;
  Periods periods;
  std::vector<PatchSystem> systems;     ///< per type
  std::vector<bool> usable;             ///< per type: may be proposed (viability.h)
  std::vector<std::size_t> usable_types;
  /// Per type, the fragment pairs (a < b) an instance must keep clear of each other: all but the patch's own
  /// contact pairs (patch.h).
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> clear_pairs;
  double max_extent_m = 0;              ///< largest distance of a sample from its patch's centroid
  double max_half_duration_s = 0;       ///< largest half time span of a patch
  std::vector<Eigen::AlignedBox2d> obstacle_bounds;  ///< per obstacle, over the region's time span and margins

  /// The end of fragment `f` of `paths` (first or last sample) with its pose class.
  [[nodiscard]] EndPoint end_point(std::size_t type, const std::vector<Path>& paths, std::size_t f, bool is_exit) const;
};

}  // namespace throng::tiling
