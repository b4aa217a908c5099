#include <throng/core/timer.h>
#include <throng/linalg/least_squares.h>

#include <Eigen/Cholesky>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace throng::linalg {
namespace {

using Index = Eigen::Index;
using Clock = std::chrono::steady_clock;


// Schur complement pivots below this fraction of the largest are rounding: those constraint rows are redundant
// (linear combinations of others). Exact redundancy leaves ~1e-16 with a direct backend and ~ the iterative
// tolerance (1e-12) with PETSc.
constexpr double redundant_pivot = 1e-9;

// The blocks of Q = Aᵀ diag(w) A the solver needs, assembled straight from A without forming Q:
//   FF = Q_FF (#free by #free, both triangles) and PF = Q_PF = Q_FPᵀ (#pinned by #free),
// column c of each from Q[:, free_unknowns[c]] = Σ_r w_r A(r, j) A(r, :)ᵀ, for the free columns `columns`
// (free positions, increasing; nullptr: all). The other columns stay empty: a distributed backend reads only the
// columns of its own rows (SpdSolver::owned_columns), so each rank assembles and keeps only those. The pattern is
// structural (zero weights keep their entries), so new weights never change it. Each entry is summed over the
// rows r in increasing order as w_r (A(r, j) A(r, k)), the same sum for (j, k) and (k, j): FF is exactly
// symmetric, and the same inputs give the same bits.
struct NormalBlocks {
  SparseMatrix FF, PF;
};

NormalBlocks normal_blocks(const SparseMatrix& A, const Eigen::VectorXd& w, const std::vector<Index>& free_unknowns,
                           const std::vector<Index>& free_position, const std::vector<Index>& pin_slot, Index pinned,
                           const std::vector<Index>* columns) {
  const SparseMatrix At = A.transpose();  // the rows of A as columns (a temporary copy of A)
  const Index n = A.cols();
  const auto nf = static_cast<Index>(free_unknowns.size());
  std::vector<double> sum(static_cast<std::size_t>(n), 0.0);
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  std::vector<int> touched;
  std::vector<int> ff_outer(static_cast<std::size_t>(nf) + 1, 0), pf_outer(static_cast<std::size_t>(nf) + 1, 0);
  std::vector<int> ff_inner, pf_inner;
  std::vector<double> ff_values, pf_values;
  std::vector<std::pair<int, double>> pinned_entries;
  std::size_t next = 0;  // position in `columns`
  for (Index c = 0; c < nf; ++c) {
    const bool wanted = columns == nullptr || (next < columns->size() && (*columns)[next] == c);
    if (wanted && columns != nullptr) ++next;
    if (wanted) {
      const Index j = free_unknowns[static_cast<std::size_t>(c)];
      touched.clear();
      for (SparseMatrix::InnerIterator row(A, j); row; ++row) {
        const double weight = w[row.row()];
        const double a_rj = row.value();
        for (SparseMatrix::InnerIterator it(At, row.row()); it; ++it) {
          const auto k = static_cast<std::size_t>(it.row());
          if (!seen[k]) {
            seen[k] = 1;
            sum[k] = 0.0;
            touched.push_back(static_cast<int>(k));
          }
          sum[k] += weight * (a_rj * it.value());
        }
      }
      std::sort(touched.begin(), touched.end());
      pinned_entries.clear();
      for (int k : touched) {
        const auto ku = static_cast<std::size_t>(k);
        seen[ku] = 0;
        if (free_position[ku] >= 0) {
          ff_inner.push_back(static_cast<int>(free_position[ku]));
          ff_values.push_back(sum[ku]);
        } else {
          pinned_entries.emplace_back(static_cast<int>(pin_slot[ku]), sum[ku]);
        }
      }
      std::sort(pinned_entries.begin(), pinned_entries.end());  // pin slots follow the caller's order
      for (const auto& [slot, value] : pinned_entries) {
        pf_inner.push_back(slot);
        pf_values.push_back(value);
      }
    }
    ff_outer[static_cast<std::size_t>(c) + 1] = static_cast<int>(ff_inner.size());
    pf_outer[static_cast<std::size_t>(c) + 1] = static_cast<int>(pf_inner.size());
  }
  auto make = [&](Index rows, std::vector<int>& outer, std::vector<int>& inner, std::vector<double>& values) {
    if (inner.empty()) return SparseMatrix(rows, nf);
    return SparseMatrix(Eigen::Map<const SparseMatrix>(rows, nf, static_cast<Index>(inner.size()), outer.data(),
                                                       inner.data(), values.data()));
  };
  NormalBlocks blocks;
  blocks.FF = make(nf, ff_outer, ff_inner, ff_values);
  blocks.PF = make(pinned, pf_outer, pf_inner, pf_values);
  return blocks;
}

// The rows `keep` (new index per old row, −1 dropped) of the columns `columns` of M, as a new matrix with
// `rows` rows. Used to cut Cᵀ into its free and pinned parts.
SparseMatrix select(const SparseMatrix& M, const std::vector<Index>& keep, Index rows, const std::vector<Index>& columns) {
  // Compressed arrays written directly: one counting pass, one filling pass. (Eigen's reserve() on a matrix
  // with no column writes out of bounds.)
  const auto cols = static_cast<Index>(columns.size());
  std::vector<int> outer(static_cast<std::size_t>(cols) + 1, 0);
  for (Index c = 0; c < cols; ++c) {
    int count = 0;
    for (SparseMatrix::InnerIterator it(M, columns[static_cast<std::size_t>(c)]); it; ++it) count += keep[static_cast<std::size_t>(it.row())] >= 0;
    outer[static_cast<std::size_t>(c) + 1] = outer[static_cast<std::size_t>(c)] + count;
  }
  const auto nnz = static_cast<std::size_t>(outer.back());
  std::vector<int> inner(nnz);
  std::vector<double> values(nnz);
  std::vector<std::pair<int, double>> column;
  for (Index c = 0; c < cols; ++c) {
    const auto begin = static_cast<std::size_t>(outer[static_cast<std::size_t>(c)]);
    auto k = begin;
    bool sorted = true;
    for (SparseMatrix::InnerIterator it(M, columns[static_cast<std::size_t>(c)]); it; ++it) {
      const Index r = keep[static_cast<std::size_t>(it.row())];
      if (r < 0) continue;
      sorted = sorted && (k == begin || inner[k - 1] < r);
      inner[k] = static_cast<int>(r);
      values[k++] = it.value();
    }
    if (sorted) continue;
    // `keep` is not increasing (pin slots follow the caller's order): sort the column's rows.
    column.clear();
    for (std::size_t e = begin; e < k; ++e) column.emplace_back(inner[e], values[e]);
    std::sort(column.begin(), column.end());
    for (std::size_t e = begin; e < k; ++e) std::tie(inner[e], values[e]) = column[e - begin];
  }
  SparseMatrix out(rows, cols);
  if (nnz == 0) return out;
  return SparseMatrix(Eigen::Map<const SparseMatrix>(rows, cols, static_cast<Index>(nnz), outer.data(), inner.data(), values.data()));
}

std::vector<Index> iota(Index n) {
  std::vector<Index> v(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = i;
  return v;
}

}  // namespace

struct ConstrainedLeastSquares::State {
  explicit State(const SolverOptions& o) : options(o), backend(make_spd_solver(o)) {}

