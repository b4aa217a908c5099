#include "blas_threads.h"

#include <throng/core/parallel.h>
#include <throng/linalg/spd_solver.h>
#include <throng/linalg/two_level.h>

#include <Eigen/CholmodSupport>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace throng::linalg {
namespace {

using Index = Eigen::Index;
using Clock = std::chrono::steady_clock;
using CholmodMatrix = Eigen::SparseMatrix<Complex, Eigen::ColMajor, SuiteSparse_long>;
using ColumnBlock = Eigen::Matrix<Complex, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor>;

// Power iterations for λ_max(S A) (the damping). The estimate approaches λ_max from below; the cycle needs
// ω < 2/λ_max and takes ω = 1/λ, so an estimate within a factor 2 is enough (8 iterations: within 5 % on the
// editing systems, where 20 changed the iteration counts by none).
constexpr int power_iterations = 8;
// Relative diagonal shift of the Galerkin matrix (see two_level.h).
constexpr double coarse_shift = 1e-10;
// Fine rows per chunk of the Galerkin product Uᴴ (A U): bounds the temporary A U.
constexpr Index galerkin_chunk = 32768;

// One group's block, factorised as LLᴴ in band storage: row i holds L(i, i − width .. i), L(i, i) last.
struct Band {
  std::vector<int> members;  // the group's unknowns, increasing
  int width = 0;             // half-bandwidth in the group's own numbering
  std::size_t offset = 0;    // first entry in the shared factor storage
};

}  // namespace

struct TwoLevelPreconditioner::State {
  const ComplexSparse* A = nullptr;
  TwoLevelOptions options;
  TwoLevelInfo info;
  std::vector<Band> bands;
  std::vector<Complex> factor;  // every band's L, one after the other
  ComplexSparse U, Ut;          // coarse basis (zero columns dropped) and its adjoint, rows compressed
  Eigen::CholmodSupernodalLLT<CholmodMatrix, Eigen::Lower> coarse;
  // Workspace of apply() (kept between calls: no page is faulted in again per application).
  ComplexBlock rest, post, t, c_rhs, c_out;
  ColumnBlock coarse_in, coarse_out;

  Complex* row(const Band& b, int i) { return factor.data() + b.offset + static_cast<std::size_t>(i) * static_cast<std::size_t>(b.width + 1); }

  void factorize_band(Band& b, const std::vector<int>& local) {
    const int n = static_cast<int>(b.members.size());
    const int w = b.width;
    // Lower band of the block.
    for (int i = 0; i < n; ++i) {
      const int global = b.members[static_cast<std::size_t>(i)];
      Complex* r = row(b, i);
      for (ComplexSparse::InnerIterator it(*A, global); it; ++it) {
        const int j = local[static_cast<std::size_t>(it.col())];
        if (j < 0 || j > i || j < i - w) continue;
        r[w - (i - j)] = it.value();
      }
    }
    // LLᴴ in place: L(i, k) = (A(i, k) − Σ_m L(i, m) conj(L(k, m))) / L(k, k).
    for (int i = 0; i < n; ++i) {
      Complex* ri = row(b, i);
      const int first = std::max(0, i - w);
      for (int k = first; k <= i; ++k) {
        const Complex* rk = row(b, k);
        Complex s = ri[w - (i - k)];
        for (int m = std::max(first, k - w); m < k; ++m) s -= conj_times(rk[w - (k - m)], ri[w - (i - m)]);
        if (k < i) {
          ri[w - (i - k)] = s / rk[w].real();
        } else {
          if (!(s.real() > 0) || !std::isfinite(s.real())) {
            throw SingularMatrixError("the system is not positive definite: a smoother block has pivot " +
                                          std::to_string(s.real()) + " at unknown " + std::to_string(b.members[static_cast<std::size_t>(i)]),
                                      b.members[static_cast<std::size_t>(i)]);
          }
          ri[w] = std::sqrt(s.real());
        }
      }
    }
  }

  // z = S r on the unknowns of band b, every column (z and r may be the same block).
  void solve_band(Band& b, const ComplexBlock& r, ComplexBlock& z, std::vector<Complex>& y) {
    const int n = static_cast<int>(b.members.size());
    const int w = b.width;
    const Index k = r.cols();
    y.resize(static_cast<std::size_t>(n));
    for (Index c = 0; c < k; ++c) {
      for (int i = 0; i < n; ++i) {  // L y = r
        const Complex* ri = row(b, i);
        Complex s = r(b.members[static_cast<std::size_t>(i)], c);
        for (int m = std::max(0, i - w); m < i; ++m) s -= times(ri[w - (i - m)], y[static_cast<std::size_t>(m)]);
        y[static_cast<std::size_t>(i)] = s / ri[w].real();
      }
      for (int i = n - 1; i >= 0; --i) {  // Lᴴ x = y
        Complex s = y[static_cast<std::size_t>(i)];
        for (int m = i + 1; m <= std::min(n - 1, i + w); ++m) s -= conj_times(row(b, m)[w - (m - i)], y[static_cast<std::size_t>(m)]);
        y[static_cast<std::size_t>(i)] = s / row(b, i)[w].real();
      }
      for (int i = 0; i < n; ++i) z(b.members[static_cast<std::size_t>(i)], c) = y[static_cast<std::size_t>(i)];
    }
  }

