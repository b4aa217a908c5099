// Validation of Options: every impossible value is a ConfigError naming the field.
#include <throng/core/errors.h>
#include <throng/sketch/sketch.h>

#include <cmath>
#include <sstream>
#include <string>

namespace throng::sketch {
namespace {

[[noreturn]] void fail(const char* field, double value, const char* expected) {
  std::ostringstream message;
  message << "sketch option " << field << " = " << value << ", expected " << expected;
  throw ConfigError(message.str());
}

void require_positive(const char* field, double value) {
  if (!(std::isfinite(value) && value > 0)) fail(field, value, "a finite value > 0");
}

void require_non_negative(const char* field, double value) {
  if (!(std::isfinite(value) && value >= 0)) fail(field, value, "a finite value ≥ 0");
}

}  // namespace

void validate(const Options& o) {
  if (o.smoothing_window < 0) fail("smoothing_window", o.smoothing_window, "≥ 0 points");
  require_non_negative("resample_spacing_m", o.resample_spacing_m);
  require_positive("speed_scale", o.speed_scale);
  require_non_negative("narrow_width_m", o.narrow_width_m);
  require_positive("wide_width_m", o.wide_width_m);
  if (!(o.wide_width_m > o.narrow_width_m)) {
    fail("wide_width_m", o.wide_width_m, ("> narrow_width_m = " + std::to_string(o.narrow_width_m)).c_str());
  }
  require_positive("narrow_distance_m", o.narrow_distance_m);
  require_positive("wide_distance_m", o.wide_distance_m);
  require_non_negative("irregularity_gain", o.irregularity_gain);
  require_positive("irregularity_max", o.irregularity_max);
  require_positive("agent_radius_m", o.agent_radius_m);
  require_positive("follow_radius_m", o.follow_radius_m);
  require_non_negative("obstacle_distance_m", o.obstacle_distance_m);
  require_non_negative("trajectory_weight", o.trajectory_weight);
  require_non_negative("avoid_weight", o.avoid_weight);
  require_non_negative("obstacle_weight", o.obstacle_weight);
  if (o.trajectory_weight == 0) fail("trajectory_weight", 0, "> 0 (agents would never follow their path)");
  require_positive("time_step_s", o.time_step_s);
  require_non_negative("direction_filter_s", o.direction_filter_s);
  require_non_negative("max_acceleration_m_s2", o.max_acceleration_m_s2);
  require_positive("output_rate_hz", o.output_rate_hz);
  require_non_negative("duration_s", o.duration_s);
  require_positive("max_duration_s", o.max_duration_s);
  if (o.end_of_path != EndOfPath::stop && o.end_of_path != EndOfPath::remove) {
    fail("end_of_path", static_cast<double>(o.end_of_path), "stop or remove");
  }
}

}  // namespace throng::sketch
