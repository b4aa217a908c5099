#include <throng/core/assignment.h>
#include <throng/core/errors.h>
#include <throng/stitch/boundary.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <string>

namespace throng::stitch {
namespace {

using Index = Eigen::Index;

constexpr int max_rounds = 30;               // per start
constexpr double same_start = 1e-6;          // radians: starts closer than this are one
constexpr double falling = 1e-12;            // relative decrease that counts as still improving
constexpr double better_than_earlier = 1e-9; // relative margin a later fit needs to replace an earlier one

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
  Eigen::MatrixXd cost(n, n);
  for (Index i = 0; i < n; ++i) {
    const Eigen::RowVector2d a = last_of_first.row(i) - shift_a;
    for (Index k = 0; k < n; ++k) cost(i, k) = (a - (first_of_second.row(k) - shift_b)).norm();
  }
  const Assignment assignment = solve_assignment(cost, "stitch matching cost");
  Correspondence c;
  c.total_distance = assignment.cost;
  c.second_of_first.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    c.second_of_first[static_cast<std::size_t>(i)] = static_cast<std::size_t>(assignment.column_of_row[static_cast<std::size_t>(i)]);
  }
  return c;
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

  double best = std::numeric_limits<double>::infinity();
  std::set<std::vector<std::size_t>> refined;  // matchings already aligned (from any start): same continuation
  Points matched(n, 2), moved(n, 2);
  for (std::size_t s = 0; s < angles.size(); ++s) {
    Eigen::Isometry2d m = Eigen::Isometry2d::Identity();
    if (s > 0 || matching == Matching::centred) {
      m.linear() = Eigen::Rotation2Dd(angles[s]).toRotationMatrix();
      m.translation() = centre_a - m.linear() * centre_b;
    }
    ++fit.starts;
    double previous = std::numeric_limits<double>::infinity();
    for (int round = 0; round < max_rounds; ++round) {
      for (Index i = 0; i < n; ++i) moved.row(i) = (m * Eigen::Vector2d(first_of_second.row(i).transpose())).transpose();
      Correspondence c = match_boundary(last_of_first, moved, Matching::world);
      ++fit.rounds;
      if (!refined.insert(c.second_of_first).second) break;
      for (Index i = 0; i < n; ++i) matched.row(i) = first_of_second.row(static_cast<Index>(c.second_of_first[static_cast<std::size_t>(i)]));
      m = align(matched, last_of_first, alignment);
      const double cost = summed_distance(last_of_first, matched, m);
      c.total_distance = cost;
      if (cost < best * (1 - better_than_earlier)) {
        best = cost;
        fit.correspondence = std::move(c);
        fit.alignment = m;
        fit.start_rotation = angles[s];
      }
      if (!(cost < previous * (1 - falling))) break;
      previous = cost;
    }
  }
  return fit;
}

}  // namespace throng::stitch
