// The main of every benchmark program: sets up the process as the program does (throng/process/process.h: the
// BLAS kernels, the heap's huge pages), then runs the benchmarks.
#include <benchmark/benchmark.h>

#include <throng/process/huge_pages.h>
#include <throng/process/process.h>

int main(int argc, char** argv) {
  throng::restart_with_huge_pages(argv);  // as the program does (throng/process/huge_pages.h)
  const throng::Process process;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
