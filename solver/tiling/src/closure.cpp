// Bridger::close (bridges.h): a planned sequence of patches from a dangling exit to a dangling entry.
#include "bridges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace throng::tiling {
namespace {

// A state of the plan: an open exit reached by placing `placement` on the exit of `parent`.
struct Step {
  Eigen::Vector2d position;
  double heading = 0;
  double time = 0;
  std::size_t pose_class = 0;
  std::size_t parent = 0;
  Placement placement;
  double rank = 0;
};

// The placement of fragment f of `type` whose entry lies exactly on the end `from` (as Algorithm 2 places its
// candidates), and where that leaves its exit.
Step follow(const Step& from, std::uint32_t type, std::uint32_t f, const Fragment& fr) {
  Step s;
  Transform t;
  t.angle = wrap_angle(from.heading - fr.headings.front());
  t.translation = from.position - rotate(fr.positions.front(), t.angle);
  t.time_shift = from.time - fr.times.front();
  s.position = t.apply(fr.positions.back());
  s.heading = wrap_angle(fr.headings.back() + t.angle);
  s.time = fr.times.back() + t.time_shift;
  s.pose_class = fr.exit_class;
  s.placement = {0, type, f, t};
  return s;
}

}  // namespace

bool Bridger::close(FragmentRef exit, const std::vector<EndPoint>& entries) {
  const Problem& problem = state_.problem();
  const SearchOptions& o = problem.options.search;
  const Periods& periods = problem.periods;
  constexpr std::size_t beam = 48;
  constexpr std::size_t plans_per_entry = 3;
  // The single-character fragments (a patch of more characters would open new ends).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> singles;
  double fastest = 0;
  for (std::uint32_t k : problem.usable_types) {
    const PatchType& type = problem.library.types[k];
    if (type.character_count() != 1) continue;
    for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
      const Fragment& fr = type.fragments[f];
      if (!fr.is_character()) continue;
      singles.emplace_back(k, f);
      fastest = std::max(fastest, (fr.positions.back() - fr.positions.front()).norm() / (fr.times.back() - fr.times.front()));
    }
  }
  if (singles.empty()) return false;
  const auto toroidal = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    Eigen::Vector2d d = b - a;
    for (int axis = 0; axis < 2; ++axis) {
      const double p = periods.p[static_cast<std::size_t>(axis)];
      if (p > 0) d[axis] -= std::round(d[axis] / p) * p;
    }
    return d;
  };

  const LiveInstance& holder = state_.at(exit.instance);
  const EndPoint start = problem.end_point(holder.type, holder.paths, exit.fragment, true);
  for (const EndPoint& n : entries) {
    // The entry's time one period at most ahead, at least a patch after the exit.
    double target = n.time;
    if (periods.p[2] > 0) {
      while (target < start.time + shortest_s_) target += periods.p[2];
      while (target - periods.p[2] >= start.time + shortest_s_) target -= periods.p[2];
    }
    if (target < start.time + shortest_s_) continue;
    // Beam search level by level; a plan is a level whose exit a bridge joins to n.
    std::vector<Step> steps{Step{start.position, start.heading, start.time, start.pose_class, 0, {}, 0}};
    std::vector<std::size_t> level{0};
    std::vector<std::pair<double, std::size_t>> plans;  // (bridge residual, last step)
    while (!level.empty() && plans.size() < plans_per_entry) {
      std::vector<std::size_t> next;
      for (std::size_t i : level) {
        for (const auto& [k, f] : singles) {
          const Fragment& fr = problem.library.types[k].fragments[f];
          if (fr.entry_class != steps[i].pose_class) continue;
          Step s = follow(steps[i], k, f, fr);
          const double left = target - s.time;
          const Eigen::Vector2d to_n = toroidal(s.position, n.position);
          if (left < -problem.options.match.time_s || to_n.norm() > fastest * std::max(0.0, left) + 2 * problem.max_extent_m) continue;
          s.parent = i;
          // Nearer first; then facing it.
          s.rank = to_n.norm() + (to_n.norm() > 1e-6 ? std::abs(wrap_angle(std::atan2(to_n.y(), to_n.x()) - s.heading)) : 0.0);
          steps.push_back(s);
          const std::size_t id = steps.size() - 1;
          next.push_back(id);
          // Does a bridge join this exit to n?
          for (const auto& [bk, bf] : singles) {
            const Fragment& br = problem.library.types[bk].fragments[bf];
            if (br.entry_class != s.pose_class || br.exit_class != n.pose_class) continue;
            const EndPoint here{s.position, s.heading, s.time, s.pose_class};
            const auto fit = bridge_fit(br, false, here, s.position + to_n, target, n.heading, problem.options.match);
            if (fit) {
              plans.emplace_back(fit->second, id);
              break;
            }
          }
        }
      }
      // The best `beam` of the next level, one per cell of 0.5 m, 30° and pose class.
      std::sort(next.begin(), next.end(), [&](std::size_t a, std::size_t b) {
        return std::tie(steps[a].rank, a) < std::tie(steps[b].rank, b);
      });
      std::map<std::tuple<long, long, long, std::size_t>, bool> taken;
      level.clear();
      for (std::size_t i : next) {
        const Step& s = steps[i];
        const auto key = std::make_tuple(std::lround(s.position.x() * 2), std::lround(s.position.y() * 2),
                                         std::lround(s.heading * 6 / 3.14159265358979), s.pose_class);
        if (taken[key]) continue;
        taken[key] = true;
        level.push_back(i);
        if (level.size() == beam) break;
      }
    }
    std::sort(plans.begin(), plans.end());
    for (const auto& plan : plans) {
      std::vector<std::size_t> path;
      for (std::size_t i = plan.second; i != 0; i = steps[i].parent) path.push_back(i);
      std::reverse(path.begin(), path.end());
      // Applied patch by patch, each placed on the actual exit.
      std::vector<std::uint32_t> placed;
      FragmentRef at = exit;
      bool fits = true;
      for (std::size_t i : path) {
        if (report_.search_steps >= o.max_steps) return false;
        const LiveInstance& x = state_.at(at.instance);
        const EndPoint e = problem.end_point(x.type, x.paths, at.fragment, true);
        const Placement& planned = steps[i].placement;
        const Fragment& fr = problem.library.types[planned.type].fragments[planned.fragment];
        const Step actual = follow(Step{e.position, e.heading, e.time, e.pose_class, 0, {}, 0}, planned.type, planned.fragment, fr);
        std::uint32_t id = 0;
        if (!place(actual.placement, at, 1, false, &id)) {
          fits = false;
          break;
        }
        placed.push_back(id);
        at = {id, planned.fragment};
      }
      if (fits && one(at, 1)) return true;
      for (auto it = placed.rbegin(); it != placed.rend(); ++it) state_.remove(*it);
    }
  }
  return false;
}

}  // namespace throng::tiling
