#include "fiedler.h"

#include "dense.h"

#include <throng/core/errors.h>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Spectra/SymEigsShiftSolver.h>
#include <Spectra/SymEigsSolver.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace throng::formation {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Lanczos basis sizes. Shift-invert: λ2 is often nearly repeated (round crowds: λ2 ≈ λ3), and a basis of 24
// resolves the cluster in a few restarts. Plain Lanczos on L: a wider basis halves the products (measured on
// a 10,000-individual scatter: 2,433 products with 32 vectors, 1,491 with 64, 1,255 with 128 at more cost each).
constexpr Eigen::Index shift_invert_vectors = 24;
constexpr Eigen::Index plain_vectors = 64;
constexpr double tolerance = 1e-8;  // Spectra's relative residual of the Ritz value
constexpr int restarts = 1000;
// Shift of the shift-invert, relative to the largest weighted degree: far below λ2 of a crowd graph (about
// (π/diameter)² times a typical weight: 1.2e-3 for a 10,000-individual scatter of degree ~6), so it barely slows
// convergence, and far above rounding.
constexpr double relative_shift = 1e-7;
// Shift of plain Lanczos, relative to the largest weighted degree (see LiftedLaplacian).
constexpr double plain_shift = 1e-3;
// Largest sparse factor worth making, in entries per item. A crowd graph whose keyframes keep neighbours
// together is nearly planar, with small separators, and its factor in AMD order is small: measured on one
// scatter's Delaunay graph, 11, 17, 27 entries per item at 625, 5,000, 50,000 individuals (1.2e7 flops, 0.03 s
// at 10,000). A graph summed over keyframes that reshuffle the crowd is an expander without small separators:
// its factor is nearly dense (122, 240, 1,855 entries per item at 625, 1,250, 10,000: 7.3e10 flops and 220 MB
// at 10,000), but its λ2 is large, and plain Lanczos on L converges in a few hundred products (313 at 10,000),
// where on the planar graph it needs about 1,500.
constexpr std::size_t factor_entries_per_item = 200;

using Factor = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower>;  // AMD ordering

// Entries below the diagonal of the LDLᵀ factor of the symmetric matrix whose lower triangle is `lower`, in the
// AMD order Factor uses, counted along the elimination tree as Factor's own analysis counts them; but the count
// stops as soon as it passes `budget` (returning more than the budget) and nothing of the factor is allocated:
// Factor's analysis would allocate the whole predicted factor of an expander before anything could decline it.
std::size_t factor_entries(const SparseMatrix& lower, std::size_t budget) {
  const Eigen::Index m = lower.rows();
  const SparseMatrix full = lower.selfadjointView<Eigen::Lower>();
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse_order;
  Eigen::AMDOrdering<int>()(full, inverse_order);
  SparseMatrix permuted(m, m);
  permuted.selfadjointView<Eigen::Upper>() = lower.selfadjointView<Eigen::Lower>().twistedBy(inverse_order.inverse());
  std::vector<int> parent(static_cast<std::size_t>(m), -1), mark(static_cast<std::size_t>(m), -1);
  std::size_t entries = 0;
  for (int k = 0; k < static_cast<int>(m); ++k) {
    // Row k of L: every node reachable in the elimination tree from the entries of column k above the diagonal.
    mark[static_cast<std::size_t>(k)] = k;
    for (SparseMatrix::InnerIterator it(permuted, k); it; ++it) {
      for (int i = static_cast<int>(it.row()); i < k && mark[static_cast<std::size_t>(i)] != k; i = parent[static_cast<std::size_t>(i)]) {
        if (parent[static_cast<std::size_t>(i)] < 0) parent[static_cast<std::size_t>(i)] = k;
        mark[static_cast<std::size_t>(i)] = k;
        if (++entries > budget) return entries;
      }
    }
  }
  return entries;
}

