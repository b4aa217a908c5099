// The petsc backend as a plugin: libthrong_petsc.so, loaded by the first solver that asks for the backend.
//
// Why: PETSc brings 48 shared libraries of its own (hypre, MUMPS, ScaLAPACK, SuperLU_dist, Trilinos, Scotch, X11,
// ...). Linked into the program, the dynamic loader mapped and relocated all 113 at every command's start, whichever
// method it ran. Loaded only by a solve that asks for `backend: petsc`, every other command starts with 65:
// `throng --version` from start to exit (bench/program/bench_program, medians of 5, in turn twice) 85.2, 98.2 ms
// -> 42.9, 41.2 ms. A solve with the petsc backend loads them when it starts, as the program did before.
//
// The plugin and the program are built together, by one build with one compiler and one C++ library, so C++ types
// cross the boundary (SolverOptions, the SpdSolver the plugin makes, whose methods run in the plugin through its
// virtual table) and so do exceptions (libstdc++ matches a NumericalError thrown in the plugin to the program's by
// its type's name). The plugin holds no state of the program's: it calls nothing of mpi.cpp, which starts MPI
// before it starts PETSc (start_petsc()).
#pragma once

#include <throng/linalg/solver_options.h>
#include <throng/linalg/spd_solver.h>

namespace throng::linalg::petsc {

/// What the plugin gives the program. `token` is the build's THRONG_PETSC_PLUGIN_TOKEN (solver/linalg/CMakeLists.txt:
/// a hash of the headers both sides share and of the compiler), so that a plugin of another build (a stale copy
/// beside a newer throng-main) is refused rather than called.
struct Plugin {
  const char* token;
  std::size_t options_size;  ///< sizeof(SolverOptions) where the plugin was built
  /// Starts PETSc on the initialised MPI, on PETSC_COMM_WORLD = MPI_COMM_SELF when `independent_ranks` (else
  /// MPI_COMM_WORLD), without PETSc's signal handlers; nothing when it runs. NumericalError when PETSc fails.
  void (*start)(bool independent_ranks);
  /// PetscFinalize, when start() started PETSc (process exit, before MPI_Finalize).
  void (*finish)();
  /// Whether PETSc runs (started and not finalised).
  bool (*running)();
  /// The backend's solver (PETSc must run). ConfigError for bad options.
  SpdSolver* (*make_solver)(const SolverOptions& options);
};

/// The plugin's file name; the program looks for it beside its own executable, then where the build made it.
constexpr const char* plugin_file = "libthrong_petsc.so";

}  // namespace throng::linalg::petsc

extern "C" {
/// The plugin's one entry point (exported by libthrong_petsc.so).
using ThrongPetscPluginEntry = const throng::linalg::petsc::Plugin* (*)();
}
