// move_lanes.h's steps for the build's own target (SSE2 on x86-64), and the choice between them and AVX2's.
#define THRONG_MOVE_LANES sse2
#include "move_lanes.inc"

#include "neighbour_sum.h"

namespace throng::sketch::detail {

const MoveLanes& move_lanes() noexcept {
  static constexpr MoveLanes sse2_lanes{sse2::wanted_velocities, sse2::moved_places, sse2::velocities_and_facings};
  static constexpr MoveLanes avx2_lanes{avx2::wanted_velocities, avx2::moved_places, avx2::velocities_and_facings};
  static const MoveLanes& chosen = has_avx2() ? avx2_lanes : sse2_lanes;
  return chosen;
}

}  // namespace throng::sketch::detail
