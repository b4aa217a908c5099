// What a process sets up once, before it runs any method: the BLAS kernel set, the thread limit, and the
// communicator of its ranks. The program creates one Process first thing and passes what a method needs
// (its Communicator, a thread count) to it; no method reads or sets process-wide state itself. Library users and
// test programs create one too (tests/support/catch_main.cpp, bench/common/main.cpp).
//
//   throng::Process process;                  // BLAS kernels chosen before any BLAS call
//   process.limit_threads(options.threads);   // TBB and OpenMP (Eigen's dense kernels), 0: every hardware thread
//   auto run = collide::run(input, job, progress, process.communicator());
//
// Ranks: `communicator()` is MPI's world when the process was started by mpiexec (MPI is initialised on the
// first call then), else Communicator::single(). Batches that give each rank its own jobs call
// use_ranks_independently() first (PETSc on this rank alone) and pass Communicator::single() to the methods.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/parallel.h>

#include <cstddef>
#include <memory>
#include <string>

namespace throng {

class Process {
 public:
  /// Chooses the BLAS kernels (blas_kernels.h). One per process; nothing else is set up until asked.
  Process();
  ~Process();
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  /// Limits TBB and OpenMP to `threads` (0: every hardware thread) from now on; a later call replaces the limit.
  void limit_threads(std::size_t threads);
  /// The limit in force (every hardware thread before limit_threads).
  [[nodiscard]] std::size_t threads() const noexcept;

  /// The ranks a method spreads its work over: MPI's world when started by mpiexec, else one process (also
  /// after use_ranks_independently).
  [[nodiscard]] const Communicator& communicator() const;
  /// This process's rank among every rank started with it, and their number (0 and 1 without mpiexec); rank 0
  /// writes the outputs of a collective run and gathers a batch's summary.
  [[nodiscard]] int world_rank() const;
  [[nodiscard]] int world_size() const;
  /// For batches: every rank solves alone from now on (throng/linalg/mpi.h use_ranks_independently).
  void use_ranks_independently();

  /// The BLAS kernel set in use ("" without OpenBLAS).
  [[nodiscard]] const std::string& blas_kernels() const noexcept { return kernels_; }

 private:
  std::string kernels_;
  std::unique_ptr<ThreadLimit> threads_;
  bool independent_ = false;
};

}  // namespace throng