  SolverOptions options;
  std::unique_ptr<SpdSolver> backend;

  // Objective.
  SparseMatrix A;
  Eigen::VectorXd weights;

  // Pins: the free unknowns in increasing order, and each unknown's free position or pin slot (−1 if none).
  std::vector<Index> pinned;
  std::vector<Index> free_unknowns;
  std::vector<Index> free_position;
  std::vector<Index> pin_slot;
  // Blocks of Q = AᵀWA. Q_FF lives only from assembly to factorisation (the backend keeps what it needs: a
  // factor, or its own rows); Q_PF = Q_FPᵀ is kept for the right-hand sides. With a distributed backend both hold
  // only the columns of this rank's rows (`owned`, free positions; empty: all).
  SparseMatrix Q_FF, Q_PF;
  std::vector<Index> owned;

  // Constraints, rows scaled to unit length, stored transposed (one column per constraint).
  SparseMatrix CT;         // #unknowns by #constraints
  Eigen::VectorXd row_norm;  // original length of each row (0 for an empty row)
  SparseMatrix CT_F, CT_P;   // free and pinned parts

  // Schur complement S = C_F Q_FF⁻¹ C_Fᵀ over the first `schur_rows` constraints; Y = Q_FF⁻¹ C_Fᵀ when cached.
  Index schur_rows = 0;
  Eigen::MatrixXd S;
  Eigen::LDLT<Eigen::MatrixXd> S_ldlt;
  Index S_rank = 0;
  Eigen::MatrixXd Y;
  bool y_cached = true;

  // Hints for the backend.
  Eigen::MatrixXd modes;
  int block_size = 1;
  bool complex_pairs = false;

  // What is stale. blocks_stale: Q_FF and Q_PF lack the current weights (or were released).
  bool blocks_stale = true;
  bool analysis_stale = true;
  bool factor_stale = true;

