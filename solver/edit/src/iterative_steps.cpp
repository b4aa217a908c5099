#include "iterative_steps.h"

#include "systems.h"

#include <throng/core/errors.h>
#include <throng/linalg/conjugate_gradients.h>
#include <throng/linalg/least_squares.h>
#include <throng/linalg/solution_history.h>

#include <Eigen/QR>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

namespace throng::edit {
namespace {

using Index = Eigen::Index;
using linalg::Complex;
using linalg::ComplexBlock;
using linalg::ComplexSparse;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// The handle-basis and constraint columns (solved once per handle or constraint set) stop at this fraction of
// their size: a drag's error from them is this fraction of its own displacement.
constexpr double column_relative_tolerance = 1e-7;
// Schur pivots below this fraction of the largest are redundant constraint rows. The constraint columns' own
// error (column_relative_tolerance) leaves exactly redundant rows this much above zero at most.
constexpr double redundant_pivot = 1e-6;
// Constraint corrections: the first from S, then refinements against the residual (S is symmetrised).
constexpr int constraint_passes = 3;
// Solutions kept for the drags' starts (linalg/solution_history.h): 8 measured best at 300 agents (fewer: more
// iterations on curved gestures; more: memory, 2 × 16 bytes per unknown each).
constexpr int history_size = 8;

// The real handle basis (2·#handles by #coordinates, rows x, y per handle) as a complex one (#handles by
// #coordinates / 2), when it has the complex-pair form of request.h (columns in pairs acting as one complex
// coordinate: [[Re β, −Im β], [Im β, Re β]] per handle). Returns false when it has not.
bool complex_basis(const linalg::SparseMatrix& B, ComplexSparse& out) {
  if (B.cols() % 2 != 0 || B.rows() % 2 != 0) return false;
  const Eigen::MatrixXd dense = Eigen::MatrixXd(B);
  const Index h = B.rows() / 2, m = B.cols() / 2;
  std::vector<Eigen::Triplet<Complex>> entries;
  for (Index k = 0; k < h; ++k) {
    for (Index c = 0; c < m; ++c) {
      const double re = dense(2 * k, 2 * c), im = dense(2 * k + 1, 2 * c);
      if (dense(2 * k, 2 * c + 1) != -im || dense(2 * k + 1, 2 * c + 1) != re) return false;
      if (re != 0 || im != 0) entries.emplace_back(k, c, Complex(re, im));
    }
  }
  out.resize(h, m);
  out.setFromTriplets(entries.begin(), entries.end());
  out.makeCompressed();
  return true;
}

// The real constraint rows C (#rows by 2·#vertices) scaled to unit length, as complex columns over the free
// and the pinned vertices, and as real columns.
void constraint_columns(const linalg::SparseMatrix& C, const VertexSplit& split, ComplexSparse& CF, ComplexSparse& CP,
                        linalg::SparseMatrix& CT, Eigen::VectorXd& norms) {
  CT = C.transpose();
  norms.resize(CT.cols());
  for (Index c = 0; c < CT.cols(); ++c) {
    norms[c] = CT.col(c).norm();
    if (!std::isfinite(norms[c])) throw std::invalid_argument("IterativeSteps: a constraint row is not finite");
    if (norms[c] > 0) CT.col(c) /= norms[c];
  }
  std::vector<Eigen::Triplet<Complex>> free_entries, pinned_entries;
  for (Index c = 0; c < CT.cols(); ++c) {
    for (linalg::SparseMatrix::InnerIterator it(CT, c); it; ++it) {
      const auto v = static_cast<std::size_t>(it.row() / 2);
      // Re(conj(ĉ) z) = c_x x + c_y y  with  ĉ = c_x + i c_y.
      const Complex value = it.row() % 2 == 0 ? Complex(it.value(), 0) : Complex(0, it.value());
      if (split.free_index[v] >= 0) free_entries.emplace_back(split.free_index[v], c, value);
      else pinned_entries.emplace_back(split.pin_index[v], c, value);
    }
  }
  CF.resize(static_cast<Index>(split.free.size()), CT.cols());
  CF.setFromTriplets(free_entries.begin(), free_entries.end());
  CF.makeCompressed();
  CP.resize(static_cast<Index>(split.pinned.size()), CT.cols());
  CP.setFromTriplets(pinned_entries.begin(), pinned_entries.end());
  CP.makeCompressed();
}

ComplexBlock dense(const ComplexSparse& M) { return ComplexBlock(Eigen::MatrixXcd(M)); }

}  // namespace

struct IterativeSteps::Step {
  StepKind kind = StepKind::deformation;
  double alpha = 0, beta = 0;
  ComplexSystem system;
  std::unique_ptr<linalg::TwoLevelPreconditioner> preconditioner;
  ComplexBlock Z;     // Q_FF⁻¹ Q_FP B (#free by #coordinates)
  ComplexBlock Y;     // Q_FF⁻¹ Ĉ_F (#free by #constraint rows)
  Eigen::LDLT<Eigen::MatrixXd> S;  // Re(Ĉ_Fᴴ Y), symmetrised
  Eigen::MatrixXd S_raw;           // Re(Ĉ_Fᴴ Y) as computed
  // The drags' solutions so far (h with a basis, the change from the input without), whose span gives the next
  // drag's start (linalg/solution_history.h), and the last one.
  linalg::SolutionHistory history{history_size};
  ComplexBlock warm;
  // Kept between drags so that a drag faults no new page in: right-hand side, A x, positions, CG's vectors.
  ComplexBlock rhs, ax;
  // Step 2: a guess at the drag's solution from step 1's result and Q_FF times it (solve_step); with a basis,
  // guess_product = Q_FF (Z − Z₁) from the precompute, so that Q_FF times the guess costs no product with Q_FF.
  ComplexBlock guess, a_guess, guess_product;
  Eigen::VectorXcd z;
  linalg::CgWorkspace workspace;
  int iterations = 0;
  double last_step = 0;