  // z = scale · S r (every group in parallel; groups own disjoint rows).
  void smooth(const ComplexBlock& r, ComplexBlock& z, double scale) {
    z.resize(r.rows(), r.cols());
    parallel_for(bands.size(), 16, [&](std::size_t begin, std::size_t end) {
      std::vector<Complex> y;
      for (std::size_t g = begin; g < end; ++g) {
        solve_band(bands[g], r, z, y);
        if (scale != 1.0) {
          for (int member : bands[g].members) z.row(member) *= scale;
        }
      }
    });
  }

  // z += U Ac⁻¹ Uᴴ r.
  void add_coarse(const ComplexBlock& r, ComplexBlock& z) {
    if (U.cols() == 0) return;
    multiply(Ut, r, c_rhs);
    coarse_in = c_rhs;  // CHOLMOD reads column-major blocks
    {
      const BlasThreadScope threads(options.blas_threads);
      coarse_out = coarse.solve(coarse_in);
    }
    c_out = coarse_out;
    multiply(U, c_out, t);
    z += t;
  }

  void build_coarse(const ComplexSparse& basis) {
    // Drop all-zero columns (groups or times the basis does not reach among these unknowns).
    std::vector<char> used(static_cast<std::size_t>(basis.cols()), 0);
    for (Index i = 0; i < basis.outerSize(); ++i)
      for (ComplexSparse::InnerIterator it(basis, i); it; ++it) used[static_cast<std::size_t>(it.col())] |= it.value() != Complex(0);
    std::vector<int> column(used.size(), -1);
    int kept = 0;
    for (std::size_t c = 0; c < used.size(); ++c) column[c] = used[c] ? kept++ : -1;
    std::vector<Eigen::Triplet<Complex>> entries;
    entries.reserve(static_cast<std::size_t>(basis.nonZeros()));
    for (Index i = 0; i < basis.outerSize(); ++i)
      for (ComplexSparse::InnerIterator it(basis, i); it; ++it)
        if (column[static_cast<std::size_t>(it.col())] >= 0) entries.emplace_back(i, column[static_cast<std::size_t>(it.col())], it.value());
    U.resize(basis.rows(), kept);
    U.setFromTriplets(entries.begin(), entries.end());
    U.makeCompressed();
    Ut = U.adjoint();
    Ut.makeCompressed();
    info.coarse_size = kept;
    if (kept == 0) return;
    // Galerkin matrix Uᴴ A U, summed over chunks of fine rows (in order: the same bits every run).
    Eigen::SparseMatrix<Complex, Eigen::ColMajor, int> galerkin(kept, kept);
    for (Index first = 0; first < A->rows(); first += galerkin_chunk) {
      const Index rows = std::min(galerkin_chunk, A->rows() - first);
      const ComplexSparse AU = A->middleRows(first, rows) * U;
      const Eigen::SparseMatrix<Complex, Eigen::ColMajor, int> Uc = U.middleRows(first, rows);
      galerkin += Eigen::SparseMatrix<Complex, Eigen::ColMajor, int>(Uc.adjoint()) * AU;
    }
    // Its lower triangle in CHOLMOD's 64-bit indices, the diagonal real and shifted.
    std::vector<Eigen::Triplet<Complex, SuiteSparse_long>> lower_entries;
    lower_entries.reserve(static_cast<std::size_t>(galerkin.nonZeros() / 2 + kept));
    for (Index j = 0; j < galerkin.outerSize(); ++j) {
      for (Eigen::SparseMatrix<Complex, Eigen::ColMajor, int>::InnerIterator it(galerkin, j); it; ++it) {
        if (it.row() > j) lower_entries.emplace_back(it.row(), j, it.value());
        if (it.row() == j) lower_entries.emplace_back(j, j, Complex(it.value().real() * (1.0 + coarse_shift), 0.0));
      }
    }
    CholmodMatrix lower(kept, kept);
    lower.setFromTriplets(lower_entries.begin(), lower_entries.end());
    const BlasThreadScope threads(options.blas_threads);
    auto& common = coarse.cholmod();
    common.print = 0;
    common.nmethods = 1;
    common.method[0].ordering = CHOLMOD_NESDIS;
    coarse.compute(lower);
    if (coarse.info() != Eigen::Success) {
      throw SingularMatrixError("the coarse (Galerkin) matrix of the two-level preconditioner is not positive definite: "
                                "the system is singular",
                                -1);
    }
    info.coarse_factor_entries = common.lnz;
  }

