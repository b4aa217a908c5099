#include <test_paths.h>

#include <catch2/catch.hpp>

#include <string>

namespace {

// Runs the probe under mpiexec with `ranks` processes and returns its output; skips when mpiexec is absent.
std::string run_probe(int ranks) {
  const std::string mpiexec = throng::test::mpiexec();
  if (mpiexec.empty()) return "SKIP";
  std::string output;
  const std::string command = mpiexec + " -np " + std::to_string(ranks) + " --oversubscribe " + THRONG_LINALG_PROBE;
  const int status = throng::test::run_command(command, &output);
  INFO(command << "\n" << output);
  CHECK(status == 0);
  return output;
}

}  // namespace

TEST_CASE("collectives and the petsc backend on 1 rank") {
  const std::string out = run_probe(1);
  if (out == "SKIP") {
    WARN("mpiexec not found: MPI test skipped");
    return;
  }
  CHECK_THAT(out, Catch::Matchers::Contains("ranks 1") && Catch::Matchers::Contains("ok petsc agrees with eigen"));
}

TEST_CASE("collectives and the petsc backend on 2 ranks") {
  const std::string out = run_probe(2);
  if (out == "SKIP") {
    WARN("mpiexec not found: MPI test skipped");
    return;
  }
  CHECK_THAT(out, Catch::Matchers::Contains("ranks 2") && Catch::Matchers::Contains("ok every rank has the same solution"));
}

TEST_CASE("without mpiexec nothing starts MPI until asked, and the petsc backend still works") {
  std::string output;
  const int status = throng::test::run_command(THRONG_LINALG_PROBE, &output);
  INFO(output);
  CHECK(status == 0);
  CHECK_THAT(output, Catch::Matchers::Contains("ranks 1") && Catch::Matchers::Contains("ok petsc agrees with eigen"));
}
