// The split job's runner (jobs.h): one part of a crowd, by time, by a range of frames, by agents, or both.
#include <throng/core/errors.h>
#include <throng/stitch/jobs.h>

namespace throng::stitch {

SplitRun split(const Crowd& input, const SplitJob& job, bool other) {
  if (other && (job.by_range() || (job.by_time() && job.by_agents()))) {
    throw ConfigError("a second output needs a split by time or by agents alone: a range (frames, times), or a split "
                      "by time and agents together, has no single other part");
  }
  const CrowdMotion& motion = input.motion;
  if (motion.frame_count() == 0) throw InputError("split: the crowd has no frames");
  SplitRun out;
  out.first_frame = 0;
  out.last_frame = motion.frame_count() - 1;
  std::vector<std::string> names;
  if (job.by_time()) {
    const std::size_t k = job.at_frame ? *job.at_frame : frame_nearest(motion, *job.at_time);
    if (k == 0 || k + 1 >= motion.frame_count()) {
      throw ConfigError("split at frame " + std::to_string(k) + ": expected a frame in [1, " +
                        std::to_string(motion.frame_count() >= 2 ? motion.frame_count() - 2 : 0) +
                        "] so that both parts hold two frames or more (the crowd has " + std::to_string(motion.frame_count()) +
                        " frames)");
    }
    const bool second = (job.keep == Part::second) != other;
    (second ? out.first_frame : out.last_frame) = k;
    names.emplace_back(second ? "second" : "first");
  } else if (job.by_range()) {
    if (job.frames) {
      out.first_frame = static_cast<std::size_t>((*job.frames)[0]);
      out.last_frame = static_cast<std::size_t>((*job.frames)[1]);
    } else {
      out.first_frame = frame_nearest(motion, (*job.times)[0]);
      out.last_frame = frame_nearest(motion, (*job.times)[1]);
    }
    names.emplace_back("range");
  }
  CrowdMotion crowd = motion;
  if (job.by_agents()) {
    AgentSelection selection;
    selection.ids = job.agents.value_or(std::vector<std::int64_t>{});
    for (std::int64_t s : job.species.value_or(std::vector<std::int64_t>{})) selection.species.push_back(static_cast<std::int32_t>(s));
    const bool rest = (job.keep_agents == AgentPart::rest) != (other && !job.by_time());
    crowd = take_agents(motion, select_agents(motion, selection, rest));
    names.emplace_back(rest ? "rest" : "selected");
  }
  if (job.by_time() || job.by_range() || job.present_throughout) {
    out.crowd.motion = slice_frames(crowd, out.first_frame, out.last_frame, job.present_throughout);
  } else {
    out.crowd.motion = std::move(crowd);
  }
  out.crowd.scene = input.scene;
  for (const std::string& n : names) out.part += (out.part.empty() ? "" : "+") + n;
  return out;
}

SplitRun run(const Crowds& inputs, const SplitJob& job, Progress&, const Communicator&) { return split(*inputs.at(0), job); }

void describe(ReportWriter& w, const SplitRun& run) {
  const CrowdMotion& m = run.crowd.motion;
  w.text("part", run.part);
  w.count("agents", m.agent_count());
  w.count("frames", m.frame_count());
  w.counts("input_frames", {run.first_frame, run.last_frame});
  w.numbers("times_s", {m.times.empty() ? 0.0 : m.times.front(), m.times.empty() ? 0.0 : m.times.back()});
}

}  // namespace throng::stitch
