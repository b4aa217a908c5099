#include "backends.h"
#include "petsc_loader.h"

#include <throng/core/errors.h>

namespace throng::linalg {

std::vector<std::string> available_backends() {
#ifdef THRONG_HAVE_PETSC
  return {"eigen", "petsc"};
#else
  return {"eigen"};
#endif
}

std::unique_ptr<SpdSolver> make_spd_solver(const SolverOptions& options) {
  if (options.backend == "eigen") return make_eigen_solver(options);
  if (options.backend == "petsc") {
#ifdef THRONG_HAVE_PETSC
    const petsc::Plugin& plugin = petsc::loaded_plugin();
    mpi::start_petsc(plugin);
    return std::unique_ptr<SpdSolver>(plugin.make_solver(options));
#else
    throw ConfigError("solver backend 'petsc' was requested but this build has no PETSc (configure with "
                      "-DTHRONG_WITH_PETSC=ON after installing petsc-dev); available: eigen");
#endif
  }
  std::string names;
  for (const auto& name : available_backends()) names += (names.empty() ? "" : ", ") + name;
  throw ConfigError("unknown solver backend '" + options.backend + "': expected one of " + names);
}

}  // namespace throng::linalg
