#include "../graph/synthetic_crowd.h"

#include <test_paths.h>
#include <throng/io/crowd_file.h>
#include <throng/linalg/solver_options.h>

#include <fstream>

#include <catch2/catch.hpp>

#include <string>

namespace {

// Runs a probe under mpiexec with `ranks` processes and returns its output (mpiexec is required: the test command
// installs it).
std::string run_probe(int ranks, const std::string& probe = THRONG_LINALG_PROBE, const std::string& args = "") {
  const std::string mpiexec = throng::test::required_mpiexec();
  std::string output;
  // OpenMPI refuses root unless both variables are set (CI runs as root); set here, as the test's ENVIRONMENT
  // property may carry only one of them.
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec + " -np " +
                              std::to_string(ranks) + " --oversubscribe " + probe + args;
  const int status = throng::test::run_command(command, &output);
  INFO(command << "\n" << output);
  CHECK(status == 0);
  return output;
}

}  // namespace

TEST_CASE("collectives and the petsc backend on 1 rank") {
  const std::string out = run_probe(1);
  CHECK_THAT(out, Catch::Matchers::Contains("ranks 1") && Catch::Matchers::Contains("ok petsc agrees with eigen"));
}

TEST_CASE("collectives and the petsc backend on 2 ranks") {
  const std::string out = run_probe(2);
  CHECK_THAT(out, Catch::Matchers::Contains("ranks 2") && Catch::Matchers::Contains("ok every rank has the same solution"));
}

TEST_CASE("independent ranks (a farm): each rank's petsc solve runs on that rank alone") {
  const std::string out = run_probe(2, THRONG_LINALG_PROBE, " independent");
  CHECK_THAT(out, Catch::Matchers::Contains("ranks 2") && Catch::Matchers::Contains("ok the backend runs on 1 rank") &&
                      Catch::Matchers::Contains("ok petsc agrees with eigen") &&
                      Catch::Matchers::Contains("ok every rank has the same solution"));
  CHECK_THAT(out, !Catch::Matchers::Contains("on 2 ranks"));
}

TEST_CASE("without mpiexec nothing starts MPI until asked, and the petsc backend still works") {
  std::string output;
  const int status = throng::test::run_command(THRONG_LINALG_PROBE, &output);
  INFO(output);
  CHECK(status == 0);
  CHECK_THAT(output, Catch::Matchers::Contains("ranks 1") && Catch::Matchers::Contains("ok petsc agrees with eigen"));
}

TEST_CASE("an edit with the petsc backend on 1 and 2 ranks agrees with the eigen backend") {
  for (int ranks : {1, 2}) {
    const std::string out = run_probe(ranks, THRONG_EDIT_PROBE);
    CHECK_THAT(out, Catch::Matchers::Contains("ranks " + std::to_string(ranks)) &&
                        Catch::Matchers::Contains("ok eigen and petsc agree"));
  }
}

TEST_CASE("throng edit under mpiexec -np 2 with the petsc backend writes the eigen backend's result once") {
  const std::string mpiexec = throng::test::required_mpiexec();
  const auto dir = throng::test::scratch_dir("mpi_edit");
  throng::CrowdFile input;
  input.motion = throng::test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.3, 0.2);
  throng::write_crowd_file(dir / "in.h5", input);
  std::ofstream(dir / "job.yaml") << "clip: {sample_step: 2}\ndrags:\n  - {frames: [0, 1]}\n"
                                     "  - {frames: [-2, end], offset: [3, -2], rotation: 0.3}\n";
  const std::string program = throng::test::throng_program().string();
  const std::string args = " edit " + (dir / "in.h5").string() + " --job " + (dir / "job.yaml").string() + " -o ";
  std::string out;
  REQUIRE(throng::test::run_command(program + " -q" + args + (dir / "eigen.h5").string(), &out) == 0);
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec +
                              " -np 2 --oversubscribe " + program + " --json -q" + args + (dir / "petsc.h5").string() +
                              " --backend petsc";
  INFO(command);
  REQUIRE(throng::test::run_command(command, &out) == 0);
  INFO(out);
  CHECK_THAT(out, Catch::Matchers::Contains("\"ranks\": 2") && Catch::Matchers::Contains("on 2 ranks"));
  // One report: only rank 0 prints and writes.
  CHECK(out.find("\"output\"") == out.rfind("\"output\""));
  const throng::CrowdFile eigen = throng::read_crowd_file(dir / "eigen.h5"), petsc = throng::read_crowd_file(dir / "petsc.h5");
  double gap = 0;
  for (std::size_t k = 0; k < eigen.motion.positions.size(); ++k) {
    gap = std::max(gap, std::abs(eigen.motion.positions[k] - petsc.motion.positions[k]));
  }
  CHECK(gap < 1e4 * throng::linalg::SolverOptions{}.relative_tolerance);  // as in edit_probe: measured ~1e-11 m
}
