// Presence of characters in areas over time: the measure behind density per area (options.h DensityOptions).
//
// Time is cut into bins of `bin_s` over a span [t0, t1) (on a periodic time axis the span is the period and
// times wrap). For each area (the region's own, then each DensityZone) and bin, `occupancy` is the mean number
// of characters inside the area over the bin: ∫ count(t) dt / bin_s. A path adds, for each of its segments (the
// character moves linearly between samples), the time the segment spends inside the area (exact: the
// segment's parameter interval inside the box, on every periodic image of the box), spread over the bins by
// time. `target` is per_m2 × the area's area in the bin (the box area, or the obstacle-free area of the box on
// a raster, at the bin's middle time when obstacles move).
//
// Projections (our addition, for phase 1's cap): an end whose chain will go on — a dangling end, or an exit
// beyond the end of the region's time span while the horizon goes on (a windowed run) — is assumed to walk
// straight on at `projection_speed_mps` (entries: to have come straight from behind) until it leaves the region
// by a side that is not periodic, or reaches the end of the horizon (entries: the start of the span that may
// still change, `freeze`). Phase 2 continues dangling ends with straight walks first (candidates in library
// order), so a sparse crowd's chains do run that way; the cap then counts what a seed patch will become. On a
// tile periodic on both spatial axes and in time nothing is projected (a loop closes in an unknown way).
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace throng::tiling {

/// An area and its density: a box in tile coordinates.
struct PresenceArea {
  Eigen::Vector2d min{0, 0};
  Eigen::Vector2d max{0, 0};
  double per_m2 = 0;
};

/// The areas a density applies to: the region's own (when DensityOptions::per_m2 > 0), then every zone.
[[nodiscard]] std::vector<PresenceArea> presence_areas(const Region& region, const DensityOptions& options);

/// What the bins span and how projections run.
struct PresenceSpan {
  double t0 = 0;          ///< first bin's start
  double t1 = 0;          ///< end of the last bin (rounded up to whole bins; the period on a periodic time axis)
  double freeze = -1e300; ///< projected entries stop here (nothing before may change)
  double horizon_t1 = 0;  ///< projected exits stop here; exits beyond the region's t1 but before this go on
};

class Presence {
 public:
  /// Bins over `span` for the areas of `options` in `environment` (region, obstacles, sinks).
  Presence(const Environment& environment, const DensityOptions& options, const PresenceSpan& span);

  [[nodiscard]] bool enabled() const noexcept { return !areas_.empty(); }
  [[nodiscard]] std::size_t areas() const noexcept { return areas_.size(); }
  [[nodiscard]] std::size_t bins() const noexcept { return bins_; }
  [[nodiscard]] double bin_s() const noexcept { return bin_s_; }
  [[nodiscard]] double bin_start(std::size_t bin) const noexcept { return span_.t0 + static_cast<double>(bin) * bin_s_; }
  /// The bin of time t; bins() when outside the span (non-periodic time).
  [[nodiscard]] std::size_t bin_of(double t) const noexcept;
  [[nodiscard]] double occupancy(std::size_t area, std::size_t bin) const { return occupancy_[area * bins_ + bin]; }
  [[nodiscard]] double target(std::size_t area, std::size_t bin) const { return target_[area * bins_ + bin]; }

  /// Changes to the occupancy, collected before they are applied or tested: (flat index area × bins + bin, value).
  struct Delta {
    std::vector<std::pair<std::size_t, double>> terms;
    void clear() noexcept { terms.clear(); }
  };

  /// Adds sign × the presence of a character fragment's path to `delta`.
  void path(const Path& path, double sign, Delta& delta) const;
  /// Adds sign × the projected presence of an end (see the file comment) to `delta`; nothing when it does not
  /// project. `dangling`: the end needs a partner; otherwise it is free (then only exits beyond the region's
  /// t1 within the horizon, outside every sink, project).
  void projection(const Eigen::Vector2d& position, double heading, double time, bool is_exit, bool dangling, double sign,
                  Delta& delta) const;

  void apply(const Delta& delta);
  /// True when applying `delta` leaves every bin it raises at or below `factor` × target (bins it lowers, and
  /// bins already above, are not held against it unless it raises them).
  [[nodiscard]] bool fits(const Delta& delta, double factor) const;

 private:
  void segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double ta, double tb, double sign, Delta& delta) const;
  void spread(std::size_t area, double t0, double t1, double sign, Delta& delta) const;

  const Environment& environment_;
  Region region_;
  Eigen::Vector3d periods_;
  PresenceSpan span_;
  double bin_s_ = 1;
  double speed_ = 1.3;
  bool project_ = true;
  std::size_t bins_ = 0;
  std::vector<PresenceArea> areas_;
  std::vector<double> occupancy_;  // areas × bins
  std::vector<double> target_;
};

/// Seconds a character at `position` walking at `speed` along `direction` (a unit vector) takes to leave
/// `region` by a side that is not periodic; +∞ when it never does, 0 when it is outside already.
[[nodiscard]] double time_to_side(const Region& region, const Eigen::Vector2d& position, const Eigen::Vector2d& direction,
                                  double speed);

/// The area of `box` not covered by any obstacle of `scene` at time `time` (on a periodic axis, by any image),
/// counted on a raster of at most `cell_m` (coarser when the box would need more than 250,000 cells).
[[nodiscard]] double free_area(const Scene& scene, const Eigen::Vector2d& min, const Eigen::Vector2d& max, double time,
                               double cell_m);

}  // namespace throng::tiling
