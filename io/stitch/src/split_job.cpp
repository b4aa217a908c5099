#include <throng/io/split_job.h>
#include <throng/stitch/schema.h>

namespace throng::stitch {

void read_job(const ConfigNode& job, SplitJob& s) {
  read_options(job, describe, s);
  // What the schema cannot say: how the keys go together.
  const auto at = [&](const char* key) { return job.at(key); };
  if (s.frames && (*s.frames)[0] >= (*s.frames)[1]) at("frames").fail("the first frame must come before the last");
  if (s.times && !((*s.times)[0] < (*s.times)[1])) at("times").fail("the first time must come before the last");
  if (s.keep && !s.by_time()) at("keep").fail("keep chooses a part of a split at at_frame or at_time, and there is none");
  if (s.agents && s.agents->empty()) at("agents").fail("an empty agent list selects nobody: leave the key out, or list ids");
  if (s.species && s.species->empty()) {
    at("species").fail("an empty species list selects nobody: leave the key out, or list species");
  }
  if (s.keep_agents && !s.by_agents()) {
    at("keep_agents").fail("keep_agents chooses a part of a split by agents, and there is no agents or species key");
  }
  if (s.at_frame && s.at_time) job.fail("give at_frame or at_time, not both");
  if (s.frames && s.times) job.fail("give frames or times, not both");
  if (s.by_time() && s.by_range()) job.fail("give a split point (at_frame, at_time) or a range (frames, times), not both");
  if (!s.by_time() && !s.by_range() && !s.by_agents()) {
    job.fail("nothing to split by: give at_frame, at_time, frames, times, agents or species");
  }
  job.finish();
}

void write_data(const h5::Group& record, const SplitRun& part) {
  record.write("ids", part.crowd.motion.ids, {part.crowd.motion.ids.size()});
}

}  // namespace throng::stitch
