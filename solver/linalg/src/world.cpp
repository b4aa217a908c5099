// MPI's world as a Communicator (throng/core/communicator.h), through the collectives of mpi.h.
#include <throng/linalg/mpi.h>

namespace throng::mpi {
namespace {

class World final : public Communicator {
 public:
  int rank() const override { return mpi::rank(); }
  int size() const override { return mpi::size(); }
  std::vector<std::vector<double>> all_gather(std::span<const double> data) const override { return mpi::all_gather(data); }
  void broadcast(std::vector<std::byte>& data, int root) const override { mpi::broadcast(data, root); }
  double sum(double value) const override { return mpi::sum(value); }
};

}  // namespace

const Communicator& world() {
  static const World w;
  return w;
}

}  // namespace throng::mpi