  // λ_max(S A) by power iteration from a fixed start (deterministic).
  double largest_eigenvalue() {
    const Index n = A->rows();
    ComplexBlock v(n, 1), w, s;
    for (Index i = 0; i < n; ++i) v(i, 0) = Complex(1.0 + static_cast<double>(i % 7) / 7.0, static_cast<double>(i % 5) / 5.0);
    double lambda = 1;
    for (int k = 0; k < power_iterations; ++k) {
      multiply(*A, v, w);
      smooth(w, s, 1.0);
      const double before = std::sqrt(column_dots(v, v)[0].real());
      const double after = std::sqrt(column_dots(s, s)[0].real());
      if (!(after > 0) || !std::isfinite(after)) break;
      lambda = after / before;
      v = s / after;
    }
    return lambda;
  }
};

TwoLevelPreconditioner::TwoLevelPreconditioner(const ComplexSparse& A, const std::vector<std::vector<int>>& groups,
                                               const ComplexSparse& coarse_basis, const TwoLevelOptions& options)
    : state_(std::make_unique<State>()) {
  const auto start = Clock::now();
  State& s = *state_;
  s.A = &A;
  s.options = options;
  const Index n = A.rows();
  if (A.cols() != n) throw std::invalid_argument("TwoLevelPreconditioner: the matrix is not square");
  if (coarse_basis.rows() != n) {
    throw std::invalid_argument("TwoLevelPreconditioner: the coarse basis has " + std::to_string(coarse_basis.rows()) +
                                " rows for " + std::to_string(n) + " unknowns");
  }
  // Groups: cover every unknown once; each group's local numbering and its half-bandwidth.
  std::vector<int> group_of(static_cast<std::size_t>(n), -1), local(static_cast<std::size_t>(n), -1);
  s.bands.resize(groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::size_t i = 0; i < groups[g].size(); ++i) {
      const int u = groups[g][i];
      if (u < 0 || u >= n || group_of[static_cast<std::size_t>(u)] >= 0 || (i > 0 && u <= groups[g][i - 1])) {
        throw std::invalid_argument("TwoLevelPreconditioner: group " + std::to_string(g) + " holds unknown " + std::to_string(u) +
                                    " out of range, twice, or out of increasing order");
      }
      group_of[static_cast<std::size_t>(u)] = static_cast<int>(g);
      local[static_cast<std::size_t>(u)] = static_cast<int>(i);
    }
    s.bands[g].members = groups[g];
  }
  for (Index u = 0; u < n; ++u) {
    if (group_of[static_cast<std::size_t>(u)] < 0) throw std::invalid_argument("TwoLevelPreconditioner: unknown " + std::to_string(u) + " is in no group");
  }
  std::size_t total = 0;
  for (auto& b : s.bands) {
    int width = 0;
    for (std::size_t i = 0; i < b.members.size(); ++i) {
      for (ComplexSparse::InnerIterator it(A, b.members[i]); it; ++it) {
        const auto c = static_cast<std::size_t>(it.col());
        if (group_of[c] == group_of[static_cast<std::size_t>(b.members[i])]) width = std::max(width, std::abs(local[c] - static_cast<int>(i)));
      }
    }
    b.width = width;
    b.offset = total;
    total += b.members.size() * static_cast<std::size_t>(width + 1);
  }
  s.factor.assign(total, Complex(0));
  s.info.smoother_entries = total;
  // A per-group local index (−1 outside the group) for the band assembly: one shared array, each group marks
  // and clears its own members, so groups are factorised one after another.
  std::vector<int> mark(static_cast<std::size_t>(n), -1);
  for (auto& b : s.bands) {
    for (std::size_t i = 0; i < b.members.size(); ++i) mark[static_cast<std::size_t>(b.members[i])] = static_cast<int>(i);
    s.factorize_band(b, mark);
    for (int u : b.members) mark[static_cast<std::size_t>(u)] = -1;
  }
  s.build_coarse(coarse_basis);
  s.info.damping = 1.0 / std::max(1.0, s.largest_eigenvalue());
  s.info.setup_seconds = std::chrono::duration<double>(Clock::now() - start).count();
}

TwoLevelPreconditioner::~TwoLevelPreconditioner() = default;

void TwoLevelPreconditioner::apply(const ComplexBlock& r, ComplexBlock& z) {
  State& s = *state_;
  const double omega = s.info.damping;
  s.smooth(r, z, omega);
  if (s.options.cycle == TwoLevelCycle::additive) {
    s.add_coarse(r, z);
    return;
  }
  residual(*s.A, z, r, s.rest);
  s.add_coarse(s.rest, z);
  residual(*s.A, z, r, s.rest);
  s.smooth(s.rest, s.post, omega);
  z += s.post;
}

const TwoLevelInfo& TwoLevelPreconditioner::info() const noexcept { return state_->info; }

}  // namespace throng::linalg
