// The time warp job (`throng timewarp DEFORMED.h5 --reference ORIGINAL.h5 -o OUT.h5`, or a `timewarp` step of
// `throng run` with `inputs: [deformed, original]`, the same order as on the command line) and the warp it stores
// under /parameters/throng/timewarp (solver/timewarp/timewarp.h for the method, schema.h for the options).
//
// Job keys (all optional; defaults shown):
//
//   smoothing_time: 0             # seconds over which the warp's speed-up may change; 0: Eq. 12's closed form
//   min_interval_ratio: 0.25      # each frame interval may shrink to this fraction of its length ...
//   max_interval_ratio: 4         # ... or stretch to this multiple (the clamp; the report says when it acts)
//   output_rate: 0                # frames per second of the output; 0: the input's rate
//   spline: not_a_knot            # not_a_knot | natural: the resampling splines' end condition
//   time_tolerance: 1e-6          # seconds: how close a reference frame's time must be to a deformed frame's
#pragma once

#include <throng/io/job_file.h>
#include <throng/timewarp/runner.h>

namespace throng::timewarp {

/// Writes the warp beside the report (timewarp/runner.h) in /parameters/throng/timewarp (the job is options
/// alone: read_job and effective_job are job_file.h's):
///   source_time       float64[T]    the deformed crowd's frame times (old time)
///   warped_time       float64[T]    their new times (the warp: old time → new time, linear between frames)
///   inverse_interval  float64[T−1]  s_i = 1/Δt'_i (1/s)
///   bound             int32[T−1]    0, or −1/+1 for an interval held at min/max_interval_ratio
void write_data(const h5::Group& record, const Run& run);

}  // namespace throng::timewarp
