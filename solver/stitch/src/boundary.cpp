#include <throng/core/planar_assignment.h>
#include <throng/core/planar_index.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/stitch/boundary.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <string>

namespace throng::stitch {
namespace {

using Index = Eigen::Index;

constexpr int max_rounds = 30;               // per start
constexpr double same_start = 0.175;         // radians (10°): starts closer than this are one
constexpr double falling = 1e-12;            // relative decrease that counts as still improving
constexpr double better_than_earlier = 1e-9; // relative margin a later fit needs to replace an earlier one
constexpr double screen_margin = 0.25;       // screened fits within 25 % of the best are refined exactly

Eigen::Vector2d centroid(const Eigen::Ref<const Points>& p) { return p.colwise().mean().transpose(); }

// The angle of the principal axis of `p` (radians), or NaN when its points are all at one place.
double principal_angle(const Eigen::Ref<const Points>& p) {
  const Points centred = p.rowwise() - p.colwise().mean();
  const Eigen::Matrix2d covariance = centred.transpose() * centred;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance);
  if (!(eigen.eigenvalues()(1) > 0)) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector2d axis = eigen.eigenvectors().col(1);
  return std::atan2(axis.y(), axis.x());
}

// The angle difference wrapped into (−π, π].
double wrapped(double angle) {
  const double w = std::remainder(angle, 2 * std::numbers::pi);
  return w <= -std::numbers::pi ? w + 2 * std::numbers::pi : w;
}

double summed_distance(const Eigen::Ref<const Points>& to, const Points& from, const Eigen::Isometry2d& m) {
  double sum = 0;
  for (Index i = 0; i < to.rows(); ++i) sum += (to.row(i).transpose() - m * Eigen::Vector2d(from.row(i).transpose())).norm();
  return sum;
}

}  // namespace

namespace {

// The exact matching of two point sets (same count), started from `state` when given (see assign_planar).
Correspondence matching_of(const Eigen::Ref<const Points>& a, const Eigen::Ref<const Points>& b,
                           PlanarAssignmentState* state) {
  const Assignment assignment = assign_planar(a, b, "stitch matching", state);
  Correspondence c;
  c.total_distance = assignment.cost;
  c.second_of_first.resize(static_cast<std::size_t>(a.rows()));
  for (Index i = 0; i < a.rows(); ++i) {
    c.second_of_first[static_cast<std::size_t>(i)] = static_cast<std::size_t>(assignment.column_of_row[static_cast<std::size_t>(i)]);
  }
  return c;
}

}  // namespace

Correspondence match_boundary(const Eigen::Ref<const Points>& last_of_first, const Eigen::Ref<const Points>& first_of_second,
                              Matching matching) {
  const Index n = last_of_first.rows();
  if (first_of_second.rows() != n) {
    throw InputError("matching: " + std::to_string(n) + " agents against " + std::to_string(first_of_second.rows()));
  }
  Eigen::RowVector2d shift_a(0, 0), shift_b(0, 0);
  if (matching == Matching::centred && n > 0) {
    shift_a = last_of_first.colwise().mean();
    shift_b = first_of_second.colwise().mean();
  }
  return matching_of(last_of_first.rowwise() - shift_a, first_of_second.rowwise() - shift_b, nullptr);
}

Eigen::Isometry2d align(const Eigen::Ref<const Points>& from, const Eigen::Ref<const Points>& to, Alignment alignment) {
  Eigen::Isometry2d m = Eigen::Isometry2d::Identity();
  if (alignment == Alignment::none || from.rows() == 0) return m;
  if (alignment == Alignment::translation) {
    m.translation() = centroid(to) - centroid(from);
    return m;
  }
  // Eigen::umeyama without scaling: the least-squares rotation + translation (reflections excluded).
  const Eigen::Matrix3d h = Eigen::umeyama(Eigen::MatrixXd(from.transpose()), Eigen::MatrixXd(to.transpose()), false);
  m.linear() = h.topLeftCorner<2, 2>();
  m.translation() = h.topRightCorner<2, 1>();
  // Points all at one place determine no rotation: umeyama then returns the identity rotation, kept as is.
  return m;
}

