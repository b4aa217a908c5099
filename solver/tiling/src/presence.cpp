#include "presence.h"

#include <throng/core/obstacle.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace throng::tiling {
namespace {

constexpr double infinity = std::numeric_limits<double>::infinity();

// The parameter interval [u0, u1] ⊂ [0, 1] of a + u (b − a) inside [lo, hi] on one axis; empty when u0 > u1.
void clip(double a, double b, double lo, double hi, double& u0, double& u1) {
  const double d = b - a;
  if (d == 0) {
    if (a < lo || a > hi) u0 = 1, u1 = 0;
    return;
  }
  double s = (lo - a) / d, e = (hi - a) / d;
  if (s > e) std::swap(s, e);
  u0 = std::max(u0, s);
  u1 = std::min(u1, e);
}

// Image shifts k (as integers) of the interval [lo, hi] by k·period that can meet [smin, smax].
void image_range(double smin, double smax, double lo, double hi, double period, long& first, long& last) {
  if (period <= 0) {
    first = last = 0;
    return;
  }
  first = static_cast<long>(std::floor((smin - hi) / period));
  last = static_cast<long>(std::ceil((smax - lo) / period));
}

}  // namespace

std::vector<PresenceArea> presence_areas(const Region& region, const DensityOptions& options) {
  std::vector<PresenceArea> areas;
  if (options.per_m2 > 0) areas.push_back({region.min, region.max, options.per_m2});
  for (const DensityZone& z : options.zones) areas.push_back({z.min, z.max, z.per_m2});
  return areas;
}

double free_area(const Scene& scene, const Eigen::Vector2d& min, const Eigen::Vector2d& max, double time, double cell_m) {
  const Eigen::Vector2d size = max - min;
  double cell = cell_m;
  constexpr double max_cells = 250000;
  if (size.x() / cell * size.y() / cell > max_cells) cell = std::sqrt(size.x() * size.y() / max_cells);
  const auto nx = std::max<long>(1, std::lround(std::ceil(size.x() / cell)));
  const auto ny = std::max<long>(1, std::lround(std::ceil(size.y() / cell)));
  const double cx = size.x() / static_cast<double>(nx), cy = size.y() / static_cast<double>(ny);
  Eigen::Vector2d period(0, 0);
  if (scene.region) {
    const Eigen::Vector3d p = periods(*scene.region);
    period = {p.x(), p.y()};
  }
  std::vector<Eigen::AlignedBox2d> bounds;
  for (const Obstacle& o : scene.obstacles) bounds.push_back(bounds_at(o, time));
  long covered = 0;
  for (long i = 0; i < nx; ++i) {
    for (long j = 0; j < ny; ++j) {
      const Eigen::Vector2d q(min.x() + (static_cast<double>(i) + 0.5) * cx, min.y() + (static_cast<double>(j) + 0.5) * cy);
      bool inside = false;
      for (std::size_t k = 0; k < scene.obstacles.size() && !inside; ++k) {
        for (int ix = -1; ix <= 1 && !inside; ++ix) {
          for (int iy = -1; iy <= 1 && !inside; ++iy) {
            if ((ix != 0 && period.x() <= 0) || (iy != 0 && period.y() <= 0)) continue;
            const Eigen::Vector2d image = q + Eigen::Vector2d(ix * period.x(), iy * period.y());
            if (!bounds[k].contains(image)) continue;
            inside = distance_to(scene.obstacles[k], image, time).signed_distance < 0;
          }
        }
      }
      covered += inside ? 1 : 0;
    }
  }
  return size.x() * size.y() * (1.0 - static_cast<double>(covered) / static_cast<double>(nx * ny));
}

