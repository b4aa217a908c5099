#include <throng/core/errors.h>
#include <throng/core/format.h>
#include <throng/io/formation_job.h>
#include <throng/formation/schema.h>
#include <throng/io/formation_shapes.h>

#include <algorithm>
#include <iterator>
#include <cmath>
#include <numbers>
#include <numeric>
#include <sstream>

namespace throng {
namespace {

using formation::AdjacencyEdits;
using formation::EdgeScale;
using formation::Group;
using formation::Options;
using formation::OrientationAlignment;
using formation::Pair;
using formation::Reordering;


int read_index(const ConfigNode& node) {
  const std::int64_t v = node.as_int();
  if (v < 0 || v > 100'000'000) node.fail("individual " + std::to_string(v) + " is not an index ≥ 0");
  return static_cast<int>(v);
}

std::vector<int> read_indices(const ConfigNode& node) {
  std::vector<int> out;
  for (const ConfigNode& e : node.elements()) out.push_back(read_index(e));
  return out;
}

std::vector<Pair> read_pairs(const ConfigNode& node) {
  std::vector<Pair> out;
  for (const ConfigNode& e : node.elements()) {
    const std::vector<ConfigNode> ab = e.elements();
    if (ab.size() != 2) e.fail("a pair is [a, b], found " + std::to_string(ab.size()) + " entries");
    out.push_back({read_index(ab[0]), read_index(ab[1])});
  }
  return out;
}

// Every individual of the named groups of `root` (names as written, or the generated g0, g0.1 ...).
void collect(const Group& g, std::vector<int>& out) {
  out.insert(out.end(), g.members.begin(), g.members.end());
  for (const Group& s : g.subgroups) collect(s, out);
}
const Group* find_group(const Group& g, const std::string& name) {
  if (g.name == name) return &g;
  for (const Group& s : g.subgroups)
    if (const Group* f = find_group(s, name)) return f;
  return nullptr;
}

AdjacencyEdits read_edits(const ConfigNode& node, const std::optional<Group>& hierarchy) {
  AdjacencyEdits edits;
  edits.where = node.where();
  if (auto r = node.find("remove")) edits.remove = read_pairs(*r);
  if (auto a = node.find("add")) edits.add = read_pairs(*a);
  if (auto s = node.find("scale")) {
    for (const ConfigNode& e : s->elements()) {
      const ConfigNode f = e.at("factor");
      const double factor = f.as_double();
      if (!std::isfinite(factor) || !(factor > 0)) f.fail("factor must be a finite number > 0, got " + with_digits(factor, 6));
      bool any = false;
      if (auto p = e.find("pairs")) {
        edits.scale.push_back(EdgeScale{read_pairs(*p), {}, factor});
        any = true;
      }
      if (auto m = e.find("members")) {
        edits.scale.push_back(EdgeScale{{}, read_indices(*m), factor});
        any = true;
      }
      if (auto gs = e.find("groups")) {
        for (const ConfigNode& name_node : gs->elements()) {
          const std::string name = name_node.as_string();
          const Group* g = hierarchy ? find_group(*hierarchy, name) : nullptr;
          if (!g) name_node.fail("no hierarchy group is named '" + name + "' (groups need a hierarchy given as a tree, sizes or nested)");
          EdgeScale scale{{}, {}, factor};
          collect(*g, scale.members);
          edits.scale.push_back(std::move(scale));
        }
        any = true;
      }
      if (!any) e.fail("a scale edit needs pairs, members or groups");
    }
  }
  return edits;
}

Group read_group(const ConfigNode& node, const std::string& fallback_name) {
  Group g;
  g.name = fallback_name;
  if (auto n = node.find("name")) g.name = n->as_string();
  if (auto m = node.find("members")) g.members = read_indices(*m);
  if (auto s = node.find("groups")) {
    const std::vector<ConfigNode> list = s->elements();
    for (std::size_t i = 0; i < list.size(); ++i) g.subgroups.push_back(read_group(list[i], g.name + "." + std::to_string(i)));
  }
  return g;
}

// Levels of consecutive individuals: the node at `level` has sizes[level] items, individuals at the last level
// and groups above it (named g0, g0.1, ...).
Group nested_group(const std::vector<int>& sizes, std::size_t level, int& next, const std::string& name) {
  Group g;
  g.name = name;
  if (level + 1 == sizes.size()) {
    for (int i = 0; i < sizes[level]; ++i) g.members.push_back(next++);
    return g;
  }
  for (int i = 0; i < sizes[level]; ++i)
    g.subgroups.push_back(nested_group(sizes, level + 1, next, (level == 0 ? "g" : name + ".") + std::to_string(i)));
  return g;
}

std::vector<int> read_sizes(const ConfigNode& node) {
  std::vector<int> sizes;
  for (const ConfigNode& e : node.elements()) {
    const std::int64_t v = e.as_int();
    if (v < 1 || v > 10'000'000) e.fail("a group size must be ≥ 1, got " + std::to_string(v));
    sizes.push_back(static_cast<int>(v));
  }
  if (sizes.empty()) node.fail("give at least one size");
  return sizes;
}

// The hierarchy key: a tree, sizes, nested or auto. Returns the tree (none for auto).
std::optional<Group> read_hierarchy(const ConfigNode& node, Options& options) {
  if (node.has("auto")) {
    const ConfigNode a = node.at("auto");
    const std::int64_t v = a.as_int();
    if (v < 2 || v > 10'000'000) a.fail("auto: the largest group must be at least 2 items, got " + std::to_string(v));
    options.auto_group_size = static_cast<int>(v);
    if (node.yaml().size() != 1) node.fail("auto takes no other hierarchy keys");
    return std::nullopt;
  }
  if (node.has("sizes")) {
    if (node.yaml().size() != 1) node.fail("sizes takes no other hierarchy keys");
    Group root;
    root.name = "root";
    int next = 0;
    const std::vector<int> sizes = read_sizes(node.at("sizes"));
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      Group g;
      g.name = "g" + std::to_string(i);
      for (int k = 0; k < sizes[i]; ++k) g.members.push_back(next++);
      root.subgroups.push_back(std::move(g));
    }
    return root;
  }
  if (node.has("nested")) {
    if (node.yaml().size() != 1) node.fail("nested takes no other hierarchy keys");
    int next = 0;
    return nested_group(read_sizes(node.at("nested")), 0, next, "root");
  }
  return read_group(node, "root");
}

// A number of the keyframe data (a coordinate, a time) written as YAML's .nan or .inf: bad data, an InputError
// (exit 3) like the formation's other data problems and as animate_formation reports NaN positions given in
// code. Anything that is not a number at all is left to as_double (a ConfigError: the job's syntax).
void require_finite_data(const ConfigNode& node, const std::string& what) {
  if (!node.is_scalar()) return;
  double v = 0.0;
  if (YAML::convert<double>::decode(node.yaml(), v) && !std::isfinite(v))
    throw InputError(node.where() + ": " + what + " is '" + node.yaml().Scalar() +
                     "', not a finite number; keyframe data must be finite");
}

// A keyframe's `facing`: every individual's facing there, as a yaw about +z in degrees counter-clockwise from
// +x (on the ground; a 3-D formation levels its individuals there): one number for everyone, a list with one per
// individual (row order), or {toward: point} for each to face a point ([x, y] or [x, y, z]; only its direction
// on the ground counts; an individual standing on the point keeps +x). Shapes: see Keyframe::facings.
std::vector<Eigen::Quaterniond> read_facings(const ConfigNode& facing, const Eigen::MatrixXd& positions) {
  const auto n = static_cast<std::size_t>(positions.rows());
  auto yaw = [](double degrees) {
    return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()));
  };
  auto finite = [&](const ConfigNode& node, double v) {
    if (!std::isfinite(v)) node.fail("facing must be finite degrees");
    return v;
  };
  if (facing.is_scalar()) return std::vector<Eigen::Quaterniond>(n, yaw(finite(facing, facing.as_double())));
  if (facing.is_sequence()) {
    const std::vector<double> degrees = facing.as_doubles();
    if (degrees.size() != n)
      facing.fail(std::to_string(degrees.size()) + " facings for " + std::to_string(n) +
                  " individuals (give one number for everyone, or one per individual)");
    std::vector<Eigen::Quaterniond> out;
    for (double d : degrees) out.push_back(yaw(finite(facing, d)));
    return out;
  }
  if (!facing.is_map()) facing.fail("give facing as degrees, a list of degrees, or {toward: [x, y]}");
  const ConfigNode toward = facing.at("toward");
  const std::vector<double> point = toward.as_doubles({2, 3});
  for (double v : point) finite(toward, v);
  std::vector<Eigen::Quaterniond> out;
  for (std::size_t i = 0; i < n; ++i) {
    const auto row = static_cast<Eigen::Index>(i);
    const double dx = point[0] - positions(row, 0), dy = point[1] - positions(row, 1);
    out.push_back(std::hypot(dx, dy) > 0 ? yaw(std::atan2(dy, dx) * 180.0 / std::numbers::pi) : yaw(0));
  }
  return out;
}

