// The main of every benchmark program: sets up the process as the program does (throng/process/process.h: the
// BLAS kernels), then runs the benchmarks.
#include <benchmark/benchmark.h>

#include <throng/process/process.h>

int main(int argc, char** argv) {
  const throng::Process process;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
