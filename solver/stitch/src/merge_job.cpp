// The merge job's runner (jobs.h): two or more crowds in one, in order.
#include <throng/core/errors.h>
#include <throng/stitch/jobs.h>
#include <throng/stitch/schema.h>

namespace throng::stitch {

void describe(OptionBinder& b, MergeJob& job) { describe(b, job.options); }

MergeRun run(const Crowds& inputs, const MergeJob& job, Progress& progress, const Communicator&) {
  if (inputs.size() < 2) throw ConfigError("merge needs at least two crowds, got " + std::to_string(inputs.size()));
  progress.update(0.0, "merge");
  MergeRun m;
  m.inputs = inputs.size();
  m.crowd.motion = inputs[0]->motion;
  m.crowd.scene = inputs[0]->scene;
  m.group.assign(inputs[0]->motion.agent_count(), 0);
  m.id_shifts.push_back(0);
  for (std::size_t k = 1; k < inputs.size(); ++k) {
    Merged merged;
    try {
      merged = merge(m.crowd.motion, m.crowd.scene, inputs[k]->motion, inputs[k]->scene, job.options);
    } catch (const InputError& e) {
      throw InputError("merging input " + std::to_string(k + 1) + " into inputs 1.." + std::to_string(k) + ": " + e.what());
    }
    std::vector<std::int32_t> group;
    for (std::size_t j : merged.first_agents) group.push_back(m.group[j]);
    group.resize(merged.crowd.agent_count(), static_cast<std::int32_t>(k));
    m.group = std::move(group);
    m.id_shifts.push_back(merged.report.id_shift);
    const MergeReport& r = merged.report;
    if (r.left_out_first + r.left_out_second > 0) {
      m.warnings.push_back("input " + std::to_string(k + 1) + ": " + std::to_string(r.left_out_first + r.left_out_second) +
                           " agent(s) present at no merged frame were left out");
    }
    m.reports.push_back(r);
    m.crowd.motion = std::move(merged.crowd);
    m.crowd.formation_edges = std::move(merged.formation_edges);
    m.crowd.scene = std::move(merged.scene);
  }
  m.crowd.scene = merge_scenes(m.crowd.scene, job.scene);
  std::size_t interpolated = 0;
  for (const MergeReport& r : m.reports) interpolated += r.interpolated_frames_first + r.interpolated_frames_second;
  if (interpolated > 0) {
    m.notes.push_back("the crowds' frame times differ; " + std::to_string(interpolated) +
                      " crowd-frames were interpolated (cubic splines)");
  }
  progress.update(1.0, "merge: done");
  return m;
}

void describe(ReportWriter& w, const MergeRun& run) {
  const CrowdMotion& m = run.crowd.motion;
  std::vector<std::size_t> cross, left_out, joined;
  std::size_t shared_obstacles = 0;
  std::size_t interpolated = 0;
  bool dropped = false;
  for (const MergeReport& r : run.reports) {
    cross.push_back(r.cross_edges);
    left_out.push_back(r.left_out_first + r.left_out_second);
    joined.push_back(r.joined);
    shared_obstacles += r.shared_obstacles;
    interpolated += r.interpolated_frames_first + r.interpolated_frames_second;
    dropped = dropped || r.velocities_dropped;
  }
  w.count("inputs", run.inputs);
  w.count("agents", m.agent_count());
  w.count("frames", m.frame_count());
  w.numbers("times_s", {m.times.empty() ? 0.0 : m.times.front(), m.times.empty() ? 0.0 : m.times.back()});
  w.integers("id_shifts", run.id_shifts);
  w.counts("cross_edges", cross);
  w.count("interpolated_frames", interpolated);
  w.counts("left_out", left_out);
  w.flag("velocities_dropped", dropped);
  w.count("obstacles", run.crowd.scene.obstacles.size());
  w.count("shared_obstacles", shared_obstacles);
  w.counts("joined", joined);
}

}  // namespace throng::stitch
