#include <throng/core/errors.h>
#include <throng/edit/schema.h>
#include <throng/io/edge_edits.h>
#include <throng/io/edit_job.h>

#include <algorithm>
#include <cstdint>
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

YAML::Node entry(const edit::Acceleration& v) {
  YAML::Node n;
  n["agent"] = v.agent;
  n["type"] = "acceleration";
  n["frame"] = v.frame;
  n["acceleration"] = flow(v.acceleration);
  return n;
}

YAML::Node entry(const edit::Sum& v) {
  YAML::Node n;
  n["type"] = "sum";
  n["agents"] = yaml_integers(v.agents);
  if (!v.weights.empty()) n["weights"] = yaml_numbers(v.weights);
  n["frames"] = request_frames_yaml(v.first_frame, v.last_frame);
  if (v.value) n["value"] = flow(*v.value);
  return n;
}

YAML::Node entry(const edit::Row& v) {
  YAML::Node n;
  n["type"] = "row";
  YAML::Node terms(YAML::NodeType::Sequence);
  for (const edit::RowTerm& t : v.terms) {
    YAML::Node term;
    term.SetStyle(YAML::EmitterStyle::Flow);
    term["agent"] = t.agent;
    term["frame"] = t.frame;
    term["axis"] = t.axis == 0 ? "x" : "y";
    term["coefficient"] = yaml_number(t.coefficient);
    terms.push_back(term);
  }
  n["terms"] = terms;
  n["value"] = yaml_number(v.value);
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

// {type: sum, agents: [...], weights: [...], frames: [a, b], value: [x, y]}: distinct agents, one weight each
// (or none: 1/n), not all zero.
edit::Sum read_sum(const ConfigNode& c) {
  edit::Sum sum;
  const ConfigNode agents = c.at("agents");
  sum.agents = ids(agents);
  if (sum.agents.empty()) agents.fail("a sum needs at least one agent");
  for (std::size_t i = 0; i < sum.agents.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (sum.agents[i] == sum.agents[j]) agents.fail("agent " + std::to_string(sum.agents[i]) + " is named twice");
    }
  }
  if (auto w = c.find("weights")) {
    sum.weights = w->as_doubles();
    if (sum.weights.size() != sum.agents.size()) {
      w->fail(std::to_string(sum.weights.size()) + " weights for " + std::to_string(sum.agents.size()) +
              " agents (give one per agent, or leave weights out for 1/n each)");
    }
    if (std::all_of(sum.weights.begin(), sum.weights.end(), [](double x) { return x == 0.0; })) {
      w->fail("every weight is 0, so the row says nothing");
    }
  }
  std::tie(sum.first_frame, sum.last_frame) = request_range(c);
  if (auto v = c.find("value")) sum.value = point(*v);
  return sum;
}

// {type: row, terms: [{agent, frame, axis: x|y, coefficient}], value}: terms distinct in (agent, frame, axis) as
// written (the editor checks again once negative frames are resolved), coefficients not all zero.
edit::Row read_row(const ConfigNode& c) {
  edit::Row row;
  const ConfigNode terms = c.at("terms");
  const std::vector<ConfigNode> list = terms.elements();
  if (list.empty()) terms.fail("a row needs at least one term");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const ConfigNode& t = list[i];
    edit::RowTerm term;
    term.agent = t.at("agent").as_int();
    term.frame = request_frame(t.at("frame"));
    const ConfigNode axis = t.at("axis");
    const std::string name = axis.as_string();
    if (name != "x" && name != "y") axis.fail("unknown axis '" + name + "': expected x or y");
    term.axis = name == "x" ? 0 : 1;
    if (auto v = t.find("coefficient")) term.coefficient = v->as_double();
    for (std::size_t j = 0; j < row.terms.size(); ++j) {
      const edit::RowTerm& o = row.terms[j];
      if (o.agent == term.agent && o.frame == term.frame && o.axis == term.axis) {
        t.fail("the same coordinate as terms[" + std::to_string(j) + "] (agent " + std::to_string(term.agent) + ", frame " +
               std::to_string(term.frame) + ", " + name + "): add their coefficients into one term");
      }
    }
    row.terms.push_back(term);
  }
  if (std::all_of(row.terms.begin(), row.terms.end(), [](const edit::RowTerm& t) { return t.coefficient == 0.0; })) {
    terms.fail("every coefficient is 0, so the row says nothing");
  }
  row.value = c.at("value").as_double();
  return row;
}

