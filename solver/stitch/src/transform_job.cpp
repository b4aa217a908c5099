// The transform job's runner (jobs.h): a clip placed in space and time.
#include <throng/stitch/jobs.h>

#include <Eigen/Geometry>

#include <numbers>

namespace throng::stitch {
namespace {

Eigen::Vector2d point(const std::vector<double>& xy) { return {xy[0], xy[1]}; }

}  // namespace

TransformOptions resolve(const TransformJob& job, const CrowdMotion& crowd) {
  TransformOptions o;
  o.rotation = job.rotate * std::numbers::pi / 180.0;
  if (job.pivot) o.pivot = point(*job.pivot);
  if (job.translate) o.translation = point(*job.translate);
  o.time_scale = job.time_scale;
  o.time_shift = job.time_shift.value_or(0.0);
  o.frame_rate_hz = job.frame_rate;
  o.id_offset = job.id_offset;
  if (job.species) o.species = static_cast<std::int32_t>(*job.species);
  if (job.place_at) {
    // The centroid rotates about the pivot too; the translation then carries it to place_at.
    const Eigen::Vector2d centroid = first_frame_centroid(crowd);
    const Eigen::Vector2d pivot = o.pivot ? *o.pivot : centroid;
    const Eigen::Vector2d rotated = pivot + Eigen::Rotation2Dd(o.rotation) * (centroid - pivot);
    o.translation = point(*job.place_at) - rotated;
  }
  if (job.start_time && !crowd.times.empty()) o.time_shift = *job.start_time - crowd.times.front();
  return o;
}

TransformRun run(const Crowds& inputs, const TransformJob& job, Progress&, const Communicator&) {
  const Crowd& input = *inputs.at(0);
  TransformRun out;
  out.crowd = input;
  out.applied = resolve(job, input.motion);
  transform(out.crowd.motion, out.crowd.scene, out.applied);
  return out;
}

void describe(ReportWriter& w, const TransformRun& run) {
  const CrowdMotion& m = run.crowd.motion;
  w.count("agents", m.agent_count());
  w.count("frames", m.frame_count());
  w.numbers("times_s", {m.times.empty() ? 0.0 : m.times.front(), m.times.empty() ? 0.0 : m.times.back()});
  w.number("rotation_deg", run.applied.rotation * 180.0 / std::numbers::pi);
  w.numbers("translation_m", {run.applied.translation.x(), run.applied.translation.y()});
  w.number("time_shift_s", run.applied.time_shift);
}

}  // namespace throng::stitch
