#include "rotation_power.h"

#include "dense.h"

#include <throng/core/union_find.h>
#include <throng/core/errors.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>

namespace throng::formation {
namespace {

constexpr double epsilon = std::numeric_limits<double>::epsilon();
// Separates conjugate eigenvalue pairs in the Hermitian matrix Sym(B) − iγ Skew(B): e^{±iθ} map to cos θ ± γ sin θ.
// Any irrational-looking value works; distinct angles collide only by accident (θ2 = 2·atan(γ) − θ1).
constexpr double gamma_separation = 0.6180339887498949;

// Level above which an off-diagonal entry of W = Vᵀ G V is a real coupling rather than rounding.
double coupling_level(Eigen::Index n) { return 32.0 * std::sqrt(static_cast<double>(std::max<Eigen::Index>(n, 1))) * epsilon; }

struct Plane {
  Eigen::VectorXd first, second;  // columns (2p, 2p+1) of Z
  double angle = 0.0;
};

// Groups of indices coupled (directly or through others) by entries of w above `level`.
std::vector<std::vector<int>> coupled_clusters(const Eigen::MatrixXd& w, double level) {
  const int n = static_cast<int>(w.rows());
  UnionFind sets(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < j; ++i) {
      if (std::abs(w(i, j)) > level || std::abs(w(j, i)) > level) sets.join(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
    }
  }
  std::vector<std::vector<int>> clusters(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) clusters[sets.root(static_cast<std::size_t>(i))].push_back(i);
  clusters.erase(std::remove_if(clusters.begin(), clusters.end(), [](const auto& c) { return c.empty(); }),
                 clusters.end());
  return clusters;
}

// Resolves one block B (m×m, orthogonal) of W into invariant planes and ±1 directions, in local coordinates.
void resolve_block(const Eigen::MatrixXd& b, double level, std::vector<Plane>& planes, Eigen::MatrixXd& plus,
                   Eigen::MatrixXd& minus) {
  const Eigen::Index m = b.rows();
  const Eigen::MatrixXd sym = 0.5 * (b + b.transpose());
  const Eigen::MatrixXd skew = 0.5 * (b - b.transpose());
  Eigen::MatrixXd local(m, 0);  // orthonormal plane vectors found so far
  if (m >= 2) {
    Eigen::MatrixXcd h = sym.cast<std::complex<double>>() - std::complex<double>(0.0, gamma_separation) * skew.cast<std::complex<double>>();
    Eigen::VectorXd values;
    dense::hermitian_eigen(h, values);
    const Eigen::MatrixXcd bc = b.cast<std::complex<double>>();
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::VectorXcd u = h.col(k);
      const std::complex<double> lambda = u.dot(bc * u);  // u* B u
      if (lambda.imag() <= level) continue;  // the conjugate of a plane already taken, or a ±1 direction
      // Re u and Im u span the invariant plane (even when u is mixed with its conjugate partner).
      Eigen::VectorXd x = u.real(), y = u.imag();
      x -= local * (local.transpose() * x);
      if (x.norm() < 0.5 / std::sqrt(2.0)) continue;
      x.normalize();
      y -= local * (local.transpose() * y);
      y -= x * x.dot(y);
      if (y.norm() < 0.5 / std::sqrt(2.0)) continue;
      y.normalize();
      local.conservativeResize(Eigen::NoChange, local.cols() + 2);
      local.col(local.cols() - 2) = x;
      local.col(local.cols() - 1) = y;
    }
  }
  const Eigen::Index p = local.cols();
  const Eigen::MatrixXd b_local = dense::multiply(b, false, local);
  for (Eigen::Index k = 0; k < p; k += 2) {
    const Eigen::Matrix2d block = local.middleCols(k, 2).transpose() * b_local.middleCols(k, 2);
    Plane plane;
    plane.first = local.col(k);
    plane.second = local.col(k + 1);
    plane.angle = std::atan2(0.5 * (block(1, 0) - block(0, 1)), 0.5 * (block(0, 0) + block(1, 1)));
    if (plane.angle < 0) {  // the same rotation seen from the other side: swap the axes
      std::swap(plane.first, plane.second);
      plane.angle = -plane.angle;
    }
    planes.push_back(std::move(plane));
  }
  if (p == m) return;
  // The rest of the block: B = ±1 there. An orthonormal basis of the complement of the planes, split by the sign
  // of B's symmetric part.
  Eigen::MatrixXd complement;
  if (p == 0) {
    complement = Eigen::MatrixXd::Identity(m, m);
  } else {
    Eigen::MatrixXd projector = Eigen::MatrixXd::Identity(m, m) - dense::multiply(local.transpose(), true, local.transpose());
    Eigen::VectorXd values;
    dense::symmetric_eigen(projector, values);
    complement = projector.rightCols(m - p);  // eigenvalue 1
  }
  Eigen::MatrixXd restricted = dense::multiply(complement, true, dense::multiply(sym, false, complement));
  Eigen::VectorXd signs;
  dense::symmetric_eigen(restricted, signs);
  const Eigen::MatrixXd directions = dense::multiply(complement, false, restricted);
  for (Eigen::Index k = 0; k < directions.cols(); ++k) {
    Eigen::MatrixXd& target = signs(k) < 0 ? minus : plus;
    target.conservativeResize(m, target.cols() + 1);
    target.col(target.cols() - 1) = directions.col(k);
  }
}

}  // namespace

