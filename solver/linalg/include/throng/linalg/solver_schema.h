// The schema of SolverOptions (throng/core/schema.h): the `solver:` block of the edit and stitch jobs. The one
// list of backend names is here.
#pragma once

#include <throng/core/schema.h>
#include <throng/linalg/solver_options.h>

#include <string>
#include <vector>

namespace throng::linalg {

/// Every backend this program knows, whether or not this build has it ("eigen", "petsc"); a known backend this
/// build lacks is refused when a solver is made, with the reason.
[[nodiscard]] const std::vector<std::string>& backend_names();

/// SolverOptions::method's words ("auto", "direct", "iterative"): the schema's choice, checked where the method
/// is used (edit::validate; check_options leaves words to their users).
[[nodiscard]] const std::vector<std::string>& method_names();

/// `backend` has the flag --backend (the edit command's); the other keys have none.
void describe(OptionBinder& b, SolverOptions& o);

/// How the group-motion editor solves its systems (method, auto_direct_vertices, position_tolerance, coarse_*,
/// compare_direct): part of edit's `solver:` block only (stitch solves directly and does not read them).
/// `method` has the flag --solver-method.
void describe_method(OptionBinder& b, SolverOptions& o);

}  // namespace throng::linalg
