#include "text.h"

#include <throng/core/errors.h>
#include <throng/core/facing_carry.h>
#include <throng/stitch/transform.h>
#include <throng/timewarp/resample.h>

#include <Eigen/Geometry>

#include <cmath>
#include <optional>
#include <utility>
#include <vector>
#include <numbers>
#include <string>

namespace throng::stitch {
namespace {

// The rigid motion p ↦ pivot + R (p − pivot) + translation as an isometry.
Eigen::Isometry2d rigid_motion(double rotation, const Eigen::Vector2d& pivot, const Eigen::Vector2d& translation) {
  Eigen::Isometry2d m = Eigen::Isometry2d::Identity();
  m.linear() = Eigen::Rotation2Dd(rotation).toRotationMatrix();
  m.translation() = pivot + translation - m.linear() * pivot;
  return m;
}

}  // namespace

void validate(const TransformOptions& o) {
  auto finite = [](const char* name, double v) {
    if (!std::isfinite(v)) throw ConfigError(std::string(name) + " " + detail::number(v) + ": expected a finite number");
  };
  finite("rotation", o.rotation);
  finite("translation x", o.translation.x());
  finite("translation y", o.translation.y());
  finite("time_shift", o.time_shift);
  if (o.pivot) {
    finite("pivot x", o.pivot->x());
    finite("pivot y", o.pivot->y());
  }
  if (!(std::isfinite(o.time_scale) && o.time_scale > 0)) {
    throw ConfigError("time_scale " + detail::number(o.time_scale) + ": expected a finite factor > 0");
  }
  if (!(std::isfinite(o.frame_rate_hz) && o.frame_rate_hz >= 0)) {
    throw ConfigError("frame_rate " + detail::number(o.frame_rate_hz) + ": expected a rate > 0 in Hz, or 0 to keep the frames");
  }
}

Eigen::Vector2d first_frame_centroid(const CrowdMotion& crowd) {
  Eigen::Vector2d sum(0, 0);
  std::size_t count = 0;
  if (crowd.frame_count() == 0) return sum;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
    if (!crowd.present(0, a)) continue;
    sum += crowd.position(0, a).head<2>();
    ++count;
  }
  return count > 0 ? Eigen::Vector2d(sum / static_cast<double>(count)) : sum;
}

void transform(CrowdMotion& crowd, Scene& scene, const TransformOptions& o) {
  validate(o);
  for (std::int64_t id : crowd.ids) {
    if (id + o.id_offset < 0) {
      throw InputError("id_offset " + std::to_string(o.id_offset) + " would give agent " + std::to_string(id) +
                       " the negative id " + std::to_string(id + o.id_offset));
    }
  }
  const Eigen::Vector2d pivot = o.pivot ? *o.pivot : first_frame_centroid(crowd);
  const Eigen::Isometry2d motion = rigid_motion(o.rotation, pivot, o.translation);
  const Eigen::Matrix2d R = motion.linear();
  const double t0 = crowd.times.empty() ? 0.0 : crowd.times.front();
  auto retime = [&](double t) { return t0 + o.time_scale * (t - t0) + o.time_shift; };
  // Actions follow the new speeds where a retiming moves an agent into another walk/stand/run class
  // (facing_carry.h); that needs the crowd as it was, kept only when it can happen.
  std::optional<CrowdMotion> before;
  if (!crowd.actions.empty() && o.time_scale != 1.0) before = crowd;

  for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
    crowd.times[f] = retime(crowd.times[f]);
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      auto p = crowd.position(f, a);
      if (!std::isfinite(p.x())) continue;
      p.head<2>() = motion * Eigen::Vector2d(p.head<2>());
      if (!crowd.velocities.empty()) {
        Eigen::Map<Eigen::Vector3d> v(crowd.velocities.data() + crowd.index(f, a));
        v.head<2>() = R * Eigen::Vector2d(v.head<2>());
        v /= o.time_scale;
      }
    }
  }
  // Facing turns with the crowd: every orientation by the rotation about +z (exactly; absent ones stay NaN).
  if (!crowd.orientations.empty()) {
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(o.rotation, Eigen::Vector3d::UnitZ()));
    for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
      for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
        if (crowd.present(f, a)) crowd.orientation(f, a) = (turn * Eigen::Quaterniond(crowd.orientation(f, a))).normalized();
      }
    }
  }
  if (before && crowd.frame_count() > 0) {
    // Actions only: with the orientations set aside carry_facing leaves the facing (turned exactly above) alone.
    std::vector<double> facing = std::move(crowd.orientations);
    crowd.orientations.clear();
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      carry_facing(*before, crowd, CarriedSpan{a, a, 0, crowd.frame_count() - 1, 0, 0.0});
    }
    crowd.orientations = std::move(facing);
  }
  for (auto& id : crowd.ids) id += o.id_offset;
  if (o.species) std::fill(crowd.species.begin(), crowd.species.end(), *o.species);

  for (Obstacle& obstacle : scene.obstacles) {
    move_rigidly(obstacle, motion, o.rotation);
    for (PoseKey& key : obstacle.motion) key.time = retime(key.time);
  }
  if (scene.region) {
    Region& r = *scene.region;
    Eigen::AlignedBox2d box;
    for (const auto& corner : {r.min, r.max, Eigen::Vector2d(r.min.x(), r.max.y()), Eigen::Vector2d(r.max.x(), r.min.y())}) {
      box.extend(motion * corner);
    }
    const double quarters = o.rotation / (0.5 * std::numbers::pi);
    const double nearest = std::round(quarters);
    if (std::abs(quarters - nearest) > 1e-12) {
      r.periodic[0] = r.periodic[1] = false;
    } else if (static_cast<long long>(nearest) % 2 != 0) {
      std::swap(r.periodic[0], r.periodic[1]);
    }
    r.min = box.min();
    r.max = box.max();
    r.t0 = retime(r.t0);
    r.t1 = retime(r.t1);
  }
  if (o.frame_rate_hz > 0 && crowd.frame_count() >= 2) {
    const std::vector<double> times = timewarp::uniform_times(crowd.times.front(), crowd.times.back(), o.frame_rate_hz);
    crowd = timewarp::resample_crowd(crowd, crowd.times, times, timewarp::SplineEnd::not_a_knot, !crowd.velocities.empty());
  }
}

}  // namespace throng::stitch
