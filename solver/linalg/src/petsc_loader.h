// The program's side of petsc_plugin.h: finding and loading the plugin, and starting PETSc through it (defined in
// builds with PETSc only).
#pragma once

#include "petsc_plugin.h"

#include <filesystem>
#include <vector>

namespace throng::linalg::petsc {

/// The first of `paths` that dlopen loads and that is this build's plugin (its token and sizeof(SolverOptions)),
/// kept loaded to the process's end.
/// ConfigError naming each path tried and why it failed (dlopen's own message, or "not this build's plugin").
[[nodiscard]] const Plugin& load_plugin(const std::vector<std::filesystem::path>& paths);

/// The plugin, loaded by the first call that succeeds (load_plugin of plugin_file beside the running executable,
/// then where the build made it).
[[nodiscard]] const Plugin& loaded_plugin();

}  // namespace throng::linalg::petsc

namespace throng::mpi {

/// Initialises MPI (ensure_initialized), then PETSc through `plugin` on the communicator use_ranks_independently
/// chose, once; PETSc is finalised at process exit before MPI. NumericalError when either fails to start.
void start_petsc(const linalg::petsc::Plugin& plugin);

}  // namespace throng::mpi