  // (AᵀW b)_F for the last b: a caller whose b does not change between solves (only pins or d do) skips the
  // product with A, the largest matrix of the problem.
  Eigen::MatrixXd last_b;
  Eigen::MatrixXd last_r;
  // The free part of the last solve's first back-substitution: the start of the next one for iterative backends.
  Eigen::MatrixXd last_x0;

  // A solver whose analysis this one may reuse (share_analysis).
  const ConstrainedLeastSquares* analysis_source = nullptr;

  // Pin basis (set_pin_basis): x_P = B u, Z = Q_FF⁻¹ Q_FP B, and Q_FF⁻¹ last_r for the basis path.
  SparseMatrix pin_basis;
  Eigen::MatrixXd Z;
  bool basis_stale = true;
  Eigen::MatrixXd last_g;

  LeastSquaresReport report;

  [[nodiscard]] Index n() const { return A.cols(); }
  [[nodiscard]] Index m() const { return CT.cols(); }
  [[nodiscard]] Index free_count() const { return static_cast<Index>(free_unknowns.size()); }

  void invalidate_factor() {
    factor_stale = true;
    last_b.resize(0, 0);
    last_x0.resize(0, 0);
    last_g.resize(0, 0);
    basis_stale = true;
    invalidate_schur();
  }
  [[nodiscard]] bool has_basis() const { return pin_basis.cols() > 0; }
  // Z is worth precomputing only when each of its columns is a back-substitution (a direct backend): with an
  // iterative backend every column is a whole Krylov solve, and a drag is one warm-started solve with its own
  // pin values (measured on the battlefield edit, 8 basis columns per step: 16 CG solves in precompute against
  // 2 per drag).
  [[nodiscard]] bool basis_solves() const {
    return has_basis() && backend->is_direct() && pin_basis.cols() <= ConstrainedLeastSquares::max_basis_columns;
  }

  // Z = Q_FF⁻¹ Q_FP B, one block of back-substitutions.
  void solve_basis() {
    const Eigen::MatrixXd rhs = Eigen::MatrixXd(SparseMatrix(SparseMatrix(Q_PF.transpose()) * pin_basis));
    Z = free_count() > 0 ? solve_free(rhs) : Eigen::MatrixXd(0, pin_basis.cols());
    report.basis_columns += static_cast<int>(pin_basis.cols());
    basis_stale = false;
  }
  void invalidate_schur() {
    schur_rows = 0;
    S.resize(0, 0);
    Y.resize(0, 0);
    y_cached = true;
  }

  void build_pin_maps() {
    const Index n_ = n();
    free_position.assign(static_cast<std::size_t>(n_), -1);
    pin_slot.assign(static_cast<std::size_t>(n_), -1);
    for (std::size_t k = 0; k < pinned.size(); ++k) {
      const Index p = pinned[k];
      if (p < 0 || p >= n_) {
        throw std::invalid_argument("ConstrainedLeastSquares: pinned unknown " + std::to_string(p) + " is outside [0, " +
                                    std::to_string(n_) + ")");
      }
      if (pin_slot[static_cast<std::size_t>(p)] >= 0) {
        throw std::invalid_argument("ConstrainedLeastSquares: unknown " + std::to_string(p) + " is pinned twice");
      }
      pin_slot[static_cast<std::size_t>(p)] = static_cast<Index>(k);
    }
    free_unknowns.clear();
    for (Index i = 0; i < n_; ++i) {
      if (pin_slot[static_cast<std::size_t>(i)] < 0) {
        free_position[static_cast<std::size_t>(i)] = static_cast<Index>(free_unknowns.size());
        free_unknowns.push_back(i);
      }
    }
  }

  // Q_FF and Q_PF with the current weights: every column, or this rank's when the backend said which.
  void assemble_blocks(bool all_columns) {
    NormalBlocks blocks = normal_blocks(A, weights, free_unknowns, free_position, pin_slot,
                                        static_cast<Index>(pinned.size()), all_columns || owned.empty() ? nullptr : &owned);
    Q_FF = std::move(blocks.FF);
    Q_PF = std::move(blocks.PF);
    blocks_stale = false;
  }

  // Keeps only the owned columns of Q_PF (after the backend's analysis named them).
  void keep_owned_columns() {
    if (owned.empty()) return;
    SparseMatrix kept(Q_PF.rows(), Q_PF.cols());
    std::vector<Eigen::Triplet<double>> entries;
    for (Index c : owned)
      for (SparseMatrix::InnerIterator it(Q_PF, c); it; ++it) entries.emplace_back(it.row(), c, it.value());
    kept.setFromTriplets(entries.begin(), entries.end());
    Q_PF = std::move(kept);
  }

