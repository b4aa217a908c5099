#include "direct_steps.h"

#include <chrono>

namespace throng::edit {
namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

DirectSteps::DirectSteps(const FeatureSet& features, const Positions& original, const Options& options)
    : features_(features), original_(original), options_(options), step1_solver_(options.solver), step2_solver_(options.solver) {
  const auto vertices = original.rows();
  const Eigen::MatrixXd modes = similarity_modes(original);
  step1_ = step1_objective(features, vertices, options.alpha, options.beta);
  step1_solver_.set_objective(std::move(step1_.A), step1_.weights);  // the solver's copy is the only one
  step1_solver_.set_near_null_space(modes, 2);
  step1_solver_.set_complex_pairs(true);  // every feature row is complex-linear in (x, y) pairs
  if (options.scale_compensation) {
    step2_ = step2_objective(features, vertices, options.alpha_prime, options.beta_prime);
    step2_solver_.set_objective(std::move(step2_.A), step2_.weights);
    step2_solver_.set_near_null_space(modes, 2);
    step2_solver_.set_complex_pairs(true);
    step2_solver_.share_analysis(&step1_solver_);
  }
}

void DirectSteps::apply(const ResolvedRequest& resolved, const ResolvedRequest* previous) {
  const bool scale = options_.scale_compensation;
  if (previous == nullptr || resolved.handle_vertices != previous->handle_vertices) {
    const auto pinned = resolved.pinned_unknowns();
    step1_solver_.set_pinned(pinned);
    if (scale) step2_solver_.set_pinned(pinned);
  }
  if (previous == nullptr || resolved.handle_vertices != previous->handle_vertices ||
      !same_matrix(resolved.handle_basis, previous->handle_basis)) {
    step1_solver_.set_pin_basis(resolved.handle_basis);
    if (scale) step2_solver_.set_pin_basis(resolved.handle_basis);
  }
  if (previous == nullptr || !same_matrix(resolved.C, previous->C)) {
    step1_solver_.set_constraints(resolved.C);
    if (scale) step2_solver_.set_constraints(resolved.C);
  }
}

void DirectSteps::precompute(const ResolvedRequest& current) {
  const auto start = Clock::now();
  // Both steps' Q_FF have one pattern (the same features, the same pins): step 2 copies step 1's symbolic
  // analysis (ordering and supernodes) before either is factorised, so only symbols are copied.
  step1_solver_.analyze();
  if (options_.scale_compensation) step2_solver_.analyze();
  step1_solver_.precompute();
  if (options_.scale_compensation) step2_solver_.precompute();
  // Step 1's b never changes, so its Q_FF⁻¹ r_b (one back-substitution, which the solver keeps) is part of the
  // precompute: every drag, the first included, then costs step 1 a dense product only (measured at 1,000
  // agents: the first drag's step 1 took 1.1 s, the next ones 0.05 s).
  if (step1_solver_.precomputes_basis()) (void)step1_solver_.solve_in_basis(step1_.b, current.handle_coordinates, current.d);
  precompute_seconds_ = seconds_since(start);
}

bool DirectSteps::is_ready() const {
  return step1_solver_.is_ready() && (!options_.scale_compensation || step2_solver_.is_ready());
}

void DirectSteps::solve(const ResolvedRequest& current, Positions& x1, Positions& x2, Report& report) {
  const auto start = Clock::now();
  // Pins as coordinates in the handles' basis (request.h): step 1's b never changes, so a drag costs it no
  // back-substitution; step 2's b does (the fitted triangles): one back-substitution.
  const Eigen::VectorXd& pins = current.handle_coordinates;
  x1 = as_positions(step1_solver_.solve_in_basis(step1_.b, pins, current.d));
  report.max_constraint_residual = step1_solver_.report().max_constraint_residual;
  report.step1_seconds = seconds_since(start);
  if (options_.scale_compensation) {
    const auto fit_start = Clock::now();
    set_step2_targets(features_, original_, x1, step2_.b);
    report.fit_seconds = seconds_since(fit_start);
    x2 = as_positions(step2_solver_.solve_in_basis(step2_.b, pins, current.d));
    report.max_constraint_residual = std::max(report.max_constraint_residual, step2_solver_.report().max_constraint_residual);
  } else {
    x2 = x1;
  }
  report.solve_seconds = seconds_since(start);
  describe(report);
}

void DirectSteps::describe(Report& r) const {
  const bool scale = options_.scale_compensation;
  const auto& one = step1_solver_.report();
  const auto& two = step2_solver_.report();
  r.method = "direct";
  r.precompute_seconds = precompute_seconds_;
  r.analyze_seconds = one.analyze_seconds + (scale ? two.analyze_seconds : 0.0);
  r.factorize_seconds = one.factorize_seconds + (scale ? two.factorize_seconds : 0.0);
  r.factorization = one.factorization.method;
  r.fallback = one.factorization.fallback_reason;
  r.factor_nonzeros = one.factorization.factor_nonzeros + (scale ? two.factorization.factor_nonzeros : 0.0);
  r.reciprocal_condition = one.factorization.reciprocal_condition;
  if (scale) {
    const double step2 = two.factorization.reciprocal_condition;
    if (step2 > 0 && (r.reciprocal_condition <= 0 || step2 < r.reciprocal_condition)) r.reciprocal_condition = step2;
  }
  r.factorizations = one.factorizations + two.factorizations;
  r.analyses = one.analyses + two.analyses - one.adopted_analyses - two.adopted_analyses;
  r.schur_columns = one.schur_columns + two.schur_columns;
}

}  // namespace throng::edit
