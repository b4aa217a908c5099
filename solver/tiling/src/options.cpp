#include <throng/tiling/options.h>
#include <throng/tiling/schema.h>

#include <throng/core/errors.h>

#include <cmath>
#include <sstream>

namespace throng::tiling {
namespace {

void require(bool ok, const char* name, double value, const char* expected) {
  if (ok) return;
  std::ostringstream m;
  m << "tiling option " << name << " = " << value << ", expected " << expected;
  throw ConfigError(m.str());
}

void positive(const char* name, double v) { require(v > 0 && std::isfinite(v), name, v, "a finite value > 0"); }

}  // namespace

void validate(const Options& o) {
  check_options(describe, o, "tiling option ");  // every range: the schema (schema.h)
  // The rules that tie options together.
  require(o.search.jitter_distance_end_m >= o.search.jitter_distance_start_m, "search.jitter_end.distance",
          o.search.jitter_distance_end_m, "≥ search.jitter_start.distance");
  require(o.search.jitter_angle_end_rad >= o.search.jitter_angle_start_rad, "search.jitter_end.angle",
          o.search.jitter_angle_end_rad, "≥ search.jitter_start.angle");
  require(o.search.jitter_time_end_s >= o.search.jitter_time_start_s, "search.jitter_end.time", o.search.jitter_time_end_s,
          "≥ search.jitter_start.time");
  if (o.preference.position) positive("preference.position.sigma", o.preference.position->sigma_m2);
  if (o.preference.direction) positive("preference.direction.sigma", o.preference.direction->sigma_rad2);
  if (o.preference.time) positive("preference.time.sigma", o.preference.time->sigma_s2);
  positive("preference.label_sigma", o.preference.label_sigma);
  for (const auto& [label, cost] : o.preference.label_costs) {
    require(std::isfinite(cost) && cost >= 0, ("preference.labels." + label).c_str(), cost, "a finite value ≥ 0");
  }
}

}  // namespace throng::tiling
