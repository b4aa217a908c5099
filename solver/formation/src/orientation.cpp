#include "orientation.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <cmath>
#include <limits>
#include <numbers>

namespace throng::formation {
namespace {

// Principal axes (columns, largest variance first) and variances of the rows of `a` (already centred).
void principal_axes(const Eigen::MatrixXd& a, Eigen::MatrixXd& axes, Eigen::VectorXd& variances) {
  const Eigen::MatrixXd covariance = a.transpose() * a;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(covariance);
  axes = solver.eigenvectors().rowwise().reverse();
  variances = solver.eigenvalues().reverse();
}

bool nearly_isotropic(const Eigen::VectorXd& variances, double tolerance) {
  const double total = variances.sum();
  if (!(total > 0)) return true;
  for (Eigen::Index i = 0; i + 1 < variances.size(); ++i) {
    // A zero variance pair (collinear points in 3-D) is a degenerate plane whose axes are undefined too.
    if (variances(i) - variances(i + 1) <= tolerance * total) return true;
  }
  return false;
}

}  // namespace

Eigen::MatrixXd best_rotation(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const Eigen::MatrixXd m = a.transpose() * b;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::MatrixXd u = svd.matrixU();
  const Eigen::MatrixXd v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0) u.col(u.cols() - 1) *= -1.0;
  return u * v.transpose();
}

std::vector<Eigen::MatrixXd> principal_axis_rotations(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                                      double isotropy_tolerance) {
  Eigen::MatrixXd axes_a, axes_b;
  Eigen::VectorXd var_a, var_b;
  principal_axes(a, axes_a, var_a);
  principal_axes(b, axes_b, var_b);
  if (nearly_isotropic(var_a, isotropy_tolerance) || nearly_isotropic(var_b, isotropy_tolerance)) return {};
  // Rows of a·O have axes Oᵀ·axes_a; match them to axes_b up to signs: O = axes_a D axes_bᵀ.
  const auto d = static_cast<int>(a.cols());
  std::vector<Eigen::MatrixXd> out;
  for (int mask = 0; mask < (1 << d); ++mask) {
    Eigen::VectorXd signs(d);
    for (int i = 0; i < d; ++i) signs(i) = (mask >> i) & 1 ? -1.0 : 1.0;
    const Eigen::MatrixXd o = axes_a * signs.asDiagonal() * axes_b.transpose();
    if (o.determinant() > 0) out.push_back(o);
  }
  return out;
}

std::vector<Eigen::MatrixXd> keyframe_orientations(const std::vector<Eigen::MatrixXd>& centred,
                                                   OrientationAlignment alignment, double isotropy_tolerance) {
  const auto d = centred.front().cols();
  std::vector<Eigen::MatrixXd> out(centred.size(), Eigen::MatrixXd::Identity(d, d));
  if (alignment == OrientationAlignment::none) return out;
  Eigen::MatrixXd previous = centred.front();  // body_{k−1}
  for (std::size_t k = 1; k < centred.size(); ++k) {
    const Eigen::MatrixXd& shape = centred[k];
    if (shape.squaredNorm() == 0.0 || previous.squaredNorm() == 0.0) {  // a single point: no orientation
      previous = shape;
      continue;
    }
    std::vector<Eigen::MatrixXd> candidates;
    if (alignment == OrientationAlignment::pca) candidates = principal_axis_rotations(shape, previous, isotropy_tolerance);
    if (candidates.empty()) candidates.push_back(best_rotation(shape, previous));
    double best = std::numeric_limits<double>::infinity();
    for (const Eigen::MatrixXd& o : candidates) {
      const double cost = (shape * o - previous).squaredNorm();
      if (cost < best) {
        best = cost;
        out[k] = o;
      }
    }
    previous = shape * out[k];
  }
  return out;
}

OrientationTrack::OrientationTrack(std::vector<Eigen::MatrixXd> rotations) : rotations_(std::move(rotations)) {
  if (rotations_.front().rows() != 2) return;
  for (std::size_t k = 0; k < rotations_.size(); ++k) {
    const double raw = std::atan2(rotations_[k](1, 0), rotations_[k](0, 0));
    if (k == 0) {
      angles_.push_back(raw);
    } else {
      double step = std::remainder(raw - angles_.back(), 2 * std::numbers::pi);
      if (step <= -std::numbers::pi) step += 2 * std::numbers::pi;
      angles_.push_back(angles_.back() + step);
    }
  }
}

Eigen::MatrixXd OrientationTrack::evaluate(const ControlKeys& keys, const SplineWeights& w) const {
  const auto& k = keys.keys;
  if (!angles_.empty()) {
    double angle = 0.0;
    for (int i = 0; i < 4; ++i) angle += w.c[static_cast<std::size_t>(i)] * angles_[static_cast<std::size_t>(k[static_cast<std::size_t>(i)])];
    return Eigen::Rotation2Dd(angle).toRotationMatrix();
  }
  // Eq. 5 in cumulative form (as the eigenbases, spectral_group.cpp): with the rotations between consecutive
  // keyframes R0 = O_n O_{n−1}ᵀ, R1 = O_{n+1} O_nᵀ, R2 = O_{n+2} O_{n+1}ᵀ (each its principal, shortest turn),
  // O(t) = R2^{c2} R1^{c1+c2} R0^{−c−1} O_n.
  auto key = [&](int i) -> Eigen::Matrix3d { return rotations_[static_cast<std::size_t>(k[static_cast<std::size_t>(i)])]; };
  auto power = [](const Eigen::Matrix3d& r, double c) {
    Eigen::AngleAxisd p(r);
    p.angle() *= c;
    return p.toRotationMatrix();
  };
  Eigen::Matrix3d result = key(1);
  result = power(key(1) * key(0).transpose(), -w.c[0]) * result;
  result = power(key(2) * key(1).transpose(), w.c[2] + w.c[3]) * result;
  result = power(key(3) * key(2).transpose(), w.c[3]) * result;
  return result;
}

}  // namespace throng::formation