// Keyframe positions: `positions` rows or generated `shapes`.
Eigen::MatrixXd read_positions(const ConfigNode& key) {
  const bool has_positions = key.has("positions"), has_shapes = key.has("shapes");
  if (has_positions == has_shapes) key.fail("give a keyframe either positions or shapes");
  if (has_shapes) return generate_shapes(key.at("shapes"));
  const ConfigNode rows = key.at("positions");
  const std::vector<ConfigNode> list = rows.elements();
  if (list.empty()) rows.fail("no positions");
  if (list.front().is_sequence())
    for (const ConfigNode& c : list.front().elements()) require_finite_data(c, "individual 0's coordinate");
  const std::size_t d = list.front().as_doubles({2, 3}).size();
  Eigen::MatrixXd out(static_cast<Eigen::Index>(list.size()), static_cast<Eigen::Index>(d));
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (list[i].is_sequence())
      for (const ConfigNode& c : list[i].elements()) require_finite_data(c, "individual " + std::to_string(i) + "'s coordinate");
    const std::vector<double> v = list[i].as_doubles({2, 3});
    if (v.size() != d)
      throw InputError(list[i].where() + ": individual " + std::to_string(i) + " has " + std::to_string(v.size()) +
                       " coordinates, individual 0 has " + std::to_string(d) + "; a formation is all 2-D or all 3-D");
    for (std::size_t a = 0; a < d; ++a) out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(a)) = v[a];
  }
  return out;
}

