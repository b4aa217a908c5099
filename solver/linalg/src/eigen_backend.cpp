// The default backend: CHOLMOD supernodal Cholesky (through Eigen's CholmodSupport, linked with OpenBLAS, 64-bit
// indices), and Eigen's SimplicialLDLT when CHOLMOD reports a failure other than lack of memory. With the
// complex-pairs hint, the matrix is factored as the complex Hermitian matrix it is in real form: half the
// unknowns, half the factor's memory and about half its flops (measured: 300 agents × 300 samples, factor
// 8.1 s → 4.0 s, solve 0.15 s → 0.09 s).
//
// Why supernodal: measured here on a 1,000-agent × 100-frame space-time system, Eigen's SimplicialLDLT
// factorises in ~40 s, a METIS-ordered simplicial LLᵀ in ~19 s, CHOLMOD supernodal in ~1.9 s; the supernodal
// path spends its time in dense BLAS kernels on the separators.
#include "backends.h"
#include "blas_threads.h"

#include <throng/core/errors.h>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace throng::linalg {
namespace {

// A factor whose (min/max diagonal)² is below this is treated as singular. Exact arithmetic would give a zero
// pivot; rounding leaves one near ε·‖Q‖, i.e. a ratio near 1e-16 .. 1e-30. Well-posed editing systems of a
// few hundred thousand unknowns measure above 1e-9 (tests/linalg): the threshold sits in between.
constexpr double singular_reciprocal_condition = 1e-13;

const char* ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    default: return "other";
  }
}

// Bytes of physical memory the kernel says can still be used, or nullopt when unknown.
std::optional<double> available_memory_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  double kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024.0;
  }
  return std::nullopt;
}

std::string gib(double bytes) {
  std::ostringstream out;
  out.precision(3);
  out << bytes / (1024.0 * 1024.0 * 1024.0) << " GiB";
  return out.str();
}

std::string singular_message(const char* by, double rcond) {
  std::ostringstream out;
  out << "the system is singular: " << by << " factor's (min/max diagonal)² is " << rcond << " (≤ "
      << singular_reciprocal_condition << "); the constraints and pins leave some unknowns undetermined";
  return out.str();
}

// The lower triangle of a real symmetric matrix, with CHOLMOD's 64-bit indices.
Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long> lower_triangle(const SparseMatrix& matrix) {
  Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long> lower(matrix.rows(), matrix.cols());
  Eigen::VectorX<SuiteSparse_long> counts = Eigen::VectorX<SuiteSparse_long>::Zero(matrix.cols());
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) counts[j] += it.row() >= j ? 1 : 0;
  }
  lower.reserve(counts);
  for (Eigen::Index j = 0; j < matrix.outerSize(); ++j) {
    for (SparseMatrix::InnerIterator it(matrix, j); it; ++it) {
      if (it.row() >= j) lower.insert(it.row(), j) = it.value();
    }
  }
  lower.makeCompressed();
  return lower;
}

