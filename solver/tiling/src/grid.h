// A uniform grid over (x, y, t) with periodic or clamped axes: the addressing shared by the space-time index
// of path segments and the index of dangling ends.
#pragma once

#include <throng/core/scene.h>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace throng::tiling {

/// One axis of the grid. Periodic axes have cells that divide the period exactly and wrap; other axes cover
/// [lo − margin, hi + margin] and clamp: a value beyond falls in the edge cell (still correct, only slower).
struct GridAxis {
  double origin = 0;
  double cell = 1;
  int count = 1;
  bool periodic = false;

  GridAxis() = default;
  /// Callers check cells() first: counts beyond an int are not representable.
  GridAxis(double lo, double hi, double margin, double cell_size, bool is_periodic) : periodic(is_periodic) {
    count = static_cast<int>(cells(lo, hi, margin, cell_size, periodic));
    if (periodic) {
      cell = (hi - lo) / count;
      origin = lo;
    } else {
      cell = cell_size;
      origin = lo - margin;
    }
  }

  /// The number of cells such an axis has, in floating point (no overflow however small the cell).
  [[nodiscard]] static double cells(double lo, double hi, double margin, double cell_size, bool is_periodic) {
    return std::max(1.0, is_periodic ? std::round((hi - lo) / cell_size) : std::ceil((hi - lo + 2 * margin) / cell_size));
  }

  /// Raw (unwrapped, unclamped) cell of a value.
  [[nodiscard]] long raw(double v) const noexcept { return static_cast<long>(std::floor((v - origin) / cell)); }
  /// The cell a raw index stands for.
  [[nodiscard]] int cell_of(long raw_index) const noexcept {
    if (periodic) {
      const long m = raw_index % count;
      return static_cast<int>(m < 0 ? m + count : m);
    }
    return static_cast<int>(std::clamp<long>(raw_index, 0, count - 1));
  }
  /// The raw range [first, last] to visit for values in [lo, hi]: at most `count` cells, each once.
  void range(double lo, double hi, long& first, long& last) const noexcept {
    first = raw(lo);
    last = raw(hi);
    if (periodic) {
      if (last - first + 1 >= count) last = first + count - 1;
    } else {
      first = std::clamp<long>(first, 0, count - 1);
      last = std::clamp<long>(last, 0, count - 1);
    }
  }
};

/// Three axes and the flat cell numbering.
struct Grid3 {
  GridAxis x, y, t;

  Grid3() = default;
  Grid3(const Region& region, double cell_m, double cell_s, double margin_m, double margin_s)
      : x(region.min.x(), region.max.x(), margin_m, cell_m, region.periodic[0]),
        y(region.min.y(), region.max.y(), margin_m, cell_m, region.periodic[1]),
        t(region.t0, region.t1, margin_s, cell_s, region.periodic[2]) {}

  /// The cells such a grid has, in floating point: what to check before building one.
  [[nodiscard]] static double cells(const Region& region, double cell_m, double cell_s, double margin_m, double margin_s) {
    return GridAxis::cells(region.min.x(), region.max.x(), margin_m, cell_m, region.periodic[0]) *
           GridAxis::cells(region.min.y(), region.max.y(), margin_m, cell_m, region.periodic[1]) *
           GridAxis::cells(region.t0, region.t1, margin_s, cell_s, region.periodic[2]);
  }

  [[nodiscard]] std::size_t cells() const noexcept {
    return static_cast<std::size_t>(x.count) * static_cast<std::size_t>(y.count) * static_cast<std::size_t>(t.count);
  }
  [[nodiscard]] std::size_t flat(int ix, int iy, int it) const noexcept {
    return (static_cast<std::size_t>(ix) * static_cast<std::size_t>(y.count) + static_cast<std::size_t>(iy)) *
               static_cast<std::size_t>(t.count) +
           static_cast<std::size_t>(it);
  }

  /// Calls visit(flat cell) for every cell overlapping the box [x0, x1] × [y0, y1] × [t0, t1].
  template <class Visit>
  void for_each_cell(double x0, double x1, double y0, double y1, double t0, double t1, Visit&& visit) const {
    long ax, bx, ay, by, at, bt;
    x.range(x0, x1, ax, bx);
    y.range(y0, y1, ay, by);
    t.range(t0, t1, at, bt);
    for (long i = ax; i <= bx; ++i) {
      const int cx = x.cell_of(i);
      for (long j = ay; j <= by; ++j) {
        const int cy = y.cell_of(j);
        for (long k = at; k <= bt; ++k) visit(flat(cx, cy, t.cell_of(k)));
      }
    }
  }
};

}  // namespace throng::tiling
