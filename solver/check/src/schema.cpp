#include <throng/check/schema.h>

namespace throng::check {

void describe(OptionBinder& b, Settings& s) {
  b.field({.key = "margin", .unit = "m", .range = Range::non_negative(), .flag = "--margin", .help = "added to the clearances"},
          s.margin);
  b.field({.key = "edge_frames", .range = Range::closed(0, 1e9), .flag = "--edge-frames",
           .help = "frames at each end of a presence run left out of every measure"},
          s.edge_frames);
  b.field({.key = "heading_min_speed", .unit = "m/s", .range = Range::positive(), .flag = "--heading-min-speed",
           .help = "no turning rate where a neighbouring speed is below this"},
          s.heading_min_speed);
  b.field({.key = "contact_tolerance", .unit = "m", .range = Range::non_negative(),
           .help = "overlaps shallower than this are rounding, not contacts"},
          s.contact_tolerance);
  b.field({.key = "obstacle_samples", .range = Range::closed(1, 1e6), .help = "points per frame interval tested against obstacles"},
          s.obstacle_samples);
  b.field({.key = "time_tolerance", .unit = "s", .range = Range::non_negative(),
           .help = "a crowd frame and a reference frame within this are the same"},
          s.time_tolerance_s);
}

void describe(OptionBinder& b, Job& job) {
  b.field({.key = "speed_ratio", .range = Range::positive(), .flag = "--speed-ratio",
           .help = "with --reference: max speed = this × the reference's fastest"},
          job.speed_ratio);
  b.field({.key = "max_speed", .unit = "m/s", .range = Range::positive(), .flag = "--max-speed", .help = "fastest speed allowed"},
          job.max_speed);
  b.field({.key = "max_acceleration", .unit = "m/s²", .range = Range::positive(), .flag = "--max-acceleration",
           .help = "largest acceleration allowed"},
          job.max_acceleration);
  b.field({.key = "acceleration_p99", .unit = "m/s²", .range = Range::positive(), .flag = "--acceleration-p99",
           .help = "99th percentile of acceleration allowed"},
          job.acceleration_p99);
  b.field({.key = "max_turning_rate", .unit = "rad/s", .range = Range::positive(), .flag = "--max-turning-rate",
           .help = "largest turning rate allowed"},
          job.max_turning_rate);
  b.field({.key = "turning_rate_p99", .unit = "rad/s", .range = Range::positive(), .flag = "--turning-rate-p99",
           .help = "99th percentile of turning rate allowed"},
          job.turning_rate_p99);
  b.field({.key = "max_facing_rate", .unit = "rad/s", .range = Range::positive(), .flag = "--max-facing-rate",
           .help = "largest facing rate allowed (crowds with facings)"},
          job.max_facing_rate);
  b.field({.key = "max_displacement", .unit = "m", .range = Range::positive(), .flag = "--max-displacement",
           .help = "largest move from the reference allowed"},
          job.max_displacement);
  b.field({.key = "max_pair_contacts", .range = Range::non_negative(), .flag = "--max-pair-contacts",
           .help = "distinct pairs of agents in contact allowed (default: the reference's, else not checked)"},
          job.max_pair_contacts);
  b.field({.key = "max_obstacle_contacts", .range = Range::non_negative(), .flag = "--max-obstacle-contacts",
           .help = "distinct agent–obstacle pairs in contact allowed (default: the reference's, else not checked)"},
          job.max_obstacle_contacts);
  describe(b, job.settings);
}

Limits limits_of(const Job& job, const Statistics* reference) {
  Limits limits;
  if (reference != nullptr) limits = limits_from_reference(*reference, limits, job.speed_ratio);
  for (auto [value, field] : {std::pair{job.max_speed, &Limits::max_speed}, {job.max_acceleration, &Limits::max_acceleration},
                              {job.acceleration_p99, &Limits::acceleration_p99}, {job.max_turning_rate, &Limits::max_turning_rate},
                              {job.turning_rate_p99, &Limits::turning_rate_p99}, {job.max_facing_rate, &Limits::max_facing_rate},
                              {job.max_displacement, &Limits::max_displacement}}) {
    if (value) limits.*field = *value;
  }
  if (job.max_pair_contacts) limits.max_pair_contacts = job.max_pair_contacts;
  if (job.max_obstacle_contacts) limits.max_obstacle_contacts = job.max_obstacle_contacts;
  return limits;
}

}  // namespace throng::check
