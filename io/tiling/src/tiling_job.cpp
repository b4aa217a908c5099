// The tiling job (tiling_job.h): what the file says, read without building anything (the library is built when
// the job runs: tiling/runner.h prepare()).
#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/io/data_options.h>
#include <throng/io/scene_config.h>
#include <throng/io/tiling_job.h>
#include <throng/tiling/schema.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace throng {
namespace {

using namespace tiling;

constexpr double deg = std::numbers::pi / 180.0;

YAML::Node flow(std::initializer_list<double> values) { return yaml_numbers(values); }

std::vector<Zone> read_zones(const ConfigNode& job, const char* key) {
  std::vector<Zone> zones;
  const auto node = job.find(key);
  if (!node) return zones;
  for (const ConfigNode& z : node->elements()) {
    Zone zone;
    const std::vector<double> c = z.at("center").as_doubles({2});
    zone.center = {c[0], c[1]};
    zone.radius_m = z.at("radius").as_double();
    if (!(zone.radius_m > 0)) z.at("radius").fail("expected a radius > 0");
    if (const auto t = z.find("time")) {
      const std::vector<double> tt = t->as_doubles({2});
      if (!(tt[1] >= tt[0])) t->fail("expected [t0, t1] with t1 ≥ t0");
      zone.t0 = tt[0];
      zone.t1 = tt[1];
    }
    zones.push_back(zone);
  }
  return zones;
}

YAML::Node zones_yaml(const std::vector<Zone>& zones) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const Zone& z : zones) {
    YAML::Node n;
    n["center"] = flow({z.center.x(), z.center.y()});
    n["radius"] = yaml_number(z.radius_m);
    if (z.t0 > -1e299 || z.t1 < 1e299) n["time"] = flow({z.t0, z.t1});
    list.push_back(n);
  }
  return list;
}

// The library's keys: built-in names (known names and groups; nothing is built), the recorded crowd's dataset
// (resolved against the job's folder), the preferences by type name.
void read_library(const ConfigNode& job, TilingJob& parsed) {
  const ConfigNode lib = job.at("library");
  LibrarySpec& spec = parsed.library;
  if (const auto builtin = lib.find("builtin")) {
    for (const ConfigNode& n : builtin->elements()) spec.builtin.push_back(n.as_string());
    if (spec.builtin.empty()) builtin->fail("give at least one built-in patch or group, or leave builtin out");
    try {
      (void)builtin_names(spec.builtin);
    } catch (const ConfigError& e) {
      builtin->fail(e.what());
    }
  }
  if (const auto real = lib.find("real")) {
    spec.real = true;
    parsed.real_dataset = std::filesystem::absolute(real->at("dataset").as_path()).lexically_normal().string();
  }
  if (const auto file = lib.find("file")) {
    parsed.library_file = std::filesystem::absolute(file->as_path()).lexically_normal().string();
  }
  if (spec.builtin.empty() && !spec.real && parsed.library_file.empty()) {
    lib.fail("give `builtin` patches, `real` patches, a saved library `file`, or several");
  }
  if (const auto prefs = lib.find("preferences")) {
    for (const std::string& name : prefs->keys()) {
      const ConfigNode v = prefs->at(name);
      const double w = v.as_double();
      if (!(w > 0)) v.fail("a preference must be > 0");
      spec.preferences.emplace_back(name, w);
    }
  }
}

// A keyframe's patch must be in the library: checked here when the library holds built-in patches alone (their
// names are known without building them), when the job runs otherwise.
void check_patch_name(const ConfigNode& patch, const LibrarySpec& spec, const std::string& library_file) {
  if (spec.real || !library_file.empty()) return;
  const std::vector<std::string> names = builtin_names(spec.builtin);
  const std::string name = patch.as_string();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    patch.fail("no patch type named '" + name + "' in the library (" + join_words(names) + ")");
  }
}

