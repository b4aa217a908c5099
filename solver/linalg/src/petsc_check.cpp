#include "petsc_check.h"

#include <throng/core/errors.h>

#include <string>

namespace throng::linalg::petsc {
namespace {

thread_local std::string first_message;

PetscErrorCode record(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                      PetscErrorType type, const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL) {
    first_message = std::string(message != nullptr ? message : "") + " (in " + (function ? function : "?") + ", " +
                    (file ? file : "?") + ":" + std::to_string(line) + ")";
  }
  return code;
}

}  // namespace

void install_error_handler() { (void)PetscPushErrorHandler(record, nullptr); }

void check(PetscErrorCode code, const char* call) {
  if (code == 0) return;
  std::string text = first_message;
  first_message.clear();
  if (text.empty()) {
    const char* generic = nullptr;
    PetscErrorMessage(code, &generic, nullptr);
    text = generic != nullptr ? generic : "unknown error";
  }
  throw NumericalError(std::string("PETSc: ") + call + " failed: " + text);
}

}  // namespace throng::linalg::petsc