Presence::Presence(const Environment& environment, const DensityOptions& options, const PresenceSpan& span)
    : environment_(environment), region_(*environment.scene.region), periods_(periods(*environment.scene.region)),
      span_(span), bin_s_(options.bin_s), speed_(options.projection_speed_mps) {
  areas_ = presence_areas(region_, options);
  if (areas_.empty()) return;
  if (region_.periodic[2]) {
    span_.t0 = region_.t0;
    span_.t1 = region_.t1;
    // Whole bins dividing the period.
    bins_ = static_cast<std::size_t>(std::max(1.0, std::round((span_.t1 - span_.t0) / options.bin_s)));
    bin_s_ = (span_.t1 - span_.t0) / static_cast<double>(bins_);
  } else {
    bins_ = static_cast<std::size_t>(std::max(1.0, std::ceil((span_.t1 - span_.t0) / bin_s_ - 1e-9)));
    span_.t1 = span_.t0 + static_cast<double>(bins_) * bin_s_;
  }
  project_ = !(region_.periodic[0] && region_.periodic[1] && region_.periodic[2]);
  occupancy_.assign(areas_.size() * bins_, 0.0);
  target_.assign(areas_.size() * bins_, 0.0);
  const bool moving = std::any_of(environment.scene.obstacles.begin(), environment.scene.obstacles.end(),
                                  [](const Obstacle& o) { return o.is_moving(); });
  for (std::size_t a = 0; a < areas_.size(); ++a) {
    const PresenceArea& area = areas_[a];
    const double box = (area.max - area.min).prod();
    const bool free = options.free_area && !environment.scene.obstacles.empty();
    const double still = free && !moving ? free_area(environment.scene, area.min, area.max, span_.t0, options.area_cell_m) : box;
    for (std::size_t b = 0; b < bins_; ++b) {
      const double size = free && moving ? free_area(environment.scene, area.min, area.max, bin_start(b) + 0.5 * bin_s_,
                                                     options.area_cell_m)
                                         : still;
      target_[a * bins_ + b] = area.per_m2 * size;
    }
  }
}

std::size_t Presence::bin_of(double t) const noexcept {
  if (region_.periodic[2]) {
    const double p = span_.t1 - span_.t0;
    const double w = std::fmod(std::fmod(t - span_.t0, p) + p, p);
    return std::min(bins_ - 1, static_cast<std::size_t>(w / bin_s_));
  }
  if (t < span_.t0 || t >= span_.t1) return bins_;
  return std::min(bins_ - 1, static_cast<std::size_t>((t - span_.t0) / bin_s_));
}

void Presence::spread(std::size_t area, double t0, double t1, double sign, Delta& delta) const {
  if (!(t1 > t0)) return;
  if (region_.periodic[2]) {
    const double p = span_.t1 - span_.t0;
    // Shift into the period, then split where the interval wraps (an interval longer than a period covers
    // every bin once per period).
    const double shift = std::floor((t0 - span_.t0) / p) * p;
    t0 -= shift;
    t1 -= shift;
    while (t1 > t0) {
      const double end = std::min(t1, span_.t1);
      for (std::size_t b = bin_of(t0); b < bins_; ++b) {
        const double lo = std::max(t0, bin_start(b)), hi = std::min(end, bin_start(b) + bin_s_);
        if (hi > lo) delta.terms.emplace_back(area * bins_ + b, sign * (hi - lo) / bin_s_);
        if (bin_start(b) + bin_s_ >= end) break;
      }
      t0 = span_.t0;
      t1 -= p;
    }
    return;
  }
  t0 = std::max(t0, span_.t0);
  t1 = std::min(t1, span_.t1);
  if (!(t1 > t0)) return;
  for (std::size_t b = bin_of(t0); b < bins_; ++b) {
    const double lo = std::max(t0, bin_start(b)), hi = std::min(t1, bin_start(b) + bin_s_);
    if (hi > lo) delta.terms.emplace_back(area * bins_ + b, sign * (hi - lo) / bin_s_);
    if (bin_start(b) + bin_s_ >= t1) break;
  }
}

