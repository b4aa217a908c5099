// Placing a clip (paper §3: "Each motion clip can be relocated in the timeline, and deformed/transformed to
// arbitrary locations and orientations in a virtual environment"): a rigid motion in the plane, a retiming, and
// new ids or species for duplicates. The scene moves with the crowd.
//
// Order: positions p ↦ pivot + R(rotation) (p − pivot) + translation (z kept); times t ↦ t0 + time_scale (t − t0)
// + time_shift, t0 the crowd's first time; velocities rotate and divide by time_scale; orientations (facing) turn
// by the rotation about +z; actions stay, except that a walk/stand/run action follows the new speed where a
// time_scale moves it into another class (throng/core/facing_carry.h). Obstacles: static shapes
// are moved like positions; moving obstacles get the same rigid motion composed with their poses, and retimed
// keys; a new frame rate resamples last. A region becomes the bounding box of its moved corners, keeping its periodic flags only when the rotation
// is a multiple of 90° (swapped for odd multiples); its time span is retimed.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/scene.h>

#include <Eigen/Core>

#include <cstdint>
#include <optional>

namespace throng::stitch {

struct TransformOptions {
  double rotation = 0.0;                 ///< radians, counter-clockwise
  /// The fixed point of the rotation (metres); default: the centroid of the agents present at the first frame.
  std::optional<Eigen::Vector2d> pivot;
  Eigen::Vector2d translation{0, 0};     ///< metres, after the rotation
  double time_scale = 1.0;               ///< > 0: durations multiply by this (2 = twice as slow)
  double time_shift = 0.0;               ///< seconds added to every time (after scaling)
  std::int64_t id_offset = 0;            ///< added to every id (ids must stay ≥ 0)
  std::optional<std::int32_t> species;   ///< every agent's species becomes this
  /// > 0: after retiming, resample at this many frames per second from the first frame's time (each agent through
  /// a not-a-knot cubic spline, throng/timewarp/resample.h; velocities, if the crowd has them, from the splines'
  /// derivatives); 0 keeps the frames.
  double frame_rate_hz = 0.0;
};

/// Checks the values (finite, time_scale > 0); ConfigError naming the option.
void validate(const TransformOptions& options);

/// The centroid of the agents present at the crowd's first frame (x, y); (0, 0) when nobody is.
[[nodiscard]] Eigen::Vector2d first_frame_centroid(const CrowdMotion& crowd);

/// Applies `options` to `crowd` and `scene` in place. InputError when an id would become negative.
void transform(CrowdMotion& crowd, Scene& scene, const TransformOptions& options);

}  // namespace throng::stitch
