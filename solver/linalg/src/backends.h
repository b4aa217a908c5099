// The backends' factories, private to the layer (spd_solver.cpp picks one by name).
#pragma once

#include <throng/linalg/spd_solver.h>

#include <memory>

namespace throng::linalg {

std::unique_ptr<SpdSolver> make_eigen_solver(const SolverOptions& options);
#ifdef THRONG_HAVE_PETSC
std::unique_ptr<SpdSolver> make_petsc_solver(const SolverOptions& options);
#endif

}  // namespace throng::linalg