// `formation.splits`: [{agents: [ids of one side], frames: [first, last|end]}] (frames index the input, from 0).
void read_splits(const ConfigNode& job, FormationOptions& o) {
  const auto formation = job.find("formation");
  if (!formation) return;
  const auto splits = formation->find("splits");
  if (!splits) return;
  for (const ConfigNode& e : splits->elements()) {
    FormationSplit split;
    const ConfigNode agents = e.at("agents");
    split.agents = ids(agents);
    if (split.agents.empty()) agents.fail("a split needs the agents of one side");
    for (std::size_t i = 0; i < split.agents.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (split.agents[i] == split.agents[j]) agents.fail("agent " + std::to_string(split.agents[i]) + " is named twice");
      }
    }
    if (const auto frames = e.find("frames")) {
      const std::vector<ConfigNode> ends = frames->elements();
      if (ends.size() != 2) frames->fail("expected [first, last] (last may be 'end'), found " + std::to_string(ends.size()) + " values");
      auto frame = [](const ConfigNode& n, bool end_allowed) -> std::size_t {
        if (end_allowed && n.is_scalar() && n.as_string() == "end") return std::numeric_limits<std::size_t>::max();
        const std::int64_t v = n.as_int();
        if (v < 0) n.fail("frame " + std::to_string(v) + " is negative: frames are indices into the input, from 0");
        return static_cast<std::size_t>(v);
      };
      split.first_frame = frame(ends[0], false);
      split.last_frame = frame(ends[1], true);
      if (split.first_frame > split.last_frame) {
        frames->fail("first frame " + std::to_string(split.first_frame) + " is after the last " + std::to_string(split.last_frame));
      }
    }
    o.splits.push_back(std::move(split));
  }
}

void write_splits(YAML::Node& out, const FormationOptions& o) {
  if (o.splits.empty()) return;
  YAML::Node list(YAML::NodeType::Sequence);
  for (const FormationSplit& split : o.splits) {
    YAML::Node n;
    n["agents"] = yaml_integers(split.agents);
    YAML::Node frames(YAML::NodeType::Sequence);
    frames.SetStyle(YAML::EmitterStyle::Flow);
    frames.push_back(static_cast<std::uint64_t>(split.first_frame));
    if (split.last_frame == std::numeric_limits<std::size_t>::max()) {
      frames.push_back("end");
    } else {
      frames.push_back(static_cast<std::uint64_t>(split.last_frame));
    }
    n["frames"] = frames;
    list.push_back(n);
  }
  out["formation"]["splits"] = list;
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
    } else if (kind == "acceleration") {
      edit::Acceleration a;
      a.agent = c.at("agent").as_int();
      a.frame = request_frame(c.at("frame"));
      if (auto v = c.find("acceleration")) a.acceleration = point(*v);
      r.constraints.emplace_back(a);
    } else if (kind == "sum") {
      r.constraints.emplace_back(read_sum(c));
    } else if (kind == "row") {
      r.constraints.emplace_back(read_row(c));
    } else {
      type.fail("unknown constraint type '" + kind + "': expected relative_position, velocity, on_line, acceleration, sum or row");
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
  read_splits(job, parsed.options.formation);
  read_handles(job, parsed.request);
  read_constraints(job, parsed.request);
  job.finish();
}

YAML::Node effective_job(const Job& job) {
  YAML::Node out(YAML::NodeType::Map);  // a map already, so the writer's copy of the handle shares it
  write_options(out, describe, job);
  write_edge_edits(out, job.options.formation);
  write_splits(out, job.options.formation);
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