// Two rows at the same position: InputError at `where`.
void require_distinct(const Eigen::MatrixXd& p, const ConfigNode& where, std::size_t k) {
  std::vector<Eigen::Index> order(static_cast<std::size_t>(p.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  auto less = [&](Eigen::Index a, Eigen::Index b) {
    for (Eigen::Index c = 0; c < p.cols(); ++c)
      if (p(a, c) != p(b, c)) return p(a, c) < p(b, c);
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) {
    if (p.row(order[i]) == p.row(order[i - 1])) {
      std::ostringstream s;
      s << where.where() << ": keyframe " << k << ": individuals " << std::min(order[i], order[i - 1]) << " and "
        << std::max(order[i], order[i - 1]) << " are both at (" << p(order[i], 0) << ", " << p(order[i], 1)
        << (p.cols() == 3 ? ", " + with_digits(p(order[i], 2), 6) : std::string()) << "); every individual needs its own position";
      throw InputError(s.str());
    }
  }
}

}  // namespace

void read_job(const ConfigNode& job, FormationJob& parsed) {
  Options& o = parsed.options;
  read_options(job, formation::describe, o);

  if (auto h = job.find("hierarchy")) {
    if (h->is_scalar() && h->as_string() == "flat") {
      o.auto_group_size = 0;
    } else {
      if (!h->is_map())
        h->fail("hierarchy is flat or a mapping: a tree (name, members, groups), {sizes: [...]}, {nested: [...]} or {auto: N}");
      parsed.problem.hierarchy = read_hierarchy(*h, o);
    }
    if (parsed.problem.hierarchy) parsed.problem.hierarchy->where = h->where();
    parsed.hierarchy_yaml = YAML::Clone(h->yaml());
  }
  if (auto e = job.find("edits")) {
    parsed.problem.edits = read_edits(*e, parsed.problem.hierarchy);
    parsed.edits_yaml = YAML::Clone(e->yaml());
  }
  if (auto ids = job.find("ids")) {
    for (const ConfigNode& id : ids->elements()) parsed.problem.ids.push_back(id.as_int());
    std::vector<std::int64_t> sorted = parsed.problem.ids;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) ids->fail("ids must be distinct");
  }

  const bool has_keyframes = job.has("keyframes"), has_crowd = job.has("from_crowd");
  if (has_keyframes == has_crowd) job.fail("give either keyframes or from_crowd");
  if (has_crowd) {
    const ConfigNode c = job.at("from_crowd");
    FormationCrowdSource source;
    if (auto f = c.find("file")) source.file = f->as_path().string();
    const ConfigNode frames = c.at("frames");
    for (const ConfigNode& f : frames.elements()) source.frames.push_back(static_cast<long>(f.as_int()));
    if (source.frames.size() < 2) frames.fail("give at least 2 frames");
    if (auto t = c.find("times")) {
      source.times = t->as_doubles({source.frames.size()});
      for (std::size_t k = 1; k < source.times.size(); ++k)
        if (!(source.times[k] > source.times[k - 1])) t->fail("times must increase strictly");
    }
    if (auto d = c.find("dimension")) {
      const std::int64_t v = d->as_int();
      if (v != 2 && v != 3) d->fail("dimension must be 2 or 3");
      source.dimension = static_cast<int>(v);
    }
    parsed.from_crowd = std::move(source);
  } else {
    const ConfigNode keys = job.at("keyframes");
    const std::vector<ConfigNode> list = keys.elements();
    if (list.size() < 2) keys.fail("give at least 2 keyframes, found " + std::to_string(list.size()));
    parsed.keyframes_yaml = YAML::Node(YAML::NodeType::Sequence);
    for (std::size_t k = 0; k < list.size(); ++k) {
      const ConfigNode& key = list[k];
      formation::Keyframe keyframe;
      keyframe.where = key.where();
      const ConfigNode time = key.at("time");
      require_finite_data(time, "keyframe " + std::to_string(k) + "'s time");
      keyframe.time_s = time.as_double();
      if (!std::isfinite(keyframe.time_s)) time.fail("time must be a finite number of seconds");
      keyframe.positions = read_positions(key);
      if (auto e = key.find("edits")) keyframe.edits = read_edits(*e, parsed.problem.hierarchy);
      if (auto sharp = key.find("sharp")) keyframe.sharp = sharp->as_bool();  // a sharp corner (formation.h)
      if (auto facing = key.find("facing")) keyframe.facings = read_facings(*facing, keyframe.positions);
      if (k > 0) {
        const formation::Keyframe& first = parsed.problem.keyframes.front();
        const formation::Keyframe& previous = parsed.problem.keyframes.back();
        if (!(keyframe.time_s > previous.time_s))
          throw InputError(time.where() + ": keyframe " + std::to_string(k) + " is at " + with_digits(keyframe.time_s, 6) +
                           " s, not after keyframe " + std::to_string(k - 1) + "'s " + with_digits(previous.time_s, 6) +
                           " s; keyframe times must increase strictly");
        if (keyframe.positions.rows() != first.positions.rows())
          throw InputError(key.where() + ": keyframe " + std::to_string(k) + " has " +
                           std::to_string(keyframe.positions.rows()) + " individuals, keyframe 0 has " +
                           std::to_string(first.positions.rows()) + "; every keyframe holds the same individuals");
        if (keyframe.positions.cols() != first.positions.cols())
          throw InputError(key.where() + ": keyframe " + std::to_string(k) + " is " +
                           std::to_string(keyframe.positions.cols()) + "-D, keyframe 0 is " +
                           std::to_string(first.positions.cols()) + "-D");
      }
      require_distinct(keyframe.positions, key, k);
      parsed.problem.keyframes.push_back(std::move(keyframe));
      parsed.keyframes_yaml.push_back(YAML::Clone(key.yaml()));
    }
    const auto n = static_cast<std::size_t>(parsed.problem.keyframes.front().positions.rows());
    if (!parsed.problem.ids.empty() && parsed.problem.ids.size() != n)
      job.at("ids").fail(std::to_string(parsed.problem.ids.size()) + " ids for " + std::to_string(n) + " individuals");
  }
  job.finish();
}