namespace {

// From the start `m`: pair each point of `to` with its nearest point of m·from (not a matching: a point may be
// chosen twice), align those pairs, repeat until the pairs repeat or the summed distance stops falling. A cheap
// iteration, O(n log n) a round (a k-d tree of `from`).
struct NearestFit {
  double score = std::numeric_limits<double>::infinity();  // least summed distance reached
  Eigen::Isometry2d alignment = Eigen::Isometry2d::Identity();  // where it was reached
};

NearestFit nearest_fit(const Eigen::Ref<const Points>& to, const Eigen::Ref<const Points>& from, Eigen::Isometry2d m,
                       Alignment alignment) {
  const Index n = to.rows();
  const PlanarIndex index(from);  // m is rigid: the nearest m·from of a point is m·(the nearest from of m⁻¹·point)
  std::vector<Index> nearest(static_cast<std::size_t>(n)), previous_pairs;
  Points paired(n, 2);
  NearestFit best;
  double previous = best.score;
  for (int round = 0; round < max_rounds; ++round) {
    const Eigen::Isometry2d back = m.inverse(Eigen::Isometry);
    for (Index i = 0; i < n; ++i) {
      const auto at = static_cast<Index>(index.nearest(back * Eigen::Vector2d(to.row(i).transpose())));
      nearest[static_cast<std::size_t>(i)] = at;
      paired.row(i) = from.row(at);
    }
    if (nearest == previous_pairs) break;
    previous_pairs = nearest;
    m = align(paired, to, alignment);
    const double cost = summed_distance(to, paired, m);
    if (cost < best.score) best = {cost, m};
    if (!(cost < previous * (1 - falling))) break;
    previous = cost;
  }
  return best;
}

}  // namespace

