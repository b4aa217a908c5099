// The processes a method may spread its work over, passed in by whoever runs it: a method never reads
// process-wide state to find them. `Communicator::single()` is one process (rank 0 of 1, every collective a
// copy); the program passes MPI's world (throng/linalg/mpi.h: mpi::world()) when launched by mpiexec.
// Collectives must be called by every rank in the same order (SPMD).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace throng {

class Communicator {
 public:
  virtual ~Communicator() = default;
  [[nodiscard]] virtual int rank() const = 0;
  [[nodiscard]] virtual int size() const = 0;
  /// Every rank's `data`, in rank order, on every rank (sizes may differ between ranks).
  [[nodiscard]] virtual std::vector<std::vector<double>> all_gather(std::span<const double> data) const = 0;
  /// Replaces `data` on every rank with root's `data`.
  virtual void broadcast(std::vector<std::byte>& data, int root) const = 0;
  /// Σ over ranks of one value, on every rank.
  [[nodiscard]] virtual double sum(double value) const = 0;

  /// One process: rank 0 of 1.
  [[nodiscard]] static const Communicator& single();
};

}  // namespace throng
