// The index of dangling ends: which entries (or exits) of the tiling a new exit (or entry) could be stitched to.
// A grid over (x, y, t) of end points, kept up to date as ends become dangling or connected.
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/tiling.h>

#include "geometry.h"
#include "grid.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace throng::tiling {

/// A character end in world coordinates.
struct EndPoint {
  Eigen::Vector2d position{0, 0};
  double heading = 0;
  double time = 0;
  std::size_t pose_class = 0;
};

/// A dangling end that matches a query, with its offset to the query: image (periods) such that
/// query ≈ end + image ⊙ period, and the normalised distance used to rank matches.
struct EndMatch {
  FragmentRef end;
  std::array<int, 3> image{0, 0, 0};
  double score = 0;  ///< (d/d_max)² + (Δθ/θ_max)² + (Δt/t_max)²
};

class EndIndex {
 public:
  EndIndex(const Region& region, const MatchThresholds& match);

  /// The grid an index for these thresholds uses: cells of the match distance and time (at least 0.25 m,
  /// 0.25 s), reaching 10 m and 10 s plus twice the thresholds beyond the region.
  [[nodiscard]] static double cell_m(const MatchThresholds& m) { return std::max(m.distance_m, 0.25); }
  [[nodiscard]] static double cell_s(const MatchThresholds& m) { return std::max(m.time_s, 0.25); }
  [[nodiscard]] static double margin_m(const MatchThresholds& m) { return 2 * m.distance_m + 10.0; }
  [[nodiscard]] static double margin_s(const MatchThresholds& m) { return 2 * m.time_s + 10.0; }

  /// Adds or removes a dangling end (is_exit says which side of the fragment).
  void insert(FragmentRef ref, bool is_exit, const EndPoint& end);
  void remove(FragmentRef ref, bool is_exit, const EndPoint& end);

  /// Dangling ends of the opposite side (`want_exits`) that match `query` (same pose class, within the
  /// thresholds on the nearest image), appended to `out` in no particular order.
  void matches(const EndPoint& query, bool want_exits, std::vector<EndMatch>& out) const;

  /// Dangling ends of the side `want_exits` whose nearest image lies within `radius_m` of `query` and whose
  /// time, on that image, lies in [query.time + dt_lo, query.time + dt_hi], with the image; same pose class not
  /// required. The candidates a bridge patch (one end on `query`, the other on the found end) could join.
  void near(const EndPoint& query, bool want_exits, double radius_m, double dt_lo, double dt_hi,
            std::vector<EndMatch>& out) const;

  [[nodiscard]] std::size_t size() const noexcept { return size_; }

 private:
  struct Entry {
    EndPoint end;
    FragmentRef ref;
  };
  std::vector<Entry>& cell_of(bool is_exit, const EndPoint& e);

  Grid3 grid_;
  Periods periods_;
  MatchThresholds match_;
  std::vector<std::vector<Entry>> entries_, exits_;
  std::size_t size_ = 0;
};

}  // namespace throng::tiling
