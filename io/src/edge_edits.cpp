#include <throng/io/edge_edits.h>

#include <cstdint>
#include <limits>
#include <vector>

namespace throng {
namespace {

constexpr std::size_t to_end = std::numeric_limits<std::size_t>::max();  // EdgeEdit's "to the end"

std::size_t frame(const ConfigNode& node, bool end_allowed, const std::string& frames_of) {
  if (end_allowed && node.is_scalar() && node.as_string() == "end") return to_end;
  const std::int64_t v = node.as_int();
  if (v < 0) node.fail("frame " + std::to_string(v) + " is negative: frames are indices into " + frames_of + ", from 0");
  return static_cast<std::size_t>(v);
}

YAML::Node flow_sequence() {
  YAML::Node n(YAML::NodeType::Sequence);
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

}  // namespace

void read_edge_edits(const ConfigNode& job, FormationOptions& o, const std::string& frames_of) {
  const auto formation = job.find("formation");
  if (!formation) return;
  const auto edits = formation->find("edits");
  if (!edits) return;
  for (const ConfigNode& e : edits->elements()) {
    const auto add = e.find("add");
    const auto remove = e.find("remove");
    if (static_cast<bool>(add) == static_cast<bool>(remove)) e.fail("give exactly one of add: [a, b] or remove: [a, b]");
    const ConfigNode& pair = add ? *add : *remove;
    std::vector<std::int64_t> agents;
    for (const ConfigNode& id : pair.elements()) agents.push_back(id.as_int());
    if (agents.size() != 2) pair.fail("expected two agent ids, found " + std::to_string(agents.size()));
    if (agents[0] == agents[1]) pair.fail("an edge needs two different agents, got " + std::to_string(agents[0]) + " twice");
    EdgeEdit edit{agents[0], agents[1], 0, to_end, static_cast<bool>(add)};
    if (const auto frames = e.find("frames")) {
      const std::vector<ConfigNode> ends = frames->elements();
      if (ends.size() != 2) frames->fail("expected [first, last] (last may be 'end'), found " + std::to_string(ends.size()) + " values");
      edit.first_frame = frame(ends[0], false, frames_of);
      edit.last_frame = frame(ends[1], true, frames_of);
      if (edit.first_frame > edit.last_frame) {
        frames->fail("first frame " + std::to_string(edit.first_frame) + " is after the last " + std::to_string(edit.last_frame));
      }
    }
    o.edits.push_back(edit);
  }
}

void write_edge_edits(YAML::Node& job, const FormationOptions& o) {
  if (o.edits.empty()) return;
  YAML::Node edits(YAML::NodeType::Sequence);
  for (const EdgeEdit& e : o.edits) {
    YAML::Node pair = flow_sequence();
    pair.push_back(e.agent_a);
    pair.push_back(e.agent_b);
    YAML::Node frames = flow_sequence();
    frames.push_back(static_cast<std::uint64_t>(e.first_frame));
    if (e.last_frame == to_end) {
      frames.push_back("end");
    } else {
      frames.push_back(static_cast<std::uint64_t>(e.last_frame));
    }
    YAML::Node n;
    n[e.add ? "add" : "remove"] = pair;
    n["frames"] = frames;
    edits.push_back(n);
  }
  job["formation"]["edits"] = edits;
}

}  // namespace throng
