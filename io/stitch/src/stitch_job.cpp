#include <throng/io/edge_edits.h>
#include <throng/io/stitch_job.h>
#include <throng/stitch/schema.h>

namespace throng::stitch {

void read_job(const ConfigNode& node, StitchJob& job) {
  read_options(node, describe, job);
  read_edge_edits(node, job.options.formation, "the stitched output");
  node.finish();
}

void write_data(const h5::Group& record, const StitchRun& run) {
  for (std::size_t k = 0; k < run.joints.size(); ++k) {
    const h5::Group j = record.create_group("joint_" + std::to_string(k + 1));
    // The joint's agents are the clip-so-far's, with its ids (a later joint may leave some out).
    j.write("first_ids", run.joint_ids[k], {run.joint_ids[k].size()});
    j.write("second_ids", run.joints[k].second_ids, {run.joints[k].second_ids.size()});
  }
}

}  // namespace throng::stitch
