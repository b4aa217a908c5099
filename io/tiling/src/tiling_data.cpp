// The tiling data in a crowd file written by `throng tile` (tiling_data.h).
#include <throng/core/errors.h>
#include <throng/io/crowd_file.h>
#include <throng/io/tiling_data.h>

namespace throng {

using namespace tiling;

namespace {

void put_path(std::vector<double>& out, const Path& p) {
  for (std::size_t s = 0; s < p.times.size(); ++s) out.insert(out.end(), {p.positions[s].x(), p.positions[s].y(), p.headings[s], p.times[s]});
}

}  // namespace

}  // namespace throng

namespace throng::tiling {

void write_data(const h5::Group& g, const Run& run) {
  const PatchLibrary& library = run.library;
  const TilingResult& result = run.result;
  const Environment& environment = run.environment;
  const CheckOptions& check = run.check;
  const Characters& characters = run.characters;
  const LayoutOptions& layout = run.layout;
  // The library.
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

  // The tiling.
  const Tiling& t = result.tiling;
  const h5::Group inst = g.create_group("instances");
  std::vector<std::int64_t> type;
  std::vector<double> transform, paths;
  std::vector<std::int32_t> keyframed;
  for (const Instance& i : t.instances) {
    type.push_back(static_cast<std::int64_t>(i.type));
    transform.insert(transform.end(), {i.transform.translation.x(), i.transform.translation.y(), i.transform.angle, i.transform.time_shift});
    keyframed.push_back(i.keyframed ? 1 : 0);
    for (const Path& p : i.paths) put_path(paths, p);
  }
  const auto I = static_cast<std::uint64_t>(t.instances.size());
  inst.write("type", type, {I});
  inst.write("transform", transform, {I, 4});
  inst.write("keyframed", keyframed, {I});
  inst.write("paths", paths, {paths.size() / 4, 4}, h5::Layout{true});
  std::vector<std::int64_t> conn;
  for (const Connection& c : t.connections) {
    conn.insert(conn.end(), {c.from.instance, c.from.fragment, c.to.instance, c.to.fragment, c.image[0], c.image[1], c.image[2]});
  }
  g.write("connections", conn, {t.connections.size(), 7});
  const auto zones = [](const std::vector<Zone>& z) {
    std::vector<double> v;
    for (const Zone& zone : z) v.insert(v.end(), {zone.center.x(), zone.center.y(), zone.radius_m, zone.t0, zone.t1});
    return v;
  };
  g.write("sources", zones(environment.sources), {environment.sources.size(), 5});
  g.write("sinks", zones(environment.sinks), {environment.sinks.size(), 5});
  std::vector<std::int64_t> pieces;
  for (std::size_t a = 0; a < characters.pieces.size(); ++a) {
    for (const AgentPiece& p : characters.pieces[a]) {
      pieces.insert(pieces.end(), {static_cast<std::int64_t>(a), p.fragment.instance, p.fragment.fragment, p.copy[0], p.copy[1], p.copy[2]});
    }
  }
  g.create_group("agents").write("pieces", pieces, {pieces.size() / 6, 6});
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
  g.set_attribute("match_distance", check.match.distance_m);
  g.set_attribute("match_angle", check.match.angle_rad);
  g.set_attribute("match_time", check.match.time_s);
  g.set_attribute("obstacle_step", check.obstacle_step_m);
  g.set_attribute("obstacle_step_time", check.obstacle_step_s);
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

}  // namespace

bool has_tiling_data(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw IoError(path.string() + ": no such file");
  const h5::File file = h5::File::open(path);
  if (!file.root().has("parameters")) return false;
  const h5::Group parameters = file.root().open_group("parameters");
  return parameters.has("throng") && parameters.open_group("throng").has("tiling");
}

TilingData read_tiling_data(const std::filesystem::path& path) {
  TilingData out;
  const CrowdFile crowd = read_crowd_file(path);
  out.environment.scene = crowd.scene;
  const h5::File file = h5::File::open(path);
  const h5::Group params = open_throng_parameters(file);
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
    if (!(*own >= 0 && *own <= static_cast<double>(crowd.scene.obstacles.size()))) {
      throw InputError(g.where() + ": tile_obstacles = " + std::to_string(*own) + " of " +
                       std::to_string(crowd.scene.obstacles.size()) + " obstacles in the scene");
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
  if (labels.size() != K || preference.size() != K || type_fragments.size() != K + 1 || radius.size() != F ||
      type_fragments.back() != static_cast<std::int64_t>(F)) {
    throw InputError(lib.where() + ": the library's datasets disagree in size");
  }
  const auto bad = [&](const std::string& what) { throw InputError(lib.where() + ": " + what); };
  for (std::size_t k = 0; k < K; ++k) {
    PatchType t;
    t.name = names[k];
    t.label = labels[k];
    t.preference = preference[k];
    if (type_fragments[k] < 0 || type_fragments[k + 1] < type_fragments[k]) bad("type_fragments not increasing");
    for (auto f = static_cast<std::size_t>(type_fragments[k]); f < static_cast<std::size_t>(type_fragments[k + 1]); ++f) {
      Fragment fr;
      fr.kind = fragments[4 * f] == 0 ? FragmentKind::character : FragmentKind::prop;
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
    if (v[0] < 0 || v[1] < 0 || v[2] < 0 || v[3] < 0) throw InputError(g.where("connections") + ": negative index in row " + std::to_string(c));
    out.tiling.connections.push_back({{static_cast<std::uint32_t>(v[0]), static_cast<std::uint32_t>(v[1])},
                                      {static_cast<std::uint32_t>(v[2]), static_cast<std::uint32_t>(v[3])},
                                      {static_cast<int>(v[4]), static_cast<int>(v[5]), static_cast<int>(v[6])}});
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
  out.pieces.resize(crowd.motion.agent_count());
  for (std::size_t k = 0; k < NP; ++k) {
    const std::int64_t* v = pieces.data() + 6 * k;
    if (v[0] < 0 || static_cast<std::size_t>(v[0]) >= out.pieces.size() || v[1] < 0 ||
        static_cast<std::size_t>(v[1]) >= out.tiling.instances.size() || v[2] < 0 ||
        static_cast<std::size_t>(v[2]) >= out.tiling.instances[static_cast<std::size_t>(v[1])].paths.size()) {
      throw InputError(g.where("agents/pieces") + ": row " + std::to_string(k) + " names a missing agent, instance or fragment");
    }
    out.pieces[static_cast<std::size_t>(v[0])].push_back(
        {{static_cast<std::uint32_t>(v[1]), static_cast<std::uint32_t>(v[2])},
         {static_cast<int>(v[3]), static_cast<int>(v[4]), static_cast<int>(v[5])}});
  }
  CheckOptions& c = out.check;
  c.limits.stretch_m = attribute(g, "limit_stretch");
  c.limits.bend_rad = attribute(g, "limit_bend");
  c.limits.time_shift_s = attribute(g, "limit_time_shift");
  c.limits.frame_period_s = attribute(g, "limit_frame_period");
  c.limits.bend_min_segment_m = attribute(g, "limit_bend_min_segment");
  c.match.distance_m = attribute(g, "match_distance");
  c.match.angle_rad = attribute(g, "match_angle");
  c.match.time_s = attribute(g, "match_time");
  c.obstacle_step_m = attribute(g, "obstacle_step");
  c.obstacle_step_s = attribute(g, "obstacle_step_time");
  return out;
}

}  // namespace throng