  void split_constraints() {
    const auto all = iota(m());
    CT_F = select(CT, free_position, free_count(), all);
    CT_P = select(CT, pin_slot, static_cast<Index>(pinned.size()), all);
  }

  // True when the pins take or leave whole nodes of `size` consecutive unknowns.
  [[nodiscard]] bool pins_keep_nodes(int size) const {
    if (size <= 1) return true;
    if (n() % size != 0) return false;
    for (Index node = 0; node < n() / size; ++node) {
      const bool first_free = free_position[static_cast<std::size_t>(node * size)] >= 0;
      for (int k = 1; k < size; ++k) {
        if ((free_position[static_cast<std::size_t>(node * size + k)] >= 0) != first_free) return false;
      }
    }
    return true;
  }

  // The backend's hints on the free unknowns: complex pairs, near-null-space modes and their node size.
  void pass_hints() {
    backend->set_complex_pairs(complex_pairs && pins_keep_nodes(2));
    if (modes.cols() == 0) {
      backend->set_near_null_space(Eigen::MatrixXd(), 1);
      return;
    }
    const int bs = pins_keep_nodes(block_size) ? block_size : 1;
    Eigen::MatrixXd restricted(free_count(), modes.cols());
    for (Index i = 0; i < free_count(); ++i) restricted.row(i) = modes.row(free_unknowns[static_cast<std::size_t>(i)]);
    backend->set_near_null_space(restricted, bs);
  }

  void factorize() {
    try {
      backend->factorize(Q_FF);
    } catch (const SingularMatrixError& e) {
      const Index unknown = e.index() >= 0 && e.index() < free_count() ? free_unknowns[static_cast<std::size_t>(e.index())] : -1;
      throw SingularMatrixError(e.what(), unknown);
    }
  }

  // Solves Q_FF X = B.
  Eigen::MatrixXd solve_free(const Eigen::Ref<const Eigen::MatrixXd>& B) {
    Eigen::MatrixXd X(B.rows(), B.cols());
    backend->solve(B, X);
    report.last_solve = backend->solve_info();
    return X;
  }

  // Adds Schur complement rows and columns for constraints [schur_rows, m()).
  void extend_schur() {
    const Index m_ = m();
    const Index m0 = schur_rows;
    const Index nf = free_count();
    const double cache_bytes = static_cast<double>(nf) * static_cast<double>(m_) * sizeof(double);
    if (cache_bytes > options.schur_cache_megabytes * 1024.0 * 1024.0) {
      y_cached = false;
      Y.resize(0, 0);
    }
    S.conservativeResize(m_, m_);
    if (y_cached) Y.conservativeResize(nf, m_);
    constexpr Index block = 64;
    for (Index c0 = m0; c0 < m_; c0 += block) {
      const Index k = std::min(block, m_ - c0);
      const Eigen::MatrixXd rhs = Eigen::MatrixXd(CT_F.middleCols(c0, k));
      const Eigen::MatrixXd Yk = nf > 0 ? solve_free(rhs) : Eigen::MatrixXd(0, k);
      report.schur_columns += static_cast<int>(k);
      // Columns c0..c0+k of S for every constraint so far; mirror into the rows.
      const Eigen::MatrixXd Sk = CT_F.leftCols(c0 + k).transpose() * Yk;
      S.block(0, c0, c0 + k, k) = Sk;
      S.block(c0, 0, k, c0) = Sk.topRows(c0).transpose();
      if (y_cached) Y.middleCols(c0, k) = Yk;
    }
    schur_rows = m_;
    S_ldlt.compute(S);
    const Eigen::VectorXd D = S_ldlt.vectorD();
    const double largest = D.size() > 0 ? D.cwiseAbs().maxCoeff() : 0.0;
    S_rank = 0;
    for (Index i = 0; i < D.size(); ++i) S_rank += D[i] > redundant_pivot * largest ? 1 : 0;
    report.constraint_rank = S_rank;
  }

  // λ with S λ = g, pivots judged redundant set to zero (a solution whenever the system is consistent).
  Eigen::MatrixXd schur_solve(const Eigen::MatrixXd& g) const {
    const Eigen::VectorXd D = S_ldlt.vectorD();
    const double largest = D.size() > 0 ? D.cwiseAbs().maxCoeff() : 0.0;
    Eigen::MatrixXd y = S_ldlt.transpositionsP() * g;
    S_ldlt.matrixL().solveInPlace(y);
    for (Index i = 0; i < D.size(); ++i) y.row(i) *= D[i] > redundant_pivot * largest ? 1.0 / D[i] : 0.0;
    S_ldlt.matrixU().solveInPlace(y);
    return S_ldlt.transpositionsP().transpose() * y;
  }

