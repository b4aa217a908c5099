// Fuzz target: read_crowd_file on arbitrary bytes (HDF5 crowd files; corpus: tests/fuzz/corpus/crowd_file).
#include "fuzz_input.h"

#include <throng/io/crowd_file.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const throng::fuzz::InputFile file(data, size);
  throng::fuzz::expect_only_throng_errors([&] { (void)throng::read_crowd_file(throng::fuzz::InputFile::path(), throng::fuzz::fuzz_limits()); });
  return 0;
}
