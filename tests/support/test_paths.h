// Where tests find the project's files, the shared real data, a scratch folder, Python and mpiexec.
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
/// ../shared/data/real beside the project root; empty if absent (tests then SKIP with a message).
std::filesystem::path real_data_dir();
/// A fresh, empty folder for this test case under the build folder (removed and re-created on each call).
std::filesystem::path scratch_dir(const std::string& name);
/// Debian's /usr/bin/python3 (which has h5py, numpy, MDAnalysis); empty if not found.
std::string system_python();
/// mpiexec; empty if not found.
std::string mpiexec();

/// Runs a shell command; returns its exit status (0..255) and fills `output` with stdout+stderr if given.
int run_command(const std::string& command, std::string* output = nullptr);

}  // namespace throng::test