  // The constraint rows that take part in a contradiction seen by the right-hand side g (= C_F x0 − e). Each
  // redundant pivot i of P S Pᵀ = L D Lᵀ gives a null vector z = Pᵀ L⁻ᵀ e_i of S; the system S λ = g is
  // inconsistent along z when zᵀg ≠ 0, and the rows with z_r ≠ 0 are the ones that disagree.
  std::vector<Index> conflicting_rows(const Eigen::MatrixXd& g, double tolerance) const {
    const Eigen::VectorXd D = S_ldlt.vectorD();
    const double largest = D.size() > 0 ? D.cwiseAbs().maxCoeff() : 0.0;
    std::vector<bool> involved(static_cast<std::size_t>(m()), false);
    for (Index i = 0; i < D.size(); ++i) {
      if (D[i] > redundant_pivot * largest) continue;
      Eigen::VectorXd z = Eigen::VectorXd::Unit(m(), i);
      S_ldlt.matrixU().solveInPlace(z);
      z = S_ldlt.transpositionsP().transpose() * z;
      z /= z.cwiseAbs().maxCoeff();
      if ((z.transpose() * g).cwiseAbs().maxCoeff() <= tolerance) continue;
      for (Index r = 0; r < m(); ++r) involved[static_cast<std::size_t>(r)] = involved[static_cast<std::size_t>(r)] || std::abs(z[r]) > 1e-8;
    }
    std::vector<Index> rows;
    for (Index r = 0; r < m(); ++r) {
      if (involved[static_cast<std::size_t>(r)]) rows.push_back(r);
    }
    return rows;
  }
};

ConstrainedLeastSquares::ConstrainedLeastSquares(const SolverOptions& options)
    : state_(std::make_unique<State>(options)) {}

ConstrainedLeastSquares::~ConstrainedLeastSquares() = default;
ConstrainedLeastSquares::ConstrainedLeastSquares(ConstrainedLeastSquares&&) noexcept = default;
ConstrainedLeastSquares& ConstrainedLeastSquares::operator=(ConstrainedLeastSquares&&) noexcept = default;

void ConstrainedLeastSquares::set_objective(const SparseMatrix& A, const Eigen::Ref<const Eigen::VectorXd>& weights) {
  set_objective(SparseMatrix(A), weights);
}

void ConstrainedLeastSquares::set_objective(SparseMatrix&& A, const Eigen::Ref<const Eigen::VectorXd>& weights) {
  State& s = *state_;
  if (A.rows() != weights.size()) {
    throw std::invalid_argument("ConstrainedLeastSquares: " + std::to_string(weights.size()) + " weights for " +
                                std::to_string(A.rows()) + " rows");
  }
  if (A.cols() != s.n()) {
    // A new unknown count drops the pins, constraints and hints that referred to the old one.
    s.pinned.clear();
    s.CT.resize(A.cols(), 0);
    s.row_norm.resize(0);
    s.modes.resize(0, 0);
  }
  s.A = std::move(A);
  s.A.makeCompressed();
  s.analysis_stale = true;
  set_weights(weights);
}

void ConstrainedLeastSquares::set_weights(const Eigen::Ref<const Eigen::VectorXd>& weights) {
  if (weights.size() != state_->A.rows()) {
    throw std::invalid_argument("ConstrainedLeastSquares: " + std::to_string(weights.size()) + " weights for " +
                                std::to_string(state_->A.rows()) + " rows");
  }
  if (!weights.allFinite() || (weights.array() < 0).any()) {
    throw std::invalid_argument("ConstrainedLeastSquares: weights must be finite and ≥ 0");
  }
  state_->weights = weights;
  state_->blocks_stale = true;
  state_->invalidate_factor();
}

void ConstrainedLeastSquares::set_pinned(std::vector<Eigen::Index> pinned) {
  state_->pinned = std::move(pinned);
  state_->analysis_stale = true;
  state_->invalidate_factor();
}

void ConstrainedLeastSquares::set_pin_basis(const SparseMatrix& basis) {
  state_->pin_basis = basis;
  state_->pin_basis.makeCompressed();
  state_->Z.resize(0, 0);
  state_->basis_stale = true;
}

void ConstrainedLeastSquares::set_constraints(const SparseMatrix& C) {
  state_->CT.resize(state_->n(), 0);
  state_->row_norm.resize(0);
  state_->invalidate_schur();
  add_constraints(C);
}

void ConstrainedLeastSquares::add_constraints(const SparseMatrix& C) {
  State& s = *state_;
  if (C.rows() == 0) return;
  if (C.cols() != s.n()) {
    throw std::invalid_argument("ConstrainedLeastSquares: constraints have " + std::to_string(C.cols()) +
                                " columns, the objective " + std::to_string(s.n()) + " unknowns");
  }
  SparseMatrix added = C.transpose();
  Eigen::VectorXd norms(added.cols());
  for (Index c = 0; c < added.cols(); ++c) {
    norms[c] = added.col(c).norm();
    if (!std::isfinite(norms[c])) throw std::invalid_argument("ConstrainedLeastSquares: constraint row is not finite");
    if (norms[c] > 0) added.col(c) /= norms[c];
  }
  SparseMatrix joined(s.n(), s.m() + added.cols());
  joined.reserve(s.CT.nonZeros() + added.nonZeros());
  // Column-major concatenation: copy both blocks column by column.
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(s.CT.nonZeros() + added.nonZeros()));
  for (Index c = 0; c < s.m(); ++c)
    for (SparseMatrix::InnerIterator it(s.CT, c); it; ++it) entries.emplace_back(it.row(), c, it.value());
  for (Index c = 0; c < added.cols(); ++c)
    for (SparseMatrix::InnerIterator it(added, c); it; ++it) entries.emplace_back(it.row(), s.m() + c, it.value());
  joined.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd all_norms(s.m() + added.cols());
  all_norms << s.row_norm, norms;
  s.CT = std::move(joined);
  s.row_norm = std::move(all_norms);
  if (!s.analysis_stale) s.split_constraints();
}

