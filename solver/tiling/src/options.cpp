#include <throng/tiling/options.h>
#include <throng/tiling/schema.h>

#include <throng/core/errors.h>

#include <cmath>
#include <sstream>
#include <string>

namespace throng::tiling {
namespace {

void require(bool ok, const char* name, double value, const char* expected) {
  if (ok) return;
  std::ostringstream m;
  m << "tiling option " << name << " = " << value << ", expected " << expected;
  throw ConfigError(m.str());
}

void positive(const char* name, double v) { require(v > 0 && std::isfinite(v), name, v, "a finite value > 0"); }
void non_negative(const char* name, double v) { require(v >= 0 && std::isfinite(v), name, v, "a finite value ≥ 0"); }

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
  require(o.limits.speed_ratio == 0 || o.limits.speed_ratio >= 1, "limits.speed_ratio", o.limits.speed_ratio,
          "0 (no speed limit) or ≥ 1 (below 1 the library's own motion would break it)");
  if (o.preference.position) positive("preference.position.sigma", o.preference.position->sigma_m2);
  if (o.preference.direction) positive("preference.direction.sigma", o.preference.direction->sigma_rad2);
  if (o.preference.time) positive("preference.time.sigma", o.preference.time->sigma_s2);
  positive("preference.label_sigma", o.preference.label_sigma);
  for (const auto& [label, cost] : o.preference.label_costs) {
    require(std::isfinite(cost) && cost >= 0, ("preference.labels." + label).c_str(), cost, "a finite value ≥ 0");
  }
  // Density per area is not a job key (library users set it): its ranges are checked here.
  const DensityOptions& d = o.density;
  non_negative("density.per_m2", d.per_m2);
  positive("density.area_cell", d.area_cell_m);
  require(d.tolerance > 0 && d.tolerance < 1, "density.tolerance", d.tolerance, "a fraction in (0, 1)");
  positive("density.bin", d.bin_s);
  positive("density.report_window", d.report_window_s);
  require(d.report_window_s >= d.bin_s, "density.report_window", d.report_window_s, "≥ density.bin");
  positive("density.projection_speed", d.projection_speed_mps);
  for (std::size_t z = 0; z < d.zones.size(); ++z) {
    const DensityZone& zone = d.zones[z];
    const std::string name = "density.zones[" + std::to_string(z) + "]";
    require(zone.min.allFinite() && zone.max.allFinite() && zone.max.x() > zone.min.x() && zone.max.y() > zone.min.y(),
            (name + ".max − min").c_str(), (zone.max - zone.min).minCoeff(), "a box with max > min on x and y");
    require(zone.per_m2 > 0 && std::isfinite(zone.per_m2), (name + ".per_m2").c_str(), zone.per_m2, "a finite value > 0");
  }
}

}  // namespace throng::tiling
