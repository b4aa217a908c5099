// PETSc error handling for this layer (built only with PETSc): PETSc reports errors through return codes, every
// call is checked, and a failure becomes a NumericalError carrying PETSc's own message.
#pragma once

#include <petscsys.h>

namespace throng::linalg::petsc {

/// Installs the handler that records PETSc's message instead of printing a traceback (once, after
/// PetscInitialize).
void install_error_handler();

/// Throws NumericalError("PETSc: <call> failed: <message>") when code is non-zero.
void check(PetscErrorCode code, const char* call);

}  // namespace throng::linalg::petsc

#define THRONG_PETSC_CHECK(call) ::throng::linalg::petsc::check((call), #call)
