// Starting PETSc leaves the program's signal handlers alone (the plugin's start, solver/linalg/src/petsc_plugin.cpp,
// run by the petsc backend's first solver): PETSc installs its own
// for SIGTERM, SIGINT, SIGSEGV, SIGFPE, ... unless told -no_signal_handler, and an interrupted solve must reach the
// output's cleanup (io's AtomicOutput), not PETSc's handler, which prints a stack and aborts.
#include <throng/linalg/spd_solver.h>

#include "petsc_loader.h"

#include <catch2/catch.hpp>

#include <csignal>

namespace {

void marker_handler(int) {}

struct sigaction current(int signal) {
  struct sigaction action {};
  sigaction(signal, nullptr, &action);
  return action;
}

}  // namespace

TEST_CASE("starting MPI and PETSc keeps the program's own signal handlers") {
  const int signals[] = {SIGTERM, SIGINT, SIGHUP, SIGSEGV, SIGFPE, SIGBUS};
  struct sigaction before[6];
  for (int i = 0; i < 6; ++i) {
    struct sigaction marker {};
    marker.sa_handler = marker_handler;
    sigemptyset(&marker.sa_mask);
    sigaction(signals[i], &marker, &before[i]);
  }
  REQUIRE_FALSE(throng::linalg::petsc::loaded_plugin().running());  // PETSc starts below, not before
  throng::linalg::SolverOptions options;
  options.backend = "petsc";
  const auto solver = throng::linalg::make_spd_solver(options);  // loads the plugin and starts MPI and PETSc
  REQUIRE(solver->name() == "petsc");
  for (int i = 0; i < 6; ++i) {
    INFO("signal " << signals[i]);
    CHECK(current(signals[i]).sa_handler == marker_handler);
    sigaction(signals[i], &before[i], nullptr);
  }
}
