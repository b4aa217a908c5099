// Where tests find the project's files, the recorded crowds, a scratch folder, Python and mpiexec.
#pragma once

#include <filesystem>
#include <string>

namespace throng::test {

/// The project's source root (configs/, tests/ ...).
std::filesystem::path source_dir();
/// The build folder (the `throng` program is build_dir()/drivers/throng).
std::filesystem::path build_dir();
/// The `throng` program built alongside the tests.
std::filesystem::path throng_program();
/// The recorded crowds shipped with the project (data/real: ETH/BIWI and UCY, with their credit).
std::filesystem::path real_data_dir();
/// A fresh, empty folder for this test case under the build folder (removed and re-created on each call).
std::filesystem::path scratch_dir(const std::string& name);
/// Debian's /usr/bin/python3 (which has h5py, numpy, MDAnalysis); empty if not found.
std::string system_python();
/// mpiexec; empty if not found.
std::string mpiexec();

/// Ends this test case as SKIPPED: prints `reason` and exits with code 77, which CTest reports as "Skipped"
/// (SKIP_RETURN_CODE, tests/CMakeLists.txt), never as passed. Only for what a build legitimately lacks (a build
/// configured without PETSc); what the README's test command installs (data, mpiexec, Python) must be there.
[[noreturn]] void skip(const std::string& reason);

/// mpiexec, which the test command installs (openmpi-bin): fails the test when it is missing.
std::string required_mpiexec();

/// Runs a shell command; returns its exit status (0..255) and fills `output` with stdout+stderr if given.
int run_command(const std::string& command, std::string* output = nullptr);

}  // namespace throng::test
