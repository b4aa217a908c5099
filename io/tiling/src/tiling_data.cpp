// The tiling data in a crowd file written by `throng tile` (tiling_data.h).
#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/crowd_file.h>
#include <throng/io/crowd_file_parts.h>
#include <throng/io/tiling_data.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace throng {

using namespace tiling;

namespace {

void put_path(std::vector<double>& out, const Path& p) {
  for (std::size_t s = 0; s < p.times.size(); ++s) out.insert(out.end(), {p.positions[s].x(), p.positions[s].y(), p.headings[s], p.times[s]});
}

}  // namespace

}  // namespace throng

namespace throng::tiling {

void write_library(const h5::Group& g, const PatchLibrary& library) {
  const h5::Group lib = g.create_group("library");
  lib.write("pose_classes", library.pose_classes);
  std::vector<std::string> names, labels;
  std::vector<double> preference, radius, samples;
  std::vector<std::int64_t> type_fragments{0}, fragments, constraints;
  for (std::size_t k = 0; k < library.types.size(); ++k) {
    const PatchType& t = library.types[k];
    names.push_back(t.name);
    labels.push_back(t.label);
    preference.push_back(t.preference);
    for (const Fragment& f : t.fragments) {
      fragments.insert(fragments.end(), {f.is_character() ? 0 : 1, static_cast<std::int64_t>(f.entry_class),
                                         static_cast<std::int64_t>(f.exit_class), static_cast<std::int64_t>(samples.size() / 4)});
      radius.push_back(f.radius_m);
      for (std::size_t s = 0; s < f.sample_count(); ++s) {
        samples.insert(samples.end(), {f.positions[s].x(), f.positions[s].y(), f.headings[s], f.times[s]});
      }
    }
    type_fragments.push_back(static_cast<std::int64_t>(radius.size()));
    for (const InterpersonalConstraint& c : t.constraints) {
      constraints.insert(constraints.end(), {static_cast<std::int64_t>(k), static_cast<std::int64_t>(c.fragment_a),
                                             static_cast<std::int64_t>(c.sample_a), static_cast<std::int64_t>(c.fragment_b),
                                             static_cast<std::int64_t>(c.sample_b)});
    }
  }
  const auto K = static_cast<std::uint64_t>(library.types.size());
  const auto F = static_cast<std::uint64_t>(radius.size());
  lib.write("type_name", names);
  lib.write("type_label", labels);
  lib.write("type_preference", preference, {K});
  lib.write("type_fragments", type_fragments, {K + 1});
  lib.write("fragment", fragments, {F, 4});
  lib.write("fragment_radius", radius, {F});
  lib.write("samples", samples, {samples.size() / 4, 4});
  lib.write("constraints", constraints, {constraints.size() / 5, 5});
}

void write_tile_settings(const h5::Group& g, const Environment& environment, const LayoutOptions& layout,
                         const CheckOptions& check) {
  const auto zones = [](const std::vector<Zone>& z) {
    std::vector<double> v;
    for (const Zone& zone : z) v.insert(v.end(), {zone.center.x(), zone.center.y(), zone.radius_m, zone.t0, zone.t1});
    return v;
  };
  g.write("sources", zones(environment.sources), {environment.sources.size(), 5});
  g.write("sinks", zones(environment.sinks), {environment.sinks.size(), 5});
  const Region& tile = *environment.scene.region;
  g.write("region", std::vector<double>{tile.min.x(), tile.min.y(), tile.max.x(), tile.max.y(), tile.t0, tile.t1}, {6});
  g.write("region_periodic", std::vector<std::int32_t>{tile.periodic[0], tile.periodic[1], tile.periodic[2]}, {3});
  g.write("repeat", std::vector<std::int64_t>{layout.repeat[0], layout.repeat[1], layout.repeat[2]}, {3});
  g.set_attribute("tile_obstacles", static_cast<std::int64_t>(environment.scene.obstacles.size()));

  // Check options (the report joins them: tiling/runner.h).
  g.set_attribute("limit_stretch", check.limits.stretch_m);
  g.set_attribute("limit_bend", check.limits.bend_rad);
  g.set_attribute("limit_time_shift", check.limits.time_shift_s);
  g.set_attribute("limit_frame_period", check.limits.frame_period_s);
  g.set_attribute("limit_bend_min_segment", check.limits.bend_min_segment_m);
  g.set_attribute("limit_speed_ratio", check.limits.speed_ratio);
  g.set_attribute("match_distance", check.match.distance_m);
  g.set_attribute("match_angle", check.match.angle_rad);
  g.set_attribute("match_time", check.match.time_s);
  g.set_attribute("obstacle_step", check.obstacle_step_m);
  g.set_attribute("obstacle_step_time", check.obstacle_step_s);
}

TilingRows tiling_rows(const std::vector<Instance>& instances, const std::vector<Connection>& connections) {
  TilingRows rows;
  for (const Instance& i : instances) {
    rows.types.push_back(static_cast<std::int64_t>(i.type));
    rows.transforms.insert(rows.transforms.end(),
                           {i.transform.translation.x(), i.transform.translation.y(), i.transform.angle, i.transform.time_shift});
    rows.keyframed.push_back(i.keyframed ? 1 : 0);
    for (const Path& p : i.paths) put_path(rows.paths, p);
  }
  for (const Connection& c : connections) {
    rows.connections.insert(rows.connections.end(),
                            {c.from.instance, c.from.fragment, c.to.instance, c.to.fragment, c.image[0], c.image[1], c.image[2]});
  }
  return rows;
}

void write_data(const h5::Group& g, const Run& run) {
  write_library(g, run.library);
  const Characters& characters = run.characters;
  // The tiling.
  const Tiling& t = run.result.tiling;
  const h5::Group inst = g.create_group("instances");
  const TilingRows rows = tiling_rows(t.instances, t.connections);
  const auto I = static_cast<std::uint64_t>(t.instances.size());
  inst.write("type", rows.types, {I});
  inst.write("transform", rows.transforms, {I, 4});
  inst.write("keyframed", rows.keyframed, {I});
  inst.write("paths", rows.paths, {rows.paths.size() / 4, 4}, h5::Layout{true});
  g.write("connections", rows.connections, {t.connections.size(), 7});
  std::vector<std::int64_t> pieces;
  for (std::size_t a = 0; a < characters.pieces.size(); ++a) {
    for (const AgentPiece& p : characters.pieces[a]) {
      pieces.insert(pieces.end(), {static_cast<std::int64_t>(a), p.fragment.instance, p.fragment.fragment, p.copy[0], p.copy[1], p.copy[2]});
    }
  }
  g.create_group("agents").write("pieces", pieces, {pieces.size() / 6, 6});
  write_tile_settings(g, run.environment, run.layout, run.check);
}

}  // namespace throng::tiling

