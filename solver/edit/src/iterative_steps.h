// The iterative method of the Editor (edit_steps.h; SolverOptions::method "iterative"): both steps solved by
// conjugate gradients on their complex normal matrices (complex_systems.h) with the two-level space-time
// preconditioner (throng/linalg/two_level.h over coarse_space.h's chains and coarse basis), so no giant factor is
// built or swept: a drag costs step 1 a dense product and step 2 one or two preconditioned iterations.
//
// Everything is solved as a change from the input. The input positions x⁰ have zero energy in both steps (the
// features are measured on them), so for pins at their input places x⁰ is the exact solution of either step:
//  * step 1 is linear in the handles' displacement. With the handles' complex basis (pins x_P = B u; a drag:
//    the coordinates e^{iθ} and a translation, a pin: its position; request.h) and u⁰ the coordinates of the
//    input places (B u⁰ = x⁰_P), step 1 is x_F = x⁰_F − Z₁ (u − u⁰) with Z₁ = Q₁_FF⁻¹ Q₁_FP B, solved once per
//    handle set (a few columns, all at once). A drag is one dense product.
//  * step 2's right-hand side also changes with the triangles fitted to step 1 (Eq. 8–10): x_F = x⁰_F −
//    Z₂ (u − u⁰) + h, where Q₂_FF h = r(fits) is the ESC targets' change from the input's edges. h is solved per
//    drag, started from the Galerkin solution in the span of the previous drags' h (the fits change little between
//    the drags of one gesture) and, before the first drag, of four probes the precompute solves (probe_drags).
//  * general constraints (real rows Re(ĉᴴ z) = d) through the Schur complement S = Re(Ĉᴴ Q⁻¹ Ĉ) with
//    Y = Q_FF⁻¹ Ĉ_F solved once per constraint set; the correction λ is computed from S and Y as they are, so the
//    constraints hold to rounding whatever the iterative error of Y (refined twice: S is symmetrised for its
//    factorisation).
// With more handle coordinates than linalg::ConstrainedLeastSquares::max_basis_columns, each step is one
// conjugate-gradient solve per drag for the change from x⁰, started from the previous drag's.
//
// Accuracy: the handles are met exactly and the constraints to rounding; every other position is within about
// SolverOptions::position_tolerance of the exact solution (conjugate gradients stop when the error they estimate
// is left is below that, linalg/conjugate_gradients.h; the handle bases and constraint columns are solved to
// 10⁻⁷ of their size). The Report gives that estimate (solver_error_m); SolverOptions::compare_direct measures
// the difference itself (direct_difference_m).
#pragma once

#include "coarse_space.h"
#include "complex_systems.h"
#include "edit_steps.h"

#include <throng/graph/features.h>
#include <throng/graph/motion_graph.h>
#include <throng/linalg/two_level.h>

#include <Eigen/Cholesky>

#include <memory>

namespace throng::edit {

class IterativeSteps final : public EditSteps {
 public:
  IterativeSteps(const MotionGraph& graph, const FeatureSet& features, const Options& options);
  ~IterativeSteps() override;

  void apply(const ResolvedRequest& resolved, const ResolvedRequest* previous) override;
  void expect_drags(bool drags_follow) override { drags_follow_ = drags_follow; }
  void precompute(const ResolvedRequest& current) override;
  [[nodiscard]] bool is_ready() const override;
  void solve(const ResolvedRequest& current, Positions& x1, Positions& x2, Report& report) override;
  void describe(Report& report) const override;

 private:
  struct Step;  // one step's system, preconditioner, handle basis and Schur complement
  void solve_step(Step& step, const ResolvedRequest& current, const Eigen::VectorXcd& du, const Eigen::VectorXcd* rhs,
                  Positions& x, Report& report);
  // Seeds step 2's solution history (precompute, when drags follow, with a handle basis and scale compensation):
  // one drag of `current` moved probe_offset_m along +x, +y, −x and −y, each solved as a drag is (a probe that
  // fails, by the constraints or the solver, ends the probing). The drag: the last one that places a vertex the
  // previous request did not handle (a selection just added in a session), else the first the request moves,
  // else the last; one that places its vertices alone (so that its coordinates move exactly its rows). Why: a
  // drag's step 2 starts from the span of the solutions before it, and without them the first drags of a gesture
  // cost the most (10,000 agents: 116 and 24 CG iterations, 19 and 4.2 s, against 1-2 once two drags were
  // solved; with the probes 2, then 1). The probes move that cost into the precompute, once per handle set.
  void probe_drags(const ResolvedRequest& current);
  static constexpr double probe_offset_m = 1.0;  // how far a probe moves the drag
  bool drags_follow_ = true;                     // expect_drags
  std::vector<Eigen::Index> previous_handles_;   // the handle vertices of the request applied before (sorted)

  const MotionGraph& graph_;
  const FeatureSet& features_;
  Options options_;
  // Handles and constraints.
  std::vector<Eigen::Index> handles_;
  VertexSplit split_;
  bool handles_stale_ = true, basis_stale_ = true, constraints_stale_ = true;
  linalg::ComplexSparse basis_;   // B: #pinned by #coordinates (complex), rows in pin-slot order
  Eigen::VectorXcd u0_;           // coordinates of the input's handle places
  bool use_basis_ = false;
  linalg::ComplexSparse CF_, CP_;  // the constraints' complex rows ĉ (unit length), as columns: #free (#pinned) by #rows
  linalg::SparseMatrix CT_;        // the same rows in real form, as columns: 2·#vertices by #rows
  Eigen::VectorXd row_norm_;
  // The input positions (complex), all vertices and free ones.
  Eigen::VectorXcd z0_, z0_free_;
  SpaceTimeCoarsening coarsening_;
  std::unique_ptr<Step> step1_, step2_;
  Eigen::VectorXcd esc_rhs_;       // step 2's right-hand side from the fits
  std::vector<std::size_t> spatial_ranges_;  // spatial_sample_ranges (the features and the samples do not change)
  // Facts for the report.
  double precompute_seconds_ = 0, assemble_seconds_ = 0, preconditioner_seconds_ = 0, columns_seconds_ = 0;
  int precompute_iterations_ = 0, precomputes_ = 0;
};

}  // namespace throng::edit
