#include <throng/linalg/solver_schema.h>

namespace throng::linalg {

const std::vector<std::string>& backend_names() {
  static const std::vector<std::string> names{"eigen", "petsc"};
  return names;
}

void describe(OptionBinder& b, SolverOptions& o) {
  b.choice({.key = "backend", .flag = "--backend", .help = "sparse solver: eigen (CHOLMOD) or petsc (distributed over MPI ranks)"},
           o.backend, backend_names());
  b.field({.key = "blas_threads", .range = Range::closed(0, 1024), .help = "BLAS threads inside the backend (0: the process's)"},
          o.blas_threads);
  b.field({.key = "relative_tolerance", .range = {0.0, 1.0, true, true}, .help = "petsc: stop at ‖Qx − b‖ ≤ tol·‖b‖"},
          o.relative_tolerance);
  b.field({.key = "max_iterations", .range = Range::closed(1, 1e9), .help = "petsc: iterations per solve at most"},
          o.max_iterations);
  b.field({.key = "petsc_prefix", .help = "PETSc options prefix of this solver (ends with _)"}, o.petsc_prefix);
  b.field({.key = "petsc_options", .help = "PETSc options, without the prefix"}, o.petsc_options);
  b.field({.key = "constraint_tolerance", .range = {0.0, 1.0, true, true},
           .help = "a constraint is met when |c·x − d| ≤ tol·(1 + ‖x‖∞)"},
          o.constraint_tolerance);
  b.field({.key = "schur_cache_megabytes", .unit = "MB", .range = Range::non_negative(),
           .help = "memory for the cached Schur complement columns"},
          o.schur_cache_megabytes);
}

}  // namespace throng::linalg
