// The stroke-driven crowd job (`throng sketch JOB.yaml -o OUT.h5`, or a `sketch` step of `throng run`), and the
// method data it stores in the output under /parameters/throng/sketch.
//
// Job file (every key but strokes optional; defaults shown; lengths in metres, times in seconds):
//
//   strokes:
//     main: [[x, y, t], ...]          # the main line, drawn at times t (strictly increasing): path and speed
//     auxiliary:                      # one or more auxiliary lines: spread and irregularity
//       - [[x, y], ...]               # [x, y] or [x, y, t] per point (times are not used)
//   agents:
//     count: 50                       # placed between the outermost auxiliary lines at the start ...
//     positions: [[x, y], ...]        # ... or given (then count is their number; count, if given, must agree)
//     radius: 0.25                    # body radius, kept clear of obstacles
//   smoothing_window: 5               # δ: points on each side in Eq. 1, 9, 10
//   resample_spacing: 0               # > 0: resample the main line every so many metres first (0: as drawn)
//   speed_scale: 1                    # multiplies the drawing speed (Eq. 5)
//   width: {narrow: 2, wide: 20}                     # W_N, W_W of Eq. 7
//   standard_distance: {narrow: 0.7, wide: 2}        # s_N, s_W of Eq. 7
//   irregularity: {gain: 1, max: 0.2}                # α of Eq. 12, E_MAX of Eq. 13
//   follow_radius: 1                  # R of Eq. 14
//   obstacle_distance: 0.5            # from an obstacle's boundary, where Eq. 18's push starts
//   slide_around_obstacles: true      # turn a path force that points into an obstacle along its boundary
//   weights: {trajectory: 1, avoid: 2, obstacle: 2}  # Eq. 20 (avoid: 0 switches agent avoidance off)
//   time_step: 0.04                   # Δt
//   output_rate: 25                   # frames per second in the output
//   duration: 0                       # seconds to simulate; 0: until every agent has finished its path ...
//   max_duration: 600                 # ... but no longer than this
//   end_of_path: stop                 # stop | remove
//   obstacles: [...]                  # see throng/io/scene_config.h (circles, polygons, walls, moving)
//
// The seed of the per-agent draws (Eq. 13) is the program's --seed. The strokes and agent positions are part of
// the job, so every error in them is a ConfigError (exit 2) naming the line: too few points, a number missing,
// NaN, main-line times not increasing, a zero-length stroke, an agent starting inside an obstacle, more agents
// than automatic placement fits between the outer auxiliary lines (at agents.count).
// See throng/sketch/sketch.h for the method and the meaning of each option.
#pragma once

#include <throng/io/job_file.h>
#include <throng/sketch/runner.h>

namespace throng::sketch {

/// Reads and checks a whole job (the seed stays at its default: the command sets it from --seed), then calls
/// node.finish() (unknown keys are errors). ConfigError naming the line.
void read_job(const ConfigNode& node, Job& job);
/// The job with every option at its effective value (for --print-config and the output's provenance).
[[nodiscard]] YAML::Node effective_job(const Job& job);
/// Writes beside the report (sketch/runner.h) in /parameters/throng/sketch:
///   strokes/main        float64[K][3]  x, y, t as given;  strokes/auxiliary_<i>  float64[K_i][3] (x, y, t)
///                       when the line was given with times, else float64[K_i][2]
///   course/main         float64[K][2]  the main line as used (pauses merged, resampled)
///   course/speed, width, standard_distance, irregularity, correction_scale   float64[K]   (Eq. 5, 6, 7, 12, 13)
///   agents/start        float64[N][2];  agents/weights float64[N][#strokes] (Eq. 2–3);
///   agents/correction_draw float64[N] (u_j, Eq. 13);  agents/arrival_time float64[N] (NaN: did not arrive)
void write_data(const h5::Group& record, const Run& run);

}  // namespace throng::sketch
