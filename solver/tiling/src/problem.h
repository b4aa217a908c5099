// What every chain of a tiling run reads and nobody writes: the library with its precomputed deformation
// systems, the environment, the options, and values derived once from them. A windowed run (windowed.h) makes
// one Problem per window over the same precomputed systems.
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include "deformation.h"
#include "end_index.h"
#include "geometry.h"
#include "presence.h"

#include <Eigen/Geometry>

#include <limits>
#include <memory>
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

/// What depends on the library and the deformation options only: built once, shared by every window.
struct PatchPrecompute {
  PatchPrecompute(const PatchLibrary& library, const DeformationOptions& options);

  std::vector<PatchSystem> systems;     ///< per type
  std::vector<bool> usable;             ///< per type: may be proposed (viability.h)
  std::vector<std::size_t> usable_types;
  /// Per type, the fragment pairs (a < b) an instance must keep clear of each other: all but the patch's own
  /// contact pairs (patch.h).
  std::vector<std::vector<std::pair<std::size_t, std::size_t>>> clear_pairs;
  double max_extent_m = 0;              ///< largest distance of a sample from its patch's centroid
  double max_half_duration_s = 0;       ///< largest half time span of a patch
};

/// The part of the time axis one window of a windowed run works on (windowed.h). The region rule still uses
/// the environment's region (its t1 is the window's end).
struct TimeWindow {
  double sample_t0 = 0;    ///< phase 1 draws middle times in [sample_t0, sample_t1]
  double sample_t1 = 0;
  double freeze = 0;       ///< no new or re-deformed sample may lie before this time; the grids start here
  double horizon_t0 = 0;   ///< the start of the whole run: density bins are aligned to it
  double horizon_t1 = 0;   ///< the end of the whole run (presence.h: exits beyond the window go on to here)
};

struct Problem {
  /// The whole region at once.
  Problem(const PatchLibrary& library, const Environment& environment, const Options& options);
  /// One window of a windowed run over shared precomputed systems.
  Problem(std::shared_ptr<const PatchPrecompute> precompute, const PatchLibrary& library, const Environment& environment,
          const Options& options, const TimeWindow& window);

  std::shared_ptr<const PatchPrecompute> precompute;
  const PatchLibrary& library;
  const Environment& environment;
  const Options& options;
  Region region;                        ///< the region rule's (the environment's)
  Region index_region;                  ///< what the grids cover: the region, from `freeze` on in a window
  Periods periods;
  const std::vector<PatchSystem>& systems;
  const std::vector<bool>& usable;
  const std::vector<std::size_t>& usable_types;
  const std::vector<std::vector<std::pair<std::size_t, std::size_t>>>& clear_pairs;
  double max_extent_m = 0;
  double max_half_duration_s = 0;
  double sample_t0 = 0;                 ///< phase 1's middle times (the region's span, or the window's); the
  double sample_t1 = 0;                 ///< density is controlled in the bins they overlap
  double freeze = -std::numeric_limits<double>::infinity();  ///< see TimeWindow
  PresenceSpan presence_span;           ///< what the density bins cover (presence.h)
  TimeWindow window;                    ///< as given (the whole region's span when not windowed)
  std::vector<Eigen::AlignedBox2d> obstacle_bounds;  ///< per obstacle, over the grids' time span and margins
  double max_speed_m_s = 0;             ///< no deformed segment is faster (speed_limit(), patch.h)

  /// The end of fragment `f` of `paths` (first or last sample) with its pose class.
  [[nodiscard]] EndPoint end_point(std::size_t type, const std::vector<Path>& paths, std::size_t f, bool is_exit) const;
};

}  // namespace throng::tiling