void resolve_formation_keyframes(FormationJob& job, const Crowd* crowd) {
  if (!job.from_crowd) return;
  if (crowd == nullptr) throw ConfigError("from_crowd: no crowd to take the keyframes from (give from_crowd.file)");
  const CrowdMotion& m = crowd->motion;
  std::vector<std::size_t> frames;
  for (long f : job.from_crowd->frames) {
    const long T = static_cast<long>(m.frame_count());
    const long frame = f < 0 ? T + f : f;
    if (frame < 0 || frame >= T)
      throw InputError("from_crowd.frames: frame " + std::to_string(f) + " is outside the crowd's " + std::to_string(T) + " frames");
    frames.push_back(static_cast<std::size_t>(frame));
  }
  job.problem.keyframes = formation::keyframes_from_motion(m, frames, job.from_crowd->dimension);
  for (std::size_t k = 0; k < job.from_crowd->times.size(); ++k) job.problem.keyframes[k].time_s = job.from_crowd->times[k];
  const std::string crowd_name = job.from_crowd->file.empty() ? std::string("the input crowd") : job.from_crowd->file;
  for (std::size_t k = 0; k < frames.size(); ++k)
    job.problem.keyframes[k].where = crowd_name + " frame " + std::to_string(frames[k]);
  if (job.problem.ids.empty()) job.problem.ids = m.ids;
  else if (job.problem.ids.size() != m.agent_count())
    throw ConfigError("ids: " + std::to_string(job.problem.ids.size()) + " ids for the crowd's " +
                      std::to_string(m.agent_count()) + " agents");
}

