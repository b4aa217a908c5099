#include "collision.h"

#include <throng/core/parallel.h>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <limits>

namespace throng::formation {
namespace {

constexpr double over_relaxation = 0.5;

using Points = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
using ConstPoints = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;

// Uniform cell grid over one frame's points (counting sort; within a cell, indices ascending), for the pairs
// closer than `cell`. Flat in z when every point has the same z.
class NeighbourGrid {
 public:
  void build(const ConstPoints& p, double cell) {
    const auto n = static_cast<std::size_t>(p.rows());
    lo_ = p.colwise().minCoeff();
    const Eigen::RowVector3d hi = p.colwise().maxCoeff();
    cell_ = cell;
    // Keep the grid about the size of the crowd: a sparse crowd gets bigger cells.
    for (;;) {
      for (int a = 0; a < 3; ++a) dims_[a] = static_cast<long>(std::floor((hi(a) - lo_(a)) / cell_)) + 1;
      if (static_cast<double>(dims_[0]) * static_cast<double>(dims_[1]) * static_cast<double>(dims_[2]) <= 4.0 * static_cast<double>(n) + 64) break;
      cell_ *= 2;
    }
    const auto cells = static_cast<std::size_t>(dims_[0] * dims_[1] * dims_[2]);
    start_.assign(cells + 1, 0);
    cell_of_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      cell_of_[i] = index(coords(p.row(static_cast<Eigen::Index>(i))));
      ++start_[cell_of_[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
    order_.resize(n);
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) order_[fill[cell_of_[i]]++] = static_cast<int>(i);
  }

  // Calls visit(j) for every j in the cells around point x (including i itself), in a fixed order.
  template <class Visit>
  void around(const Eigen::RowVector3d& x, Visit&& visit) const {
    const std::array<long, 3> c = coords(x);
    for (long dz = -1; dz <= 1; ++dz) {
      const long z = c[2] + dz;
      if (z < 0 || z >= dims_[2]) continue;
      for (long dy = -1; dy <= 1; ++dy) {
        const long y = c[1] + dy;
        if (y < 0 || y >= dims_[1]) continue;
        for (long dx = -1; dx <= 1; ++dx) {
          const long xx = c[0] + dx;
          if (xx < 0 || xx >= dims_[0]) continue;
          const std::size_t cell = index({xx, y, z});
          for (std::size_t k = start_[cell]; k < start_[cell + 1]; ++k) visit(order_[k]);
        }
      }
    }
  }

 private:
  std::array<long, 3> coords(const Eigen::RowVector3d& x) const {
    std::array<long, 3> c{};
    for (int a = 0; a < 3; ++a)
      c[static_cast<std::size_t>(a)] = std::clamp(static_cast<long>(std::floor((x(a) - lo_(a)) / cell_)), 0L, dims_[a] - 1);
    return c;
  }
  std::size_t index(const std::array<long, 3>& c) const {
    return static_cast<std::size_t>((c[2] * dims_[1] + c[1]) * dims_[0] + c[0]);
  }

  Eigen::RowVector3d lo_;
  double cell_ = 1.0;
  long dims_[3] = {1, 1, 1};
  std::vector<std::size_t> start_, cell_of_;
  std::vector<int> order_;
};

// Unit direction from j to i; coincident points separate along x by index order (deterministic).
Eigen::RowVector3d away(const Eigen::RowVector3d& xi, const Eigen::RowVector3d& xj, int i, int j, double& distance) {
  const Eigen::RowVector3d diff = xi - xj;
  distance = diff.norm();
  if (distance > 0) return diff / distance;
  return Eigen::RowVector3d(i < j ? -1.0 : 1.0, 0.0, 0.0);
}

void simulate_social_forces(std::vector<double>& positions, std::size_t n, const std::vector<double>& times,
                            const CollisionOptions& o, Progress& progress) {
  const std::size_t frames = times.size();
  const std::vector<double> path = positions;  // the goals
  const auto rows = static_cast<Eigen::Index>(n);
  auto frame = [&](const std::vector<double>& v, std::size_t f) { return ConstPoints(v.data() + f * n * 3, rows, 3); };
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> x = frame(path, 0);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> v = (frame(path, 1) - frame(path, 0)) / (times[1] - times[0]);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> force(rows, 3);
  const double reach = o.min_distance_m + 6.0 * o.repulsion_range_m;  // exp(−6) ≈ 0.25 % of A beyond
  NeighbourGrid grid;
  for (std::size_t f = 0; f + 1 < frames; ++f) {
    const double span = times[f + 1] - times[f];
    const auto steps = static_cast<int>(std::ceil(span / o.time_step_s - 1e-9));
    const double h = span / steps;
    const auto p0 = frame(path, f), p1 = frame(path, f + 1);
    const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> path_velocity = (p1 - p0) / span;
    for (int s = 0; s < steps; ++s) {
      const double along = static_cast<double>(s) / steps;
      grid.build(ConstPoints(x.data(), rows, 3), reach);
      parallel_for(n, 64, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          const auto ii = static_cast<Eigen::Index>(i);
          const Eigen::RowVector3d goal = p0.row(ii) + along * (p1.row(ii) - p0.row(ii));
          const Eigen::RowVector3d desired = path_velocity.row(ii) + (goal - x.row(ii)) / o.tracking_time_s;
          Eigen::RowVector3d total = (desired - v.row(ii)) / o.relaxation_time_s;
          grid.around(x.row(ii), [&](int j) {
            if (j == static_cast<int>(i)) return;
            double d = 0.0;
            const Eigen::RowVector3d dir = away(x.row(ii), x.row(j), static_cast<int>(i), j, d);
            if (d < reach)
              total += o.repulsion_strength_m_per_s2 * std::exp((o.min_distance_m - d) / o.repulsion_range_m) * dir;
          });
          force.row(ii) = total;
        }
      });
      v += h * force;
      x += h * v;
    }
    Points(positions.data() + (f + 1) * n * 3, rows, 3) = x;
    progress.update(0.6 * static_cast<double>(f + 1) / static_cast<double>(frames - 1), "formation collisions");
  }
}

// Each coordinate path: min Σ (x_f − y_f)² + λ Σ (x_{f−1} − 2x_f + x_{f+1})² over the free frames, pinned frames
// held at `pins` values. λ = (smoothing time · frame rate)⁴ puts the filter's cut-off near the smoothing time.
void smooth(std::vector<double>& positions, const std::vector<double>& pins, std::size_t n,
            const std::vector<double>& times, const std::vector<char>& pinned, double smoothing_time_s) {
  const std::size_t frames = times.size();
  if (frames < 3) return;
  const double rate = static_cast<double>(frames - 1) / (times.back() - times.front());
  const double lambda = std::pow(smoothing_time_s * rate, 4.0);
  std::vector<int> free_index(frames, -1);
  int free_count = 0;
  for (std::size_t f = 0; f < frames; ++f)
    if (!pinned[f]) free_index[f] = free_count++;
  if (free_count == 0) return;
  // A = I + λ DᵀD on the free frames; pinned frames move to the right-hand side.
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<std::vector<std::pair<std::size_t, double>>> pinned_terms(static_cast<std::size_t>(free_count));
  for (std::size_t f = 0; f < frames; ++f)
    if (!pinned[f]) entries.emplace_back(free_index[f], free_index[f], 1.0);
  for (std::size_t c = 1; c + 1 < frames; ++c) {
    const std::size_t idx[3] = {c - 1, c, c + 1};
    const double coef[3] = {1.0, -2.0, 1.0};
    for (int a = 0; a < 3; ++a) {
      if (pinned[idx[a]]) continue;
      for (int b = 0; b < 3; ++b) {
        const double value = lambda * coef[a] * coef[b];
        if (pinned[idx[b]]) {
          pinned_terms[static_cast<std::size_t>(free_index[idx[a]])].emplace_back(idx[b], value);
        } else {
          entries.emplace_back(free_index[idx[a]], free_index[idx[b]], value);
        }
      }
    }
  }
  Eigen::SparseMatrix<double> a(free_count, free_count);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(a);
  const std::size_t columns = n * 3;
  parallel_for(columns, 16, [&](std::size_t begin, std::size_t end) {
    Eigen::VectorXd rhs(free_count);
    for (std::size_t col = begin; col < end; ++col) {
      for (std::size_t f = 0; f < frames; ++f) {
        if (pinned[f]) continue;
        double value = positions[f * columns + col];
        for (const auto& [pf, w] : pinned_terms[static_cast<std::size_t>(free_index[f])]) value -= w * pins[pf * columns + col];
        rhs(free_index[f]) = value;
      }
      const Eigen::VectorXd x = solver.solve(rhs);
      for (std::size_t f = 0; f < frames; ++f)
        positions[f * columns + col] = pinned[f] ? pins[f * columns + col] : x(free_index[f]);
    }
  });
}

// Gauss–Seidel projection of one frame to the minimum distance; returns false if sweeps ran out. A pair counts
// as too close below (1 − 1e-7)·min_distance. It is pushed apart along its separation in `guide` (the
// social-force simulation, whose individuals pass each other on a side that changes smoothly from frame to
// frame), so that neighbouring frames, projected independently, resolve a contact the same way instead of
// jumping between sides; along its current separation when the guide has none. Over-relaxed: a pair short by δ
// ends (1 + 1e-4)·min_distance + over_relaxation·δ apart, a cushion that keeps neighbouring pushes from undoing
// it (measured on the paper's 1,260-person crowd: half the sweeps). After the first sweep only the
// neighbourhoods of individuals that moved are searched again (the active set), so a sweep costs in proportion
// to the contacts, not to the crowd.
bool project_frame(Points p, const ConstPoints& guide, double min_distance, int sweeps) {
  const auto n = static_cast<int>(p.rows());
  const double too_close = min_distance * (1.0 - 1e-7);
  NeighbourGrid grid;
  std::vector<int> active(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) active[static_cast<std::size_t>(i)] = i;
  std::vector<char> moved(static_cast<std::size_t>(n), 0);
  std::vector<std::pair<int, int>> pairs;
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    grid.build(ConstPoints(p.data(), n, 3), min_distance);
    // Close pairs touching an active individual, each once, in a fixed order.
    pairs.clear();
    for (const int i : active) {
      grid.around(p.row(i), [&](int j) {
        if (j != i && (p.row(i) - p.row(j)).squaredNorm() < too_close * too_close) pairs.emplace_back(std::min(i, j), std::max(i, j));
      });
    }
    if (pairs.empty()) return true;
    std::sort(pairs.begin(), pairs.end());
    pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    std::fill(moved.begin(), moved.end(), 0);
    for (const auto& [i, j] : pairs) {
      const Eigen::RowVector3d r = p.row(i) - p.row(j);
      const double d = r.norm();
      if (d >= too_close) continue;  // already separated by an earlier push of this sweep
      const double target = min_distance * (1.0 + 1e-4) + over_relaxation * (min_distance - d);
      double guide_distance = 0.0;
      const Eigen::RowVector3d dir = away(guide.row(i), guide.row(j), i, j, guide_distance);
      Eigen::RowVector3d push;
      if (guide_distance > 1e-3 * min_distance) {
        // Move i by s·dir and j by −s·dir with |r + 2s·dir| = target: 4s² + 4s(r·dir) + |r|² − target² = 0.
        const double along = r.dot(dir);
        const double s = 0.5 * (-along + std::sqrt(along * along - r.squaredNorm() + target * target));
        push = s * dir;
      } else {
        double current = 0.0;
        push = 0.5 * (target - d) * away(p.row(i), p.row(j), i, j, current);
      }
      p.row(i) += push;
      p.row(j) -= push;
      moved[static_cast<std::size_t>(i)] = moved[static_cast<std::size_t>(j)] = 1;
    }
    active.clear();
    for (int i = 0; i < n; ++i)
      if (moved[static_cast<std::size_t>(i)]) active.push_back(i);
  }
  return false;
}

}  // namespace

