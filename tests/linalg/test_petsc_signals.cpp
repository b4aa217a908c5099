// Starting PETSc leaves the program's signal handlers alone (solver/linalg/src/mpi.cpp): PETSc installs its own
// for SIGTERM, SIGINT, SIGSEGV, SIGFPE, ... unless told -no_signal_handler, and an interrupted solve must reach the
// output's cleanup (io's AtomicOutput), not PETSc's handler, which prints a stack and aborts.
#include <throng/linalg/mpi.h>

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
  throng::mpi::ensure_initialized();
  for (int i = 0; i < 6; ++i) {
    INFO("signal " << signals[i]);
    CHECK(current(signals[i]).sa_handler == marker_handler);
    sigaction(signals[i], &before[i], nullptr);
  }
}
