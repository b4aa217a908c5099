// One chunk's zlib stream made by ChunkDeflater (io/src/chunk_deflate.h), the step that compresses every chunk of
// every crowd file throng writes: bytes of chunk per second.
//
//   BM_DeflateChunk/kind:0  a 10,000-agent frame's x positions (80 KB, 8 byte planes: 0-5 noise, stored; 6-7
//                           structured), coded with the dataset's plane codes at ISA-L's level 0: the sketch's path
//   BM_DeflateChunk/kind:1  the same chunk, its structured planes at ISA-L's level 1 (a dataset without codes)
//   BM_DeflateChunk/kind:2  a chunk without noise (a slow ramp, 80 KB), deflated whole at level 1
//
// The chunks are those of a walk, as the tests' (tests/io/test_chunk_deflate.cpp): agent i at 12 + 0.01 i m, plus
// up to 0.2 m of jitter.
//
// Run: build/release/bench/io/bench_io --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "chunk_deflate.h"
#include "filtered_chunks.h"

#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <vector>

using namespace throng::h5::detail;

namespace {

constexpr std::size_t agents = 10'000;

// The shuffle filter's byte planes of `values` (filtered_chunks.h), as filter_chunks hands them to the deflater.
std::vector<unsigned char> planes_of(const std::vector<double>& values) {
  std::vector<unsigned char> out(8 * values.size());
  shuffle(reinterpret_cast<const unsigned char*>(values.data()), values.size(), 8, 8, out.data());
  return out;
}

std::vector<double> walk(std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::vector<double> v(agents);
  for (std::size_t i = 0; i < agents; ++i) v[i] = 12.0 + 0.01 * static_cast<double>(i) + jitter(random);
  return v;
}

std::vector<unsigned char> ramp() {
  std::vector<unsigned char> v(8 * agents);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<unsigned char>(i / 300);
  return v;
}

void BM_DeflateChunk(benchmark::State& state) {
  const auto kind = state.range(0);
  const std::vector<unsigned char> chunk = kind == 2 ? ramp() : planes_of(walk(2));
  // The dataset's codes, made from its first chunk (another frame of the walk), as filter_chunks makes them.
  const std::vector<unsigned char> first = planes_of(walk(1));
  const std::vector<unsigned char> sample = structured_planes(first.data(), first.size(), 8, 0);
  const PlaneCodes codes(sample.data(), sample.size());
  ChunkDeflater deflater(1);
  std::vector<unsigned char> out(ChunkDeflater::bound(chunk.size(), 8));
  std::size_t made = 0;
  for (auto _ : state) {
    int status = 0;
    made = deflater.deflate(chunk.data(), chunk.size(), 8, 0, out.data(), out.size(), &status, kind == 0 ? &codes : nullptr);
    if (made == 0) state.SkipWithError("ISA-L failed");
    benchmark::DoNotOptimize(out.data());
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * chunk.size()));
  state.counters["stream_share"] = static_cast<double>(made) / static_cast<double>(chunk.size());
}
BENCHMARK(BM_DeflateChunk)->ArgName("kind")->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

}  // namespace
