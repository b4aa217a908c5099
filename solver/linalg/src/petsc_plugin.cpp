// The plugin's side of petsc_plugin.h: its entry point, and PETSc's start and finish (built into
// libthrong_petsc.so with petsc_backend.cpp, never into the program).
#include "petsc_plugin.h"

#include "backends.h"
#include "petsc_check.h"

#include <throng/core/errors.h>

#include <memory>

namespace throng::linalg::petsc {
namespace {

bool started = false;  // we called PetscInitialize

void start(bool independent_ranks) {
  PetscBool up = PETSC_FALSE;
  PetscInitialized(&up);
  if (up) return;
  if (independent_ranks) PETSC_COMM_WORLD = MPI_COMM_SELF;
  // PETSc would otherwise install its own handlers for SIGTERM, SIGINT, SIGSEGV, ... over the program's: an
  // interrupted solve must reach the output's cleanup (io's AtomicOutput removes its temporary file and
  // re-raises), not PETSc's handler, which prints a stack and aborts. Options may be set before initialising.
  if (PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr) != 0)
    throw NumericalError("PETSc: could not set -no_signal_handler");
  if (PetscInitializeNoArguments() != 0) throw NumericalError("PETSc: PetscInitialize failed");
  started = true;
  install_error_handler();
}

void finish() {
  if (!started) return;
  started = false;
  (void)PetscFinalize();
}

bool running() {
  PetscBool up = PETSC_FALSE, done = PETSC_FALSE;
  PetscInitialized(&up);
  PetscFinalized(&done);
  return up && !done;
}

SpdSolver* make_solver(const SolverOptions& options) { return make_petsc_solver(options).release(); }

constexpr Plugin plugin{THRONG_PETSC_PLUGIN_TOKEN, sizeof(SolverOptions), start, finish, running, make_solver};

}  // namespace
}  // namespace throng::linalg::petsc

extern "C" __attribute__((visibility("default"))) const throng::linalg::petsc::Plugin* throng_petsc_plugin() {
  return &throng::linalg::petsc::plugin;
}
