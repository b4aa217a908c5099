// A plugin of "another build" for test_petsc_plugin.cpp: the entry point of libthrong_petsc.so with a token the
// program does not know, which the loader must refuse without calling anything in it.
#include "petsc_plugin.h"

namespace {
constexpr throng::linalg::petsc::Plugin other{"another build", sizeof(throng::linalg::SolverOptions), nullptr, nullptr,
                                              nullptr, nullptr};
}  // namespace

extern "C" __attribute__((visibility("default"))) const throng::linalg::petsc::Plugin* throng_petsc_plugin() {
  return &other;
}
