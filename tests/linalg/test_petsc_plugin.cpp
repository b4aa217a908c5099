// The petsc backend as a plugin (solver/linalg/src/petsc_plugin.h, petsc_loader.h): what the loader says when it
// cannot load one, and the plugin's errors reaching the program as the program's own types.
#include "petsc_loader.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/linalg/spd_solver.h>

#include <catch2/catch.hpp>

#include <fstream>

using namespace throng;
using Catch::Matchers::Contains;

TEST_CASE("the petsc plugin's loader names each file it tried and why it failed") {
  const auto dir = test::scratch_dir("petsc_plugin");
  const auto garbage = dir / "libthrong_petsc.so";
  std::ofstream(garbage) << std::string(4096, 'x');  // long enough to be read as a header, and not one
  const std::vector<std::filesystem::path> paths{dir / "missing" / "libthrong_petsc.so", garbage, "libz.so.1",
                                                 FAKE_PETSC_PLUGIN};
  try {
    (void)linalg::petsc::load_plugin(paths);
    FAIL("a plugin was loaded from none");
  } catch (const ConfigError& e) {
    const std::string message = e.what();
    CHECK_THAT(message, Contains("solver backend 'petsc': its plugin libthrong_petsc.so cannot be loaded"));
    CHECK_THAT(message, Contains((dir / "missing" / "libthrong_petsc.so").string() +
                                 ": cannot open shared object file: No such file or directory; "));
    CHECK_THAT(message, Contains(garbage.string() + ": invalid ELF header; "));
    CHECK_THAT(message, Contains("libz.so.1: not this build's plugin"));  // a library, but not the plugin
    CHECK_THAT(message, Contains(std::string(FAKE_PETSC_PLUGIN) + ": not this build's plugin"));  // another build's
    CHECK_THAT(message, Contains("keep it beside throng-main, or use backend: eigen"));
  }
}

TEST_CASE("the petsc plugin is this build's, and its errors reach the program as the program's types") {
  const linalg::petsc::Plugin& plugin = linalg::petsc::loaded_plugin();  // this build's: its token accepted
  CHECK(plugin.options_size == sizeof(linalg::SolverOptions));
  linalg::SolverOptions options;
  options.backend = "petsc";
  options.petsc_prefix = "no_underscore";  // thrown by the plugin's solver, caught here as a ConfigError
  CHECK_THROWS_MATCHES(linalg::make_spd_solver(options), ConfigError,
                       Catch::Matchers::Message("solver.petsc_prefix 'no_underscore' must end with '_'"));
  options.petsc_prefix = "t_plugin_";
  const auto solver = linalg::make_spd_solver(options);
  CHECK(plugin.running());
  // A solve through the plugin's virtual table: Q = tridiag(-1, 4, -1), 50 × 50.
  linalg::SparseMatrix Q(50, 50);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < 50; ++i) {
    entries.emplace_back(i, i, 4.0);
    if (i > 0) entries.emplace_back(i, i - 1, -1.0);
    if (i + 1 < 50) entries.emplace_back(i, i + 1, -1.0);
  }
  Q.setFromTriplets(entries.begin(), entries.end());
  solver->analyze(Q);
  solver->factorize(Q);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Ones(50, 1);
  Eigen::MatrixXd X(50, 1);
  solver->solve(B, X);
  CHECK((Q * X - B).norm() <= 1e-10 * B.norm());
}
