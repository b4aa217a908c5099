#include "merge_poses.h"
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
#include <unordered_map>

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

// A crowd at every merged frame: copied where the frame is one of its own, interpolated inside its time span
// otherwise (cubic splines for positions, slerp and the earlier sample's action for poses), absent outside.
struct OnGrid {
  std::vector<double> positions;     ///< #grid by #agents by 3
  std::vector<double> orientations;  ///< #grid by #agents by 4, when poses are asked for
  std::vector<std::int32_t> actions; ///< #grid by #agents, when poses are asked for
  std::size_t interpolated = 0;      ///< merged frames where the crowd was interpolated
};

// `poses`: the crowd carries orientations and actions (detail::with_poses) and they are taken along.
OnGrid on_grid(const CrowdMotion& crowd, const std::vector<GridFrame>& grid, bool is_first, bool poses) {
  const std::size_t n = crowd.agent_count();
  OnGrid out;
  out.positions.assign(grid.size() * n * 3, absent);
  if (poses) {
    out.orientations.assign(grid.size() * n * 4, absent);
    out.actions.assign(grid.size() * n, -1);
  }
  auto copy = [&](const CrowdMotion& from, std::size_t f, std::size_t g) {
    std::copy_n(from.positions.begin() + static_cast<std::ptrdiff_t>(from.index(f, 0)), 3 * n,
                out.positions.begin() + static_cast<std::ptrdiff_t>(g * n * 3));
    if (!poses) return;
    std::copy_n(from.orientations.begin() + static_cast<std::ptrdiff_t>(f * n * 4), 4 * n,
                out.orientations.begin() + static_cast<std::ptrdiff_t>(g * n * 4));
    std::copy_n(from.actions.begin() + static_cast<std::ptrdiff_t>(f * n), n, out.actions.begin() + static_cast<std::ptrdiff_t>(g * n));
  };
  std::vector<double> needed;
  std::vector<std::size_t> needed_at;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    const std::size_t f = is_first ? grid[g].first : grid[g].second;
    if (f != none) {
      copy(crowd, f, g);
    } else if (crowd.frame_count() >= 2 && grid[g].time > crowd.times.front() && grid[g].time < crowd.times.back()) {
      needed.push_back(grid[g].time);
      needed_at.push_back(g);
    }
  }
  out.interpolated = needed.size();
  if (!needed.empty()) {
    const CrowdMotion r = timewarp::resample_crowd(crowd, crowd.times, needed);
    for (std::size_t k = 0; k < needed.size(); ++k) copy(r, k, needed_at[k]);
  }
  return out;
}

// Identical obstacles: the same shape, motion and name, bit for bit (two clips of one scene carry the same walls).
bool same_obstacle(const Obstacle& a, const Obstacle& b) {
  if (a.name != b.name || a.shape.index() != b.shape.index() || a.motion.size() != b.motion.size()) return false;
  for (std::size_t k = 0; k < a.motion.size(); ++k) {
    const PoseKey &p = a.motion[k], &q = b.motion[k];
    if (p.time != q.time || p.translation != q.translation || p.angle != q.angle) return false;
  }
  if (const auto* c = std::get_if<Circle>(&a.shape)) {
    const auto& d = std::get<Circle>(b.shape);
    return c->center == d.center && c->radius == d.radius;
  }
  if (const auto* w = std::get_if<Wall>(&a.shape)) {
    const auto& v = std::get<Wall>(b.shape);
    return w->a == v.a && w->b == v.b && w->thickness == v.thickness;
  }
  return std::get<ConvexPolygon>(a.shape).vertices == std::get<ConvexPolygon>(b.shape).vertices;
}