BoundaryFit fit_boundary(const Eigen::Ref<const Points>& last_of_first, const Eigen::Ref<const Points>& first_of_second,
                         const Headings& headings, Matching matching, Alignment alignment) {
  const Index n = last_of_first.rows();
  if (first_of_second.rows() != n) {
    throw InputError("matching: " + std::to_string(n) + " agents against " + std::to_string(first_of_second.rows()));
  }
  BoundaryFit fit;
  if (alignment == Alignment::none || n == 0) {
    fit.correspondence = match_boundary(last_of_first, first_of_second, matching);
    fit.starts = fit.rounds = 1;
    return fit;
  }

  // Start rotations (radians, about G′'s centroid), the option's own frame first.
  std::vector<double> angles{0.0};
  auto add = [&](double angle) {
    if (!std::isfinite(angle)) return;
    for (double a : angles) {
      if (std::abs(wrapped(angle - a)) < same_start) return;
    }
    angles.push_back(wrapped(angle));
  };
  if (alignment == Alignment::rigid) {
    if (headings.first.norm() > 0 && headings.second.norm() > 0) {
      add(std::atan2(headings.first.y(), headings.first.x()) - std::atan2(headings.second.y(), headings.second.x()));
    }
    const double axes = principal_angle(last_of_first) - principal_angle(first_of_second);
    add(axes);
    add(axes + std::numbers::pi);
  }
  const Eigen::Vector2d centre_a = centroid(last_of_first), centre_b = centroid(first_of_second);
  auto start = [&](std::size_t s) {
    Eigen::Isometry2d m = Eigen::Isometry2d::Identity();
    if (s > 0 || matching == Matching::centred) {
      m.linear() = Eigen::Rotation2Dd(angles[s]).toRotationMatrix();
      m.translation() = centre_a - m.linear() * centre_b;
    }
    return m;
  };
  fit.starts = angles.size();

  // Screening: every start's nearest-neighbour fit. Then the paper's single matching and alignment in the
  // option's own frame (one round, so the result is never farther than it), and the exact refinement from the
  // best-scoring nearest-neighbour fit.
  std::vector<Eigen::Isometry2d> exact{start(0)};
  std::vector<double> exact_angle{0.0};
  std::vector<int> exact_rounds{alignment == Alignment::rigid ? 1 : max_rounds};
  // How well an alignment continues G's heading: the cosine between G's last step and the aligned G′'s first
  // (0 when either group stands still: then it decides nothing).
  const bool moving = headings.first.norm() > 0 && headings.second.norm() > 0;
  auto continuity = [&](const Eigen::Isometry2d& m) {
    if (!moving) return 0.0;
    return headings.first.normalized().dot((m.linear() * headings.second).normalized());
  };
  // Of fits (score, continuity), those that keep the group walking forward (within 90° of G's heading) when
  // both groups move and any does, else all.
  auto forward = [&](const std::vector<double>& cont) {
    std::vector<std::size_t> pool;
    for (std::size_t k = 0; k < cont.size(); ++k) {
      if (!moving || cont[k] >= 0) pool.push_back(k);
    }
    if (pool.empty()) {
      for (std::size_t k = 0; k < cont.size(); ++k) pool.push_back(k);
    }
    return pool;
  };
  // The least score of the pool (ties keep the earlier).
  auto least = [&](const std::vector<double>& score, const std::vector<std::size_t>& pool) {
    std::size_t chosen = pool.front();
    for (std::size_t k : pool) {
      if (score[k] < score[chosen] * (1 - better_than_earlier)) chosen = k;
    }
    return chosen;
  };
  if (alignment == Alignment::rigid) {
    std::vector<NearestFit> screened;
    std::vector<double> score, cont;
    for (std::size_t s = 0; s < angles.size(); ++s) {
      screened.push_back(nearest_fit(last_of_first, first_of_second, start(s), alignment));
      score.push_back(screened.back().score);
      cont.push_back(continuity(screened.back().alignment));
    }
    // Refined exactly: the forward fits scoring within screen_margin of the best of them (the screen is only a
    // proxy of the matching's distance), one per rotation (10°).
    const std::vector<std::size_t> pool = forward(cont);
    const double bound = score[least(score, pool)] * (1 + screen_margin);
    std::vector<double> rotations;
    for (std::size_t k : pool) {
      if (!(score[k] <= bound)) continue;
      const double r = std::atan2(screened[k].alignment.linear()(1, 0), screened[k].alignment.linear()(0, 0));
      if (std::any_of(rotations.begin(), rotations.end(), [&](double q) { return std::abs(wrapped(r - q)) < same_start; })) continue;
      rotations.push_back(r);
      exact.push_back(screened[k].alignment);
      exact_angle.push_back(angles[k]);
      exact_rounds.push_back(max_rounds);
    }
  }

  // Each run's best fit, the runs side by side (each its own matchings, so the fits are the same whatever the
  // thread count: the paper's round, far apart in the option's frame, is the slowest matching, and the refined
  // runs go on beside it); then the choice between them.
  std::vector<BoundaryFit> runs(exact.size());
  std::vector<double> run_cost(exact.size(), std::numeric_limits<double>::infinity()), run_cont(exact.size(), 0.0);
  std::vector<std::size_t> run_rounds(exact.size(), 0);
  parallel_for(exact.size(), 1, [&](std::size_t begin, std::size_t end) {
    Points matched(n, 2), moved(n, 2);
    for (std::size_t s = begin; s < end; ++s) {
      PlanarAssignmentState state;  // each matching of the run starts from the one before (the agents moved a little)
      Eigen::Isometry2d m = exact[s];
      std::set<std::vector<std::size_t>> refined;  // matchings this run has aligned: a repeat ends it
      double& best = run_cost[s];
      BoundaryFit& fit_s = runs[s];
      double previous = std::numeric_limits<double>::infinity();
      for (int round = 0; round < exact_rounds[s]; ++round) {
        for (Index i = 0; i < n; ++i) moved.row(i) = (m * Eigen::Vector2d(first_of_second.row(i).transpose())).transpose();
        Correspondence c = matching_of(last_of_first, moved, &state);
        ++run_rounds[s];
        if (!refined.insert(c.second_of_first).second) break;
        for (Index i = 0; i < n; ++i) matched.row(i) = first_of_second.row(static_cast<Index>(c.second_of_first[static_cast<std::size_t>(i)]));
        m = align(matched, last_of_first, alignment);
        const double cost = summed_distance(last_of_first, matched, m);
        c.total_distance = cost;
        if (cost < best * (1 - better_than_earlier)) {
          best = cost;
          fit_s.correspondence = std::move(c);
          fit_s.alignment = m;
          fit_s.start_rotation = exact_angle[s];
          run_cont[s] = continuity(m);
        }
        if (!(cost < previous * (1 - falling))) break;
        previous = cost;
      }
    }
  });
  for (std::size_t r : run_rounds) fit.rounds += r;
  const std::size_t chosen = least(run_cost, forward(run_cont));
  runs[chosen].starts = fit.starts;
  runs[chosen].rounds = fit.rounds;
  return runs[chosen];
}

}  // namespace throng::stitch
