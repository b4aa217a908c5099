#include <throng/core/errors.h>
#include <throng/io/command_job.h>
#include <throng/io/transform_job.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

namespace throng {
namespace {

Eigen::Vector2d point(const ConfigNode& node) {
  const std::vector<double> v = node.as_doubles({2});
  for (double x : v) {
    if (!std::isfinite(x)) node.fail("expected finite coordinates");
  }
  return {v[0], v[1]};
}

double finite(const ConfigNode& node) {
  const double v = node.as_double();
  if (!std::isfinite(v)) node.fail("expected a finite number");
  return v;
}

}  // namespace

TransformJob read_transform_job(const ConfigNode& job) {
  TransformJob t;
  auto& o = t.options;
  if (auto r = job.find("rotate")) {
    t.rotate_degrees = finite(*r);
    o.rotation = t.rotate_degrees * std::numbers::pi / 180.0;
  }
  if (auto p = job.find("pivot")) o.pivot = point(*p);
  const auto translate = job.find("translate");
  const auto place_at = job.find("place_at");
  if (translate && place_at) job.fail("give translate or place_at, not both");
  if (translate) o.translation = point(*translate);
  if (place_at) t.place_at = point(*place_at);
  if (auto s = job.find("time_scale")) {
    o.time_scale = s->as_double();
    if (!(std::isfinite(o.time_scale) && o.time_scale > 0)) s->fail("time_scale " + s->as_string() + ": expected a factor > 0");
  }
  const auto shift = job.find("time_shift");
  const auto start = job.find("start_time");
  if (shift && start) job.fail("give time_shift or start_time, not both");
  if (shift) o.time_shift = finite(*shift);
  if (start) t.start_time = finite(*start);
  if (auto r = job.find("frame_rate")) {
    o.frame_rate_hz = r->as_double();
    if (!(std::isfinite(o.frame_rate_hz) && o.frame_rate_hz >= 0)) r->fail("frame_rate: expected a rate > 0 in Hz, or 0 to keep the frames");
  }
  if (auto i = job.find("id_offset")) o.id_offset = i->as_int();
  if (auto s = job.find("species")) {
    const std::int64_t v = s->as_int();
    if (v < 0 || v > std::numeric_limits<std::int32_t>::max()) s->fail("species " + std::to_string(v) + ": expected an integer in [0, 2147483647]");
    o.species = static_cast<std::int32_t>(v);
  }
  job.finish();
  return t;
}

YAML::Node effective_transform_job(const TransformJob& t) {
  YAML::Node out(YAML::NodeType::Map);
  const auto& o = t.options;
  out["rotate"] = yaml_number(t.rotate_degrees);
  if (o.pivot) out["pivot"] = flow_numbers({o.pivot->x(), o.pivot->y()});
  if (t.place_at) out["place_at"] = flow_numbers({t.place_at->x(), t.place_at->y()});
  else out["translate"] = flow_numbers({o.translation.x(), o.translation.y()});
  out["time_scale"] = yaml_number(o.time_scale);
  if (t.start_time) out["start_time"] = yaml_number(*t.start_time);
  else out["time_shift"] = yaml_number(o.time_shift);
  out["frame_rate"] = yaml_number(o.frame_rate_hz);
  out["id_offset"] = o.id_offset;
  if (o.species) out["species"] = *o.species;
  return out;
}

stitch::TransformOptions resolve_transform(const TransformJob& job, const CrowdMotion& crowd) {
  stitch::TransformOptions o = job.options;
  if (job.place_at) {
    // The centroid rotates about the pivot too; the translation then carries it to place_at.
    const Eigen::Vector2d centroid = stitch::first_frame_centroid(crowd);
    const Eigen::Vector2d pivot = o.pivot ? *o.pivot : centroid;
    const Eigen::Vector2d rotated = pivot + Eigen::Rotation2Dd(o.rotation) * (centroid - pivot);
    o.translation = *job.place_at - rotated;
  }
  if (job.start_time && !crowd.times.empty()) o.time_shift = *job.start_time - crowd.times.front();
  return o;
}

}  // namespace throng
