// Fuzz target: import_crowd on arbitrary bytes: format detection and every reader behind it (frame id x y,
// PeTrack, CSV tables, JuPedSim/PedPy HDF5, obsmat, crowd files; corpus: tests/fuzz/corpus/import). Inputs of odd
// size are read with a frame rate given, so the readers get past the rate and build the crowd; even ones without.
#include "fuzz_input.h"

#include <throng/io/import_crowd.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const throng::fuzz::InputFile file(data, size);
  throng::ImportOptions options;
  options.fps = size % 2 == 1 ? 25.0 : 0.0;
  throng::fuzz::expect_only_throng_errors(
      [&] { (void)throng::import_crowd(throng::fuzz::InputFile::path(), options, throng::fuzz::fuzz_limits()); });
  return 0;
}