// The lower triangle of the complex Hermitian matrix Z whose real form is `matrix` (interleaved pairs):
// Q[2a..2a+1, 2b..2b+1] = [[Re Z_ab, −Im Z_ab], [Im Z_ab, Re Z_ab]]. The two copies of each part, summed in
// different orders when Q was assembled, are averaged; a difference beyond rounding means Q is not of this form
// and the caller's hint was wrong (an internal error).
Eigen::SparseMatrix<std::complex<double>, Eigen::ColMajor, SuiteSparse_long> complex_lower_triangle(const SparseMatrix& matrix) {
  using Complex = std::complex<double>;
  const Eigen::Index pairs = matrix.rows() / 2;
  const double scale = matrix.coeffs().cwiseAbs().maxCoeff();
  std::vector<Eigen::Triplet<Complex, SuiteSparse_long>> entries;
  entries.reserve(static_cast<std::size_t>(matrix.nonZeros() / 4 + pairs));
  std::vector<double> re0, re1, im0, im1;  // per row pair a: Q[2a,2b], Q[2a+1,2b+1], Q[2a+1,2b], −Q[2a,2b+1]
  std::vector<Eigen::Index> touched;
  std::vector<char> seen(static_cast<std::size_t>(pairs), 0);
  re0.assign(static_cast<std::size_t>(pairs), 0);
  re1 = im0 = im1 = re0;
  for (Eigen::Index b = 0; b < pairs; ++b) {
    for (int side = 0; side < 2; ++side) {
      for (SparseMatrix::InnerIterator it(matrix, 2 * b + side); it; ++it) {
        const Eigen::Index a = it.row() / 2;
        if (a < b) continue;
        const auto k = static_cast<std::size_t>(a);
        if (!seen[k]) {
          seen[k] = 1;
          touched.push_back(a);
        }
        const bool odd_row = (it.row() % 2) == 1;
        if (side == 0) (odd_row ? im0 : re0)[k] += it.value();
        if (side == 1) (odd_row ? re1 : im1)[k] += odd_row ? it.value() : -it.value();
      }
    }
    for (Eigen::Index a : touched) {
      const auto k = static_cast<std::size_t>(a);
      if (std::abs(re0[k] - re1[k]) > 1e-10 * scale || std::abs(im0[k] - im1[k]) > 1e-10 * scale) {
        throw std::logic_error("SpdSolver: the matrix is not a complex Hermitian matrix in real form at pairs (" +
                               std::to_string(a) + ", " + std::to_string(b) + ") although the caller said so");
      }
      // Diagonal entries of a Hermitian matrix are real; the imaginary parts there are rounding.
      entries.emplace_back(a, b, Complex(0.5 * (re0[k] + re1[k]), a == b ? 0.0 : 0.5 * (im0[k] + im1[k])));
      re0[k] = re1[k] = im0[k] = im1[k] = 0;
      seen[k] = 0;
    }
    touched.clear();
  }
  Eigen::SparseMatrix<Complex, Eigen::ColMajor, SuiteSparse_long> lower(pairs, pairs);
  lower.setFromTriplets(entries.begin(), entries.end());
  lower.makeCompressed();
  return lower;
}

// CHOLMOD supernodal LLᵀ (or LLᴴ) with Eigen's SimplicialLDLT as the fallback, for one scalar type.
template <typename Scalar>
class Factorization {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, SuiteSparse_long>;
  using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;

  // Eigen's CHOLMOD wrapper with access to the factor (its diagonal and permutation).
  class SupernodalLlt : public Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower> {
   public:
    // Failures become exceptions, not printed lines. Ordering: CHOLMOD's nested dissection (METIS separators,
    // CAMD on the small pieces) alone. CHOLMOD's default strategy picked the natural order for the space-time
    // systems up to a few hundred agents (they come time-major, so natural is a band) and METIS for larger ones;
    // NESDIS measured best at every size (bench_edit, complex LLᴴ of both steps, 2 cores, shared):
    //   300 agents × 300 samples: natural 106 M entries, factorise 22.0 s; AMD 144 M, 57.8 s; METIS 68.3 M,
    //   8.6 s; NESDIS 68.3 M, 6.9 s. 1,000 × 300: METIS 448 M, 140 s; NESDIS 447 M, 90 s.
    SupernodalLlt() {
      auto& common = this->cholmod();
      common.print = 0;
      common.nmethods = 1;
      common.method[0].ordering = CHOLMOD_NESDIS;
    }
    [[nodiscard]] const cholmod_factor* factor() const { return this->m_cholmodFactor; }
    [[nodiscard]] double reciprocal_condition() { return cholmod_l_rcond(this->m_cholmodFactor, &this->cholmod()); }
    // Takes a copy of another's analysed factor (symbolic, plus numeric values when it has them: factorize()
    // overwrites those), as if analyzePattern() had run on the same pattern.
    bool adopt(const SupernodalLlt& other) {
      if (other.m_cholmodFactor == nullptr || !other.m_analysisIsOk) return false;
      cholmod_factor* copy = cholmod_l_copy_factor(other.m_cholmodFactor, &this->cholmod());
      if (copy == nullptr) return false;
      if (this->m_cholmodFactor != nullptr) cholmod_l_free_factor(&this->m_cholmodFactor, &this->cholmod());
      this->m_cholmodFactor = copy;
      this->m_info = Eigen::Success;
      this->m_analysisIsOk = true;
      this->m_factorizationIsOk = false;
      return true;
    }
  };

