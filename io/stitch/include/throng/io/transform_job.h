// The transform job (`throng transform CROWD.h5 -o OUT.h5`, or a `transform` step of `throng run`): place a clip
// in space and time — rotate, translate, retime, resample, renumber (solver/stitch/transform.h; the job's schema
// in solver/stitch/schema.h, the runner in jobs.h).
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

#include <throng/io/job_file.h>
#include <throng/stitch/jobs.h>

namespace throng::stitch {

/// Reads and checks a whole job (translate or place_at, time_shift or start_time), then calls node.finish().
/// ConfigError naming the line. The effective job is job_file.h's; a transform stores no data beside its report.
void read_job(const ConfigNode& node, TransformJob& job);
inline void write_data(const h5::Group&, const TransformRun&) {}

}  // namespace throng::stitch
