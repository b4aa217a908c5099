// Density per area of a tiling, measured (options.h DensityOptions): the number of characters inside each area
// (the region's own when per_m2 > 0, then each zone) at every time, against per_m2 × the area.
//
// The count at time t is the number of character fragments whose deformed path at t lies inside the area (a
// character moves linearly between samples; exact, not sampled), on every periodic image of the area. Reported
// per window of `report_window_s` from `t0` (the last window may be shorter): the target, the mean count over the
// window, and the lowest and highest mean count over its bins of `bin_s`. A tiling meets its density when every
// window's mean lies within ±tolerance × target.
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace throng::tiling {

/// One area's figures over one window (counts of characters, not per m²).
struct AreaDensity {
  double target = 0;   ///< per_m2 × the area's (mean) area over the window
  double mean = 0;     ///< mean count over the window
  double lowest = 0;   ///< lowest mean count of a bin of the window
  double highest = 0;  ///< highest mean count of a bin of the window
  [[nodiscard]] double error() const noexcept { return target > 0 ? (mean - target) / target : 0.0; }
};

struct DensityWindow {
  double t0 = 0;
  double t1 = 0;
  std::vector<AreaDensity> areas;  ///< the region's own first (when asked for), then every zone
};

struct DensityReport {
  double tolerance = 0.1;
  std::vector<Eigen::Vector2d> area_min, area_max;  ///< the areas' boxes, in the order of DensityWindow::areas
  std::vector<double> per_m2;
  std::vector<DensityWindow> windows;
  /// Every window's mean within ±tolerance of its target (true when no density was asked for).
  [[nodiscard]] bool met() const noexcept;
  /// The largest |mean − target| / target over windows and areas.
  [[nodiscard]] double worst_error() const noexcept;
};

/// Measures the density of `tiling` over [t0, t1] (see the file comment). Nothing when the options ask for no
/// density. Throws ConfigError for t1 ≤ t0.
[[nodiscard]] DensityReport measure_density(const PatchLibrary& library, const Tiling& tiling,
                                            const Environment& environment, const DensityOptions& options, double t0,
                                            double t1);

}  // namespace throng::tiling