void read_keyframes(const ConfigNode& job, TilingJob& parsed) {
  const auto keys = job.find("keyframes");
  if (!keys) return;
  const Region& region = *parsed.environment.scene.region;
  for (const ConfigNode& k : keys->elements()) {
    KeyframeSpec key;
    key.patch = k.at("patch").as_string();
    check_patch_name(k.at("patch"), parsed.library, parsed.library_file);
    const std::vector<double> p = k.at("position").as_doubles({2});
    key.transform.translation = {p[0], p[1]};
    if (const auto a = k.find("angle")) key.transform.angle = a->as_double() * deg;
    key.transform.time_shift = k.at("time").as_double();
    for (int a = 0; a < 2; ++a) {
      if (region.periodic[static_cast<std::size_t>(a)]) continue;
      if (!(p[static_cast<std::size_t>(a)] >= region.min[a] && p[static_cast<std::size_t>(a)] <= region.max[a])) {
        std::ostringstream m;
        m << "the keyframe's position " << "xy"[a] << " = " << p[static_cast<std::size_t>(a)] << " m is outside the region ["
          << region.min[a] << ", " << region.max[a] << "]: a keyframed patch's centroid must lie inside";
        k.at("position").fail(m.str());
      }
    }
    if (!region.periodic[2] && !(key.transform.time_shift >= region.t0 && key.transform.time_shift <= region.t1)) {
      std::ostringstream m;
      m << "the keyframe's time " << key.transform.time_shift << " s is outside the region's [" << region.t0 << ", "
        << region.t1 << "]: a keyframed patch's middle time must lie inside";
      k.at("time").fail(m.str());
    }
    parsed.keyframes.push_back(key);
  }
}

void read_preference(const ConfigNode& job, TilingJob& parsed) {
  if (const auto pref = job.find("preference")) {
    Preference& p = parsed.options.preference;
    if (const auto pos = pref->find("position")) {
      const std::vector<double> t = pos->at("target").as_doubles({2});
      p.position = Preference::Position{{t[0], t[1]}, 25.0};
      if (const auto s = pos->find("sigma")) p.position->sigma_m2 = s->as_double();
      if (!(p.position->sigma_m2 > 0)) pos->fail("sigma must be > 0");
    }
    if (const auto dir = pref->find("direction")) {
      p.direction = Preference::Direction{dir->at("target").as_double() * deg, 0.5};
      if (const auto s = dir->find("sigma")) p.direction->sigma_rad2 = s->as_double() * deg * deg;
      if (!(p.direction->sigma_rad2 > 0)) dir->fail("sigma must be > 0");
    }
    if (const auto time = pref->find("time")) {
      p.time = Preference::Time{time->at("target").as_double(), 25.0};
      if (const auto s = time->find("sigma")) p.time->sigma_s2 = s->as_double();
      if (!(p.time->sigma_s2 > 0)) time->fail("sigma must be > 0");
    }
    if (const auto labels = pref->find("labels")) {
      for (const std::string& l : labels->keys()) {
        const double c = labels->at(l).as_double();
        if (!(c >= 0)) labels->at(l).fail("a label cost must be ≥ 0");
        p.label_costs[l] = c;
      }
    }
    if (const auto s = pref->find("label_sigma")) {
      p.label_sigma = s->as_double();
      if (!(p.label_sigma > 0)) s->fail("label_sigma must be > 0");
    }
  }

}

}  // namespace

void describe(OptionBinder& b, TilingJob& job) {
  tiling::describe(b, static_cast<tiling::Job&>(job));
  b.section("library", [&](OptionBinder& l) {
    if (l.present({.key = "real"}, job.library.real)) l.section("real", [&](OptionBinder& r) { describe_reading(r, job.real_import); });
  });
}

// density.zones: [{min: [x, y], max: [x, y], per_m2: d}], parts of the region with their own density.
void read_density_zones(const ConfigNode& job, TilingJob& parsed) {
  const auto density = job.find("density");
  if (!density) return;
  const auto zones = density->find("zones");
  if (!zones) return;
  for (const ConfigNode& z : zones->elements()) {
    DensityZone zone;
    const std::vector<double> lo = z.at("min").as_doubles({2}), hi = z.at("max").as_doubles({2});
    zone.min = {lo[0], lo[1]};
    zone.max = {hi[0], hi[1]};
    if (!(hi[0] > lo[0] && hi[1] > lo[1])) z.at("max").fail("expected max > min on both axes");
    const Region& r = *parsed.environment.scene.region;
    if (!(lo[0] < r.max.x() && hi[0] > r.min.x() && lo[1] < r.max.y() && hi[1] > r.min.y())) {
      z.at("min").fail("the zone lies outside the region: it holds no character ever");
    }
    zone.per_m2 = z.at("per_m2").as_double();
    if (!(zone.per_m2 > 0)) z.at("per_m2").fail("expected characters per m² > 0");
    parsed.options.density.zones.push_back(zone);
  }
}

