#include <throng/core/errors.h>
#include <throng/io/command_job.h>
#include <throng/io/split_job.h>

#include <cmath>

namespace throng {
namespace {

std::size_t frame_index(const ConfigNode& node) {
  const std::int64_t v = node.as_int();
  if (v < 0) node.fail("frame " + std::to_string(v) + " is negative: frames are indices into the input, from 0");
  return static_cast<std::size_t>(v);
}

}  // namespace

SplitJob read_split_job(const ConfigNode& job) {
  SplitJob s;
  if (auto f = job.find("at_frame")) s.at_frame = frame_index(*f);
  if (auto t = job.find("at_time")) s.at_time = t->as_double();
  if (auto f = job.find("frames")) {
    const std::vector<ConfigNode> ends = f->elements();
    if (ends.size() != 2) f->fail("expected [first, last], found " + std::to_string(ends.size()) + " values");
    s.frames = std::array<std::size_t, 2>{frame_index(ends[0]), frame_index(ends[1])};
    if ((*s.frames)[0] >= (*s.frames)[1]) f->fail("the first frame must come before the last");
  }
  if (auto t = job.find("times")) {
    const std::vector<double> v = t->as_doubles({2});
    if (!(v[0] < v[1])) t->fail("the first time must come before the last");
    s.times = std::array<double, 2>{v[0], v[1]};
  }
  if (auto k = job.find("keep")) {
    const std::string v = k->as_string();
    if (v != "first" && v != "second") k->fail("unknown value '" + v + "', expected one of: first, second");
    if (!s.by_time()) k->fail("keep chooses a part of a split at at_frame or at_time, and there is none");
    s.keep_second = v == "second";
  }
  const auto ids = job.find("agents");
  const auto species = job.find("species");
  if (ids || species) {
    stitch::AgentSelection selection;
    if (ids) {
      for (const ConfigNode& e : ids->elements()) selection.ids.push_back(e.as_int());
      if (selection.ids.empty()) ids->fail("an empty agent list selects nobody: leave the key out, or list ids");
    }
    if (species) {
      for (const ConfigNode& e : species->elements()) selection.species.push_back(static_cast<std::int32_t>(e.as_int()));
      if (selection.species.empty()) species->fail("an empty species list selects nobody: leave the key out, or list species");
    }
    s.agents = selection;
  }
  if (auto k = job.find("keep_agents")) {
    const std::string v = k->as_string();
    if (v != "selected" && v != "rest") k->fail("unknown value '" + v + "', expected one of: selected, rest");
    if (!s.agents) k->fail("keep_agents chooses a part of a split by agents, and there is no agents or species key");
    s.keep_rest = v == "rest";
  }
  if (auto p = job.find("present_throughout")) s.present_throughout = p->as_bool();
  if (s.at_frame && s.at_time) job.fail("give at_frame or at_time, not both");
  if (s.frames && s.times) job.fail("give frames or times, not both");
  if (s.by_time() && s.by_range()) job.fail("give a split point (at_frame, at_time) or a range (frames, times), not both");
  if (!s.by_time() && !s.by_range() && !s.agents) {
    job.fail("nothing to split by: give at_frame, at_time, frames, times, agents or species");
  }
  job.finish();
  return s;
}

YAML::Node effective_split_job(const SplitJob& s) {
  YAML::Node out(YAML::NodeType::Map);
  if (s.at_frame) out["at_frame"] = static_cast<std::uint64_t>(*s.at_frame);
  if (s.at_time) out["at_time"] = yaml_number(*s.at_time);
  if (s.frames) out["frames"] = flow_integers({static_cast<std::int64_t>((*s.frames)[0]), static_cast<std::int64_t>((*s.frames)[1])});
  if (s.times) out["times"] = flow_numbers({(*s.times)[0], (*s.times)[1]});
  if (s.by_time()) out["keep"] = s.keep_second ? "second" : "first";
  if (s.agents) {
    if (!s.agents->ids.empty()) out["agents"] = flow_integers(s.agents->ids);
    if (!s.agents->species.empty()) out["species"] = flow_integers(std::vector<std::int64_t>(s.agents->species.begin(), s.agents->species.end()));
    out["keep_agents"] = s.keep_rest ? "rest" : "selected";
  }
  out["present_throughout"] = s.present_throughout;
  return out;
}

SplitPart split_crowd(const CrowdMotion& input, const SplitJob& job, bool other) {
  if (other && (job.by_range() || (job.by_time() && job.agents))) {
    throw ConfigError("a second output needs a split by time or by agents alone: a range (frames, times), or a split "
                      "by time and agents together, has no single other part");
  }
  if (input.frame_count() == 0) throw InputError("split: the crowd has no frames");
  SplitPart part;
  part.first_frame = 0;
  part.last_frame = input.frame_count() - 1;
  std::vector<std::string> names;
  if (job.by_time()) {
    const std::size_t k = job.at_frame ? *job.at_frame : stitch::frame_nearest(input, *job.at_time);
    if (k == 0 || k + 1 >= input.frame_count()) {
      throw ConfigError("split at frame " + std::to_string(k) + ": expected a frame in [1, " +
                        std::to_string(input.frame_count() >= 2 ? input.frame_count() - 2 : 0) +
                        "] so that both parts hold two frames or more (the crowd has " + std::to_string(input.frame_count()) + " frames)");
    }
    const bool second = job.keep_second != other;
    (second ? part.first_frame : part.last_frame) = k;
    names.emplace_back(second ? "second" : "first");
  } else if (job.by_range()) {
    if (job.frames) {
      part.first_frame = (*job.frames)[0];
      part.last_frame = (*job.frames)[1];
    } else {
      part.first_frame = stitch::frame_nearest(input, (*job.times)[0]);
      part.last_frame = stitch::frame_nearest(input, (*job.times)[1]);
    }
    names.emplace_back("range");
  }
  CrowdMotion crowd = input;
  if (job.agents) {
    const bool rest = job.keep_rest != (other && !job.by_time());
    crowd = stitch::take_agents(input, stitch::select_agents(input, *job.agents, rest));
    names.emplace_back(rest ? "rest" : "selected");
  }
  if (job.by_time() || job.by_range() || job.present_throughout) {
    part.crowd = stitch::slice_frames(crowd, part.first_frame, part.last_frame, job.present_throughout);
  } else {
    part.crowd = std::move(crowd);
  }
  for (const std::string& n : names) part.part += (part.part.empty() ? "" : "+") + n;
  return part;
}

void write_split_data(const h5::Group& throng_parameters, const SplitPart& part) {
  const h5::Group g = throng_parameters.create_group("split");
  g.set_attribute("first_frame", static_cast<std::int64_t>(part.first_frame));
  g.set_attribute("last_frame", static_cast<std::int64_t>(part.last_frame));
  g.set_attribute("part", part.part);
  g.write("ids", part.crowd.ids, {part.crowd.ids.size()});
}

}  // namespace throng
