#include <throng/core/errors.h>
#include <throng/io/timewarp_job.h>

namespace throng {
namespace {

void bind(OptionBinder& b, timewarp::Options& o) {
  b.field("smoothing_time", o.smoothing_time, Range::non_negative());
  b.field("min_interval_ratio", o.min_interval_ratio, Range{0.0, 1.0, true, false});
  b.field("max_interval_ratio", o.max_interval_ratio, Range{1.0, 1e12, false, false});
  b.field("output_rate", o.output_rate_hz, Range::non_negative());
  b.choice("spline", o.spline_end, {{"not_a_knot", timewarp::SplineEnd::not_a_knot}, {"natural", timewarp::SplineEnd::natural}});
  b.field("time_tolerance", o.time_tolerance_s, Range::non_negative());
}

}  // namespace

TimewarpJob read_timewarp_job(const ConfigNode& job) {
  TimewarpJob t;
  OptionReader reader(job);
  bind(reader, t.options);
  job.finish();
  try {
    timewarp::validate(t.options);
  } catch (const Error& e) {
    job.fail(e.what());
  }
  return t;
}

YAML::Node effective_timewarp_job(const TimewarpJob& job) {
  YAML::Node out(YAML::NodeType::Map);
  timewarp::Options options = job.options;
  OptionWriter writer(out);
  bind(writer, options);
  return out;
}

void write_timewarp_data(const h5::Group& throng_parameters, const timewarp::Result& result) {
  const h5::Group g = throng_parameters.create_group("timewarp");
  const timewarp::Warp& w = result.warp;
  g.write("source_time", w.source_times, {w.source_times.size()});
  g.write("warped_time", w.warped_times, {w.warped_times.size()});
  g.write("inverse_interval", w.inverse_intervals, {w.inverse_intervals.size()});
  std::vector<std::int32_t> bound(w.bound.begin(), w.bound.end());
  g.write("bound", bound, {bound.size()});
  const timewarp::Report& r = result.report;
  g.set_attribute("output_rate", r.output_rate_hz);
  g.set_attribute("speed_deviation_before", r.speed_deviation_before);
  g.set_attribute("speed_deviation_after", r.speed_deviation_after);
  g.set_attribute("reference_speed_rms", r.reference_speed_rms);
  g.set_attribute("clamped_short", static_cast<std::int64_t>(r.clamped_short));
  g.set_attribute("clamped_long", static_cast<std::int64_t>(r.clamped_long));
  g.set_attribute("still_intervals", static_cast<std::int64_t>(r.still_intervals));
}

}  // namespace throng
