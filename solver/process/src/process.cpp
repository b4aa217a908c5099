#include <throng/linalg/mpi.h>
#include <throng/process/blas_kernels.h>
#include <throng/process/process.h>

namespace throng {

Process::Process() : kernels_(choose_blas_kernels()) {}

Process::~Process() = default;

void Process::limit_threads(std::size_t threads) {
  threads_.reset();  // one tbb::global_control at a time
  threads_ = std::make_unique<ThreadLimit>(threads);
}

std::size_t Process::threads() const noexcept { return threads_ ? threads_->threads() : hardware_threads(); }

const Communicator& Process::communicator() const {
  if (!independent_ && (mpi::is_initialized() || mpi::launched_by_mpiexec())) return mpi::world();
  return Communicator::single();
}

int Process::world_rank() const { return mpi::rank(); }
int Process::world_size() const { return mpi::size(); }

void Process::use_ranks_independently() {
  mpi::use_ranks_independently();
  independent_ = true;
}

}  // namespace throng