  linalg::CgReport solve(const ComplexBlock& b, ComplexBlock& x, const std::vector<double>& tolerance, int max_iterations) {
    return linalg::conjugate_gradients(system.FF, *preconditioner, b, x, tolerance, max_iterations, workspace);
  }

  // A drag's solve of Q_FF x = rhs into `warm`, started from the Galerkin start in the span of the history (and
  // of `guess`, with `a_guess` = Q_FF guess, when with_guess); the solution joins the history.
  linalg::CgReport solve_drag(double tolerance, int max_iterations, bool with_guess) {
    if (with_guess) {
      history.start(rhs, guess, a_guess, warm, workspace.R);
    } else {
      history.start(rhs, warm, workspace.R);
    }
    workspace.residual_given = true;
    const auto report = solve(rhs, warm, {tolerance}, max_iterations);
    ax = rhs - workspace.R;  // Q_FF x, from the solve's own residual
    history.add(warm, ax);
    return report;
  }

  // λ with S λ = g, redundant pivots dropped (as linalg's ConstrainedLeastSquares does).
  Eigen::VectorXd schur_solve(const Eigen::VectorXd& g) const {
    const Eigen::VectorXd D = S.vectorD();
    const double largest = D.size() > 0 ? D.cwiseAbs().maxCoeff() : 0.0;
    Eigen::VectorXd y = S.transpositionsP() * g;
    S.matrixL().solveInPlace(y);
    for (Index i = 0; i < D.size(); ++i) y[i] *= D[i] > redundant_pivot * largest ? 1.0 / D[i] : 0.0;
    S.matrixU().solveInPlace(y);
    return S.transpositionsP().transpose() * y;
  }