  // Reuses `other`'s analysis when `lower` has the pattern it analysed (the outer and inner index arrays).
  bool adopt(const Factorization& other, const Matrix& lower, FactorizationInfo& info, double& bytes) {
    if (!other.llt_ || other.pattern_outer_.size() != static_cast<std::size_t>(lower.outerSize()) + 1 ||
        other.pattern_inner_.size() != static_cast<std::size_t>(lower.nonZeros()) ||
        !std::equal(other.pattern_outer_.begin(), other.pattern_outer_.end(), lower.outerIndexPtr()) ||
        !std::equal(other.pattern_inner_.begin(), other.pattern_inner_.end(), lower.innerIndexPtr())) {
      return false;
    }
    auto llt = std::make_unique<SupernodalLlt>();
    if (!llt->adopt(*other.llt_)) return false;
    llt_ = std::move(llt);
    ldlt_.reset();
    pattern_outer_ = other.pattern_outer_;
    pattern_inner_ = other.pattern_inner_;
    info.factor_nonzeros = other.lnz_;
    lnz_ = other.lnz_;
    info.method = other.method_;
    method_ = other.method_;
    bytes = static_cast<double>(llt_->factor()->xsize) * sizeof(Scalar) + 64.0 * static_cast<double>(lower.rows());
    return true;
  }

