// The transform job (`throng transform CROWD.h5 -o OUT.h5`, or a `transform` step of `throng run`): place a clip
// in space and time — rotate, translate, retime, resample, renumber (solver/stitch/transform.h).
//
// Job keys (all optional; defaults shown; metres, seconds, degrees):
//
//   rotate: 0                     # degrees, counter-clockwise, about `pivot`
//   pivot: [x, y]                 # default: the centroid of the agents at the first frame
//   translate: [0, 0]             # metres, after the rotation ...
//   place_at: [x, y]              # ... or: move the first frame's centroid (rotated about itself) here
//   time_scale: 1                 # durations × this (2: half as fast), about the first frame's time
//   time_shift: 0                 # seconds added to every time ...
//   start_time: t                 # ... or: the first frame's new time
//   frame_rate: 0                 # > 0: resample at this many frames per second (cubic splines); 0: keep
//   id_offset: 0                  # added to every id (duplicates of a clip need distinct ids to be merged
//                                 #   without a shift; merge shifts clashing ids by itself otherwise)
//   species: k                    # every agent's species (colours in plots, groups in selections)
#pragma once

#include <throng/io/config.h>
#include <throng/stitch/transform.h>

#include <yaml-cpp/yaml.h>

#include <optional>

namespace throng {

struct TransformJob {
  stitch::TransformOptions options;          ///< rotation in radians here
  double rotate_degrees = 0.0;               ///< the job's `rotate`, as given (printed back unrounded)
  std::optional<Eigen::Vector2d> place_at;   ///< replaces options.translation when given
  std::optional<double> start_time;          ///< replaces options.time_shift when given
};

/// Reads and checks a whole job, then calls job.finish(). ConfigError naming the line.
[[nodiscard]] TransformJob read_transform_job(const ConfigNode& job);
[[nodiscard]] YAML::Node effective_transform_job(const TransformJob& job);

/// The options for this crowd: place_at and start_time turned into a translation and a time shift.
[[nodiscard]] stitch::TransformOptions resolve_transform(const TransformJob& job, const CrowdMotion& crowd);

}  // namespace throng
