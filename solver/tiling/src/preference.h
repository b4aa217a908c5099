// The preference function F = Π exp(−f_i / σ_i) (Eq. 7): the sampling law of phase 1 and the candidate order
// of phase 2 (§5.3).
//
// F factorises over position, direction, time and label, so phase 1 draws each factor on its own: the type from
// preference × exp(−f4(label) / σ4) over the usable types; the centroid from F1 over the region (a 0.1 m table,
// uniform within a cell); the direction from F2 (a 1° table); the middle time from F3 over the problem's sample
// span (the region's [t0, t1], or a window's: problem.h; a 0.05 s table). Absent terms are uniform. Tables are
// cumulative and searched by bisection: a draw costs O(log n).
#pragma once

#include <throng/core/random.h>

#include "problem.h"

#include <cstdint>
#include <vector>

namespace throng::tiling {

class PreferenceModel {
 public:
  explicit PreferenceModel(const Problem& problem);

  /// −ln F of an instance of `type` placed by `transform` (Σ f_i / σ_i; 0 without preferences).
  [[nodiscard]] double cost(std::uint32_t type, const Transform& transform) const;

  [[nodiscard]] std::uint32_t sample_type(Rng& rng) const;
  [[nodiscard]] Transform sample_transform(Rng& rng) const;

 private:
  struct Table {  // a piecewise-constant density on [lo, lo + bins · width)
    double lo = 0, width = 1;
    std::vector<double> cumulative;  // normalised, last = 1; empty: uniform
    [[nodiscard]] double draw(Rng& rng, double hi) const;
  };
  const Problem& problem_;
  std::vector<std::uint32_t> types_;
  std::vector<double> type_cumulative_;
  std::vector<double> position_cumulative_;  // nx × ny cells, row-major by x then y
  int nx_ = 0, ny_ = 0;
  double cell_x_ = 0, cell_y_ = 0;
  Table angle_, time_;
};

}  // namespace throng::tiling
