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

/// The orientation of a character facing `heading` on the ground: a yaw about +z, (x, y, z, w) =
/// (0, 0, sin(h/2), cos(h/2)).
[[nodiscard]] inline Eigen::Quaterniond yaw_orientation(double heading) noexcept {
  return {std::cos(0.5 * heading), 0.0, 0.0, std::sin(0.5 * heading)};
}

}  // namespace throng::tiling