void Presence::segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double ta, double tb, double sign,
                       Delta& delta) const {
  if (!(tb > ta)) return;
  for (std::size_t k = 0; k < areas_.size(); ++k) {
    const PresenceArea& area = areas_[k];
    long x0, x1, y0, y1;
    image_range(std::min(a.x(), b.x()), std::max(a.x(), b.x()), area.min.x(), area.max.x(), periods_.x(), x0, x1);
    image_range(std::min(a.y(), b.y()), std::max(a.y(), b.y()), area.min.y(), area.max.y(), periods_.y(), y0, y1);
    for (long ix = x0; ix <= x1; ++ix) {
      for (long iy = y0; iy <= y1; ++iy) {
        const Eigen::Vector2d shift(static_cast<double>(ix) * periods_.x(), static_cast<double>(iy) * periods_.y());
        double u0 = 0, u1 = 1;
        clip(a.x(), b.x(), area.min.x() + shift.x(), area.max.x() + shift.x(), u0, u1);
        clip(a.y(), b.y(), area.min.y() + shift.y(), area.max.y() + shift.y(), u0, u1);
        if (u1 > u0) spread(k, ta + u0 * (tb - ta), ta + u1 * (tb - ta), sign, delta);
      }
    }
  }
}

void Presence::path(const Path& path, double sign, Delta& delta) const {
  if (!enabled()) return;
  for (std::size_t s = 0; s + 1 < path.times.size(); ++s) {
    segment(path.positions[s], path.positions[s + 1], path.times[s], path.times[s + 1], sign, delta);
  }
}

void Presence::projection(const Eigen::Vector2d& position, double heading, double time, bool is_exit, bool dangling,
                          double sign, Delta& delta) const {
  if (!enabled() || !project_) return;
  const auto outside = [](double v, double lo, double hi) { return !(v > lo && v < hi); };
  for (int axis = 0; axis < 2; ++axis) {
    if (!region_.periodic[static_cast<std::size_t>(axis)] && outside(position[axis], region_.min[axis], region_.max[axis])) return;
  }
  if (!dangling) {
    // A free end goes on only when it is an exit beyond the region's time span with the horizon going on.
    if (!is_exit || region_.periodic[2] || time < region_.t1 || time >= span_.horizon_t1) return;
    for (const Zone& z : environment_.sinks) {
      if (z.contains(position, time)) return;
    }
  }
  const Eigen::Vector2d direction = (is_exit ? 1.0 : -1.0) * Eigen::Vector2d(std::cos(heading), std::sin(heading));
  double duration = time_to_side(region_, position, direction, speed_);
  if (region_.periodic[2]) {
    duration = std::min(duration, span_.t1 - span_.t0);
  } else if (is_exit) {
    duration = std::min(duration, span_.horizon_t1 - time);
  } else {
    duration = std::min(duration, time - std::max(span_.freeze, span_.t0));
  }
  if (!(duration > 0) || !std::isfinite(duration)) return;
  const Eigen::Vector2d far = position + direction * (duration * speed_);
  if (is_exit) segment(position, far, time, time + duration, sign, delta);
  else segment(far, position, time - duration, time, sign, delta);
}

double time_to_side(const Region& region, const Eigen::Vector2d& position, const Eigen::Vector2d& direction,
                    double speed) {
  double reach = infinity;  // metres to a side that is not periodic
  for (int axis = 0; axis < 2; ++axis) {
    if (region.periodic[static_cast<std::size_t>(axis)]) continue;
    if (!(position[axis] > region.min[axis] && position[axis] < region.max[axis])) return 0.0;
    if (direction[axis] == 0) continue;
    const double side = direction[axis] > 0 ? region.max[axis] : region.min[axis];
    reach = std::min(reach, (side - position[axis]) / direction[axis]);
  }
  return reach / speed;
}

void Presence::apply(const Delta& delta) {
  for (const auto& [index, value] : delta.terms) occupancy_[index] += value;
}

bool Presence::fits(const Delta& delta, double factor) const {
  // Net change per bin (a delta may add and remove in the same bin).
  std::vector<std::pair<std::size_t, double>> net(delta.terms);
  std::sort(net.begin(), net.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < net.size();) {
    double sum = 0;
    std::size_t j = i;
    for (; j < net.size() && net[j].first == net[i].first; ++j) sum += net[j].second;
    if (sum > 1e-12 && occupancy_[net[i].first] + sum > factor * target_[net[i].first]) return false;
    i = j;
  }
  return true;
}

}  // namespace throng::tiling