RotationPower RotationPower::identity(int n) {
  RotationPower r;
  r.size_ = n;
  return r;
}

RotationPower::RotationPower(const Eigen::Ref<const Eigen::MatrixXd>& g) : size_(static_cast<int>(g.rows())) {
  const Eigen::Index n = g.rows();
  const double level = coupling_level(n);
  if (n == 0 || (g - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff() <= level) return;  // the identity

  Eigen::MatrixXd v = 0.5 * (g + g.transpose());
  Eigen::VectorXd cosines;
  dense::symmetric_eigen(v, cosines);
  const Eigen::MatrixXd w = dense::multiply(v, true, dense::multiply(g, false, v));

  std::vector<Plane> planes;  // in full coordinates after the loop
  Eigen::MatrixXd fixed(n, 0), reversed(n, 0);
  for (const std::vector<int>& cluster : coupled_clusters(w, level)) {
    const auto m = static_cast<Eigen::Index>(cluster.size());
    Eigen::MatrixXd block(m, m), columns(n, m);
    for (Eigen::Index j = 0; j < m; ++j) {
      columns.col(j) = v.col(cluster[static_cast<std::size_t>(j)]);
      for (Eigen::Index i = 0; i < m; ++i) block(i, j) = w(cluster[static_cast<std::size_t>(i)], cluster[static_cast<std::size_t>(j)]);
    }
    std::vector<Plane> local_planes;
    Eigen::MatrixXd plus(m, 0), minus(m, 0);
    resolve_block(block, level, local_planes, plus, minus);
    for (Plane& plane : local_planes) {
      plane.first = columns * plane.first;
      plane.second = columns * plane.second;
      planes.push_back(std::move(plane));
    }
    auto append = [&](Eigen::MatrixXd& all, const Eigen::MatrixXd& local) {
      if (local.cols() == 0) return;
      all.conservativeResize(Eigen::NoChange, all.cols() + local.cols());
      all.rightCols(local.cols()) = dense::multiply(columns, false, local);
    };
    append(fixed, plus);
    append(reversed, minus);
  }
  if (reversed.cols() % 2 != 0) {
    throw NumericalError("spectral formation: a rotation between eigenbases has determinant −1 (" +
                         std::to_string(reversed.cols()) + " eigenvalues −1); expected +1 after sign handling");
  }
  for (Eigen::Index k = 0; k < reversed.cols(); k += 2) {
    planes.push_back(Plane{reversed.col(k), reversed.col(k + 1), std::numbers::pi});
  }
  const auto plane_columns = static_cast<Eigen::Index>(2 * planes.size());
  if (plane_columns + fixed.cols() != n) {
    throw NumericalError("spectral formation: the rotation between eigenbases could not be decomposed (" +
                         std::to_string(plane_columns + fixed.cols()) + " invariant directions for " +
                         std::to_string(n) + ")");
  }
  if (planes.empty()) return;  // the identity after all (only tiny couplings)
  basis_.resize(n, n);
  angles_.reserve(planes.size());
  for (std::size_t p = 0; p < planes.size(); ++p) {
    basis_.col(static_cast<Eigen::Index>(2 * p)) = planes[p].first;
    basis_.col(static_cast<Eigen::Index>(2 * p + 1)) = planes[p].second;
    angles_.push_back(planes[p].angle);
  }
  basis_.rightCols(fixed.cols()) = fixed;
}

void RotationPower::rotate(Eigen::Ref<Eigen::MatrixXd> w, const std::vector<double>& exponents, int group) const {
  if (is_identity()) return;
  const auto groups = static_cast<std::size_t>(w.cols() / group);
  const std::size_t planes = angles_.size();
  constexpr std::size_t groups_per_task = 16;
  const double task_work = static_cast<double>(groups_per_task * planes) * (40.0 + 6.0 * group);
  dense::for_each((groups + groups_per_task - 1) / groups_per_task, task_work, [&](std::size_t task) {
    std::vector<double> cosines(planes), sines(planes);
    const std::size_t end = std::min(groups, (task + 1) * groups_per_task);
    for (std::size_t gi = task * groups_per_task; gi < end; ++gi) {
      for (std::size_t p = 0; p < planes; ++p) {
        const double angle = exponents[gi] * angles_[p];
        cosines[p] = std::cos(angle);
        sines[p] = std::sin(angle);
      }
      for (int c = 0; c < group; ++c) {
        double* column = w.col(static_cast<Eigen::Index>(gi) * group + c).data();
        for (std::size_t p = 0; p < planes; ++p) {
          const double a = column[2 * p], b = column[2 * p + 1];
          column[2 * p] = cosines[p] * a - sines[p] * b;
          column[2 * p + 1] = sines[p] * a + cosines[p] * b;
        }
      }
    }
  });
}

Eigen::MatrixXd RotationPower::power(double c) const {
  if (is_identity()) return Eigen::MatrixXd::Identity(size_, size_);
  Eigen::MatrixXd w = basis_.transpose();
  rotate(w, std::vector<double>(static_cast<std::size_t>(size_), c), 1);
  return dense::multiply(basis_, false, w);
}

}  // namespace throng::formation