  // Symbolic phase; returns nonzeros of L, the ordering's name and the bytes the numeric factor will take.
  void analyze(const Matrix& lower, FactorizationInfo& info, double& bytes) {
    llt_ = std::make_unique<SupernodalLlt>();
    ldlt_.reset();
    llt_->analyzePattern(lower);
    const auto& common = llt_->cholmod();
    if (common.status < CHOLMOD_OK) {
      throw NumericalError("CHOLMOD could not analyse the " + std::to_string(lower.rows()) + "-unknown system (status " +
                           std::to_string(common.status) + ")");
    }
    info.factor_nonzeros = common.lnz;
    info.method = std::string("CHOLMOD supernodal ") + (std::is_same_v<Scalar, double> ? "LLᵀ" : "complex LLᴴ") + " (" +
                  ordering_name(common.method[common.selected].ordering) + ")";
    method_ = info.method;
    lnz_ = common.lnz;
    pattern_outer_.assign(lower.outerIndexPtr(), lower.outerIndexPtr() + lower.outerSize() + 1);
    pattern_inner_.assign(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
    bytes = static_cast<double>(llt_->factor()->xsize) * sizeof(Scalar) + 64.0 * static_cast<double>(lower.rows());
  }

  // Numeric phase. `unknowns_per_row` maps a row of this matrix to the caller's first unknown (1 or 2).
  void factorize(const Matrix& lower, FactorizationInfo& info, int unknowns_per_row) {
    ldlt_.reset();
    info.fallback_reason.clear();
    llt_->factorize(lower);
    const int status = llt_->cholmod().status;
    if (status == CHOLMOD_OUT_OF_MEMORY || status == CHOLMOD_TOO_LARGE) {
      throw NumericalError("CHOLMOD ran out of memory factorising the " + std::to_string(lower.rows()) +
                           "-row system (factor of " + std::to_string(static_cast<long long>(info.factor_nonzeros)) +
                           " entries); use the petsc backend (distributed over ranks) or a smaller problem");
    }
    if (llt_->info() == Eigen::Success) {
      info.reciprocal_condition = llt_->reciprocal_condition();
      if (!(info.reciprocal_condition > singular_reciprocal_condition)) {
        throw SingularMatrixError(singular_message("CHOLMOD", info.reciprocal_condition), -1);
      }
      return;
    }
    // CHOLMOD broke down at a pivot: try Eigen's LDLᵀ, which tolerates what rounding did to LLᵀ's square roots.
    const auto* factor = llt_->factor();
    const Eigen::Index broke_at = static_cast<Eigen::Index>(factor->minor) < lower.rows() && factor->Perm != nullptr
                                      ? unknowns_per_row * static_cast<SuiteSparse_long*>(factor->Perm)[factor->minor]
                                      : -1;
    info.fallback_reason = "CHOLMOD reported the matrix not positive definite at row " + std::to_string(broke_at) +
                           " (status " + std::to_string(status) + "); used Eigen SimplicialLDLT";
    ldlt_ = std::make_unique<Eigen::SimplicialLDLT<Matrix, Eigen::Lower>>();
    ldlt_->compute(lower);
    if (ldlt_->info() != Eigen::Success) {
      throw SingularMatrixError("the system is singular: CHOLMOD and Eigen's LDLᵀ both broke down (first at row " +
                                    std::to_string(broke_at) + ")",
                                broke_at);
    }
    const Eigen::VectorXd d = ldlt_->vectorD().real();
    Eigen::Index worst = 0;
    const double min_d = d.minCoeff(&worst);
    const double max_d = d.cwiseAbs().maxCoeff();
    info.reciprocal_condition = max_d > 0 ? min_d / max_d : 0;
    info.method = "Eigen SimplicialLDLT (AMD)";
    info.factor_nonzeros = static_cast<double>(ldlt_->matrixL().nestedExpression().nonZeros());
    if (!(info.reciprocal_condition > singular_reciprocal_condition)) {
      const Eigen::Index row = unknowns_per_row * ldlt_->permutationPinv().indices()[worst];
      throw SingularMatrixError(singular_message("LDLᵀ", info.reciprocal_condition), row);
    }
  }

  void solve(const Eigen::Ref<const Dense>& rhs, Eigen::Ref<Dense> solution) {
    if (ldlt_) {
      solution = ldlt_->solve(rhs);
      return;
    }
    assert(llt_ && "factorize() before solve()");
    solution = llt_->solve(rhs);
    if (llt_->info() != Eigen::Success) throw NumericalError("CHOLMOD's triangular solve failed");
  }

 private:
  std::unique_ptr<SupernodalLlt> llt_;
  std::unique_ptr<Eigen::SimplicialLDLT<Matrix, Eigen::Lower>> ldlt_;
  // The analysed pattern (for adopt()) and the method's name.
  std::vector<SuiteSparse_long> pattern_outer_, pattern_inner_;
  std::string method_;
  double lnz_ = 0;
};

class EigenSpdSolver final : public SpdSolver {
 public:
  explicit EigenSpdSolver(const SolverOptions& options) : options_(options) {}

  [[nodiscard]] std::string name() const override { return "eigen"; }

  void set_complex_pairs(bool complex_pairs) override {
    complex_pairs_ = complex_pairs;
    real_.reset();
    complex_.reset();
  }

  void analyze(const SparseMatrix& matrix) override {
    check_square(matrix);
    const BlasThreadScope threads(options_.blas_threads);
    info_ = {};
    double bytes = 0;
    if (use_complex(matrix)) {
      real_.reset();
      complex_ = std::make_unique<Factorization<std::complex<double>>>();
      complex_->analyze(complex_lower_triangle(matrix), info_, bytes);
    } else {
      complex_.reset();
      real_ = std::make_unique<Factorization<double>>();
      real_->analyze(lower_triangle(matrix), info_, bytes);
    }
    check_memory(matrix.rows(), bytes);
  }

