#include <throng/sketch/schema.h>

namespace throng::sketch {

void describe(OptionBinder& b, Options& o) {
  b.field({.key = "smoothing_window", .range = Range::closed(0, 100000), .help = "δ: points on each side (Eq. 1, 9, 10)"},
          o.smoothing_window);
  b.field({.key = "resample_spacing", .unit = "m", .range = Range::non_negative(),
           .help = "resample the main line every so many metres first (0: as drawn)"},
          o.resample_spacing_m);
  b.field({.key = "speed_scale", .range = Range::positive(), .help = "multiplies the drawing speed (Eq. 5)"}, o.speed_scale);
  b.section("width", [&](OptionBinder& w) {
    w.field({.key = "narrow", .unit = "m", .range = Range::non_negative(), .help = "W_N of Eq. 7"}, o.narrow_width_m);
    w.field({.key = "wide", .unit = "m", .range = Range::positive(), .help = "W_W of Eq. 7"}, o.wide_width_m);
  });
  b.section("standard_distance", [&](OptionBinder& s) {
    s.field({.key = "narrow", .unit = "m", .range = Range::positive(), .help = "s_N of Eq. 7"}, o.narrow_distance_m);
    s.field({.key = "wide", .unit = "m", .range = Range::positive(), .help = "s_W of Eq. 7"}, o.wide_distance_m);
  });
  b.section("irregularity", [&](OptionBinder& i) {
    i.field({.key = "gain", .range = Range::non_negative(), .help = "α of Eq. 12"}, o.irregularity_gain);
    i.field({.key = "max", .range = Range::positive(), .help = "E_MAX of Eq. 13"}, o.irregularity_max);
  });
  b.section("agents", [&](OptionBinder& a) {
    a.field({.key = "count", .range = Range::closed(1, 1e8), .help = "agents placed between the outer auxiliary lines"},
            o.agent_count);
    a.field({.key = "radius", .unit = "m", .range = Range::positive(), .help = "body radius, kept clear of obstacles"},
            o.agent_radius_m);
  });
  b.field({.key = "follow_radius", .unit = "m", .range = Range::positive(), .help = "R of Eq. 14"}, o.follow_radius_m);
  b.field({.key = "obstacle_distance", .unit = "m", .range = Range::non_negative(),
           .help = "from an obstacle's boundary, where Eq. 18's push starts"},
          o.obstacle_distance_m);
  b.field({.key = "slide_around_obstacles", .help = "turn a path force that points into an obstacle along its boundary"},
          o.slide_around_obstacles);
  b.section("weights", [&](OptionBinder& w) {
    w.field({.key = "trajectory", .range = Range::positive(), .help = "path following (Eq. 20)"}, o.trajectory_weight);
    w.field({.key = "avoid", .range = Range::non_negative(), .help = "avoidance of other agents (0: off)"}, o.avoid_weight);
    w.field({.key = "obstacle", .range = Range::non_negative(), .help = "avoidance of obstacles"}, o.obstacle_weight);
  });
  b.field({.key = "time_step", .unit = "s", .range = Range::positive(), .help = "Δt"}, o.time_step_s);
  b.field({.key = "direction_filter", .unit = "s", .range = Range::non_negative(), .flag = "--direction-filter",
           .help = "τ of the walking-direction filter: the walking velocity relaxes toward Eq. 21's over τ (0: the paper's rule)"},
          o.direction_filter_s);
  b.field({.key = "max_acceleration", .unit = "m/s²", .range = Range::non_negative(), .flag = "--max-acceleration",
           .help = "with the filter: the walking velocity changes by at most this per second (0: no bound)"},
          o.max_acceleration_m_s2);
  b.field({.key = "output_rate", .unit = "Hz", .range = Range::positive(), .help = "frames per second in the output"},
          o.output_rate_hz);
  b.field({.key = "duration", .unit = "s", .range = Range::non_negative(),
           .help = "time to simulate (0: until every agent has finished its path)"},
          o.duration_s);
  b.field({.key = "max_duration", .unit = "s", .range = Range::positive(), .help = "the longest a run with duration 0 lasts"},
          o.max_duration_s);
  b.choice({.key = "end_of_path", .help = "stop: agents gather at the end; remove: they leave the file"}, o.end_of_path,
           {{"stop", EndOfPath::stop}, {"remove", EndOfPath::remove}});
}

}  // namespace throng::sketch
