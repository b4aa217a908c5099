#include <throng/io/merge_job.h>

namespace throng::stitch {

void write_data(const h5::Group& record, const MergeRun& run) {
  record.write("group", run.group, {run.group.size()});
  std::vector<std::int64_t> interpolated;
  for (const auto& r : run.reports) {
    interpolated.push_back(static_cast<std::int64_t>(r.interpolated_frames_first));
    interpolated.push_back(static_cast<std::int64_t>(r.interpolated_frames_second));
  }
  record.write("interpolated_frames_by_merge", interpolated, {run.reports.size(), 2});
}

}  // namespace throng::stitch