// The Laplacian (lower triangle) with the constant vector's eigenvalue 0 moved to `lift` above the spectrum, so
// the smallest eigenvalue of the result is λ2, and everything shifted up by `shift`: L + lift · 11ᵀ/m + shift · I.
// The shift changes no eigenvector and no Krylov space, only Spectra's convergence test, which is relative to the
// eigenvalue: a λ2 near 0 would otherwise be held to a residual below rounding.
class LiftedLaplacian {
 public:
  using Scalar = double;
  LiftedLaplacian(const SparseMatrix& lower, double lift, double shift) : lower_(lower), lift_(lift), shift_(shift) {}
  [[nodiscard]] Eigen::Index rows() const { return lower_.rows(); }
  [[nodiscard]] Eigen::Index cols() const { return lower_.cols(); }
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y.noalias() = lower_.selfadjointView<Eigen::Lower>() * x;
    y += shift_ * x;
    y.array() += lift_ * x.mean();
  }

 private:
  const SparseMatrix& lower_;
  double lift_;
  double shift_;
};

// Spectra's shift-solve operation for L on the complement of the constant vector, from a factor of L − σI
// (σ < 0, so it is definite): y = P (L − σI)⁻¹ P x with P = I − 11ᵀ/m. The constant vector maps to 0, the
// other eigenvectors of L to (λ − σ)⁻¹ times themselves: the largest of those is λ2's.
class ProjectedShiftSolve {
 public:
  using Scalar = double;
  explicit ProjectedShiftSolve(const Factor& factor, Eigen::Index size) : factor_(factor), size_(size) {}
  [[nodiscard]] Eigen::Index rows() const { return size_; }
  [[nodiscard]] Eigen::Index cols() const { return size_; }
  void set_shift(double) {}  // the factor is made with the shift already (fiedler_by_shift_invert)
  void perform_op(const double* x_in, double* y_out) const {
    const Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y = factor_.solve((x.array() - x.mean()).matrix());
    y.array() -= y.mean();
  }

 private:
  const Factor& factor_;
  Eigen::Index size_;
};

template <typename Solver>
Eigen::VectorXd converged_vector(Solver& lanczos, Spectra::SortRule rule, Eigen::Index size, const char* how) {
  lanczos.init();  // Spectra's fixed-seed start vector: the same result on every run
  lanczos.compute(rule, restarts, tolerance);
  if (lanczos.info() != Spectra::CompInfo::Successful)
    throw NumericalError("spectral clustering: the Fiedler vector of a group of " + std::to_string(size) +
                         " items did not converge (" + how + ", " + std::to_string(restarts) + " restarts)");
  return lanczos.eigenvectors(1).col(0);
}

