#include "matching.h"

#include "orientation.h"

#include <throng/core/assignment.h>

#include <limits>
#include <numeric>

namespace throng::formation {
namespace {
constexpr int max_refinements = 20;
}  // namespace

std::vector<std::vector<int>> match_keyframes(const std::vector<Eigen::MatrixXd>& positions,
                                              OrientationAlignment alignment, double isotropy_tolerance) {
  const Eigen::Index n = positions.front().rows();
  const Eigen::Index d = positions.front().cols();
  std::vector<std::vector<int>> out(positions.size(), std::vector<int>(static_cast<std::size_t>(n)));
  std::iota(out[0].begin(), out[0].end(), 0);
  Eigen::MatrixXd previous = positions[0].rowwise() - positions[0].colwise().mean();
  for (std::size_t k = 1; k < positions.size(); ++k) {
    const Eigen::MatrixXd current = positions[k].rowwise() - positions[k].colwise().mean();
    std::vector<Eigen::MatrixXd> candidates{Eigen::MatrixXd::Identity(d, d)};
    if (alignment != OrientationAlignment::none) {
      for (Eigen::MatrixXd& o : principal_axis_rotations(current, previous, isotropy_tolerance)) candidates.push_back(std::move(o));
    }
    double best = std::numeric_limits<double>::infinity();
    Eigen::MatrixXd best_matched;
    for (const Eigen::MatrixXd& start : candidates) {
      // From this starting rotation: assign, re-fit the rotation to the assignment (least squares), repeat while
      // the cost falls (an assignment-based iterative closest point).
      Eigen::MatrixXd o = start;
      double cost_here = std::numeric_limits<double>::infinity();
      for (int iteration = 0; iteration < max_refinements; ++iteration) {
        const Eigen::MatrixXd turned = current * o;
        Eigen::MatrixXd cost(n, n);  // individual (row of previous) × row of keyframe k
        for (Eigen::Index c = 0; c < n; ++c)
          for (Eigen::Index r = 0; r < n; ++r) cost(r, c) = (previous.row(r) - turned.row(c)).squaredNorm();
        const Assignment a = solve_assignment(cost, "individual matching");
        if (!(a.cost < cost_here * (1.0 - 1e-12))) break;
        cost_here = a.cost;
        Eigen::MatrixXd matched(n, d);
        for (Eigen::Index i = 0; i < n; ++i) matched.row(i) = current.row(a.column_of_row[static_cast<std::size_t>(i)]);
        if (a.cost < best) {
          best = a.cost;
          out[k] = a.column_of_row;
          best_matched = matched;
        }
        if (alignment == OrientationAlignment::none) break;
        o = best_rotation(matched, previous);
      }
    }
    previous = std::move(best_matched);
  }
  return out;
}

}  // namespace throng::formation
