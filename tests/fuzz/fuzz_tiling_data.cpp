// Fuzz target: read_tiling_data on arbitrary bytes (crowd files written by `throng tile`, whose
// /parameters/throng/tiling `check-tiling` and `plot` read; corpus: tests/fuzz/corpus/tiling_data).
#include "fuzz_input.h"

#include <throng/io/tiling_job.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const throng::fuzz::InputFile file(data, size);
  throng::fuzz::expect_only_throng_errors([&] {
    if (throng::has_tiling_data(throng::fuzz::InputFile::path(), throng::fuzz::fuzz_limits())) {
      (void)throng::read_tiling_data(throng::fuzz::InputFile::path(), throng::fuzz::fuzz_limits());
    }
  });
  return 0;
}
