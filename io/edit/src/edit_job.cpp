#include <throng/core/errors.h>
#include <throng/io/edge_edits_job.h>
#include <throng/io/edit_job.h>

#include <limits>
#include <sstream>
#include <string>

namespace throng {
namespace {

using edit::Options;
constexpr std::size_t open_end = std::numeric_limits<std::size_t>::max();

void bind_solver(OptionBinder& b, linalg::SolverOptions& s) {
  b.choice("backend", s.backend, {"eigen", "petsc"});
  b.field("blas_threads", s.blas_threads, Range::closed(0, 1024));
  b.field("relative_tolerance", s.relative_tolerance, Range{0.0, 1.0, true, true});
  b.field("max_iterations", s.max_iterations, Range::closed(1, 1e9));
  b.field("petsc_prefix", s.petsc_prefix);
  b.field("petsc_options", s.petsc_options);
  b.field("constraint_tolerance", s.constraint_tolerance, Range{0.0, 1.0, true, true});
  b.field("schur_cache_megabytes", s.schur_cache_megabytes, Range::non_negative());
}

// Every option but the clip's frame range and agents and the formation edits (read by hand: `end`, lists).
void bind(OptionBinder& b, Options& o) {
  b.section("clip", [&](OptionBinder& c) { c.field("sample_step", o.clip.sample_step, Range::closed(1, 1e9)); });
  b.section("formation", [&](OptionBinder& f) { f.field("max_edge_length", o.formation.max_edge_length, Range::non_negative()); });
  b.section("weights", [&](OptionBinder& w) {
    w.field("alpha", o.alpha, Range::non_negative());
    w.field("beta", o.beta, Range::non_negative());
    w.field("alpha_prime", o.alpha_prime, Range::non_negative());
    w.field("beta_prime", o.beta_prime, Range::non_negative());
  });
  b.field("scale_compensation", o.scale_compensation);
  b.section("features", [&](OptionBinder& f) {
    f.field("min_length", o.features.min_length, Range::positive());
    f.field("degenerate_ratio", o.features.degenerate_ratio, Range{0.0, 1.0, false, true});
  });
  b.section("solver", [&](OptionBinder& s) { bind_solver(s, o.solver); });
  b.section("local", [&](OptionBinder& l) {  // parts: read and written by hand (a count or `auto`)
    l.field("vertices_per_part", o.local.vertices_per_part, Range::closed(1, 1e9));
    l.field("halo", o.local.halo, Range::closed(-1, 1e9));
    l.field("seed", o.local.seed, Range::closed(0, 2147483646));
    l.field("max_cached_regions", o.local.max_cached_regions, Range::closed(1, 1e6));
  });
}

// An input frame index (≥ 0), for the clip.
std::size_t frame_index(const ConfigNode& node) {
  const std::int64_t v = node.as_int();
  if (v < 0) node.fail("frame " + std::to_string(v) + " is negative: frames are indices into the input, from 0");
  return static_cast<std::size_t>(v);
}

// An input frame index, or `end` (open_end).
std::size_t frame_or_end(const ConfigNode& node) {
  if (node.is_scalar() && node.as_string() == "end") return open_end;
  return frame_index(node);
}

// A request frame: an index, negative counting back from the clip's last frame, or `end` (−1).
edit::Frame request_frame(const ConfigNode& node) {
  if (node.is_scalar() && node.as_string() == "end") return -1;
  return static_cast<edit::Frame>(node.as_int());
}

// `frames: [first, last]` of a request entry, default the whole clip.
std::pair<edit::Frame, edit::Frame> request_range(const ConfigNode& entry) {
  const auto frames = entry.find("frames");
  if (!frames) return {0, -1};
  const std::vector<ConfigNode> ends = frames->elements();
  if (ends.size() != 2) frames->fail("expected [first, last] (negative counts from the end; last may be 'end'), found " + std::to_string(ends.size()) + " values");
  return {request_frame(ends[0]), request_frame(ends[1])};
}

std::vector<std::int64_t> ids(const ConfigNode& node) {
  std::vector<std::int64_t> out;
  for (const ConfigNode& e : node.elements()) out.push_back(e.as_int());
  return out;
}

Eigen::Vector2d point(const ConfigNode& node) {
  const std::vector<double> v = node.as_doubles({2});
  return {v[0], v[1]};
}

YAML::Node flow(std::initializer_list<double> values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (double v : values) n.push_back(yaml_number(v));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node flow(const Eigen::Vector2d& p) { return flow({p.x(), p.y()}); }

YAML::Node request_frames_yaml(edit::Frame first, edit::Frame last) {
  YAML::Node n(YAML::NodeType::Sequence);
  n.push_back(first);
  n.push_back(last);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node ids_yaml(const std::vector<std::int64_t>& values) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (std::int64_t v : values) n.push_back(v);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

void read_clip(const ConfigNode& job, edit::Options& o) {
  const auto clip = job.find("clip");
  if (!clip) return;
  if (auto f = clip->find("first_frame")) o.clip.first_frame = frame_index(*f);
  if (auto f = clip->find("last_frame")) o.clip.last_frame = frame_or_end(*f);
  if (o.clip.last_frame != open_end && o.clip.last_frame <= o.clip.first_frame) {
    clip->fail("last_frame " + std::to_string(o.clip.last_frame) + " must be after first_frame " +
               std::to_string(o.clip.first_frame));
  }
  if (auto a = clip->find("agents")) {
    o.clip.agents = ids(*a);
    if (o.clip.agents.empty()) a->fail("an empty agent list selects nobody: leave agents out to take every agent");
  }
}

// local.parts: a part count (0 = global solves) or `auto` (LocalOptions::by_size: from vertices_per_part).
void read_local_parts(const ConfigNode& job, edit::Options& o) {
  const auto local = job.find("local");
  if (!local) return;
  const auto parts = local->find("parts");
  if (!parts) return;
  if (parts->is_scalar() && parts->as_string() == "auto") {
    o.local.parts = edit::LocalOptions::by_size;
    return;
  }
  if (!parts->is_scalar()) parts->fail("expected a part count or auto");
  std::int64_t v = 0;
  try {
    v = parts->as_int();
  } catch (const ConfigError&) {
    parts->fail("expected a part count (0 = global solves) or auto, found '" + parts->as_string() + "'");
  }
  if (v < 0 || v > 1000000000) parts->fail("value " + std::to_string(v) + " is out of range, expected a part count in [0, 1e9] or auto");
  o.local.parts = static_cast<int>(v);
}

void read_handles(const ConfigNode& job, edit::Request& r) {
  if (auto pins = job.find("pins")) {
    for (const ConfigNode& p : pins->elements()) {
      edit::Pin pin;
      pin.agent = p.at("agent").as_int();
      pin.frame = request_frame(p.at("frame"));
      if (auto at = p.find("position")) pin.position = point(*at);
      r.pins.push_back(pin);
    }
  }
  if (auto drags = job.find("drags")) {
    for (const ConfigNode& d : drags->elements()) {
      edit::Drag drag;
      if (auto a = d.find("agents")) {
        drag.selection.agents = ids(*a);
        if (drag.selection.agents.empty()) a->fail("an empty agent list selects nobody: leave agents out to take every agent");
      }
      std::tie(drag.selection.first_frame, drag.selection.last_frame) = request_range(d);
      if (auto v = d.find("offset")) drag.offset = point(*v);
      if (auto v = d.find("rotation")) drag.rotation = v->as_double();
      if (auto v = d.find("pivot")) drag.pivot = point(*v);
      r.drags.push_back(drag);
    }
  }
}

void read_constraints(const ConfigNode& job, edit::Request& r) {
  const auto constraints = job.find("constraints");
  if (!constraints) return;
  for (const ConfigNode& c : constraints->elements()) {
    const ConfigNode type = c.at("type");
    const std::string kind = type.as_string();
    if (kind == "relative_position") {
      edit::RelativePosition rp;
      rp.agent = c.at("agent").as_int();
      rp.other = c.at("other").as_int();
      std::tie(rp.first_frame, rp.last_frame) = request_range(c);
      if (auto v = c.find("offset")) rp.offset = point(*v);
      r.constraints.emplace_back(rp);
    } else if (kind == "velocity") {
      edit::Velocity v;
      v.agent = c.at("agent").as_int();
      v.frame = request_frame(c.at("frame"));
      v.velocity = point(c.at("velocity"));
      r.constraints.emplace_back(v);
    } else if (kind == "on_line") {
      edit::OnLine line;
      line.agent = c.at("agent").as_int();
      std::tie(line.first_frame, line.last_frame) = request_range(c);
      line.point = point(c.at("point"));
      line.direction = point(c.at("direction"));
      if (line.direction.norm() == 0) c.at("direction").fail("the direction is the zero vector");
      r.constraints.emplace_back(line);
    } else {
      type.fail("unknown constraint type '" + kind + "': expected relative_position, velocity or on_line");
    }
  }
}

}  // namespace

EditJob read_edit_job(const ConfigNode& job) {
  EditJob parsed;
  OptionReader reader(job);
  bind(reader, parsed.options);
  read_clip(job, parsed.options);
  read_local_parts(job, parsed.options);
  read_edge_edits(job, parsed.options.formation, "the input");
  read_handles(job, parsed.request);
  read_constraints(job, parsed.request);
  if (auto v = job.find("clip_only")) parsed.clip_only = v->as_bool();
  job.finish();
  try {
    edit::validate(parsed.options);
  } catch (const Error& e) {
    job.fail(e.what());
  }
  return parsed;
}

YAML::Node effective_edit_job(const EditJob& job) {
  YAML::Node out(YAML::NodeType::Map);  // a map already, so the writer's copy of the handle shares it
  edit::Options options = job.options;
  OptionWriter writer(out);
  bind(writer, options);
  out["clip_only"] = job.clip_only;
  const auto& o = job.options;
  if (o.local.parts == edit::LocalOptions::by_size) {
    out["local"]["parts"] = "auto";
  } else {
    out["local"]["parts"] = o.local.parts;
  }
  out["clip"]["first_frame"] = static_cast<std::uint64_t>(o.clip.first_frame);
  if (o.clip.last_frame == open_end) {
    out["clip"]["last_frame"] = "end";
  } else {
    out["clip"]["last_frame"] = static_cast<std::uint64_t>(o.clip.last_frame);
  }
  if (!o.clip.agents.empty()) out["clip"]["agents"] = ids_yaml(o.clip.agents);
  write_edge_edits(out, o.formation);
  const auto& r = job.request;
  if (!r.pins.empty()) {
    YAML::Node pins(YAML::NodeType::Sequence);
    for (const edit::Pin& p : r.pins) {
      YAML::Node n;
      n["agent"] = p.agent;
      n["frame"] = p.frame;
      if (p.position) n["position"] = flow(*p.position);
      pins.push_back(n);
    }
    out["pins"] = pins;
  }
  if (!r.drags.empty()) {
    YAML::Node drags(YAML::NodeType::Sequence);
    for (const edit::Drag& d : r.drags) {
      YAML::Node n;
      if (!d.selection.agents.empty()) n["agents"] = ids_yaml(d.selection.agents);
      n["frames"] = request_frames_yaml(d.selection.first_frame, d.selection.last_frame);
      n["offset"] = flow(d.offset);
      n["rotation"] = yaml_number(d.rotation);
      if (d.pivot) n["pivot"] = flow(*d.pivot);
      drags.push_back(n);
    }
    out["drags"] = drags;
  }
  if (!r.constraints.empty()) {
    YAML::Node list(YAML::NodeType::Sequence);
    for (const edit::Constraint& c : r.constraints) {
      YAML::Node n;
      std::visit(
          [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            n["agent"] = v.agent;
            if constexpr (std::is_same_v<T, edit::RelativePosition>) {
              n["type"] = "relative_position";
              n["other"] = v.other;
              n["frames"] = request_frames_yaml(v.first_frame, v.last_frame);
              if (v.offset) n["offset"] = flow(*v.offset);
            } else if constexpr (std::is_same_v<T, edit::Velocity>) {
              n["type"] = "velocity";
              n["frame"] = v.frame;
              n["velocity"] = flow(v.velocity);
            } else {
              n["type"] = "on_line";
              n["frames"] = request_frames_yaml(v.first_frame, v.last_frame);
              n["point"] = flow(v.point);
              n["direction"] = flow(v.direction);
            }
          },
          c);
      list.push_back(n);
    }
    out["constraints"] = list;
  }
  return out;
}

void write_edit_data(const h5::Group& throng_parameters, const edit::Result& result, bool clip_only, double seam_jump_m) {
  const h5::Group g = throng_parameters.create_group("edit");
  std::vector<std::int64_t> frames(result.sample_frames.begin(), result.sample_frames.end());
  g.write("sample_frames", frames, {frames.size()});
  g.write("left_out", result.report.left_out, {result.report.left_out.size()});
  g.set_attribute("first_frame", static_cast<std::int64_t>(result.first_frame));
  g.set_attribute("last_frame", static_cast<std::int64_t>(result.last_frame));
  g.set_attribute("factorization", result.report.factorization);
  g.set_attribute("clip_only", static_cast<std::int64_t>(clip_only ? 1 : 0));
  g.set_attribute("seam_jump_m", seam_jump_m);
  g.set_attribute("max_output_residual_m", result.report.max_output_residual);
  if (result.report.parts > 0) {  // a local edit: how much of the graph it solved
    g.set_attribute("local_parts", static_cast<std::int64_t>(result.report.parts));
    g.set_attribute("region_parts", static_cast<std::int64_t>(result.report.region_parts));
    g.set_attribute("region_vertices", static_cast<std::int64_t>(result.report.region_vertices));
  }
}

}  // namespace throng
