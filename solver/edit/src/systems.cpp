#include "systems.h"

#include <throng/core/parallel.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <complex>
#include <vector>

namespace throng::edit {
namespace {

using Complex = std::complex<double>;
using Triplet = Eigen::Triplet<double>;

// Appends the two real rows of Σ coefficient_k · z_k (complex coefficients on complex unknowns z = x + i y):
// (a z)_x = a_r x − a_i y,  (a z)_y = a_i x + a_r y.
void complex_rows(Eigen::Index row, const int (&vertex)[3], const Complex (&coefficient)[3], std::vector<Triplet>& out) {
  for (int k = 0; k < 3; ++k) {
    const Eigen::Index x = 2 * static_cast<Eigen::Index>(vertex[k]);
    const Complex a = coefficient[k];
    out.emplace_back(row, x, a.real());
    if (a.imag() != 0.0) out.emplace_back(row, x + 1, -a.imag());
    if (a.imag() != 0.0) out.emplace_back(row + 1, x, a.imag());
    out.emplace_back(row + 1, x + 1, a.real());
  }
}

// Rows for one feature set: residual v − (1 − c) u − c w − r, weight · term weight.
void feature_rows(const std::vector<Feature>& features, double term_weight, Eigen::Index first_row,
                  std::vector<Triplet>& entries, Eigen::VectorXd& weights, Eigen::VectorXd& b) {
  for (std::size_t k = 0; k < features.size(); ++k) {
    const Feature& f = features[k];
    const Eigen::Index row = first_row + 2 * static_cast<Eigen::Index>(k);
    const int vertex[3] = {f.v, f.u, f.w};
    const Complex coefficient[3] = {1.0, -(1.0 - f.c), -f.c};
    complex_rows(row, vertex, coefficient, entries);
    weights[row] = weights[row + 1] = f.weight * term_weight;
    b[row] = f.offset.real();
    b[row + 1] = f.offset.imag();
  }
}

Objective assemble(Eigen::Index rows, Eigen::Index vertices, const std::vector<Triplet>& entries, Eigen::VectorXd weights,
                   Eigen::VectorXd b) {
  Objective o;
  o.A.resize(rows, 2 * vertices);
  o.A.setFromTriplets(entries.begin(), entries.end());
  o.A.makeCompressed();
  o.weights = std::move(weights);
  o.b = std::move(b);
  return o;
}

Eigen::Index rows_of(const std::vector<Feature>& f) { return 2 * static_cast<Eigen::Index>(f.size()); }

}  // namespace

Objective step1_objective(const FeatureSet& features, Eigen::Index vertices, double alpha, double beta) {
  const Eigen::Index rs = rows_of(features.spatial), rt = rows_of(features.temporal), rst = rows_of(features.spatiotemporal);
  const Eigen::Index rows = rs + rt + rst;
  std::vector<Triplet> entries;
  entries.reserve(static_cast<std::size_t>(rows) * 6);
  Eigen::VectorXd weights(rows), b(rows);
  feature_rows(features.spatial, 1.0, 0, entries, weights, b);
  feature_rows(features.temporal, alpha, rs, entries, weights, b);
  feature_rows(features.spatiotemporal, beta, rs + rt, entries, weights, b);
  return assemble(rows, vertices, entries, std::move(weights), std::move(b));
}

Objective step2_objective(const FeatureSet& features, Eigen::Index vertices, double alpha_prime, double beta_prime) {
  // ESC: per spatial feature (u, v, w) the rows x_v − x_u, y_v − y_u, x_v − x_w, y_v − y_w.
  const Eigen::Index rs = 4 * static_cast<Eigen::Index>(features.spatial.size());
  const Eigen::Index rt = rows_of(features.temporal), rst = rows_of(features.spatiotemporal);
  const Eigen::Index rows = rs + rt + rst;
  std::vector<Triplet> entries;
  entries.reserve(static_cast<std::size_t>(rows) * 6);
  Eigen::VectorXd weights(rows), b = Eigen::VectorXd::Zero(rows);
  for (std::size_t k = 0; k < features.spatial.size(); ++k) {
    const Feature& f = features.spatial[k];
    const Eigen::Index row = 4 * static_cast<Eigen::Index>(k);
    for (int e = 0; e < 2; ++e) {
      const Eigen::Index other = 2 * static_cast<Eigen::Index>(e == 0 ? f.u : f.w);
      for (int d = 0; d < 2; ++d) {
        const Eigen::Index r = row + 2 * e + d;
        entries.emplace_back(r, 2 * static_cast<Eigen::Index>(f.v) + d, 1.0);
        entries.emplace_back(r, other + d, -1.0);
        weights[r] = f.weight;
      }
    }
  }
  feature_rows(features.temporal, alpha_prime, rs, entries, weights, b);
  feature_rows(features.spatiotemporal, beta_prime, rs + rt, entries, weights, b);
  return assemble(rows, vertices, entries, std::move(weights), std::move(b));
}

Eigen::Matrix<double, 3, 2> fit_without_scale(const Eigen::Matrix<double, 3, 2>& from, const Eigen::Matrix<double, 3, 2>& to) {
  const Eigen::RowVector2d from_centre = from.colwise().mean();
  const Eigen::RowVector2d to_centre = to.colwise().mean();
  // s = Σ conj(p_k) q_k over centred points; the best rotation turns by arg s.
  Complex s = 0;
  for (int k = 0; k < 3; ++k) {
    const Complex p(from(k, 0) - from_centre.x(), from(k, 1) - from_centre.y());
    const Complex q(to(k, 0) - to_centre.x(), to(k, 1) - to_centre.y());
    s += std::conj(p) * q;
  }
  const double length = std::sqrt(std::norm(s));
  const Complex turn = length > 0 ? s / length : Complex(1, 0);
  Eigen::Matrix<double, 3, 2> fitted;
  for (int k = 0; k < 3; ++k) {
    const Complex p(from(k, 0) - from_centre.x(), from(k, 1) - from_centre.y());
    const Complex q = turn * p;
    fitted.row(k) << to_centre.x() + q.real(), to_centre.y() + q.imag();
  }
  return fitted;
}

void set_step2_targets(const FeatureSet& features, const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& original,
                       const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& step1, Eigen::VectorXd& b) {
  // One fit per triangle: its three spatial features are consecutive (see FeatureSet).
  const auto& spatial = features.spatial;
  assert(spatial.size() % 3 == 0);
  parallel_for(spatial.size() / 3, 512, [&](std::size_t begin, std::size_t end) {
    for (std::size_t t = begin; t < end; ++t) {
      const Feature& corner = spatial[3 * t];
      const int vertex[3] = {corner.u, corner.v, corner.w};
      Eigen::Matrix<double, 3, 2> from, to;
      for (int k = 0; k < 3; ++k) {
        from.row(k) = original.row(vertex[k]);
        to.row(k) = step1.row(vertex[k]);
      }
      const Eigen::Matrix<double, 3, 2> fitted = fit_without_scale(from, to);
      auto fitted_of = [&](int v) -> Eigen::RowVector2d {
        for (int k = 0; k < 3; ++k) {
          if (vertex[k] == v) return fitted.row(k);
        }
        assert(false && "a spatial feature outside its triangle");
        return Eigen::RowVector2d::Zero();
      };
      for (std::size_t k = 3 * t; k < 3 * t + 3; ++k) {
        const Feature& f = spatial[k];
        const Eigen::RowVector2d fv = fitted_of(f.v);
        const Eigen::RowVector2d vu = fv - fitted_of(f.u);
        const Eigen::RowVector2d vw = fv - fitted_of(f.w);
        b.segment<4>(4 * static_cast<Eigen::Index>(k)) << vu.x(), vu.y(), vw.x(), vw.y();
      }
    }
  });
}

Eigen::MatrixXd similarity_modes(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& p) {
  const Eigen::RowVector2d centre = p.rows() > 0 ? Eigen::RowVector2d(p.colwise().mean()) : Eigen::RowVector2d(0, 0);
  Eigen::MatrixXd modes = Eigen::MatrixXd::Zero(2 * p.rows(), 4);
  for (Eigen::Index v = 0; v < p.rows(); ++v) {
    const double x = p(v, 0) - centre.x(), y = p(v, 1) - centre.y();
    modes(2 * v, 0) = 1.0;
    modes(2 * v + 1, 1) = 1.0;
    modes(2 * v, 2) = -y;
    modes(2 * v + 1, 2) = x;
    modes(2 * v, 3) = x;
    modes(2 * v + 1, 3) = y;
  }
  return modes;
}

Eigen::Matrix<double, Eigen::Dynamic, 2> as_positions(const Eigen::MatrixXd& x) {
  return Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>>(x.data(), x.rows() / 2, 2);
}

bool same_matrix(const linalg::SparseMatrix& a, const linalg::SparseMatrix& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  const auto nnz = static_cast<std::size_t>(a.nonZeros());
  const auto outer = static_cast<std::size_t>(a.outerSize()) + 1;
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + outer, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + nnz, b.innerIndexPtr()) &&
         std::equal(a.valuePtr(), a.valuePtr() + nnz, b.valuePtr());
}

}  // namespace throng::edit