void ConstrainedLeastSquares::clear_constraints() {
  state_->CT.resize(state_->n(), 0);
  state_->row_norm.resize(0);
  state_->invalidate_schur();
  if (!state_->analysis_stale) state_->split_constraints();
}

void ConstrainedLeastSquares::set_near_null_space(const Eigen::Ref<const Eigen::MatrixXd>& modes, int block_size) {
  if (modes.cols() > 0 && modes.rows() != state_->n()) {
    throw std::invalid_argument("ConstrainedLeastSquares: near-null-space modes have " + std::to_string(modes.rows()) +
                                " rows for " + std::to_string(state_->n()) + " unknowns");
  }
  state_->modes = modes;
  state_->block_size = std::max(1, block_size);
  state_->analysis_stale = true;
  state_->invalidate_factor();
}

void ConstrainedLeastSquares::set_complex_pairs(bool complex_pairs) {
  state_->complex_pairs = complex_pairs;
  state_->analysis_stale = true;
  state_->invalidate_factor();
}

void ConstrainedLeastSquares::share_analysis(const ConstrainedLeastSquares* other) { state_->analysis_source = other; }

void ConstrainedLeastSquares::analyze() {
  State& s = *state_;
  if (s.n() == 0) throw std::invalid_argument("ConstrainedLeastSquares: set_objective() with at least one unknown first");
  if (s.analysis_stale) {
    const auto start = Clock::now();
    s.build_pin_maps();
    s.owned.clear();
    s.assemble_blocks(true);  // the backend's analysis sees the whole pattern (a distributed one lays out the ranks)
    s.split_constraints();
    if (s.free_count() > 0) {
      s.pass_hints();
      const State* source = s.analysis_source != nullptr ? s.analysis_source->state_.get() : nullptr;
      const bool adopted = source != nullptr && !source->analysis_stale && source->free_count() == s.free_count() &&
                           s.backend->adopt_analysis(*source->backend, s.Q_FF);
      if (!adopted) s.backend->analyze(s.Q_FF);
      s.report.adopted_analyses += adopted ? 1 : 0;
      s.owned = s.backend->owned_columns();
      s.keep_owned_columns();
    }
    s.analysis_stale = false;
    s.factor_stale = true;
    ++s.report.analyses;
    s.report.analyze_seconds = seconds_since(start);
  }
}

void ConstrainedLeastSquares::precompute() {
  State& s = *state_;
  if (s.has_basis() && s.pin_basis.rows() != static_cast<Index>(s.pinned.size())) {
    throw std::invalid_argument("ConstrainedLeastSquares: the pin basis has " + std::to_string(s.pin_basis.rows()) +
                                " rows for " + std::to_string(s.pinned.size()) + " pinned unknowns");
  }
  analyze();
  if (s.factor_stale) {
    const auto start = Clock::now();
    if (s.blocks_stale) s.assemble_blocks(false);
    if (s.free_count() > 0) s.factorize();
    s.Q_FF = SparseMatrix();  // the backend holds its own copy (factor or rows) from here on
    s.blocks_stale = true;    // Q_PF is still current: only Q_FF was released
    s.factor_stale = false;
    s.invalidate_schur();
    ++s.report.factorizations;
    s.report.factorization = s.backend->factorization_info();
    s.report.factorize_seconds = seconds_since(start);
  }
  if (s.schur_rows < s.m()) {
    const auto start = Clock::now();
    s.extend_schur();
    s.report.schur_seconds = seconds_since(start);
  }
  if (s.basis_solves() && s.basis_stale) {
    const auto start = Clock::now();
    s.solve_basis();
    s.report.basis_seconds = seconds_since(start);
  }
}

