// Automatic placement between the outermost auxiliary lines (the paper's future work, §7), hexagonal rows
// across the course from its first point forward.
#include <throng/core/errors.h>
#include <throng/sketch/sketch.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>

#include "polyline.h"

namespace throng::sketch {
namespace {

// Agents already placed, hashed by cell (cell ≥ the largest spacing, so 3×3 cells hold every conflict).
class PlacedAgents {
 public:
  explicit PlacedAgents(double cell) : cell_(cell) {}

  [[nodiscard]] bool clear(const Eigen::Vector2d& p, double spacing) const {
    const auto [cx, cy] = cell_of(p);
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (const Entry& e : it->second) {
          const double allowed = std::max(spacing, e.spacing);
          // A tiny tolerance: slots built exactly `allowed` apart must not be rejected by rounding.
          if ((e.position - p).squaredNorm() < allowed * allowed * (1 - 1e-9)) return false;
        }
      }
    }
    return true;
  }

  void add(const Eigen::Vector2d& p, double spacing) {
    const auto [cx, cy] = cell_of(p);
    cells_[key(cx, cy)].push_back({p, spacing});
  }

 private:
  struct Entry {
    Eigen::Vector2d position;
    double spacing;
  };
  [[nodiscard]] std::pair<std::int64_t, std::int64_t> cell_of(const Eigen::Vector2d& p) const {
    return {static_cast<std::int64_t>(std::floor(p.x() / cell_)), static_cast<std::int64_t>(std::floor(p.y() / cell_))};
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return (static_cast<std::uint64_t>(x) << 32) ^ (static_cast<std::uint64_t>(y) & 0xffffffffULL);
  }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
};

bool clear_of_obstacles(const Scene& scene, const Eigen::Vector2d& p, double clearance) {
  for (const Obstacle& o : scene.obstacles) {
    if (distance_to(o, p, 0.0).signed_distance < clearance) return false;
  }
  return true;
}

}  // namespace

AgentParameters place_agents(const Course& course, std::size_t count, const Scene& scene, const Options& options) {
  validate(options);
  const std::vector<double> cumulative = detail::arc_lengths(course.main);
  const double length = cumulative.back();
  const double largest_spacing = *std::max_element(course.standard_distance.begin(), course.standard_distance.end());
  const double clearance = std::max(options.obstacle_distance_m, options.agent_radius_m);
  const double row_factor = std::sqrt(3.0) / 2.0;

  PlacedAgents placed(largest_spacing);
  std::vector<Eigen::Vector2d> start;
  std::vector<std::size_t> first_target;
  start.reserve(count);
  first_target.reserve(count);

  std::size_t row = 0;
  std::vector<std::size_t> order;
  for (double along = 0.0; start.size() < count && along <= length; ++row) {
    const detail::ArcPosition at = detail::locate(cumulative, along);
    const std::size_t k0 = at.segment, k1 = at.segment + 1;
    const double f = at.fraction;
    const Eigen::Vector2d centre = (1 - f) * course.main[k0] + f * course.main[k1];
    const Eigen::Vector2d t = (course.main[k1] - course.main[k0]).normalized();
    const Eigen::Vector2d normal(-t.y(), t.x());
    const double spacing = (1 - f) * course.standard_distance[k0] + f * course.standard_distance[k1];

    // Lateral extent of the band: outermost smoothed auxiliary points on each side (the main line if none).
    double left = 0, right = 0;
    for (std::size_t i = 0; i < course.auxiliary_count(); ++i) {
      const Eigen::Vector2d q = (1 - f) * course.smoothed[i][k0] + f * course.smoothed[i][k1];
      const double offset = normal.dot(q - centre);
      left = std::max(left, offset);
      right = std::min(right, offset);
    }
    // Slots s apart, centred; odd rows shifted by s/2 (one slot fewer) for a hexagonal packing.
    const auto across = static_cast<std::size_t>(std::floor((left - right) / spacing + 1e-9)) + 1;
    const bool shifted = row % 2 == 1 && across > 1;
    const std::size_t n = shifted ? across - 1 : across;
    const double mid = 0.5 * (left + right);
    // Centre outward (|2s − (n−1)| half-steps from the middle, then left to right), so a partly filled row
    // is centred on the band.
    order.resize(n);
    for (std::size_t s = 0; s < n; ++s) order[s] = s;
    const auto from_middle = [n](std::size_t s) {
      return std::abs(2 * static_cast<long>(s) - static_cast<long>(n - 1));
    };
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return from_middle(a) < from_middle(b); });

    const std::size_t target = f > 0 ? k1 : k0;
    for (std::size_t s : order) {
      if (start.size() == count) break;
      const double offset = mid + (static_cast<double>(s) - 0.5 * static_cast<double>(n - 1)) * spacing;
      const Eigen::Vector2d p = centre + offset * normal;
      if (!clear_of_obstacles(scene, p, clearance) || !placed.clear(p, spacing)) continue;
      placed.add(p, spacing);
      start.push_back(p);
      first_target.push_back(target);
    }
    along += spacing * row_factor;
  }
  if (start.size() < count) {
    std::ostringstream m;
    m << "sketch option agent_count = " << count << ": only " << start.size()
      << " agents fit between the auxiliary lines along the " << length
      << " m course at the standard distance (and clear of obstacles); give fewer agents, initial positions, "
         "or draw a wider or longer course";
    throw ConfigError(m.str());
  }
  AgentParameters agents = agent_parameters(course, start, options);
  agents.first_target = std::move(first_target);
  return agents;
}

}  // namespace throng::sketch
