// Fuzz target: read_csv on arbitrary bytes (`time,id,x,y,z` tables; corpus: tests/fuzz/corpus/csv).
#include "fuzz_input.h"

#include <throng/io/csv.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const throng::fuzz::InputFile file(data, size);
  throng::fuzz::expect_only_throng_errors([&] { (void)throng::read_csv(throng::fuzz::InputFile::path(), 0.25, throng::fuzz::fuzz_limits()); });
  return 0;
}
