#include <throng/core/errors.h>
#include <throng/edit/schema.h>
#include <throng/io/edge_edits.h>
#include <throng/io/edit_job.h>

#include <limits>
#include <sstream>
#include <string>
#include <variant>

namespace throng {
namespace {

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

YAML::Node flow(const Eigen::Vector2d& p) { return yaml_numbers({p.x(), p.y()}); }

YAML::Node request_frames_yaml(edit::Frame first, edit::Frame last) { return yaml_integers({first, last}); }

// One request entry as the job writes it (read_handles and read_constraints read it back).
YAML::Node entry(const edit::Pin& p) {
  YAML::Node n;
  n["agent"] = p.agent;
  n["frame"] = p.frame;
  if (p.position) n["position"] = flow(*p.position);
  return n;
}

YAML::Node entry(const edit::Drag& d) {
  YAML::Node n;
  if (!d.selection.agents.empty()) n["agents"] = yaml_integers(d.selection.agents);
  n["frames"] = request_frames_yaml(d.selection.first_frame, d.selection.last_frame);
  n["offset"] = flow(d.offset);
  n["rotation"] = yaml_number(d.rotation);
  if (d.pivot) n["pivot"] = flow(*d.pivot);
  return n;
}

YAML::Node entry(const edit::RelativePosition& v) {
  YAML::Node n;
  n["agent"] = v.agent;
  n["type"] = "relative_position";
  n["other"] = v.other;
  n["frames"] = request_frames_yaml(v.first_frame, v.last_frame);
  if (v.offset) n["offset"] = flow(*v.offset);
  return n;
}

YAML::Node entry(const edit::Velocity& v) {
  YAML::Node n;
  n["agent"] = v.agent;
  n["type"] = "velocity";
  n["frame"] = v.frame;
  n["velocity"] = flow(v.velocity);
  return n;
}

YAML::Node entry(const edit::OnLine& v) {
  YAML::Node n;
  n["agent"] = v.agent;
  n["type"] = "on_line";
  n["frames"] = request_frames_yaml(v.first_frame, v.last_frame);
  n["point"] = flow(v.point);
  n["direction"] = flow(v.direction);
  return n;
}

YAML::Node entry(const edit::Constraint& c) {
  return std::visit([](const auto& v) { return entry(v); }, c);
}

// `key: [entries]`, left out when there are none.
template <class T>
void write_list(YAML::Node& out, const char* key, const std::vector<T>& items) {
  if (items.empty()) return;
  YAML::Node list(YAML::NodeType::Sequence);
  for (const T& item : items) list.push_back(entry(item));
  out[key] = list;
}

// The clip's cross-field rules (the schema reads the values): a range that ends after it starts, and agents that
// select somebody.
void check_clip(const ConfigNode& job, const ClipOptions& clip) {
  const auto node = job.find("clip");
  if (!node) return;
  if (clip.last_frame != std::numeric_limits<std::size_t>::max() && clip.last_frame <= clip.first_frame) {
    node->fail("last_frame " + std::to_string(clip.last_frame) + " must be after first_frame " + std::to_string(clip.first_frame));
  }
  if (const auto agents = node->find("agents"); agents && clip.agents.empty()) {
    agents->fail("an empty agent list selects nobody: leave agents out to take every agent");
  }
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

}  // namespace throng

namespace throng::edit {

void read_job(const ConfigNode& job, Job& parsed) {
  read_options(job, describe, parsed);
  check_clip(job, parsed.options.clip);
  read_edge_edits(job, parsed.options.formation, "the input");
  read_handles(job, parsed.request);
  read_constraints(job, parsed.request);
  job.finish();
}

YAML::Node effective_job(const Job& job) {
  YAML::Node out(YAML::NodeType::Map);  // a map already, so the writer's copy of the handle shares it
  write_options(out, describe, job);
  write_edge_edits(out, job.options.formation);
  write_list(out, "pins", job.request.pins);
  write_list(out, "drags", job.request.drags);
  write_list(out, "constraints", job.request.constraints);
  return out;
}

void write_data(const h5::Group& g, const Run& run) {
  const std::vector<std::int64_t> frames(run.result.sample_frames.begin(), run.result.sample_frames.end());
  g.write("sample_frames", frames, {frames.size()});
  g.write("left_out_ids", run.result.report.left_out, {run.result.report.left_out.size()});
}

}  // namespace throng::edit
