// The one Catch2 main shared by every test program. It sets up the process as the program does
// (throng/process/process.h: the BLAS kernels), so a test computes with the kernels `throng` uses.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <throng/process/process.h>

int main(int argc, char* argv[]) {
  const throng::Process process;
  return Catch::Session().run(argc, argv);
}
