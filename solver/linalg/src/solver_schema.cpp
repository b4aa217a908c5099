#include <throng/linalg/solver_schema.h>

namespace throng::linalg {

const std::vector<std::string>& backend_names() {
  static const std::vector<std::string> names{"eigen", "petsc"};
  return names;
}

const std::vector<std::string>& method_names() {
  static const std::vector<std::string> names{"auto", "direct", "iterative"};
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

void describe_method(OptionBinder& b, SolverOptions& o) {
  b.choice({.key = "method", .flag = "--solver-method",
            .help = "direct: the backend's factor; iterative: conjugate gradients, two-level preconditioner (eigen only); "
                    "auto: direct up to auto_direct_vertices free vertices"},
           o.method, method_names());
  b.field({.key = "auto_direct_vertices", .range = Range::closed(0, 1e15),
           .help = "auto: the direct method up to this many free sample vertices, iterative beyond"},
          o.auto_direct_vertices);
  b.field({.key = "position_tolerance", .unit = "m", .range = Range::positive(),
           .help = "iterative: conjugate gradients stop when the error they estimate is below this"},
          o.position_tolerance);
  b.field({.key = "coarse_agents", .range = Range::closed(1, 1e9), .help = "iterative: agents per group of the coarse space"},
          o.coarse_agents);
  b.field({.key = "coarse_samples", .range = Range::closed(1, 1e9),
           .help = "iterative: samples between the coarse space's time nodes"},
          o.coarse_samples);
  b.field({.key = "coarse_functions", .range = Range::closed(4, 1e12),
           .help = "iterative: coarse functions at most (4 per agent group and time node)"},
          o.coarse_functions);
  b.field({.key = "compare_direct", .help = "also solve each drag directly and report the largest difference (direct_difference_m)"},
          o.compare_direct);
}

}  // namespace throng::linalg
