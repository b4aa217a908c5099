#include "scenes.h"

#include "fixtures.h"

#include <throng/core/assignment.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <vector>

namespace throng::test {
namespace {

constexpr int groups = 35, subgroups = 6, members = 6;
constexpr double pi = std::numbers::pi;

using Points = std::vector<Eigen::Vector2d>;

// `count` points evenly spaced by arc length along a polyline (closed: back to the start).
Points along(const Points& line, int count, bool closed) {
  Points pts = line;
  if (closed) pts.push_back(line.front());
  double total = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) total += (pts[i] - pts[i - 1]).norm();
  const double step = total / (closed ? count : count - 1);
  Points out;
  for (int k = 0; k < count; ++k) {
    double s = k * step;
    std::size_t i = 1;
    while (i + 1 < pts.size() && s > (pts[i] - pts[i - 1]).norm()) {
      s -= (pts[i] - pts[i - 1]).norm();
      ++i;
    }
    const Eigen::Vector2d dir = (pts[i] - pts[i - 1]).normalized();
    out.push_back(pts[i - 1] + std::min(s, (pts[i] - pts[i - 1]).norm()) * dir);
  }
  return out;
}

Points circle(int count, double radius, Eigen::Vector2d centre, double phase = 0.0) {
  Points out;
  for (int k = 0; k < count; ++k)
    out.push_back(centre + radius * Eigen::Vector2d(std::cos(phase + 2 * pi * k / count), std::sin(phase + 2 * pi * k / count)));
  return out;
}

Points star_centres() {
  Points outline;
  for (int k = 0; k < 10; ++k) {
    const double r = k % 2 == 0 ? 60.0 : 26.0;
    const double a = pi / 2 + pi * k / 5;
    outline.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return along(outline, groups, true);
}

// A running figure: head (6 groups on a circle), then 29 groups along torso, arms and legs.
Points runner_centres() {
  Points out = circle(6, 8.0, {4.0, 80.0});
  const std::vector<Points> limbs{
      {{2.0, 66.0}, {0.0, 40.0}, {-4.0, 18.0}},        // torso
      {{-7.0, 56.0}, {-24.0, 44.0}, {-42.0, 54.0}},    // back arm
      {{9.0, 55.0}, {30.0, 44.0}, {50.0, 50.0}},       // front arm
      {{-10.0, 12.0}, {-28.0, -10.0}, {-52.0, -8.0}},  // back leg
      {{4.0, 10.0}, {26.0, -8.0}, {28.0, -40.0}}};     // front leg
  const int per_limb[5] = {5, 6, 6, 6, 6};
  for (std::size_t l = 0; l < limbs.size(); ++l)
    for (const Eigen::Vector2d& p : along(limbs[l], per_limb[l], false)) out.push_back(p);
  return out;
}

Points five_circles_centres() {
  Points out;
  const Eigen::Vector2d centres[5] = {{-36, 12}, {0, 12}, {36, 12}, {-18, -14}, {18, -14}};
  for (int c = 0; c < 5; ++c)
    for (const Eigen::Vector2d& p : circle(7, 13.0, centres[c], 0.3 * c)) out.push_back(p);
  return out;
}

// The 36 individuals of one group about its centre: six rings of six on a hexagon, turned by `turn`.
Points group_layout(double turn) {
  Points out;
  for (int s = 0; s < subgroups; ++s) {
    const Eigen::Vector2d centre(2.2 * std::cos(turn + 2 * pi * s / subgroups), 2.2 * std::sin(turn + 2 * pi * s / subgroups));
    for (const Eigen::Vector2d& p : circle(members, 0.7, centre, turn * 1.5 + s)) out.push_back(p);
  }
  return out;
}

}  // namespace

// The figure's points reordered so that group g goes to the point nearest its place in `previous` (minimum
// summed squared distance about the barycentres): a choreographer's assignment rather than an arbitrary one.
Points follow(const Points& previous, const Points& figure) {
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < figure.size(); ++i) {
    a += previous[i] / static_cast<double>(figure.size());
    b += figure[i] / static_cast<double>(figure.size());
  }
  Eigen::MatrixXd cost(static_cast<Eigen::Index>(figure.size()), static_cast<Eigen::Index>(figure.size()));
  for (std::size_t i = 0; i < figure.size(); ++i)
    for (std::size_t j = 0; j < figure.size(); ++j)
      cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = ((previous[i] - a) - (figure[j] - b)).squaredNorm();
  const Assignment assignment = solve_assignment(cost);
  Points out;
  for (std::size_t i = 0; i < figure.size(); ++i) out.push_back(figure[static_cast<std::size_t>(assignment.column_of_row[i])]);
  return out;
}

formation::Problem paper_crowd() {
  formation::Problem problem;
  Points figures[4] = {circle(groups, 45.0, {0, 0}), star_centres(), runner_centres(), five_circles_centres()};
  for (int k = 1; k < 4; ++k) figures[k] = follow(figures[k - 1], figures[k]);
  for (int k = 0; k < 4; ++k) {
    formation::Keyframe key;
    key.time_s = 11.0 * k;
    key.positions.resize(groups * subgroups * members, 2);
    for (int g = 0; g < groups; ++g) {
      const Points local = group_layout(0.4 * k + 0.1 * g);
      for (int i = 0; i < subgroups * members; ++i)
        key.positions.row(g * subgroups * members + i) = (figures[k][static_cast<std::size_t>(g)] + local[static_cast<std::size_t>(i)]).transpose();
    }
    problem.keyframes.push_back(std::move(key));
  }
  formation::Group root;
  root.name = "crowd";
  for (int g = 0; g < groups; ++g) {
    formation::Group group;
    group.name = "group " + std::to_string(g);
    for (int s = 0; s < subgroups; ++s) {
      formation::Group sub;
      sub.name = group.name + "." + std::to_string(s);
      for (int m = 0; m < members; ++m) sub.members.push_back((g * subgroups + s) * members + m);
      group.subgroups.push_back(std::move(sub));
    }
    root.subgroups.push_back(std::move(group));
  }
  problem.hierarchy = std::move(root);
  return problem;
}

formation::Problem flat_transition(int n) {
  formation::Problem problem;
  const double radius = 0.8 * std::sqrt(static_cast<double>(n));
  problem.keyframes.push_back(formation::Keyframe{0.0, scattered(n, radius, 1, 0.6), {}});
  problem.keyframes.push_back(formation::Keyframe{33.3, scattered(n, radius, 2, 0.6).rowwise() + Eigen::RowVector2d(10.0, 0.0), {}});
  return problem;
}

formation::Problem marching_crowd(int n, double& frame_rate_hz) {
  const double radius = 0.8 * std::sqrt(static_cast<double>(n));
  const Eigen::MatrixXd start = scattered(n, radius, 1, 0.6);
  const Eigen::Matrix2d stretch = Eigen::Vector2d(1.3, 1.0 / 1.3).asDiagonal();
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(20.0 * pi / 180.0).toRotationMatrix();
  const Eigen::MatrixXd end = (start * (turn * stretch).transpose()).rowwise() + Eigen::RowVector2d(20.0, 0.0);
  const double farthest = (end - start).rowwise().norm().maxCoeff();
  const double duration = farthest / 1.0;
  frame_rate_hz = 1000.0 / duration;
  formation::Problem problem;
  problem.keyframes.push_back(formation::Keyframe{0.0, start, {}});
  problem.keyframes.push_back(formation::Keyframe{duration, end, {}});
  return problem;
}

}  // namespace throng::test
