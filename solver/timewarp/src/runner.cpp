#include <throng/core/facing_carry.h>
#include <throng/timewarp/runner.h>
#include <throng/timewarp/schema.h>

#include <algorithm>
#include <cstdint>
#include <unordered_map>

namespace throng::timewarp {

void describe(OptionBinder& b, Job& job) {
  describe(b, job.options);
  b.section("guard", [&](OptionBinder& g) { describe(g, job.guard); });
}

namespace {

// The guard's source: the reference's fastest speed, and per output agent the reference agent's (same id) largest
// acceleration at every frame (the warp moved the frames, so a per-frame match by time does not exist).
Source warp_source(const CrowdMotion& output, const CrowdMotion& reference) {
  Source source;
  source.max_speed = fastest_speed(reference);
  const std::vector<double> a = accelerations(reference);
  std::unordered_map<std::int64_t, double> largest;
  for (std::size_t n = 0; n < reference.agent_count(); ++n) {
    double m = 0;
    for (std::size_t f = 0; f < reference.frame_count(); ++f) m = std::max(m, a[f * reference.agent_count() + n]);
    largest[reference.ids[n]] = m;
  }
  const std::size_t T = output.frame_count(), N = output.agent_count();
  source.acceleration.assign(T * N, 0.0);
  for (std::size_t n = 0; n < N; ++n) {
    const auto it = largest.find(output.ids[n]);
    if (it == largest.end()) continue;
    for (std::size_t f = 0; f < T; ++f) source.acceleration[f * N + n] = it->second;
  }
  return source;
}

}  // namespace

Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator&) {
  const Crowd& deformed = *inputs.at(0);
  const Crowd& reference = *inputs.at(1);
  progress.update(0.0, "timewarp");
  Result result = time_warp(deformed.motion, reference.motion, job.options);
  progress.update(0.9, "timewarp: guard");
  GuardResult guarded = guard(result.crowd, warp_source(result.crowd, reference.motion), job.guard);
  progress.update(1.0, "timewarp: done");
  Run out;
  out.crowd.motion = std::move(guarded.crowd);
  // Where the warp shortened intervals, carried facings turn faster in the new time: no faster than a person.
  limit_facing_rate(out.crowd.motion, carried_max_turn_rate);
  out.guard = guarded.report;
  out.crowd.scene = deformed.scene;
  out.warp = std::move(result.warp);
  out.report = result.report;
  if (guarded.report.warped) {
    // The stored warp and the report are what was written: the guard's slow-down composed after Eq. 12's.
    for (double& t : out.warp.warped_times) t = guarded.warp.map(t);
    for (std::size_t i = 0; i + 1 < out.warp.warped_times.size(); ++i)
      out.warp.inverse_intervals[i] = 1.0 / (out.warp.warped_times[i + 1] - out.warp.warped_times[i]);
    out.report.warped_duration_s = out.warp.warped_times.back() - out.warp.warped_times.front();
  }
  const CrowdMotion& written = out.crowd.motion;
  out.report.frames_out = written.frame_count();
  out.report.duration_out_s = written.frame_count() ? written.times.back() - written.times.front() : 0.0;
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
  // The plausibility guard after the warp (guard.h), as stitch reports it.
  describe(w, run.guard);
}

}  // namespace throng::timewarp
