// The time warp job (`throng timewarp DEFORMED.h5 --reference ORIGINAL.h5 -o OUT.h5`, or a `timewarp` step of
// `throng run` with `inputs: [deformed, original]`, the same order as on the command line) and the warp it stores under /parameters/throng/timewarp
// (solver/timewarp/timewarp.h for the method and its decisions).
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

#include <throng/io/config.h>
#include <throng/io/hdf5.h>
#include <throng/timewarp/timewarp.h>

#include <yaml-cpp/yaml.h>

namespace throng {

struct TimewarpJob {
  timewarp::Options options;
};

/// Reads and checks a whole job, then calls job.finish(). ConfigError naming the line.
[[nodiscard]] TimewarpJob read_timewarp_job(const ConfigNode& job);
[[nodiscard]] YAML::Node effective_timewarp_job(const TimewarpJob& job);

/// Writes /parameters/throng/timewarp:
///   source_time       float64[T]    the deformed crowd's frame times (old time)
///   warped_time       float64[T]    their new times (the warp: old time → new time, linear between frames)
///   inverse_interval  float64[T−1]  s_i = 1/Δt'_i (1/s)
///   bound             int32[T−1]    0, or −1/+1 for an interval held at min/max_interval_ratio
///   attributes: output_rate (Hz), speed_deviation_before, speed_deviation_after, reference_speed_rms (m/s),
///               clamped_short, clamped_long, still_intervals
void write_timewarp_data(const h5::Group& throng_parameters, const timewarp::Result& result);

}  // namespace throng
