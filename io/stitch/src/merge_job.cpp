#include <throng/core/errors.h>
#include <throng/io/merge_job.h>
#include <throng/io/scene_config.h>

#include <algorithm>

namespace throng {
namespace {

void bind(OptionBinder& b, stitch::MergeOptions& o) {
  b.choice("span", o.span, {{"overlap", stitch::MergeSpan::overlap}, {"union", stitch::MergeSpan::union_of_spans}});
  b.choice("on_id_clash", o.on_id_clash, {{"shift", stitch::IdClash::shift}, {"error", stitch::IdClash::error}});
  b.field("time_tolerance", o.time_tolerance_s, Range::non_negative());
  b.field("max_edge_length", o.max_edge_length, Range::non_negative());
}

}  // namespace

MergeJob read_merge_job(const ConfigNode& job) {
  MergeJob m;
  OptionReader reader(job);
  bind(reader, m.options);
  m.scene = read_scene(job);
  job.finish();
  return m;
}

YAML::Node effective_merge_job(const MergeJob& job) {
  YAML::Node out(YAML::NodeType::Map);
  stitch::MergeOptions options = job.options;
  OptionWriter writer(out);
  bind(writer, options);
  write_scene(out, job.scene);
  return out;
}

MergedCrowds merge_crowds(const std::vector<const CrowdFile*>& inputs, const MergeJob& job) {
  if (inputs.size() < 2) throw ConfigError("merge needs at least two crowds, got " + std::to_string(inputs.size()));
  MergedCrowds m;
  m.crowd.motion = inputs[0]->motion;
  m.crowd.scene = inputs[0]->scene;
  m.crowd.provenance.credits = inputs[0]->provenance.credits;
  m.group.assign(inputs[0]->motion.agent_count(), 0);
  m.id_shifts.push_back(0);
  for (std::size_t k = 1; k < inputs.size(); ++k) {
    stitch::Merged merged;
    try {
      merged = stitch::merge(m.crowd.motion, m.crowd.scene, inputs[k]->motion, inputs[k]->scene, job.options);
    } catch (const InputError& e) {
      throw InputError("merging input " + std::to_string(k + 1) + " into inputs 1.." + std::to_string(k) + ": " + e.what());
    }
    std::vector<std::int32_t> group;
    for (std::size_t j : merged.first_agents) group.push_back(m.group[j]);
    group.resize(merged.crowd.agent_count(), static_cast<std::int32_t>(k));
    m.group = std::move(group);
    m.id_shifts.push_back(merged.report.id_shift);
    m.reports.push_back(merged.report);
    m.crowd.motion = std::move(merged.crowd);
    m.crowd.formation_edges = std::move(merged.formation_edges);
    for (const std::string& c : inputs[k]->provenance.credits) {
      if (std::find(m.crowd.provenance.credits.begin(), m.crowd.provenance.credits.end(), c) == m.crowd.provenance.credits.end()) {
        m.crowd.provenance.credits.push_back(c);
      }
    }
    m.crowd.scene = std::move(merged.scene);
  }
  m.crowd.scene = stitch::merge_scenes(m.crowd.scene, job.scene);
  return m;
}

void write_merge_data(const h5::Group& throng_parameters, const MergedCrowds& merged) {
  const h5::Group g = throng_parameters.create_group("merge");
  g.write("group", merged.group, {merged.group.size()});
  g.write("id_shift", merged.id_shifts, {merged.id_shifts.size()});
  std::vector<std::int64_t> cross, interpolated;
  for (const auto& r : merged.reports) {
    cross.push_back(static_cast<std::int64_t>(r.cross_edges));
    interpolated.push_back(static_cast<std::int64_t>(r.interpolated_frames_first));
    interpolated.push_back(static_cast<std::int64_t>(r.interpolated_frames_second));
  }
  g.write("cross_edges", cross, {cross.size()});
  g.write("interpolated_frames", interpolated, {merged.reports.size(), 2});
}

}  // namespace throng
