#include "text.h"

#include <throng/core/errors.h>
#include <throng/graph/delaunay.h>
#include <throng/stitch/merge.h>
#include <throng/timewarp/resample.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <string>

namespace throng::stitch {
namespace {

constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

// One merged frame: its time and the frame of each crowd at that time (none: not a frame of that crowd).
struct GridFrame {
  double time;
  std::size_t first;
  std::size_t second;
};

std::vector<GridFrame> merged_grid(const std::vector<double>& a, const std::vector<double>& b, double lo, double hi, double tol) {
  auto within = [&](const std::vector<double>& t) {
    const auto begin = std::lower_bound(t.begin(), t.end(), lo - tol);
    const auto end = std::upper_bound(begin, t.end(), hi + tol);
    return std::pair{static_cast<std::size_t>(begin - t.begin()), static_cast<std::size_t>(end - t.begin())};
  };
  auto [i, i_end] = within(a);
  auto [k, k_end] = within(b);
  std::vector<GridFrame> grid;
  while (i < i_end || k < k_end) {
    GridFrame g{0, none, none};
    if (i < i_end && k < k_end && std::abs(a[i] - b[k]) <= tol) {
      g = {a[i], i++, k++};
    } else if (k >= k_end || (i < i_end && a[i] < b[k])) {
      g = {a[i], i++, none};
    } else {
      g = {b[k], none, k++};
    }
    if (!grid.empty() && g.time - grid.back().time <= tol) {
      // A frame of one crowd within the tolerance of the previous merged frame: the same frame.
      if (grid.back().first == none) grid.back().first = g.first;
      if (grid.back().second == none) grid.back().second = g.second;
      continue;
    }
    grid.push_back(g);
  }
  return grid;
}

// The crowd's positions at every merged frame: copied where the frame is one of its own, interpolated inside its
// time span otherwise, absent outside. Returns #grid by #agents by 3 and counts the interpolated frames.
std::vector<double> on_grid(const CrowdMotion& crowd, const std::vector<GridFrame>& grid, bool is_first, std::size_t& interpolated) {
  const std::size_t n = crowd.agent_count();
  std::vector<double> out(grid.size() * n * 3, absent);
  std::vector<double> needed;
  std::vector<std::size_t> needed_at;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const std::size_t f = is_first ? grid[g].first : grid[g].second;
    if (f != none) {
      std::copy_n(crowd.positions.begin() + static_cast<std::ptrdiff_t>(crowd.index(f, 0)), 3 * n,
                  out.begin() + static_cast<std::ptrdiff_t>(g * n * 3));
    } else if (crowd.frame_count() >= 2 && grid[g].time > crowd.times.front() && grid[g].time < crowd.times.back()) {
      needed.push_back(grid[g].time);
      needed_at.push_back(g);
    }
  }
  interpolated = needed.size();
  if (!needed.empty()) {
    const CrowdMotion r = timewarp::resample_crowd(crowd, crowd.times, needed);
    for (std::size_t k = 0; k < needed.size(); ++k) {
      std::copy_n(r.positions.begin() + static_cast<std::ptrdiff_t>(r.index(k, 0)), 3 * n,
                  out.begin() + static_cast<std::ptrdiff_t>(needed_at[k] * n * 3));
    }
  }
  return out;
}

std::optional<Region> merge_regions(const std::optional<Region>& a, const std::optional<Region>& b) {
  if (!a) return b;
  if (!b) return a;
  Region r = *a;
  r.min = a->min.cwiseMin(b->min);
  r.max = a->max.cwiseMax(b->max);
  r.t0 = std::min(a->t0, b->t0);
  r.t1 = std::max(a->t1, b->t1);
  const bool same_x = a->min.x() == b->min.x() && a->max.x() == b->max.x();
  const bool same_y = a->min.y() == b->min.y() && a->max.y() == b->max.y();
  const bool same_t = a->t0 == b->t0 && a->t1 == b->t1;
  r.periodic = {a->periodic[0] && b->periodic[0] && same_x, a->periodic[1] && b->periodic[1] && same_y,
                a->periodic[2] && b->periodic[2] && same_t};
  return r;
}

}  // namespace

