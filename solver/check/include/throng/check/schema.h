// The schema of `throng check-motion` (throng/core/schema.h): the checker's settings and the limits a user sets
// over the defaults (or over the reference's own, with --reference). The defaults are Settings' and Limits'
// initialisers in motion_check.h; a limit not given keeps its default.
#pragma once

#include <throng/check/motion_check.h>
#include <throng/core/schema.h>

#include <cstddef>
#include <optional>

namespace throng::check {

/// What `throng check-motion` is asked: limits given by the user (absent: the default, or the reference's),
/// the speed ratio against a reference, and the measuring settings.
struct Job {
  double speed_ratio = 1.25;  ///< with a reference: max speed = this × the reference's fastest
  std::optional<double> max_speed, max_acceleration, acceleration_p99, max_turning_rate, turning_rate_p99, max_facing_rate,
      max_displacement;
  std::optional<std::size_t> max_pair_contacts, max_obstacle_contacts;
  Settings settings;
};

void describe(OptionBinder& b, Settings& settings);
void describe(OptionBinder& b, Job& job);

/// The limits `job` asks for: the defaults, or limits_from_reference(*reference, ...) when a reference was
/// measured, then every limit the job gives.
[[nodiscard]] Limits limits_of(const Job& job, const Statistics* reference);

}  // namespace throng::check
