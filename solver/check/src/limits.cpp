// Limits: validation, limits from a reference's statistics, the verdict and its wording.
#include <throng/check/motion_check.h>
#include <throng/core/errors.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

namespace throng::check {

void validate(const Limits& l) {
  const std::pair<const char*, double> bounds[] = {
      {"max_speed", l.max_speed},         {"max_acceleration", l.max_acceleration}, {"acceleration_p99", l.acceleration_p99},
      {"max_turning_rate", l.max_turning_rate}, {"turning_rate_p99", l.turning_rate_p99},
      {"max_facing_rate", l.max_facing_rate},   {"max_displacement", l.max_displacement}};
  for (const auto& [name, value] : bounds) {
    if (!(value > 0) || std::isnan(value)) {
      std::ostringstream m;
      m << name << " " << value << ": expected a limit > 0 (or unlimited)";
      throw ConfigError(m.str());
    }
  }
}

Limits limits_from_reference(const Statistics& reference, const Limits& base, double speed_ratio) {
  if (!(std::isfinite(speed_ratio) && speed_ratio > 0)) throw ConfigError("speed_ratio: expected a ratio > 0");
  Limits l = base;
  if (reference.speed.samples > 0) l.max_speed = speed_ratio * reference.speed.max;
  l.max_acceleration = std::max(base.max_acceleration, reference.acceleration.max);
  l.acceleration_p99 = std::max(base.acceleration_p99, reference.acceleration.p99);
  l.max_turning_rate = std::max(base.max_turning_rate, reference.turning_rate.max);
  l.turning_rate_p99 = std::max(base.turning_rate_p99, reference.turning_rate.p99);
  l.max_facing_rate = std::max(base.max_facing_rate, reference.facing_rate.max);
  if (!l.max_pair_contacts) l.max_pair_contacts = reference.contacts.pairs;
  if (!l.max_obstacle_contacts) l.max_obstacle_contacts = reference.contacts.obstacle;
  return l;
}

Verdict check(const Statistics& s, const Limits& limits) {
  validate(limits);
  Verdict v;
  // Agents with a maximum beyond `bound`.
  auto agents_beyond = [&](double AgentMaxima::*field, double bound) {
    return static_cast<std::size_t>(std::count_if(s.agent_maxima.begin(), s.agent_maxima.end(),
                                                  [&](const AgentMaxima& a) { return a.*field > bound; }));
  };
  auto against = [&](const char* name, const Distribution& d, double value, double bound, double AgentMaxima::*field) {
    if (d.samples > 0 && value > bound) v.violations.push_back({name, value, bound, d.max_agent, d.max_time, agents_beyond(field, bound)});
  };
  against("max_speed", s.speed, s.speed.max, limits.max_speed, &AgentMaxima::speed);
  against("max_acceleration", s.acceleration, s.acceleration.max, limits.max_acceleration, &AgentMaxima::acceleration);
  against("acceleration_p99", s.acceleration, s.acceleration.p99, limits.acceleration_p99, &AgentMaxima::acceleration);
  against("max_turning_rate", s.turning_rate, s.turning_rate.max, limits.max_turning_rate, &AgentMaxima::turning_rate);
  against("turning_rate_p99", s.turning_rate, s.turning_rate.p99, limits.turning_rate_p99, &AgentMaxima::turning_rate);
  against("max_facing_rate", s.facing_rate, s.facing_rate.max, limits.max_facing_rate, &AgentMaxima::facing_rate);
  against("max_displacement", s.displacement, s.displacement.max, limits.max_displacement, &AgentMaxima::displacement);
  if (limits.max_pair_contacts && s.contacts.pairs > *limits.max_pair_contacts) {
    v.violations.push_back({"max_pair_contacts", static_cast<double>(s.contacts.pairs),
                            static_cast<double>(*limits.max_pair_contacts), -1, 0, s.contacts.pairs});
  }
  if (limits.max_obstacle_contacts && s.contacts.obstacle > *limits.max_obstacle_contacts) {
    v.violations.push_back({"max_obstacle_contacts", static_cast<double>(s.contacts.obstacle),
                            static_cast<double>(*limits.max_obstacle_contacts), -1, 0, s.contacts.obstacle});
  }
  return v;
}

std::string describe(const Violation& v) {
  std::ostringstream m;
  m.precision(4);
  if (v.agent < 0) {
    m << v.limit << " " << v.value << " > " << v.bound;
    return m.str();
  }
  const bool rate = v.limit.find("rate") != std::string::npos;
  const char* unit = v.limit.find("speed") != std::string::npos ? " m/s"
                     : v.limit.find("acceleration") != std::string::npos ? " m/s²"
                     : rate ? " rad/s" : " m";
  m << v.limit << " " << v.value << " > " << v.bound << unit << " (worst: agent " << v.agent << " at " << v.time << " s; "
    << v.count << (v.count == 1 ? " agent" : " agents") << " beyond)";
  return m.str();
}

}  // namespace throng::check