void read_job(const ConfigNode& job, TilingJob& parsed) {
  read_options(job, static_cast<void (*)(OptionBinder&, TilingJob&)>(describe), parsed);
  parsed.environment.scene = read_scene(job);
  if (!parsed.environment.scene.region) job.fail("a tiling job needs `region: {min, max, time, periodic}`: the box to fill");
  read_density_zones(job, parsed);
  parsed.environment.sources = read_zones(job, "sources");
  parsed.environment.sinks = read_zones(job, "sinks");
  read_library(job, parsed);
  read_preference(job, parsed);  // the preference function (Eq. 7)
  read_keyframes(job, parsed);
  const Region& r = *parsed.environment.scene.region;
  for (std::size_t a = 0; a < 3; ++a) {
    if (parsed.layout.repeat[a] > 1 && !r.periodic[a]) {
      job.at("output").at("repeat").fail(std::string("a repeat count > 1 on axis ") + "xyt"[a] +
                                         " needs a region periodic on that axis");
    }
  }
  try {
    validate(parsed.options);
  } catch (const ConfigError& e) {
    job.fail(e.what());
  }
  job.finish();
}

YAML::Node effective_job(const TilingJob& job) {
  YAML::Node out(YAML::NodeType::Map);  // a map before the writer holds it (yaml-cpp nodes share only then)
  write_options(out, static_cast<void (*)(OptionBinder&, TilingJob&)>(describe), job);
  write_scene(out, job.environment.scene);
  const LibrarySpec& spec = job.library;
  YAML::Node lib = out["library"];
  if (!spec.builtin.empty()) {
    YAML::Node names(YAML::NodeType::Sequence);
    for (const std::string& n : spec.builtin) names.push_back(n);
    names.SetStyle(YAML::EmitterStyle::Flow);
    lib["builtin"] = names;
  }
  if (spec.real) lib["real"]["dataset"] = job.real_dataset;
  if (!job.library_file.empty()) lib["file"] = job.library_file;
  if (!spec.preferences.empty()) {
    YAML::Node p;
    for (const auto& [name, w] : spec.preferences) p[name] = yaml_number(w);
    lib["preferences"] = p;
  }
  const Preference& p = job.options.preference;
  if (!p.empty() || p.label_sigma != 1.0) {
    YAML::Node pref;
    if (p.position) {
      pref["position"]["target"] = flow({p.position->target.x(), p.position->target.y()});
      pref["position"]["sigma"] = yaml_number(p.position->sigma_m2);
    }
    if (p.direction) {
      pref["direction"]["target"] = yaml_number(p.direction->target_rad / deg);
      pref["direction"]["sigma"] = yaml_number(p.direction->sigma_rad2 / (deg * deg));
    }
    if (p.time) {
      pref["time"]["target"] = yaml_number(p.time->target_s);
      pref["time"]["sigma"] = yaml_number(p.time->sigma_s2);
    }
    for (const auto& [label, cost] : p.label_costs) pref["labels"][label] = yaml_number(cost);
    pref["label_sigma"] = yaml_number(p.label_sigma);
    out["preference"] = pref;
  }
  if (!job.keyframes.empty()) {
    YAML::Node keys(YAML::NodeType::Sequence);
    for (const KeyframeSpec& k : job.keyframes) {
      YAML::Node n;
      n["patch"] = k.patch;
      n["position"] = flow({k.transform.translation.x(), k.transform.translation.y()});
      n["angle"] = yaml_number(k.transform.angle / deg);
      n["time"] = yaml_number(k.transform.time_shift);
      keys.push_back(n);
    }
    out["keyframes"] = keys;
  }
  if (!job.options.density.zones.empty()) {
    YAML::Node zones(YAML::NodeType::Sequence);
    for (const DensityZone& z : job.options.density.zones) {
      YAML::Node n;
      n["min"] = flow({z.min.x(), z.min.y()});
      n["max"] = flow({z.max.x(), z.max.y()});
      n["per_m2"] = yaml_number(z.per_m2);
      zones.push_back(n);
    }
    out["density"]["zones"] = zones;
  }
  if (!job.environment.sources.empty()) out["sources"] = zones_yaml(job.environment.sources);
  if (!job.environment.sinks.empty()) out["sinks"] = zones_yaml(job.environment.sinks);
  return out;
}

}  // namespace throng