namespace throng {

namespace {

std::vector<double> doubles(const h5::Group& g, const std::string& name, std::uint64_t cols, std::uint64_t* rows = nullptr) {
  h5::Array<double> a = g.read_doubles(name, cols ? 2 : 1);
  if (cols && a.shape[1] != cols) throw InputError(g.where(name) + ": expected " + std::to_string(cols) + " columns");
  if (rows) *rows = a.shape[0];
  return std::move(a.values);
}
std::vector<std::int64_t> ints(const h5::Group& g, const std::string& name, std::uint64_t cols, std::uint64_t* rows = nullptr) {
  h5::Array<std::int64_t> a = g.read_int64(name, cols ? 2 : 1);
  if (cols && a.shape[1] != cols) throw InputError(g.where(name) + ": expected " + std::to_string(cols) + " columns");
  if (rows) *rows = a.shape[0];
  return std::move(a.values);
}
double attribute(const h5::Group& g, const std::string& name) {
  const auto v = g.double_attribute(name);
  if (!v) throw InputError(g.where() + ": missing attribute " + name);
  return *v;
}

// A check option stored as an attribute, within the range the tiling job allows for it (a file written by hand
// could hold 1e-9 for a step the checker walks every path with).
double attribute_in(const h5::Group& g, const std::string& name, Range range) {
  const double v = attribute(g, name);
  if (!range.contains(v)) {
    std::ostringstream m;
    m << g.where() << " attribute " << name << " = " << v << ", expected " << range.describe();
    throw InputError(m.str());
  }
  return v;
}

// A stored index as the unsigned 32-bit index the tiling types hold (InputError naming the dataset otherwise).
std::uint32_t index32(std::int64_t v, const h5::Group& g, const std::string& name, std::size_t row) {
  if (v < 0 || v > static_cast<std::int64_t>(UINT32_MAX)) {
    throw InputError(g.where(name) + ": row " + std::to_string(row) + " holds index " + std::to_string(v) + ", expected 0 to 2^32 − 1");
  }
  return static_cast<std::uint32_t>(v);
}

// A stored copy offset (whole periods along an axis) as an int.
int copy_offset(std::int64_t v, const h5::Group& g, const std::string& name, std::size_t row) {
  if (v < -1000000 || v > 1000000) {
    throw InputError(g.where(name) + ": row " + std::to_string(row) + " holds copy offset " + std::to_string(v) + ", expected −10^6 to 10^6");
  }
  return static_cast<int>(v);
}

}  // namespace

namespace {

// With obstacles, the checker tests every path segment at max(1, ⌈length / obstacle_step⌉,
// ⌈duration / obstacle_step_time⌉) + 1 points (check.cpp). A file's steps are data: 1e-9 m would keep `check-tiling` busy for days, so the count is
// estimated first and refused above this many points (a 1,000-character, 100 s tiling at the default steps
// tests a few million).
constexpr double max_obstacle_points = 1e8;

void check_obstacle_work(const TilingData& data, const h5::Group& g) {
  if (data.environment.scene.obstacles.empty()) return;  // the checker samples paths only against obstacles
  const CheckOptions& c = data.check;
  double points = 0;
  for (const Instance& x : data.tiling.instances) {
    for (const Path& p : x.paths) {
      for (std::size_t s = 0; s + 1 < p.times.size(); ++s) {
        const double length = (p.positions[s + 1] - p.positions[s]).norm(), duration = p.times[s + 1] - p.times[s];
        points += std::max({1.0, std::ceil(length / c.obstacle_step_m), std::ceil(duration / c.obstacle_step_s)}) + 1;
      }
    }
  }
  if (!(points <= max_obstacle_points)) {  // NaN (a non-finite sample) refused too
    std::ostringstream m;
    m << g.where() << ": obstacle_step = " << c.obstacle_step_m << " m and obstacle_step_time = " << c.obstacle_step_s
      << " s make the check test about " << points << " points along the paths, more than " << max_obstacle_points
      << "; refused before checking";
    throw InputError(m.str());
  }
}

}  // namespace

bool has_tiling_data(const std::filesystem::path& path, const ReadLimits& limits) {
  const h5::File file = h5::File::open(path, limits);
  if (!file.root().has("parameters")) return false;
  const h5::Group parameters = file.root().open_group("parameters");
  return parameters.has("throng") && parameters.open_group("throng").has("tiling");
}

TilingData read_tiling_data(const std::filesystem::path& path, const ReadLimits& limits) {
  TilingData out;
  // One file, one budget. The frames are not read: the tiling alone is checked.
  const h5::File file = h5::File::open(path, limits);
  const Scene scene = detail::read_crowd_scene(file);
  out.environment.scene = scene;
  const h5::Group params = open_throng_parameters(file);
  const std::uint64_t agent_count = detail::crowd_agent_count(file);
  params.budget().charge(checked_product(agent_count, sizeof(std::vector<AgentPiece>)).value_or(UINT64_MAX), params.where("agents"),
                         std::to_string(agent_count) + " agents' piece lists");
  if (!params.has("tiling")) throw InputError(path.string() + ": no /parameters/throng/tiling (not written by throng tile)");
  const h5::Group g = params.open_group("tiling");
  // The tile (the scene's region is the laid extent) and its own obstacles (the first ones of the scene).
  if (g.has("region")) {
    const std::vector<double> r = doubles(g, "region", 0);
    const std::vector<std::int32_t> p = g.read_int32("region_periodic", 1).values;
    if (r.size() != 6 || p.size() != 3) throw InputError(g.where("region") + ": expected 6 bounds and 3 periodic flags");
    out.environment.scene.region = Region{{r[0], r[1]}, {r[2], r[3]}, r[4], r[5], {p[0] != 0, p[1] != 0, p[2] != 0}};
    const std::vector<std::int64_t> repeat = ints(g, "repeat", 0);
    if (repeat.size() != 3) throw InputError(g.where("repeat") + ": expected 3 counts");
    for (std::size_t a = 0; a < 3; ++a) {
      if (repeat[a] < 1 || repeat[a] > 1000 || (repeat[a] > 1 && p[a] == 0)) {
        throw InputError(g.where("repeat") + ": " + std::to_string(repeat[a]) + " copies on axis " + "xyt"[a] +
                         ", expected 1 to 1000 and 1 on an axis that is not periodic");
      }
      out.repeat[a] = static_cast<int>(repeat[a]);
    }
  }
  if (!out.environment.scene.region) throw InputError(path.string() + ": no region in the scene (not written by throng tile?)");
  if (const auto own = g.double_attribute("tile_obstacles")) {
    if (!(*own >= 0 && *own <= static_cast<double>(scene.obstacles.size()))) {
      throw InputError(g.where() + ": tile_obstacles = " + std::to_string(*own) + " of " +
                       std::to_string(scene.obstacles.size()) + " obstacles in the scene");
    }
    out.environment.scene.obstacles.resize(static_cast<std::size_t>(*own));
  }
  const h5::Group lib = g.open_group("library");
  PatchLibrary& L = out.library;
  L.pose_classes = lib.read_strings("pose_classes");
  const std::vector<std::string> names = lib.read_strings("type_name"), labels = lib.read_strings("type_label");
  const std::vector<double> preference = doubles(lib, "type_preference", 0);
  const std::vector<std::int64_t> type_fragments = ints(lib, "type_fragments", 0);
  std::uint64_t F = 0, S = 0, C = 0;
  const std::vector<std::int64_t> fragments = ints(lib, "fragment", 4, &F);
  const std::vector<double> radius = doubles(lib, "fragment_radius", 0);
  const std::vector<double> samples = doubles(lib, "samples", 4, &S);
  const std::vector<std::int64_t> constraints = ints(lib, "constraints", 5, &C);
  const std::size_t K = names.size();
  // The library built from the arrays (K types, F fragments, S samples of position, heading and time: 32 bytes),
  // charged to the file's budget beside the arrays it is built from (charged as they were read).
  lib.budget().charge(checked_sum(checked_product(K, sizeof(PatchType)).value_or(UINT64_MAX),
                                  checked_sum(checked_product(F, sizeof(Fragment)).value_or(UINT64_MAX),
                                              checked_product(S, 32).value_or(UINT64_MAX)).value_or(UINT64_MAX))
                          .value_or(UINT64_MAX),
                      lib.where(), std::to_string(K) + " patch types, " + std::to_string(F) + " fragments, " + std::to_string(S) + " samples");
  if (labels.size() != K || preference.size() != K || type_fragments.size() != K + 1 || radius.size() != F ||
      type_fragments.back() != static_cast<std::int64_t>(F)) {
    throw InputError(lib.where() + ": the library's datasets disagree in size");
  }
  const auto bad = [&](const std::string& what) { throw InputError(lib.where() + ": " + what); };
  // The whole index checked before any of it is used: a type's range is only within 0..F when every later pair
  // is ordered too (0, 100, 10 with F = 10 passes a pairwise check made type by type, then reads row 99).
  if (type_fragments.front() < 0) bad("type_fragments not increasing");
  for (std::size_t k = 0; k < K; ++k) {
    if (type_fragments[k + 1] < type_fragments[k]) bad("type_fragments not increasing");
  }
  for (std::size_t k = 0; k < K; ++k) {
    PatchType t;
    t.name = names[k];
    t.label = labels[k];
    t.preference = preference[k];
    for (auto f = static_cast<std::size_t>(type_fragments[k]); f < static_cast<std::size_t>(type_fragments[k + 1]); ++f) {
      Fragment fr;
      fr.kind = fragments[4 * f] == 0 ? FragmentKind::character : FragmentKind::prop;
      if (fragments[4 * f + 1] < 0 || fragments[4 * f + 2] < 0 ||
          static_cast<std::uint64_t>(fragments[4 * f + 1]) >= L.pose_classes.size() ||
          static_cast<std::uint64_t>(fragments[4 * f + 2]) >= L.pose_classes.size()) {
        bad("fragment " + std::to_string(f) + " names a pose class outside 0.." + std::to_string(L.pose_classes.size()) + "-1");
      }
      fr.entry_class = static_cast<std::size_t>(fragments[4 * f + 1]);
      fr.exit_class = static_cast<std::size_t>(fragments[4 * f + 2]);
      fr.radius_m = radius[f];
      const std::int64_t first = fragments[4 * f + 3];
      const std::int64_t last = f + 1 < F ? fragments[4 * (f + 1) + 3] : static_cast<std::int64_t>(S);
      if (first < 0 || last > static_cast<std::int64_t>(S) || last < first) bad("fragment sample ranges out of order");
      for (auto s = static_cast<std::size_t>(first); s < static_cast<std::size_t>(last); ++s) {
        fr.positions.emplace_back(samples[4 * s], samples[4 * s + 1]);
        fr.headings.push_back(samples[4 * s + 2]);
        fr.times.push_back(samples[4 * s + 3]);
      }
      t.fragments.push_back(std::move(fr));
    }
    L.types.push_back(std::move(t));
  }
  for (std::size_t c = 0; c < C; ++c) {
    for (std::size_t j = 0; j < 5; ++j) {
      if (constraints[5 * c + j] < 0) bad("constraint " + std::to_string(c) + " holds a negative index");
    }
    const auto k = static_cast<std::size_t>(constraints[5 * c]);
    if (k >= K) bad("a constraint names a missing type");
    L.types[k].constraints.push_back({static_cast<std::size_t>(constraints[5 * c + 1]), static_cast<std::size_t>(constraints[5 * c + 2]),
                                      static_cast<std::size_t>(constraints[5 * c + 3]), static_cast<std::size_t>(constraints[5 * c + 4])});
  }
  L.validate(path.string() + " library");

  const h5::Group inst = g.open_group("instances");
  std::uint64_t I = 0, P = 0;
  const std::vector<std::int64_t> type = ints(inst, "type", 0);
  const std::vector<double> transform = doubles(inst, "transform", 4, &I);
  const std::vector<std::int32_t> keyframed = inst.read_int32("keyframed", 1).values;
  const std::vector<double> paths = doubles(inst, "paths", 4, &P);
  if (type.size() != I || keyframed.size() != I) throw InputError(inst.where() + ": the instance datasets disagree in size");
  inst.budget().charge(checked_sum(checked_product(I, sizeof(Instance)).value_or(UINT64_MAX), checked_product(P, 32).value_or(UINT64_MAX))
                           .value_or(UINT64_MAX),
                       inst.where(), std::to_string(I) + " instances, " + std::to_string(P) + " path samples");
  std::size_t at = 0;
  for (std::size_t i = 0; i < I; ++i) {
    Instance x;
    if (type[i] < 0 || static_cast<std::size_t>(type[i]) >= K) {
      throw InputError(inst.where("type") + ": instance " + std::to_string(i) + " names type " + std::to_string(type[i]) +
                       " of " + std::to_string(K));
    }
    x.type = static_cast<std::size_t>(type[i]);
    x.transform.translation = {transform[4 * i], transform[4 * i + 1]};
    x.transform.angle = transform[4 * i + 2];
    x.transform.time_shift = transform[4 * i + 3];
    x.keyframed = keyframed[i] != 0;
    for (const Fragment& f : L.types[x.type].fragments) {
      if (at + f.sample_count() > P) throw InputError(inst.where("paths") + ": fewer samples than the instances' patches have");
      Path p;
      for (std::size_t s = 0; s < f.sample_count(); ++s, ++at) {
        p.positions.emplace_back(paths[4 * at], paths[4 * at + 1]);
        p.headings.push_back(paths[4 * at + 2]);
        p.times.push_back(paths[4 * at + 3]);
      }
      x.paths.push_back(std::move(p));
    }
    out.tiling.instances.push_back(std::move(x));
  }
  if (at != P) throw InputError(inst.where("paths") + ": more samples than the instances' patches have");
  std::uint64_t NC = 0;
  const std::vector<std::int64_t> conn = ints(g, "connections", 7, &NC);
  for (std::size_t c = 0; c < NC; ++c) {
    const std::int64_t* v = conn.data() + 7 * c;
    const std::uint32_t from = index32(v[0], g, "connections", c), from_fragment = index32(v[1], g, "connections", c);
    const std::uint32_t to = index32(v[2], g, "connections", c), to_fragment = index32(v[3], g, "connections", c);
    const auto& instances = out.tiling.instances;
    if (from >= instances.size() || to >= instances.size() || from_fragment >= instances[from].paths.size() ||
        to_fragment >= instances[to].paths.size()) {
      throw InputError(g.where("connections") + ": row " + std::to_string(c) + " names a missing instance or fragment");
    }
    out.tiling.connections.push_back({{from, from_fragment},
                                      {to, to_fragment},
                                      {copy_offset(v[4], g, "connections", c), copy_offset(v[5], g, "connections", c),
                                       copy_offset(v[6], g, "connections", c)}});
  }
  const auto zones = [&](const std::string& name) {
    std::uint64_t n = 0;
    const std::vector<double> v = doubles(g, name, 5, &n);
    std::vector<Zone> z;
    for (std::size_t k = 0; k < n; ++k) z.push_back({{v[5 * k], v[5 * k + 1]}, v[5 * k + 2], v[5 * k + 3], v[5 * k + 4]});
    return z;
  };
  out.environment.sources = zones("sources");
  out.environment.sinks = zones("sinks");
  std::uint64_t NP = 0;
  const std::vector<std::int64_t> pieces = ints(g.open_group("agents"), "pieces", 6, &NP);
  out.pieces.resize(agent_count);
  for (std::size_t k = 0; k < NP; ++k) {
    const std::int64_t* v = pieces.data() + 6 * k;
    if (v[0] < 0 || static_cast<std::size_t>(v[0]) >= out.pieces.size() || v[1] < 0 ||
        static_cast<std::size_t>(v[1]) >= out.tiling.instances.size() || v[2] < 0 ||
        static_cast<std::size_t>(v[2]) >= out.tiling.instances[static_cast<std::size_t>(v[1])].paths.size()) {
      throw InputError(g.where("agents/pieces") + ": row " + std::to_string(k) + " names a missing agent, instance or fragment");
    }
    out.pieces[static_cast<std::size_t>(v[0])].push_back(
        {{index32(v[1], g, "agents/pieces", k), index32(v[2], g, "agents/pieces", k)},
         {copy_offset(v[3], g, "agents/pieces", k), copy_offset(v[4], g, "agents/pieces", k), copy_offset(v[5], g, "agents/pieces", k)}});
  }
  CheckOptions& c = out.check;
  // The ranges of the tiling job's keys (bind above), in the file's units (radians, seconds per frame).
  c.limits.stretch_m = attribute_in(g, "limit_stretch", Range::positive());
  c.limits.bend_rad = attribute_in(g, "limit_bend", Range{0, std::numbers::pi * (1 + 1e-12), true, false});
  c.limits.time_shift_s = attribute_in(g, "limit_time_shift", Range::positive());
  c.limits.frame_period_s = attribute_in(g, "limit_frame_period", Range::positive());
  c.limits.bend_min_segment_m = attribute_in(g, "limit_bend_min_segment", Range::non_negative());
  // Files written before the speed limit (limits.speed_ratio) have none: their tilings are checked without it.
  c.limits.speed_ratio = g.has_attribute("limit_speed_ratio") ? attribute_in(g, "limit_speed_ratio", Range::non_negative()) : 0.0;
  c.match.distance_m = attribute_in(g, "match_distance", Range::positive());
  c.match.angle_rad = attribute_in(g, "match_angle", Range{0, std::numbers::pi * (1 + 1e-12), true, false});
  c.match.time_s = attribute_in(g, "match_time", Range::positive());
  c.obstacle_step_m = attribute_in(g, "obstacle_step", Range::positive());
  c.obstacle_step_s = attribute_in(g, "obstacle_step_time", Range::positive());
  check_obstacle_work(out, g);
  return out;
}

}  // namespace throng
