#include <throng/core/communicator.h>

namespace throng {
namespace {

class Single final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  std::vector<std::vector<double>> all_gather(std::span<const double> data) const override {
    return {std::vector<double>(data.begin(), data.end())};
  }
  void broadcast(std::vector<std::byte>&, int) const override {}
  double sum(double value) const override { return value; }
};

}  // namespace

const Communicator& Communicator::single() {
  static const Single one;
  return one;
}

}  // namespace throng