CollisionReport closest_approach(const std::vector<double>& positions, std::size_t individuals, std::size_t frames,
                                 double min_distance_m) {
  struct Found {
    double distance = std::numeric_limits<double>::infinity();
    std::size_t frame = 0;
    Pair pair{0, 0};
  };
  std::vector<Found> per_frame(frames);
  const auto n = static_cast<Eigen::Index>(individuals);
  parallel_for(frames, 4, [&](std::size_t begin, std::size_t end) {
    NeighbourGrid grid;
    for (std::size_t f = begin; f < end; ++f) {
      const ConstPoints p(positions.data() + f * individuals * 3, n, 3);
      grid.build(p, std::max(min_distance_m, 1e-9) * 2.0);
      Found& best = per_frame[f];
      best.frame = f;
      for (Eigen::Index i = 0; i < n; ++i) {
        grid.around(p.row(i), [&](int j) {
          if (j <= i) return;
          const double d = (p.row(i) - p.row(j)).norm();
          if (d < best.distance) {
            best.distance = d;
            best.pair = {static_cast<int>(i), j};
          }
        });
      }
    }
  });
  CollisionReport report;
  report.closest_m = std::numeric_limits<double>::infinity();
  for (const Found& f : per_frame) {
    if (f.distance < report.closest_m) {
      report.closest_m = f.distance;
      report.closest_frame = f.frame;
      report.closest_pair = f.pair;
    }
  }
  report.satisfied = report.closest_m >= min_distance_m * (1.0 - 1e-6);
  return report;
}

