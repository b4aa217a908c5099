// The process's MPI (and PETSc) lifecycle, and the few collectives other layers need, with no MPI or PETSc type
// in sight.
//
// MPI is initialised once: when something first needs it (the petsc backend, a collective) or at the first
// query when the process was started by mpiexec/mpirun; MPI errors then come back as NumericalError. PETSc (a
// plugin, linalg/src/petsc_plugin.h) is started by the first solver of the petsc backend, after MPI
// (PETSC_COMM_WORLD = MPI_COMM_WORLD, options from PETSC_OPTIONS). Both are finalised at process exit
// (std::atexit), PETSc first: objects holding PETSc handles must be destroyed before main returns.
//
// A process not started by mpiexec that never asks for MPI never initialises it: rank() is 0 and size() 1.
// Collectives must be called by every rank in the same order (SPMD).
#pragma once

#include <throng/core/communicator.h>

#include <cstddef>
#include <span>
#include <vector>

namespace throng::mpi {

/// True when the environment says this process was started by an MPI launcher (OpenMPI, MPICH, PMIx, Slurm's
/// PMI). Does not initialise anything.
[[nodiscard]] bool launched_by_mpiexec() noexcept;

/// Initialises MPI (thread level "funneled": only the main thread calls MPI), once; later calls do nothing.
/// Throws NumericalError if MPI fails to start. (PETSc starts with the petsc backend's first solver.)
void ensure_initialized();

/// For farms that give each rank its own work (`throng run` with several jobs): initialises MPI when launched
/// by mpiexec, and makes PETSc, when a solve starts it, run on this rank alone (PETSC_COMM_WORLD = MPI_COMM_SELF),
/// so the petsc backend's solves never wait for other ranks. Must come before anything else starts PETSc; throws
/// NumericalError when PETSc already runs across several ranks. rank(), size() and the collectives still span
/// every rank.
void use_ranks_independently();

/// True once ensure_initialized() has run (and finalisation has not).
[[nodiscard]] bool is_initialized() noexcept;

/// True when this build has the PETSc backend (its plugin is loaded when a solve asks for it).
[[nodiscard]] bool has_petsc() noexcept;

/// This process's rank in MPI_COMM_WORLD and the number of ranks. Initialises MPI first when launched by
/// mpiexec; otherwise, if MPI is not initialised, 0 and 1.
[[nodiscard]] int rank();
[[nodiscard]] int size();

/// Blocks until every rank arrives.
void barrier();

/// Replaces `data` on every rank with root's `data` (sizes may differ before the call).
void broadcast(std::vector<std::byte>& data, int root = 0);
void broadcast(std::vector<double>& data, int root = 0);

/// Every rank's `data`, in rank order, on root (empty on the other ranks). Sizes may differ between ranks.
[[nodiscard]] std::vector<std::vector<std::byte>> gather(std::span<const std::byte> data, int root = 0);
[[nodiscard]] std::vector<std::vector<double>> gather(std::span<const double> data, int root = 0);

/// Every rank's `data`, in rank order, on every rank.
[[nodiscard]] std::vector<std::vector<double>> all_gather(std::span<const double> data);

/// Σ over ranks and max over ranks of one value, on every rank.
[[nodiscard]] double sum(double value);
[[nodiscard]] double max(double value);

/// MPI_COMM_WORLD as a Communicator, for the program to pass to the methods that spread work over ranks
/// (src/world.cpp). Its first use initialises MPI when launched by mpiexec, as rank() does.
[[nodiscard]] const Communicator& world();

}  // namespace throng::mpi