Scene merge_scenes(const Scene& first, const Scene& second) {
  Scene s = first;
  s.obstacles.insert(s.obstacles.end(), second.obstacles.begin(), second.obstacles.end());
  s.region = merge_regions(first.region, second.region);
  return s;
}

Merged merge(const CrowdMotion& a, const Scene& scene_a, const CrowdMotion& b, const Scene& scene_b, const MergeOptions& options) {
  if (!(std::isfinite(options.time_tolerance_s) && options.time_tolerance_s >= 0)) {
    throw ConfigError("time_tolerance " + detail::number(options.time_tolerance_s) + ": expected a time ≥ 0 in seconds");
  }
  if (!(std::isfinite(options.max_edge_length) && options.max_edge_length >= 0)) {
    throw ConfigError("max_edge_length " + detail::number(options.max_edge_length) + ": expected a length ≥ 0 in metres (0: keep all)");
  }
  if (a.frame_count() == 0 || b.frame_count() == 0) {
    throw InputError(std::string("merge: the ") + (a.frame_count() == 0 ? "first" : "second") + " crowd has no frames");
  }
  const double tol = options.time_tolerance_s;
  auto span = [](const CrowdMotion& c) { return "[" + detail::number(c.times.front()) + ", " + detail::number(c.times.back()) + "] s"; };
  double lo = std::max(a.times.front(), b.times.front()), hi = std::min(a.times.back(), b.times.back());
  if (options.span == MergeSpan::overlap && lo > hi + tol) {
    throw InputError("merge: the time spans do not overlap: the first crowd covers " + span(a) + ", the second " + span(b) +
                     "; move one in time (transform time_shift) or merge with span: union");
  }
  if (options.span == MergeSpan::union_of_spans) {
    lo = std::min(a.times.front(), b.times.front());
    hi = std::max(a.times.back(), b.times.back());
  }
  const std::vector<GridFrame> grid = merged_grid(a.times, b.times, lo, hi, tol);
  if (options.span == MergeSpan::overlap && grid.size() < 2) {
    throw InputError("merge: the crowds overlap in " + std::to_string(grid.size()) + " frame only (first " + span(a) +
                     ", second " + span(b) + "); a merged crowd needs at least 2");
  }

  Merged m;
  MergeReport& report = m.report;
  // Ids: the second crowd's shift when any clashes.
  const std::set<std::int64_t> ids_a(a.ids.begin(), a.ids.end());
  std::vector<std::int64_t> clashes;
  for (std::int64_t id : b.ids) {
    if (ids_a.count(id)) clashes.push_back(id);
  }
  if (!clashes.empty()) {
    if (options.on_id_clash == IdClash::error) {
      throw InputError("merge: " + std::to_string(clashes.size()) + " agent ids are in both crowds (" + detail::id_list(clashes) +
                       "); give them distinct ids (transform id_offset) or merge with on_id_clash: shift");
    }
    report.id_shift = *ids_a.rbegin() + 1 - *std::min_element(b.ids.begin(), b.ids.end());
  }

  std::size_t interpolated_a = 0, interpolated_b = 0;
  const std::vector<double> pa = on_grid(a, grid, true, interpolated_a);
  const std::vector<double> pb = on_grid(b, grid, false, interpolated_b);
  report.interpolated_frames_first = interpolated_a;
  report.interpolated_frames_second = interpolated_b;

  // Agents present at some merged frame, first crowd's first.
  auto present_somewhere = [&](const std::vector<double>& p, std::size_t n, std::size_t agent) {
    for (std::size_t g = 0; g < grid.size(); ++g) {
      if (std::isfinite(p[(g * n + agent) * 3])) return true;
    }
    return false;
  };
  std::vector<std::size_t> keep_a, keep_b;
  for (std::size_t j = 0; j < a.agent_count(); ++j) {
    if (present_somewhere(pa, a.agent_count(), j)) keep_a.push_back(j);
    else ++report.left_out_first;
  }
  for (std::size_t j = 0; j < b.agent_count(); ++j) {
    if (present_somewhere(pb, b.agent_count(), j)) keep_b.push_back(j);
    else ++report.left_out_second;
  }

  const std::size_t na = keep_a.size(), n = na + keep_b.size();
  CrowdMotion& c = m.crowd;
  c = CrowdMotion::with_shape(grid.size(), n);
  for (std::size_t g = 0; g < grid.size(); ++g) c.times[g] = grid[g].time;
  const bool velocities = !a.velocities.empty() && !b.velocities.empty() && interpolated_a == 0 && interpolated_b == 0;
  report.velocities_dropped = !velocities && (!a.velocities.empty() || !b.velocities.empty());
  if (velocities) c.velocities.assign(c.positions.size(), absent);
  auto place = [&](const CrowdMotion& src, const std::vector<double>& p, const std::vector<std::size_t>& keep, std::size_t offset,
                   bool is_first, std::int64_t shift) {
    for (std::size_t k = 0; k < keep.size(); ++k) {
      const std::size_t j = keep[k], to = offset + k;
      c.ids[to] = src.ids[j] + shift;
      c.radii[to] = src.radii[j];
      c.species[to] = src.species[j];
      for (std::size_t g = 0; g < grid.size(); ++g) {
        std::copy_n(p.begin() + static_cast<std::ptrdiff_t>((g * src.agent_count() + j) * 3), 3,
                    c.positions.begin() + static_cast<std::ptrdiff_t>(c.index(g, to)));
        const std::size_t f = is_first ? grid[g].first : grid[g].second;
        if (velocities && f != none) {
          std::copy_n(src.velocities.begin() + static_cast<std::ptrdiff_t>(src.index(f, j)), 3,
                      c.velocities.begin() + static_cast<std::ptrdiff_t>(c.index(g, to)));
        }
      }
    }
  };
  m.first_agents = keep_a;
  m.second_agents = keep_b;
  place(a, pa, keep_a, 0, true, 0);
  place(b, pb, keep_b, na, false, report.id_shift);
  m.scene = merge_scenes(scene_a, scene_b);
  report.frames = grid.size();
  report.first_time = grid.front().time;
  report.last_time = grid.back().time;

  // Formation edges: Delaunay of the union at the first frame where both groups have agents.
  for (std::size_t g = 0; g < grid.size(); ++g) {
    std::vector<std::size_t> present;
    bool has_a = false, has_b = false;
    for (std::size_t j = 0; j < n; ++j) {
      if (!c.present(g, j)) continue;
      present.push_back(j);
      (j < na ? has_a : has_b) = true;
    }
    if (!has_a || !has_b) continue;
    Eigen::Matrix<double, Eigen::Dynamic, 2> points(static_cast<Eigen::Index>(present.size()), 2);
    for (std::size_t k = 0; k < present.size(); ++k) points.row(static_cast<Eigen::Index>(k)) = c.position(g, present[k]).head<2>().transpose();
    const Triangulation dt = delaunay_2d(points);
    for (const auto& e : dt.edges) {
      const auto i = static_cast<std::int32_t>(present[static_cast<std::size_t>(e[0])]);
      const auto j = static_cast<std::int32_t>(present[static_cast<std::size_t>(e[1])]);
      if (options.max_edge_length > 0 &&
          (c.position(g, static_cast<std::size_t>(i)) - c.position(g, static_cast<std::size_t>(j))).head<2>().norm() > options.max_edge_length) {
        continue;
      }
      m.formation_edges.push_back({std::min(i, j), std::max(i, j)});
      if ((static_cast<std::size_t>(i) < na) != (static_cast<std::size_t>(j) < na)) ++report.cross_edges;
    }
    std::sort(m.formation_edges.begin(), m.formation_edges.end());
    report.formation_frame = g;
    break;
  }
  return m;
}

}  // namespace throng::stitch