CollisionReport avoid_collisions(std::vector<double>& positions, std::size_t individuals,
                                 const std::vector<double>& times, const std::vector<std::size_t>& pinned,
                                 const CollisionOptions& options, Progress& progress) {
  const std::size_t frames = times.size();
  const std::vector<double> spectral = positions;
  std::vector<char> is_pinned(frames, 0);
  for (std::size_t f : pinned) is_pinned[f] = 1;

  if (individuals >= 2 && frames >= 2) {
    simulate_social_forces(positions, individuals, times, options, progress);
    const std::vector<double> guide = positions;
    for (int pass = 0; pass < options.smoothing_passes; ++pass) {
      smooth(positions, spectral, individuals, times, is_pinned, options.smoothing_time_s);
      parallel_for(frames, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t f = begin; f < end; ++f) {
          if (is_pinned[f]) continue;
          const auto rows = static_cast<Eigen::Index>(individuals);
          (void)project_frame(Points(positions.data() + f * individuals * 3, rows, 3),
                              ConstPoints(guide.data() + f * individuals * 3, rows, 3), options.min_distance_m,
                              options.projection_sweeps);
        }
      });
      progress.update(0.6 + 0.35 * (pass + 1) / options.smoothing_passes, "formation collisions");
    }
  }
  CollisionReport report = closest_approach(positions, individuals, frames, options.min_distance_m);
  report.ran = true;
  for (std::size_t i = 0; i < positions.size(); i += 3) {
    const double shift = std::sqrt(std::pow(positions[i] - spectral[i], 2) + std::pow(positions[i + 1] - spectral[i + 1], 2) +
                                   std::pow(positions[i + 2] - spectral[i + 2], 2));
    report.largest_shift_m = std::max(report.largest_shift_m, shift);
  }
  progress.update(1.0, "formation collisions");
  return report;
}

}  // namespace throng::formation
