// The facing and the action of a laid character between two samples of its chain: what lay_out
// (characters.cpp) and the windowed frame stream (frame_stream.cpp) both compute, so that their bits agree.
#pragma once

#include "geometry.h"

#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>

namespace throng::tiling {

/// The heading a fraction u ∈ [0, 1] of the way from h0 to h1, turning the shorter way round (the samples are a
/// tenth of a second apart: a character never turns half a circle between two), wrapped to (−π, π].
[[nodiscard]] inline double heading_between(double h0, double h1, double u) noexcept {
  return wrap_angle(h0 + u * wrap_angle(h1 - h0));
}

/// The facing a laid character shows at a frame: the patches' heading `wanted`, reached from the facing it showed
/// at the previous frame, `shown`, turning the shorter way by at most `max_turn` radians (≥ 0; infinity: no
/// limit). Patches joined with different headings (a stop, then a start the other way round: a standing
/// character's heading does not follow from its path, so the search does not match it) would otherwise snap the
/// character round between two frames (measured: up to 25 rad/s); it turns on the spot instead, and shows the
/// patches' own heading again as soon as it has caught up.
[[nodiscard]] inline double facing_toward(double shown, double wanted, double max_turn) noexcept {
  const double d = wrap_angle(wanted - shown);
  return std::abs(d) <= max_turn ? wanted : wrap_angle(shown + std::copysign(max_turn, d));
}

/// The orientation of a character facing `heading` on the ground: a yaw about +z, (x, y, z, w) =
/// (0, 0, sin(h/2), cos(h/2)).
[[nodiscard]] inline Eigen::Quaterniond yaw_orientation(double heading) noexcept {
  return {std::cos(0.5 * heading), 0.0, 0.0, std::sin(0.5 * heading)};
}

}  // namespace throng::tiling