  // Rows taking part in a contradiction seen by g (see least_squares.cpp, conflicting_rows).
  std::vector<Index> conflicting_rows(const Eigen::VectorXd& g, double tolerance) const {
    const Eigen::VectorXd D = S.vectorD();
    const double largest = D.size() > 0 ? D.cwiseAbs().maxCoeff() : 0.0;
    const Index m = D.size();
    std::vector<char> involved(static_cast<std::size_t>(m), 0);
    for (Index i = 0; i < m; ++i) {
      if (D[i] > redundant_pivot * largest) continue;
      Eigen::VectorXd null = Eigen::VectorXd::Unit(m, i);
      S.matrixU().solveInPlace(null);
      null = S.transpositionsP().transpose() * null;
      null /= null.cwiseAbs().maxCoeff();
      if (std::abs(null.dot(g)) <= tolerance) continue;
      for (Index r = 0; r < m; ++r) involved[static_cast<std::size_t>(r)] |= std::abs(null[r]) > 1e-8 ? 1 : 0;
    }
    std::vector<Index> rows;
    for (Index r = 0; r < m; ++r) {
      if (involved[static_cast<std::size_t>(r)]) rows.push_back(r);
    }
    return rows;
  }
};

IterativeSteps::IterativeSteps(const MotionGraph& graph, const FeatureSet& features, const Options& options)
    : graph_(graph), features_(features), options_(options) {
  const Clip& clip = graph.clip;
  z0_.resize(clip.positions.rows());
  for (Index v = 0; v < clip.positions.rows(); ++v) z0_[v] = Complex(clip.positions(v, 0), clip.positions(v, 1));
  step1_ = std::make_unique<Step>();
  step1_->kind = StepKind::deformation;
  step1_->alpha = options.alpha;
  step1_->beta = options.beta;
  if (options.scale_compensation) {
    step2_ = std::make_unique<Step>();
    step2_->kind = StepKind::scale_compensation;
    step2_->alpha = options.alpha_prime;
    step2_->beta = options.beta_prime;
  }
}

IterativeSteps::~IterativeSteps() = default;

void IterativeSteps::apply(const ResolvedRequest& resolved, const ResolvedRequest* previous) {
  previous_handles_ = previous != nullptr ? previous->handle_vertices : std::vector<Index>{};
  if (previous == nullptr || resolved.handle_vertices != previous->handle_vertices) handles_stale_ = true;
  if (previous == nullptr || handles_stale_ || !same_matrix(resolved.handle_basis, previous->handle_basis)) basis_stale_ = true;
  if (previous == nullptr || handles_stale_ || !same_matrix(resolved.C, previous->C)) constraints_stale_ = true;
}

bool IterativeSteps::is_ready() const { return !handles_stale_ && !basis_stale_ && !constraints_stale_; }

void IterativeSteps::precompute(const ResolvedRequest& current) {
  const auto start = Clock::now();
  const linalg::SolverOptions& o = options_.solver;
  std::vector<Step*> steps{step1_.get()};
  if (step2_) steps.push_back(step2_.get());
  if (handles_stale_) {
    const auto assemble_start = Clock::now();
    handles_ = current.handle_vertices;
    split_ = VertexSplit::of(graph_.vertex_count(), static_cast<int>(graph_.agent_count()), handles_);
    z0_free_.resize(static_cast<Index>(split_.free.size()));
    for (std::size_t i = 0; i < split_.free.size(); ++i) z0_free_[static_cast<Index>(i)] = z0_[split_.free[i]];
    for (Step* step : steps) {
      step->preconditioner.reset();
      step->system = assemble_complex(features_, step->kind, step->alpha, step->beta, split_);
      step->Z.resize(0, 0);
      step->Y.resize(0, 0);
      step->warm = ComplexBlock::Zero(static_cast<Index>(split_.free.size()), 1);
      step->history.clear();
    }
    assemble_seconds_ = seconds_since(assemble_start);
    const auto preconditioner_start = Clock::now();
    coarsening_ = make_coarsening(graph_, split_, o.coarse_agents, o.coarse_samples, o.coarse_functions, options_.local.seed);
    linalg::TwoLevelOptions two_level;
    two_level.blas_threads = o.blas_threads;
    for (Step* step : steps) {
      if (split_.free.empty()) continue;
      try {
        step->preconditioner = std::make_unique<linalg::TwoLevelPreconditioner>(step->system.FF, coarsening_.chains,
                                                                                coarsening_.basis, two_level);
      } catch (const linalg::SingularMatrixError& e) {
        // The preconditioner names a free position; the Editor names real unknowns (2 per vertex).
        const Index free = e.index();
        throw linalg::SingularMatrixError(e.what(), free >= 0 ? 2 * static_cast<Index>(split_.free[static_cast<std::size_t>(free)]) : -1);
      }
    }
    preconditioner_seconds_ = seconds_since(preconditioner_start);
    handles_stale_ = false;
    basis_stale_ = constraints_stale_ = true;
    ++precomputes_;
  }
  const auto columns_start = Clock::now();
  precompute_iterations_ = 0;
  const auto nf = static_cast<Index>(split_.free.size());
  const bool probe_now = basis_stale_;  // the history was cleared with the basis: seed it again
  if (basis_stale_) {
    // The handles' complex basis and the coordinates of their input places (B u⁰ = x⁰_P).
    use_basis_ = false;
    if (current.handle_basis.cols() <= linalg::ConstrainedLeastSquares::max_basis_columns && complex_basis(current.handle_basis, basis_)) {
      Eigen::VectorXcd input_places(static_cast<Index>(split_.pinned.size()));
      for (std::size_t k = 0; k < split_.pinned.size(); ++k) input_places[static_cast<Index>(k)] = z0_[split_.pinned[k]];
      const Eigen::MatrixXcd B = Eigen::MatrixXcd(basis_);
      u0_ = B.colPivHouseholderQr().solve(input_places);
      const double scale = 1.0 + input_places.cwiseAbs().maxCoeff();
      use_basis_ = B.cols() > 0 && (B * u0_ - input_places).cwiseAbs().maxCoeff() <= 1e-9 * scale;
    }
    for (Step* step : steps) {
      step->warm.setZero();
      step->history.clear();
      if (!use_basis_ || nf == 0) {
        step->Z.resize(0, 0);
        continue;
      }
      // Z = Q_FF⁻¹ (Q_FP B), every column at once, each to a fraction of its size (the size of B's column).
      const ComplexBlock rhs = dense(ComplexSparse(step->system.FP * basis_));
      std::vector<double> tolerance(static_cast<std::size_t>(basis_.cols()));
      const Eigen::MatrixXcd B = Eigen::MatrixXcd(basis_);
      for (Index c = 0; c < basis_.cols(); ++c) tolerance[static_cast<std::size_t>(c)] = column_relative_tolerance * std::max(1.0, B.col(c).cwiseAbs().maxCoeff());
      step->Z = ComplexBlock::Zero(nf, basis_.cols());
      const auto cg = step->solve(rhs, step->Z, tolerance, o.max_iterations);
      precompute_iterations_ = std::max(precompute_iterations_, cg.iterations);
    }
    if (step2_) {
      step2_->guess_product.resize(0, 0);
      if (use_basis_ && nf > 0) linalg::multiply(step2_->system.FF, ComplexBlock(step2_->Z - step1_->Z), step2_->guess_product);
    }
    basis_stale_ = false;
  }
  if (constraints_stale_) {
    constraint_columns(current.C, split_, CF_, CP_, CT_, row_norm_);
    const Index m = CF_.cols();
    const double bytes = 16.0 * static_cast<double>(nf) * static_cast<double>(m) * static_cast<double>(steps.size());
    if (bytes > o.schur_cache_megabytes * 1024.0 * 1024.0) {
      std::ostringstream what;
      what.precision(3);
      what << "the iterative method keeps Q⁻¹Cᵀ for its " << m << " constraint rows: " << bytes / 1e9 << " GB, above "
           << "solver.schur_cache_megabytes (" << o.schur_cache_megabytes << " MB); raise it, constrain fewer frames, or "
           << "use solver.method: direct";
      throw NumericalError(what.str());
    }
    for (Step* step : steps) {
      if (m == 0 || nf == 0) {
        step->Y.resize(nf, 0);
        step->S_raw.resize(0, 0);
        step->S.compute(Eigen::MatrixXd(0, 0));
        continue;
      }
      const ComplexBlock rhs = dense(CF_);
      // Columns' sizes from one application of the preconditioner (what the first iteration reaches).
      ComplexBlock first;
      step->preconditioner->apply(rhs, first);
      std::vector<double> tolerance = linalg::column_max_abs(first);
      for (double& t : tolerance) t = column_relative_tolerance * std::max(t, 1e-300);
      step->Y = ComplexBlock::Zero(nf, m);
      const auto cg = step->solve(rhs, step->Y, tolerance, o.max_iterations);
      precompute_iterations_ = std::max(precompute_iterations_, cg.iterations);
      // S = Re(Ĉ_Fᴴ Y) (m × m), column by column of Y.
      step->S_raw = (ComplexSparse(CF_.adjoint()) * step->Y).real();
      step->S.compute(0.5 * (step->S_raw + step->S_raw.transpose()));
    }
    constraints_stale_ = false;
  }
  if (probe_now && drags_follow_ && step2_ && use_basis_ && nf > 0) probe_drags(current);
  columns_seconds_ = seconds_since(columns_start);
  precompute_seconds_ = seconds_since(start);
}

void IterativeSteps::probe_drags(const ResolvedRequest& current) {
  // The drag (see the header): a new one, else a moved one, else the last.
  const ResolvedRequest::DragPlacement* added = nullptr;
  const ResolvedRequest::DragPlacement* moved = nullptr;
  const ResolvedRequest::DragPlacement* last = nullptr;
  for (const ResolvedRequest::DragPlacement& drag : current.drags) {
    if (!drag.alone || drag.rows.empty()) continue;
    last = &drag;
    // Its coordinates (cos θ, sin θ, t_x, t_y) are (1, 0, 0, 0) when it holds its selection in place (request.cpp).
    if (moved == nullptr && current.handle_coordinates.segment<4>(drag.column) != Eigen::Vector4d(1, 0, 0, 0)) moved = &drag;
    const bool is_new = !previous_handles_.empty() && std::any_of(drag.rows.begin(), drag.rows.end(), [&](Index row) {
      return !std::binary_search(previous_handles_.begin(), previous_handles_.end(), current.handle_vertices[static_cast<std::size_t>(row)]);
    });
    if (is_new) added = &drag;
  }
  const ResolvedRequest::DragPlacement* chosen = added ? added : moved ? moved : last;
  if (chosen == nullptr) return;
  // It moved by probe_offset_m along +x, +y, −x and −y from where the request has it, each solved as a drag is;
  // the step-2 solutions stay in the history (four around the drag span its own solution too, to second order).
  Report report;
  Positions x1, x2;
  ResolvedRequest probe = current;
  for (int k = 0; k < 4; ++k) {
    const int axis = k % 2;
    const double offset = k < 2 ? probe_offset_m : -probe_offset_m;
    probe.handle_coordinates = current.handle_coordinates;
    probe.handle_coordinates[chosen->column + 2 + axis] += offset;  // the translation's x or y (request.cpp)
    for (const Index row : chosen->rows) {
      probe.handle_targets.row(row) = current.handle_targets.row(row);
      probe.handle_targets(row, axis) += offset;
    }
    try {
      solve(probe, x1, x2, report);
    } catch (const NumericalError&) {
      // The constraints hold this drag where it is, or the solver stopped short: the probes only speed drags up,
      // so the precompute goes on without the rest (the drags report any real failure themselves).
      return;
    }
    precompute_iterations_ = std::max(precompute_iterations_, report.iterations);
  }
}

void IterativeSteps::solve_step(Step& step, const ResolvedRequest& current, const Eigen::VectorXcd& du,
                                const Eigen::VectorXcd* rhs, Positions& x, Report& report) {
  const linalg::SolverOptions& o = options_.solver;
  const auto nf = static_cast<Index>(split_.free.size());
  Eigen::VectorXcd& z = step.z;
  z = z0_free_;
  step.iterations = 0;
  step.last_step = 0;
  if (nf > 0) {
    if (use_basis_) {
      z.noalias() -= step.Z * du;
      if (rhs != nullptr) {
        step.rhs = *rhs;
        // Step 2 starts near step 1's positions z₁ = z⁰ − Z₁ du (scale compensation moves them by less than the
        // drag did): the part this solve adds would be z₁ − (z⁰ − Z du) = (Z − Z₁) du.
        step.guess.resize(nf, 1);
        step.guess.col(0) = step1_->z - z;
        step.a_guess.resize(nf, 1);
        step.a_guess.col(0).noalias() = step.guess_product * du;
        const auto cg = step.solve_drag(o.position_tolerance, o.max_iterations, true);
        step.iterations = cg.iterations;
        step.last_step = cg.error_estimate[0];
        z += step.warm.col(0);
      }
    } else {
      // The change from the input: Q_FF δ = r − Q_FP δ_P.
      Eigen::VectorXcd dp(static_cast<Index>(split_.pinned.size()));
      for (std::size_t k = 0; k < split_.pinned.size(); ++k) {
        const auto row = static_cast<Index>(k);
        dp[row] = Complex(current.handle_targets(row, 0), current.handle_targets(row, 1)) - z0_[split_.pinned[k]];
      }
      step.rhs.resize(nf, 1);
      step.rhs.col(0) = -(step.system.FP * dp);
      if (rhs != nullptr) step.rhs.col(0) += *rhs;
      // Step 2 starts near step 1's change (see above), at the price of one product with Q_FF.
      if (rhs != nullptr) {
        step.guess = step1_->warm;
        linalg::multiply(step.system.FF, step.guess, step.a_guess);
      }
      const auto cg = step.solve_drag(o.position_tolerance, o.max_iterations, rhs != nullptr);
      step.iterations = cg.iterations;
      step.last_step = cg.error_estimate[0];
      z += step.warm.col(0);
    }
  }
  // Positions: free ones solved, handles exactly at their targets.
  x.resize(static_cast<Index>(z0_.size()), 2);
  for (std::size_t i = 0; i < split_.free.size(); ++i) x.row(split_.free[i]) << z[static_cast<Index>(i)].real(), z[static_cast<Index>(i)].imag();
  for (std::size_t k = 0; k < split_.pinned.size(); ++k) x.row(split_.pinned[k]) = current.handle_targets.row(static_cast<Index>(k));
  // General constraints: x_F −= Y λ with S λ = C x − d (unit rows), refined against the residual.
  const Index m = CT_.cols();
  if (m == 0) return;
  Eigen::VectorXd d_unit = Eigen::VectorXd::Zero(m);
  for (Index c = 0; c < m; ++c) {
    if (row_norm_[c] > 0) d_unit[c] = current.d[c] / row_norm_[c];
  }
  Eigen::VectorXd flat(2 * x.rows());
  auto residual = [&] {
    for (Index v = 0; v < x.rows(); ++v) {
      flat[2 * v] = x(v, 0);
      flat[2 * v + 1] = x(v, 1);
    }
    return Eigen::VectorXd(CT_.transpose() * flat - d_unit);
  };
  Eigen::VectorXd g = residual();
  const Eigen::VectorXd first_g = g;
  for (int pass = 0; pass < constraint_passes && nf > 0; ++pass) {
    const Eigen::VectorXd lambda = step.schur_solve(g);
    const Eigen::VectorXcd correction = step.Y * lambda.cast<Complex>();
    for (std::size_t i = 0; i < split_.free.size(); ++i) {
      const Complex c = correction[static_cast<Index>(i)];
      x(split_.free[i], 0) -= c.real();
      x(split_.free[i], 1) -= c.imag();
    }
    g = residual();
  }
  const double tolerance_c = o.constraint_tolerance * (1.0 + x.cwiseAbs().maxCoeff());
  std::vector<Index> violated;
  double largest = 0;
  for (Index c = 0; c < m; ++c) {
    const double value = row_norm_[c] > 0 ? std::abs(g[c]) : std::abs(current.d[c]);
    largest = std::max(largest, value);
    if (value > tolerance_c) violated.push_back(c);
  }
  report.max_constraint_residual = std::max(report.max_constraint_residual, largest);
  if (!violated.empty()) {
    std::vector<Index> rows = nf > 0 ? step.conflicting_rows(first_g, tolerance_c) : std::vector<Index>{};
    for (Index row : violated) {
      if (std::find(rows.begin(), rows.end(), row) == rows.end()) rows.push_back(row);
    }
    std::sort(rows.begin(), rows.end());
    std::ostringstream message;
    message << "the constraints contradict each other or the pins: constraint rows ";
    for (std::size_t i = 0; i < rows.size() && i < 8; ++i) message << (i ? ", " : "") << rows[i];
    message << (rows.size() > 8 ? ", ..." : "") << " cannot all be met (largest violation " << largest << ", tolerance "
            << tolerance_c << ")";
    throw linalg::ConstraintError(message.str(), std::move(rows));
  }
}

void IterativeSteps::solve(const ResolvedRequest& current, Positions& x1, Positions& x2, Report& report) {
  const auto start = Clock::now();
  report.max_constraint_residual = 0;
  Eigen::VectorXcd du;
  if (use_basis_) {
    const Index m = basis_.cols();
    du.resize(m);
    for (Index c = 0; c < m; ++c) du[c] = Complex(current.handle_coordinates[2 * c], current.handle_coordinates[2 * c + 1]) - u0_[c];
  }
  solve_step(*step1_, current, du, nullptr, x1, report);
  report.step1_seconds = seconds_since(start);
  report.iterations = step1_->iterations;
  report.solver_error_m = step1_->last_step;
  if (step2_) {
    const auto fit_start = Clock::now();
    if (spatial_ranges_.empty()) spatial_ranges_ = spatial_sample_ranges(features_, split_);
    esc_rhs(features_, graph_.clip.positions, x1, split_, spatial_ranges_, esc_rhs_);
    report.fit_seconds = seconds_since(fit_start);
    solve_step(*step2_, current, du, &esc_rhs_, x2, report);
    report.iterations += step2_->iterations;
    report.solver_error_m = std::max(report.solver_error_m, step2_->last_step);
  } else {
    x2 = x1;
  }
  report.solve_seconds = seconds_since(start);
  describe(report);
}

void IterativeSteps::describe(Report& r) const {
  r.method = "iterative";
  r.precompute_seconds = precompute_seconds_;
  r.analyze_seconds = assemble_seconds_;
  r.factorize_seconds = preconditioner_seconds_;
  r.precompute_iterations = precompute_iterations_;
  std::ostringstream method;
  method << "two-level conjugate gradients (" << coarsening_.chains.size() << " agent chains; coarse: " << coarsening_.groups
         << " agent groups × " << coarsening_.time_nodes << " time nodes × 4)";
  r.factorization = method.str();
  r.fallback.clear();
  r.factor_nonzeros = 0;
  r.coarse_size = 0;
  for (const Step* step : {step1_.get(), step2_.get()}) {
    if (step == nullptr || !step->preconditioner) continue;
    r.factor_nonzeros += step->preconditioner->info().coarse_factor_entries + static_cast<double>(step->preconditioner->info().smoother_entries);
    r.coarse_size = static_cast<std::size_t>(step->preconditioner->info().coarse_size);
  }
  r.reciprocal_condition = 0;  // no factor of the whole system, no estimate
  r.factorizations = precomputes_ * (step2_ ? 2 : 1);
  r.analyses = precomputes_;
  r.schur_columns = static_cast<int>(CT_.cols()) * (step2_ ? 2 : 1);
}

}  // namespace throng::edit
