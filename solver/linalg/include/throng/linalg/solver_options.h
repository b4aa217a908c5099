// Options of the solver layer: which backend, how hard iterative backends work, how constraints are checked.
#pragma once

#include <Eigen/SparseCore>

#include <cstddef>
#include <string>

namespace throng::linalg {

/// The sparse matrix type of the solver layer (column-major, 32-bit indices as most producers use).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// How to solve. Filled from a job's `solver:` block or the --backend flag; written into outputs.
struct SolverOptions {
  /// "eigen" or "petsc". An unknown name, or a backend this build lacks, is a ConfigError (never a fallback).
  std::string backend = "eigen";

  // --- both ---
  /// BLAS threads inside the backends (CHOLMOD's supernodal kernels, PETSc's vector and dense kernels). 1 by
  /// default: on the project's 2-core reference machine OpenBLAS (OpenMP build) with 2 threads was slower for
  /// every front size CHOLMOD produced and 3× slower in PETSc's Krylov loops (see bench/linalg), and 1 thread
  /// keeps results independent of --threads. 0 = the process's limit.
  int blas_threads = 1;

  // --- petsc (iterative) ---
  /// Stop when ‖Q x − b‖₂ ≤ relative_tolerance · ‖b‖₂ (unpreconditioned residual norm). The error left on the
  /// unknowns is up to cond(Q) · relative_tolerance · ‖x‖: on the battlefield edit 3.8e-8 m at 1e-12 and 3e-6 m
  /// at 1e-10 (which saves ~20% of the CG iterations). Tests derive their eigen/petsc tolerance from this value.
  double relative_tolerance = 1e-12;
  /// Iteration cap per right-hand side; reaching it is a NumericalError.
  int max_iterations = 2000;
  /// PETSc options prefix of this solver: `-throng_ksp_type gmres` or `-throng_pc_type hypre` in PETSC_OPTIONS
  /// (or in `petsc_options` below) reach it. Must end with an underscore.
  std::string petsc_prefix = "throng_";
  /// Extra PETSc options applied before KSPSetFromOptions, written without the prefix, for example
  /// "-ksp_type cg -pc_type gamg". Defaults chosen in code: CG with hypre's BoomerAMG (GAMG when PETSc has no
  /// hypre); see petsc_backend.cpp for the settings and the measurements behind them.
  std::string petsc_options;

  // --- constrained least squares (least_squares.h), any backend ---
  /// A general constraint row counts as met when |c·x − d| ≤ constraint_tolerance · (1 + ‖x‖∞), with the row
  /// scaled to unit length. A violation after the solve means the constraints contradict each other or the
  /// pins: ConstraintError.
  double constraint_tolerance = 1e-8;
  /// Memory allowed for the cached columns Q⁻¹Cᵀ of the Schur complement (#free unknowns by #constraints
  /// doubles). Within it a solve with constraints costs one back-substitution and a dense product; beyond it,
  /// two back-substitutions and no cache.
  double schur_cache_megabytes = 512;

  // --- how the group-motion editor solves its space-time systems (edit::Editor; other users ignore these) ---
  /// "direct": both steps through ConstrainedLeastSquares on `backend` (eigen: CHOLMOD, exact to rounding);
  /// "iterative": conjugate gradients with a two-level space-time preconditioner in this process (edit's
  /// iterative_steps.h: positions within about position_tolerance of the exact solve, handles and constraints
  /// met exactly); "auto": direct for systems of at most auto_direct_vertices free vertices (and always with
  /// the petsc backend), iterative beyond. docs/commands/edit.md has the measurements behind the choice.
  std::string method = "auto";
  /// "auto" chooses direct up to this many free (unpinned) sample vertices. Measured crossover: below it the
  /// direct factor costs under a second and is exact; above it the iterative method precomputes and drags faster.
  std::size_t auto_direct_vertices = 20000;
  /// Iterative: conjugate gradients stop when the error they estimate is left (the last step's largest vertex
  /// move times ρ/(1 − ρ), linalg/conjugate_gradients.h) is below this (metres); measured against the direct
  /// solve in docs/commands/edit.md. > 0.
  double position_tolerance = 1e-3;
  /// Iterative: agents per group of the coarse space (METIS over the agent graph), ≥ 1.
  int coarse_agents = 25;
  /// Iterative: samples between the coarse space's time nodes, ≥ 1.
  int coarse_samples = 4;
  /// Iterative: at most this many coarse functions (4 per agent group and time node; groups grow beyond
  /// coarse_agents to stay within it): the coarse problem is factorised, at a cost that grows steeply with its
  /// size (measured: 12,000 functions factorise in about a second). ≥ 4.
  std::size_t coarse_functions = 16000;
  /// Also solve each deform() directly and report the largest position difference (edit::Report
  /// direct_difference_m): what the iterative method's error is. Costs the direct method's time and memory.
  bool compare_direct = false;
};

}  // namespace throng::linalg
