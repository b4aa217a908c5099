#include <throng/io/collide_job.h>
#include <throng/io/scene_config.h>

namespace throng::collide {

void read_job(const ConfigNode& job, Job& out) {
  if (!job.is_null() && !job.is_map()) job.fail("a collide job is a mapping of options");
  if (job.is_null()) return;
  read_options(job, describe, out);
  out.scene = read_scene(job);
  // Distances are not wrapped across periodic boundaries: a periodic region would be repaired wrongly near
  // its edges, so it is refused rather than ignored.
  if (out.scene.region) {
    const auto& periodic = out.scene.region->periodic;
    if (periodic[0] || periodic[1] || periodic[2]) {
      job.at("region").fail("collide does not support periodic regions (pairs across a periodic boundary would "
                            "not be seen); give periodic: [false, false, false] or leave the region out");
    }
  }
  job.finish();
}

void write_data(const h5::Group& record, const Run& run) {
  const std::vector<std::int64_t> history(run.report.history.begin(), run.report.history.end());
  record.write("history", history, {history.size()});
}

}  // namespace throng::collide
