#include "end_index.h"

#include <cassert>

namespace throng::tiling {

EndIndex::EndIndex(const Region& region, const MatchThresholds& match)
    : grid_(region, cell_m(match), cell_s(match), margin_m(match), margin_s(match)),
      match_(match) {
  const Eigen::Vector3d p = periods(region);
  periods_.p = {p.x(), p.y(), p.z()};
  entries_.resize(grid_.cells());
  exits_.resize(grid_.cells());
}

std::vector<EndIndex::Entry>& EndIndex::cell_of(bool is_exit, const EndPoint& e) {
  const std::size_t cell = grid_.flat(grid_.x.cell_of(grid_.x.raw(e.position.x())), grid_.y.cell_of(grid_.y.raw(e.position.y())),
                                      grid_.t.cell_of(grid_.t.raw(e.time)));
  return (is_exit ? exits_ : entries_)[cell];
}

void EndIndex::insert(FragmentRef ref, bool is_exit, const EndPoint& end) {
  cell_of(is_exit, end).push_back({end, ref});
  ++size_;
}

void EndIndex::remove(FragmentRef ref, bool is_exit, const EndPoint& end) {
  std::vector<Entry>& c = cell_of(is_exit, end);
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i].ref == ref) {
      c[i] = c.back();
      c.pop_back();
      --size_;
      return;
    }
  }
  assert(false && "EndIndex::remove: the end is not indexed where it was inserted");
}

void EndIndex::near(const EndPoint& q, bool want_exits, double radius_m, double dt_lo, double dt_hi,
                     std::vector<EndMatch>& out) const {
  const auto& cells = want_exits ? exits_ : entries_;
  grid_.for_each_cell(q.position.x() - radius_m, q.position.x() + radius_m, q.position.y() - radius_m,
                      q.position.y() + radius_m, q.time + dt_lo, q.time + dt_hi, [&](std::size_t cell) {
                        for (const Entry& e : cells[cell]) {
                          // The image of e nearest to q (in time: nearest to the window's middle).
                          const double mid = q.time + 0.5 * (dt_lo + dt_hi);
                          const std::array<int, 3> image{nearest_image(q.position.x() - e.end.position.x(), periods_.p[0]),
                                                         nearest_image(q.position.y() - e.end.position.y(), periods_.p[1]),
                                                         nearest_image(mid - e.end.time, periods_.p[2])};
                          const Eigen::Vector2d at =
                              e.end.position + Eigen::Vector2d(image[0] * periods_.p[0], image[1] * periods_.p[1]);
                          const double dt = e.end.time + image[2] * periods_.p[2] - q.time;
                          const double dist = (at - q.position).norm();
                          if (dist > radius_m || dt < dt_lo || dt > dt_hi) continue;
                          out.push_back({e.ref, image, dist});
                        }
                      });
}

void EndIndex::matches(const EndPoint& q, bool want_exits, std::vector<EndMatch>& out) const {
  const double d = match_.distance_m, dt = match_.time_s;
  const auto& cells = want_exits ? exits_ : entries_;
  grid_.for_each_cell(q.position.x() - d, q.position.x() + d, q.position.y() - d, q.position.y() + d, q.time - dt,
                      q.time + dt, [&](std::size_t cell) {
                        for (const Entry& e : cells[cell]) {
                          if (e.end.pose_class != q.pose_class) continue;
                          const std::array<int, 3> image{nearest_image(q.position.x() - e.end.position.x(), periods_.p[0]),
                                                         nearest_image(q.position.y() - e.end.position.y(), periods_.p[1]),
                                                         nearest_image(q.time - e.end.time, periods_.p[2])};
                          const Eigen::Vector2d offset =
                              q.position - e.end.position -
                              Eigen::Vector2d(image[0] * periods_.p[0], image[1] * periods_.p[1]);
                          const double time_offset = q.time - e.end.time - image[2] * periods_.p[2];
                          const double angle = std::abs(wrap_angle(q.heading - e.end.heading));
                          const double dist = offset.norm();
                          if (dist > d || std::abs(time_offset) > dt || angle > match_.angle_rad) continue;
                          out.push_back({e.ref, image,
                                         (dist / d) * (dist / d) + (angle / match_.angle_rad) * (angle / match_.angle_rad) +
                                             (time_offset / dt) * (time_offset / dt)});
                        }
                      });
}

}  // namespace throng::tiling