bool ConstrainedLeastSquares::precomputes_basis() const { return state_->basis_solves(); }

Eigen::MatrixXd ConstrainedLeastSquares::solve(const Eigen::Ref<const Eigen::MatrixXd>& b,
                                               const Eigen::Ref<const Eigen::MatrixXd>& pin_values,
                                               const Eigen::Ref<const Eigen::MatrixXd>& d) {
  return solve_any(b, pin_values, d, false);
}

Eigen::MatrixXd ConstrainedLeastSquares::solve_in_basis(const Eigen::Ref<const Eigen::MatrixXd>& b,
                                                        const Eigen::Ref<const Eigen::MatrixXd>& coordinates,
                                                        const Eigen::Ref<const Eigen::MatrixXd>& d) {
  if (!state_->has_basis()) throw std::invalid_argument("ConstrainedLeastSquares::solve_in_basis: set_pin_basis() first");
  return solve_any(b, coordinates, d, true);
}

Eigen::MatrixXd ConstrainedLeastSquares::solve_any(const Eigen::Ref<const Eigen::MatrixXd>& b,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& pins,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& d, bool in_basis) {
  State& s = *state_;
  if (!is_ready()) precompute();
  const Index k = b.cols();
  const Index pin_rows = in_basis ? s.pin_basis.cols() : static_cast<Index>(s.pinned.size());
  if (b.rows() != s.A.rows() || pins.rows() != pin_rows || d.rows() != s.m() || (pins.cols() != k && pins.size() > 0) ||
      (d.cols() != k && d.size() > 0)) {
    std::ostringstream what;
    what << "ConstrainedLeastSquares::solve: b is " << b.rows() << "×" << b.cols() << " (expected " << s.A.rows()
         << " rows), pin " << (in_basis ? "coordinates " : "values ") << pins.rows() << "×" << pins.cols() << " (expected "
         << pin_rows << " rows), d " << d.rows() << "×" << d.cols() << " (expected " << s.m() << " rows), same columns";
    throw std::invalid_argument(what.str());
  }
  if (!b.allFinite() || !pins.allFinite() || !d.allFinite()) {
    throw std::invalid_argument("ConstrainedLeastSquares::solve: a right-hand side, pin value or constraint value is not finite");
  }
  const auto start = Clock::now();
  const Index nf = s.free_count();
  const Eigen::MatrixXd given = pins.size() > 0 ? Eigen::MatrixXd(pins) : Eigen::MatrixXd::Zero(pin_rows, k);
  const Eigen::MatrixXd xp = in_basis ? Eigen::MatrixXd(s.pin_basis * given) : given;

  // (AᵀW b)_F, kept while b does not change.
  const bool new_b = s.last_b.rows() != b.rows() || s.last_b.cols() != b.cols() || s.last_b != b;
  if (new_b) {
    const Eigen::MatrixXd AtWb = s.A.transpose() * (s.weights.asDiagonal() * b);
    s.last_r.resize(nf, k);
    for (Index i = 0; i < nf; ++i) s.last_r.row(i) = AtWb.row(s.free_unknowns[static_cast<std::size_t>(i)]);
    s.last_b = b;
    s.last_g.resize(0, 0);
  }
  // r = (AᵀW b)_F − Q_FP x_P: the first back-substitution's right-hand side (and the uncached Schur path's).
  // With a distributed backend Q_PF holds this rank's columns only, so r is right in this rank's rows, the only
  // ones the backend reads.
  auto residual_rhs = [&] {
    Eigen::MatrixXd r = s.last_r;
    if (!s.pinned.empty()) r.noalias() -= s.Q_PF.transpose() * xp;
    return r;
  };

  Eigen::MatrixXd xf(nf, k);
  if (nf > 0 && in_basis && s.basis_solves()) {
    // x_F = Q_FF⁻¹ r_b − Z u: a back-substitution only when b changed.
    if (s.last_g.rows() != nf || s.last_g.cols() != k) {
      s.last_g.resize(nf, k);
      s.backend->solve(s.last_r, s.last_g);
      s.report.last_solve = s.backend->solve_info();
    }
    xf = s.last_g;
    xf.noalias() -= s.Z * given;
  } else if (nf > 0) {
    const Eigen::MatrixXd r = residual_rhs();
    if (s.last_x0.rows() == nf && s.last_x0.cols() == k) {
      xf = s.last_x0;
      s.backend->solve_from(r, xf);
    } else {
      s.backend->solve(r, xf);
    }
    s.report.last_solve = s.backend->solve_info();
    s.last_x0 = xf;
  }
  Eigen::MatrixXd d_unit = Eigen::MatrixXd::Zero(s.m(), k);
  Eigen::MatrixXd g;  // C_F x0 − (d − C_P x_P), the Schur right-hand side
  if (s.m() > 0) {
    for (Index c = 0; c < s.m(); ++c) {
      if (s.row_norm[c] > 0) d_unit.row(c) = d.row(c) / s.row_norm[c];
    }
    // S λ = C_F x0 − (d − C_P x_P);  x_F = x0 − Q_FF⁻¹ C_Fᵀ λ.
    g = s.CT_F.transpose() * xf - d_unit;
    if (!s.pinned.empty()) g.noalias() += s.CT_P.transpose() * xp;
    const Eigen::MatrixXd lambda = s.schur_solve(g);
    if (nf > 0) {
      if (s.y_cached) {
        xf.noalias() -= s.Y * lambda;
      } else {
        xf = s.solve_free(residual_rhs() - s.CT_F * lambda);
      }
    }
  }

  Eigen::MatrixXd x(s.n(), k);
  for (Index i = 0; i < nf; ++i) x.row(s.free_unknowns[static_cast<std::size_t>(i)]) = xf.row(i);
  for (std::size_t p = 0; p < s.pinned.size(); ++p) x.row(s.pinned[p]) = xp.row(static_cast<Index>(p));

  // Every constraint met? (Unit rows: the residual is in the units of x.)
  s.report.max_constraint_residual = 0;
  if (s.m() > 0) {
    const Eigen::MatrixXd residual = s.CT.transpose() * x - d_unit;
    const double tolerance = s.options.constraint_tolerance * (1.0 + x.cwiseAbs().maxCoeff());
    std::vector<Index> violated;
    for (Index c = 0; c < s.m(); ++c) {
      const double value = s.row_norm[c] > 0 ? residual.row(c).cwiseAbs().maxCoeff() : d.row(c).cwiseAbs().maxCoeff();
      s.report.max_constraint_residual = std::max(s.report.max_constraint_residual, value);
      if (value > tolerance) violated.push_back(c);
    }
    if (!violated.empty()) {
      // Name every row of the contradiction, not only the ones the pseudo-inverse happened to leave unmet.
      std::vector<Index> rows = s.conflicting_rows(g, tolerance);
      for (Index row : violated) {
        if (std::find(rows.begin(), rows.end(), row) == rows.end()) rows.push_back(row);
      }
      std::sort(rows.begin(), rows.end());
      std::ostringstream message;
      message << "the constraints contradict each other or the pins: constraint rows ";
      for (std::size_t i = 0; i < rows.size() && i < 8; ++i) message << (i ? ", " : "") << rows[i];
      message << (rows.size() > 8 ? ", ..." : "") << " cannot all be met (largest violation "
              << s.report.max_constraint_residual << ", tolerance " << tolerance << ")";
      throw ConstraintError(message.str(), std::move(rows));
    }
  }
  s.report.solve_seconds = seconds_since(start);
  return x;
}