std::string point_text(const Eigen::Vector3d& p) {
  return "(" + detail::number(p.x()) + ", " + detail::number(p.y()) + ", " + detail::number(p.z()) + ")";
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

Scene merge_scenes(const Scene& first, const Scene& second, std::size_t* shared) {
  Scene s = first;
  std::size_t same = 0;
  for (const Obstacle& o : second.obstacles) {
    const bool known = std::any_of(s.obstacles.begin(), s.obstacles.end(), [&](const Obstacle& k) { return same_obstacle(k, o); });
    if (known) ++same;
    else s.obstacles.push_back(o);
  }
  if (shared) *shared = same;
  s.region = merge_regions(first.region, second.region);
  return s;
}

Merged merge(const CrowdMotion& a, const Scene& scene_a, const CrowdMotion& b, const Scene& scene_b, const MergeOptions& options) {
  if (!(std::isfinite(options.time_tolerance_s) && options.time_tolerance_s >= 0)) {
    throw ConfigError("time_tolerance " + detail::number(options.time_tolerance_s) + ": expected a time ≥ 0 in seconds");
  }
  if (!(std::isfinite(options.join_tolerance_m) && options.join_tolerance_m >= 0)) {
    throw ConfigError("join_tolerance " + detail::number(options.join_tolerance_m) + ": expected a length ≥ 0 in metres");
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
                     ", second " + span(b) + "); a merged crowd needs at least 2 (clips in sequence: span: union)");
  }

  Merged m;
  MergeReport& report = m.report;
  // Ids: the second crowd's shift when any clashes.
  const bool join = options.join_by == JoinBy::id;
  const std::set<std::int64_t> ids_a(a.ids.begin(), a.ids.end());
  std::vector<std::int64_t> clashes;
  for (std::int64_t id : b.ids) {
    if (ids_a.count(id) && !join) clashes.push_back(id);  // joined by id, a shared id is one agent
  }
  if (!clashes.empty()) {
    if (options.on_id_clash == IdClash::error) {
      throw InputError("merge: " + std::to_string(clashes.size()) + " agent ids are in both crowds (" + detail::id_list(clashes) +
                       "); give them distinct ids (transform id_offset) or merge with on_id_clash: shift");
    }
    report.id_shift = *ids_a.rbegin() + 1 - *std::min_element(b.ids.begin(), b.ids.end());
  }

  // Poses when either crowd carries them (the other's then the defaults from its path).
  const bool poses = !a.orientations.empty() || !a.actions.empty() || !b.orientations.empty() || !b.actions.empty();
  const OnGrid ga = poses ? on_grid(detail::with_poses(a), grid, true, true) : on_grid(a, grid, true, false);
  const OnGrid gb = poses ? on_grid(detail::with_poses(b), grid, false, true) : on_grid(b, grid, false, false);
  const std::vector<double>& pa = ga.positions;
  const std::vector<double>& pb = gb.positions;
  const std::size_t interpolated_a = ga.interpolated, interpolated_b = gb.interpolated;
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
  // Joined by id: the second crowd's agents with an id of a kept agent of the first are that agent.
  std::unordered_map<std::int64_t, std::size_t> merged_index_of;
  if (join) {
    for (std::size_t k = 0; k < keep_a.size(); ++k) merged_index_of.emplace(a.ids[keep_a[k]], k);
  }
  std::vector<std::pair<std::size_t, std::size_t>> joined;  // (agent of b, merged agent)
  for (std::size_t j = 0; j < b.agent_count(); ++j) {
    if (!present_somewhere(pb, b.agent_count(), j)) {
      ++report.left_out_second;
      continue;
    }
    const auto it = merged_index_of.find(b.ids[j]);
    if (it != merged_index_of.end()) joined.emplace_back(j, it->second);
    else keep_b.push_back(j);
  }
  report.joined = joined.size();

  const std::size_t na = keep_a.size(), n = na + keep_b.size();
  CrowdMotion& c = m.crowd;
  c = CrowdMotion::with_shape(grid.size(), n);
  for (std::size_t g = 0; g < grid.size(); ++g) c.times[g] = grid[g].time;
  const bool velocities = !a.velocities.empty() && !b.velocities.empty() && interpolated_a == 0 && interpolated_b == 0;
  report.velocities_dropped = !velocities && (!a.velocities.empty() || !b.velocities.empty());
  if (velocities) c.velocities.assign(c.positions.size(), absent);
  std::vector<std::int32_t> action_of_a, action_of_b;  // per input table entry: the merged table's index
  if (poses) {
    c.orientations.assign(grid.size() * n * 4, absent);
    c.actions.assign(grid.size() * n, -1);
    action_of_a = detail::join_action_tables(c.action_table, a.actions.empty() ? standard_actions() : a.action_table);
    action_of_b = detail::join_action_tables(c.action_table, b.actions.empty() ? standard_actions() : b.action_table);
  }
  // Writes agent j of `src` at merged frame g into merged agent `to`.
  auto put = [&](const CrowdMotion& src, const OnGrid& on, const std::vector<std::int32_t>& action_of, std::size_t j,
                 std::size_t g, std::size_t to, bool is_first) {
    const std::size_t ns = src.agent_count();
    std::copy_n(on.positions.begin() + static_cast<std::ptrdiff_t>((g * ns + j) * 3), 3,
                c.positions.begin() + static_cast<std::ptrdiff_t>(c.index(g, to)));
    const std::size_t f = is_first ? grid[g].first : grid[g].second;
    if (velocities && f != none) {
      std::copy_n(src.velocities.begin() + static_cast<std::ptrdiff_t>(src.index(f, j)), 3,
                  c.velocities.begin() + static_cast<std::ptrdiff_t>(c.index(g, to)));
    }
    if (poses && std::isfinite(on.positions[(g * ns + j) * 3])) {
      std::copy_n(on.orientations.begin() + static_cast<std::ptrdiff_t>((g * ns + j) * 4), 4,
                  c.orientations.begin() + static_cast<std::ptrdiff_t>((g * n + to) * 4));
      c.action(g, to) = action_of[static_cast<std::size_t>(on.actions[g * ns + j])];
    }
  };
  auto place = [&](const CrowdMotion& src, const OnGrid& on, const std::vector<std::int32_t>& action_of,
                   const std::vector<std::size_t>& keep, std::size_t offset, bool is_first, std::int64_t shift) {
    for (std::size_t k = 0; k < keep.size(); ++k) {
      const std::size_t j = keep[k], to = offset + k;
      c.ids[to] = src.ids[j] + shift;
      c.radii[to] = src.radii[j];
      c.species[to] = src.species[j];
      for (std::size_t g = 0; g < grid.size(); ++g) put(src, on, action_of, j, g, to, is_first);
    }
  };
  m.first_agents = keep_a;
  m.second_agents = keep_b;
  place(a, ga, action_of_a, keep_a, 0, true, 0);
  place(b, gb, action_of_b, keep_b, na, false, report.id_shift);
  // The joined agents: the second crowd's samples where the first has none (or only an interpolated one); where
  // both have their own sample they must agree.
  for (const auto& [j, to] : joined) {
    for (std::size_t g = 0; g < grid.size(); ++g) {
      const Eigen::Map<const Eigen::Vector3d> q(pb.data() + (g * b.agent_count() + j) * 3);
      if (!std::isfinite(q.x())) continue;
      const bool a_own = grid[g].first != none, b_own = grid[g].second != none;
      if (c.present(g, to)) {
        if (a_own && b_own && (c.position(g, to) - q).norm() > options.join_tolerance_m) {
          throw InputError("merge, joined by id: agent " + std::to_string(c.ids[to]) + " is at " + point_text(c.position(g, to)) +
                           " in the first crowd and at " + point_text(q) + " in the second at t = " + detail::seconds(grid[g].time) +
                           " (frame " + std::to_string(grid[g].first) + " of the first, " + std::to_string(grid[g].second) +
                           " of the second), more than join_tolerance = " + detail::number(options.join_tolerance_m) +
                           " m apart: two different agents share that id (merge without join_by, or give one distinct ids)");
        }
        if (a_own || !b_own) continue;  // the first crowd's own sample, or both interpolated
      }
      put(b, gb, action_of_b, j, g, to, false);
    }
  }
  m.scene = merge_scenes(scene_a, scene_b, &report.shared_obstacles);
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