  bool adopt_analysis(const SpdSolver& other_solver, const SparseMatrix& matrix) override {
    const auto* other = dynamic_cast<const EigenSpdSolver*>(&other_solver);
    if (other == nullptr || matrix.rows() != matrix.cols() || use_complex(matrix) != other->use_complex(matrix)) return false;
    FactorizationInfo info;
    double bytes = 0;
    if (use_complex(matrix)) {
      if (!other->complex_) return false;
      auto mine = std::make_unique<Factorization<std::complex<double>>>();
      if (!mine->adopt(*other->complex_, complex_lower_triangle(matrix), info, bytes)) return false;
      real_.reset();
      complex_ = std::move(mine);
    } else {
      if (!other->real_) return false;
      auto mine = std::make_unique<Factorization<double>>();
      if (!mine->adopt(*other->real_, lower_triangle(matrix), info, bytes)) return false;
      complex_.reset();
      real_ = std::move(mine);
    }
    info_ = info;
    check_memory(matrix.rows(), bytes);
    return true;
  }

  void factorize(const SparseMatrix& matrix) override {
    check_square(matrix);
    if (!real_ && !complex_) analyze(matrix);
    const BlasThreadScope threads(options_.blas_threads);
    if (complex_) {
      complex_->factorize(complex_lower_triangle(matrix), info_, 2);
    } else {
      real_->factorize(lower_triangle(matrix), info_, 1);
    }
  }

  void solve(const Eigen::Ref<const Eigen::MatrixXd>& rhs, Eigen::Ref<Eigen::MatrixXd> solution) override {
    const BlasThreadScope threads(options_.blas_threads);
    solve_info_ = {};
    if (real_) {
      real_->solve(rhs, solution);
      return;
    }
    assert(complex_ && "factorize() before solve()");
    // Interleaved (x, y) rows are the memory layout of complex x + i y: view both sides as complex.
    using ComplexDense = Eigen::Matrix<std::complex<double>, Eigen::Dynamic, Eigen::Dynamic>;
    const Eigen::MatrixXd packed_rhs = rhs;  // contiguous, column-major
    ComplexDense complex_solution(rhs.rows() / 2, rhs.cols());
    complex_->solve(Eigen::Map<const ComplexDense>(reinterpret_cast<const std::complex<double>*>(packed_rhs.data()),
                                                   rhs.rows() / 2, rhs.cols()),
                    complex_solution);
    solution = Eigen::Map<const Eigen::MatrixXd>(reinterpret_cast<const double*>(complex_solution.data()), rhs.rows(),
                                                 rhs.cols());
  }

  [[nodiscard]] const FactorizationInfo& factorization_info() const override { return info_; }
  [[nodiscard]] const SolveInfo& solve_info() const override { return solve_info_; }

 private:
  static void check_square(const SparseMatrix& matrix) {
    if (matrix.rows() != matrix.cols()) throw std::invalid_argument("SpdSolver: the matrix is not square");
  }

  [[nodiscard]] bool use_complex(const SparseMatrix& matrix) const { return complex_pairs_ && matrix.rows() % 2 == 0; }

  // Refuses to start a factorisation the machine cannot hold, before spending minutes on it.
  static void check_memory(Eigen::Index n, double needed) {
    const auto available = available_memory_bytes();
    if (available && needed > *available) {
      throw NumericalError("the Cholesky factor of the " + std::to_string(n) + "-unknown system needs " + gib(needed) +
                           " but " + gib(*available) +
                           " are available: use the petsc backend (iterative, distributed over ranks), a shorter "
                           "clip, a coarser sampling or fewer agents");
    }
  }

  SolverOptions options_;
  bool complex_pairs_ = false;
  std::unique_ptr<Factorization<double>> real_;
  std::unique_ptr<Factorization<std::complex<double>>> complex_;
  FactorizationInfo info_;
  SolveInfo solve_info_;
};

}  // namespace

std::unique_ptr<SpdSolver> make_eigen_solver(const SolverOptions& options) {
  return std::make_unique<EigenSpdSolver>(options);
}

}  // namespace throng::linalg
