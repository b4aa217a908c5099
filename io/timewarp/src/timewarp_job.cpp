#include <throng/io/timewarp_job.h>

namespace throng::timewarp {

void write_data(const h5::Group& g, const Run& run) {
  const Warp& w = run.warp;
  g.write("source_time", w.source_times, {w.source_times.size()});
  g.write("warped_time", w.warped_times, {w.warped_times.size()});
  g.write("inverse_interval", w.inverse_intervals, {w.inverse_intervals.size()});
  const std::vector<std::int32_t> bound(w.bound.begin(), w.bound.end());
  g.write("bound", bound, {bound.size()});
}

}  // namespace throng::timewarp
