#include <throng/timewarp/schema.h>

namespace throng::timewarp {

void describe(OptionBinder& b, Options& o) {
  b.field({.key = "smoothing_time", .unit = "s", .range = Range::non_negative(), .flag = "--smoothing-time",
           .help = "time over which the warp's speed-up may change (0: Eq. 12's closed form)"},
          o.smoothing_time);
  b.field({.key = "min_interval_ratio", .range = {0.0, 1.0, true, false}, .flag = "--min-interval-ratio",
           .help = "shortest a frame interval may become, as a fraction of its length"},
          o.min_interval_ratio);
  b.field({.key = "max_interval_ratio", .range = Range::closed(1.0, 1e12), .flag = "--max-interval-ratio",
           .help = "longest a frame interval may become, as a multiple of its length"},
          o.max_interval_ratio);
  b.field({.key = "output_rate", .unit = "Hz", .range = Range::non_negative(), .flag = "--output-rate",
           .help = "frames per second of the output (0: the input's rate)"},
          o.output_rate_hz);
  b.choice({.key = "spline", .flag = "--spline", .help = "end condition of the resampling splines"}, o.spline_end,
           {{"not_a_knot", SplineEnd::not_a_knot}, {"natural", SplineEnd::natural}});
  b.field({.key = "time_tolerance", .unit = "s", .range = Range::non_negative(), .flag = "--time-tolerance",
           .help = "how close a reference frame's time must be to a deformed frame's"},
          o.time_tolerance_s);
}

void describe(OptionBinder& b, GuardOptions& o) {
  b.field({.key = "enabled", .help = "false: the output is left as it is (the paper's behaviour)"}, o.enabled);
  b.field({.key = "max_speed_ratio", .range = Range::positive(), .help = "speed limit: this × the source's fastest speed"},
          o.max_speed_ratio);
  b.field({.key = "max_acceleration", .unit = "m/s²", .range = Range::positive(),
           .help = "frames beyond this and beyond the source's own acceleration are kinks, smoothed"},
          o.max_acceleration);
  b.field({.key = "ramp_time", .unit = "s", .range = Range::positive(), .help = "σ: how the warp's slow-down ramps in and out"},
          o.ramp_time);
  b.field({.key = "smoothing_time", .unit = "s", .range = Range::positive(), .help = "first half-width of a kink's smoothing window"},
          o.smoothing_time);
  b.field({.key = "max_window_time", .unit = "s", .range = Range::positive(),
           .help = "the widest half-width tried (≥ smoothing_time)"},
          o.max_window_time);
}

}  // namespace throng::timewarp
