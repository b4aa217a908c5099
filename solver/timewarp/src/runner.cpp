#include <throng/timewarp/runner.h>
#include <throng/timewarp/schema.h>

namespace throng::timewarp {

void describe(OptionBinder& b, Job& job) { describe(b, job.options); }

Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator&) {
  const Crowd& deformed = *inputs.at(0);
  const Crowd& reference = *inputs.at(1);
  progress.update(0.0, "timewarp");
  Result result = time_warp(deformed.motion, reference.motion, job.options);
  progress.update(1.0, "timewarp: done");
  Run out;
  out.crowd.motion = std::move(result.crowd);
  out.crowd.scene = deformed.scene;
  out.warp = std::move(result.warp);
  out.report = result.report;
  const Report& r = out.report;
  if (r.clamped_short + r.clamped_long > 0) {
    out.warnings.push_back("the clamp acts on " + std::to_string(r.clamped_short + r.clamped_long) + " of " +
                           std::to_string(r.frames_in > 0 ? r.frames_in - 1 : 0) + " frame intervals (" +
                           std::to_string(r.clamped_short) + " held at min_interval_ratio, " +
                           std::to_string(r.clamped_long) + " at max_interval_ratio)");
  }
  return out;
}

void describe(ReportWriter& w, const Run& run) {
  const Report& r = run.report;
  w.count("agents", r.agents);
  w.count("frames_in", r.frames_in);
  w.count("frames", r.frames_out);
  w.number("duration_in_s", r.duration_in_s);
  w.number("duration_s", r.duration_out_s);
  w.number("warped_duration_s", r.warped_duration_s);
  w.number("output_rate", r.output_rate_hz);
  w.number("speed_deviation_before_mps", r.speed_deviation_before);
  w.number("speed_deviation_after_mps", r.speed_deviation_after);
  w.number("reference_speed_rms_mps", r.reference_speed_rms);
  w.count("clamped_short", r.clamped_short);
  w.count("clamped_long", r.clamped_long);
  w.count("still_intervals", r.still_intervals);
}

}  // namespace throng::timewarp