Eigen::Index ConstrainedLeastSquares::unknowns() const noexcept { return state_->n(); }
Eigen::Index ConstrainedLeastSquares::constraints() const noexcept { return state_->m(); }
const std::vector<Eigen::Index>& ConstrainedLeastSquares::pinned() const noexcept { return state_->pinned; }
bool ConstrainedLeastSquares::is_ready() const noexcept {
  const State& s = *state_;
  return !s.analysis_stale && !s.factor_stale && s.schur_rows == s.m() && !(s.basis_solves() && s.basis_stale);
}
const LeastSquaresReport& ConstrainedLeastSquares::report() const noexcept { return state_->report; }
const SolverOptions& ConstrainedLeastSquares::options() const noexcept { return state_->options; }

Eigen::MatrixXd solve_least_squares(const SparseMatrix& A, const Eigen::Ref<const Eigen::VectorXd>& weights,
                                    const Eigen::Ref<const Eigen::MatrixXd>& b, const std::vector<Eigen::Index>& pinned,
                                    const Eigen::Ref<const Eigen::MatrixXd>& pin_values, const SparseMatrix& C,
                                    const Eigen::Ref<const Eigen::MatrixXd>& d, const SolverOptions& options) {
  ConstrainedLeastSquares solver(options);
  solver.set_objective(A, weights);
  solver.set_pinned(pinned);
  if (C.rows() > 0) solver.set_constraints(C);
  return solver.solve(b, pin_values, d);
}

}  // namespace throng::linalg