YAML::Node effective_job(const FormationJob& job) {
  YAML::Node out(YAML::NodeType::Map);
  write_options(out, formation::describe, static_cast<const formation::Job&>(job));
  if (job.from_crowd) {
    YAML::Node c;
    if (!job.from_crowd->file.empty()) c["file"] = job.from_crowd->file;
    std::vector<double> frames(job.from_crowd->frames.begin(), job.from_crowd->frames.end());
    c["frames"] = yaml_numbers(frames);
    if (!job.from_crowd->times.empty()) c["times"] = yaml_numbers(job.from_crowd->times);
    c["dimension"] = job.from_crowd->dimension;
    out["from_crowd"] = c;
  } else {
    out["keyframes"] = YAML::Clone(job.keyframes_yaml);
  }
  if (!job.problem.ids.empty() && !job.from_crowd) {
    YAML::Node ids(YAML::NodeType::Sequence);
    for (std::int64_t id : job.problem.ids) ids.push_back(id);
    ids.SetStyle(YAML::EmitterStyle::Flow);
    out["ids"] = ids;
  }
  auto given = [](const YAML::Node& n) { return n.IsDefined() && !n.IsNull(); };
  if (given(job.edits_yaml)) out["edits"] = YAML::Clone(job.edits_yaml);
  if (given(job.hierarchy_yaml)) {
    out["hierarchy"] = YAML::Clone(job.hierarchy_yaml);
  } else if (job.options.auto_group_size > 0) {  // none given: the automatic default, as it is applied
    YAML::Node automatic(YAML::NodeType::Map);
    automatic["auto"] = job.options.auto_group_size;
    automatic.SetStyle(YAML::EmitterStyle::Flow);
    out["hierarchy"] = automatic;
  } else {
    out["hierarchy"] = "flat";
  }
  return out;
}

namespace {
void list_groups(const Group& g, std::int64_t parent, std::vector<std::string>& names, std::vector<std::int64_t>& parents) {
  const auto index = static_cast<std::int64_t>(names.size());
  names.push_back(g.name);
  parents.push_back(parent);
  for (const Group& s : g.subgroups) list_groups(s, index, names, parents);
}
}  // namespace

}  // namespace throng

namespace throng::formation {

void write_data(const h5::Group& g, const Run& run) {
  const Result& result = run.result;
  const auto& keys = run.problem.keyframes;
  const std::uint64_t K = keys.size();
  const auto n = static_cast<std::uint64_t>(keys.front().positions.rows());
  const auto d = static_cast<std::uint64_t>(keys.front().positions.cols());
  const h5::Group kg = g.create_group("keyframes");
  std::vector<double> times;
  std::vector<std::int64_t> frames, correspondence;
  std::vector<double> positions;
  for (std::uint64_t k = 0; k < K; ++k) {
    times.push_back(keys[k].time_s);
    frames.push_back(static_cast<std::int64_t>(result.keyframe_frames[k]));
    for (std::uint64_t i = 0; i < n; ++i) {
      const int row = result.correspondence[k][i];
      correspondence.push_back(row);
      for (std::uint64_t a = 0; a < d; ++a) positions.push_back(keys[k].positions(row, static_cast<Eigen::Index>(a)));
    }
  }
  kg.write("time", times, {K});
  kg.write("frame", frames, {K});
  kg.write("position", positions, {K, n, d});
  kg.write("correspondence", correspondence, {K, n});
  for (std::uint64_t k = 0; k < K; ++k) {
    std::vector<std::int32_t> edges;
    for (const Pair& e : result.keyframe_edges[k]) edges.insert(edges.end(), {e[0], e[1]});
    kg.write("edges_" + std::to_string(k), edges, {result.keyframe_edges[k].size(), 2});
  }
  std::vector<std::string> names;
  std::vector<std::int64_t> parents;
  list_groups(result.hierarchy, -1, names, parents);
  const h5::Group groups = g.create_group("groups");
  groups.write("name", names);
  groups.write("parent", parents, {parents.size()});
}

}  // namespace throng::formation
