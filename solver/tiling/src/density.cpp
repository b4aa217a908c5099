#include <throng/tiling/density.h>

#include <throng/core/errors.h>

#include "presence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace throng::tiling {

bool DensityReport::met() const noexcept { return worst_error() <= tolerance; }

double DensityReport::worst_error() const noexcept {
  double worst = 0;
  for (const DensityWindow& w : windows) {
    for (const AreaDensity& a : w.areas) worst = std::max(worst, std::abs(a.error()));
  }
  return worst;
}

DensityReport measure_density(const PatchLibrary& library, const Tiling& tiling, const Environment& environment,
                              const DensityOptions& options, double t0, double t1) {
  if (!(t1 > t0)) throw ConfigError("measure_density: the time span must have t1 > t0");
  DensityReport report;
  report.tolerance = options.tolerance;
  if (!options.enabled() || !environment.scene.region) return report;
  for (const PresenceArea& a : presence_areas(*environment.scene.region, options)) {
    report.area_min.push_back(a.min);
    report.area_max.push_back(a.max);
    report.per_m2.push_back(a.per_m2);
  }
  // Two measures over the same paths: bins of the window length (the means), and of bin_s (lowest, highest).
  DensityOptions by_window = options;
  by_window.bin_s = options.report_window_s;
  const PresenceSpan span{t0, t1, t0, t1};
  Presence windows(environment, by_window, span), bins(environment, options, span);
  Presence::Delta delta;
  for (const Instance& inst : tiling.instances) {
    const PatchType& type = library.types.at(inst.type);
    for (std::size_t f = 0; f < type.fragments.size() && f < inst.paths.size(); ++f) {
      if (!type.fragments[f].is_character()) continue;
      delta.clear();
      windows.path(inst.paths[f], 1.0, delta);
      windows.apply(delta);
      delta.clear();
      bins.path(inst.paths[f], 1.0, delta);
      bins.apply(delta);
    }
  }
  for (std::size_t w = 0; w < windows.bins(); ++w) {
    DensityWindow out;
    out.t0 = windows.bin_start(w);
    out.t1 = std::min(out.t0 + windows.bin_s(), windows.bin_start(0) + static_cast<double>(windows.bins()) * windows.bin_s());
    if (!environment.scene.region->periodic[2]) out.t1 = std::min(out.t1, t1);
    const double length = out.t1 - out.t0;
    for (std::size_t a = 0; a < windows.areas(); ++a) {
      AreaDensity d;
      // A window's bin holds ∫ count dt / window length; a last window cut short is rescaled to its length.
      d.mean = windows.occupancy(a, w) * windows.bin_s() / length;
      d.target = windows.target(a, w);
      d.lowest = std::numeric_limits<double>::infinity();
      d.highest = 0;
      for (std::size_t b = 0; b < bins.bins(); ++b) {
        const double start = bins.bin_start(b);
        if (start < out.t0 - 1e-9 || start >= out.t1 - 1e-9) continue;
        const double bin_length = std::min(bins.bin_s(), out.t1 - start);
        const double mean = bins.occupancy(a, b) * bins.bin_s() / bin_length;
        d.lowest = std::min(d.lowest, mean);
        d.highest = std::max(d.highest, mean);
      }
      if (!std::isfinite(d.lowest)) d.lowest = d.mean;
      out.areas.push_back(d);
    }
    report.windows.push_back(std::move(out));
  }
  return report;
}

}  // namespace throng::tiling
