#include <throng/io/transform_job.h>
#include <throng/stitch/schema.h>

namespace throng::stitch {

void read_job(const ConfigNode& job, TransformJob& t) {
  read_options(job, describe, t);
  if (t.translate && t.place_at) job.fail("give translate or place_at, not both");
  if (t.time_shift && t.start_time) job.fail("give time_shift or start_time, not both");
  job.finish();
}

}  // namespace throng::stitch