// Component of each item (numbered 0, 1, ... in the order of their first item) of the graph whose Laplacian's
// lower triangle is `lower`; the count through `count`.
std::vector<int> components(const SparseMatrix& lower, int& count) {
  const auto m = static_cast<std::size_t>(lower.rows());
  std::vector<int> parent(m);
  for (std::size_t i = 0; i < m; ++i) parent[i] = static_cast<int>(i);
  auto root = [&](int x) {
    while (parent[static_cast<std::size_t>(x)] != x) x = parent[static_cast<std::size_t>(x)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
    return x;
  };
  for (Eigen::Index j = 0; j < lower.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(lower, j); it; ++it)
      if (it.row() != j && it.value() != 0.0) {
        const int a = root(static_cast<int>(it.row())), b = root(static_cast<int>(j));
        if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
      }
  std::vector<int> number(m, -1), out(m);
  count = 0;
  for (std::size_t i = 0; i < m; ++i) {
    int& n = number[static_cast<std::size_t>(root(static_cast<int>(i)))];
    if (n < 0) n = count++;
    out[i] = n;
  }
  return out;
}

// `lower`: the Laplacian's lower triangle (all LAPACK reads).
Eigen::VectorXd dense_fiedler(const SparseMatrix& lower) {
  Eigen::MatrixXd l = lower.toDense();
  Eigen::VectorXd values;
  dense::symmetric_eigen(l, values);
  return l.col(1);
}

// `lower`: the Laplacian's lower triangle with every diagonal entry stored. `solver`: automatic, shift_invert
// or lanczos.
Eigen::VectorXd sparse_fiedler(const SparseMatrix& lower, FiedlerSolver solver) {
  const Eigen::Index m = lower.rows();
  const double largest_degree = std::max(lower.diagonal().maxCoeff(), 1e-300);
  const double sigma = -relative_shift * largest_degree;
  SparseMatrix shifted = lower;
  for (Eigen::Index i = 0; i < m; ++i) shifted.coeffRef(i, i) -= sigma;
  const auto budget = factor_entries_per_item * static_cast<std::size_t>(m);
  if (solver == FiedlerSolver::shift_invert || (solver == FiedlerSolver::automatic && factor_entries(lower, budget) <= budget)) {
    const Factor factor(shifted);
    if (factor.info() == Eigen::Success) {
      ProjectedShiftSolve op(factor, m);
      Spectra::SymEigsShiftSolver<ProjectedShiftSolve> lanczos(op, 1, std::min(shift_invert_vectors, m), sigma);
      return converged_vector(lanczos, Spectra::SortRule::LargestMagn, m, "shift-invert Lanczos");
    }
  }
  // Every eigenvalue of L is at most twice the largest weighted degree: lift the constant vector above that.
  LiftedLaplacian op(lower, 2.0 * largest_degree + 1.0, plain_shift * largest_degree);
  Spectra::SymEigsSolver<LiftedLaplacian> lanczos(op, 1, std::min(plain_vectors, m));
  return converged_vector(lanczos, Spectra::SortRule::SmallestAlge, m, "Lanczos");
}

}  // namespace

Eigen::VectorXd fiedler_vector(const Adjacency& graph, const std::vector<int>& subset, FiedlerSolver solver) {
  const auto m = static_cast<Eigen::Index>(subset.size());
  std::vector<int> local(static_cast<std::size_t>(graph.count), -1);
  for (Eigen::Index i = 0; i < m; ++i) local[static_cast<std::size_t>(subset[static_cast<std::size_t>(i)])] = static_cast<int>(i);
  std::vector<Eigen::Triplet<double>> entries;
  for (Eigen::Index i = 0; i < m; ++i) entries.emplace_back(i, i, 0.0);  // every diagonal entry stored
  for (const auto& [edge, weight] : graph.weights) {
    const int a = local[static_cast<std::size_t>(edge.first)], b = local[static_cast<std::size_t>(edge.second)];
    if (a < 0 || b < 0) continue;
    entries.emplace_back(std::max(a, b), std::min(a, b), -weight);
    entries.emplace_back(a, a, weight);
    entries.emplace_back(b, b, weight);
  }
  SparseMatrix lower(m, m);  // duplicates summed
  lower.setFromTriplets(entries.begin(), entries.end());
  // Disconnected: λ2 = 0, whose eigenvectors are constant on each component; an eigensolver would pick an
  // arbitrary one (and Lanczos can miss an eigenvalue of exactly 0). The component numbers, centred, sort the
  // items component by component.
  int count = 0;
  const std::vector<int> component = components(lower, count);
  Eigen::VectorXd f(m);
  if (count > 1) {
    for (Eigen::Index i = 0; i < m; ++i) f(i) = component[static_cast<std::size_t>(i)];
    f.array() -= f.mean();
    f.normalize();
  } else {
    const bool dense = solver == FiedlerSolver::dense || (solver == FiedlerSolver::automatic && m <= dense_fiedler_limit);
    f = dense ? dense_fiedler(lower) : sparse_fiedler(lower, solver);
  }
  Eigen::Index largest = 0;
  f.cwiseAbs().maxCoeff(&largest);
  if (f(largest) < 0) f = -f;
  return f;
}

}  // namespace throng::formation
