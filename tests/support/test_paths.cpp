#include "test_paths.h"

#include <array>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <sys/wait.h>

namespace throng::test {

std::filesystem::path source_dir() { return THRONG_SOURCE_DIR; }
std::filesystem::path build_dir() { return THRONG_BINARY_DIR; }
std::filesystem::path throng_program() { return build_dir() / "drivers" / "throng"; }

std::filesystem::path real_data_dir() { return source_dir() / "data" / "real"; }

std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = build_dir() / "test-scratch" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::string system_python() {
  const std::string p = THRONG_SYSTEM_PYTHON;
  return (!p.empty() && std::filesystem::exists(p)) ? p : std::string{};
}

std::string mpiexec() { return THRONG_MPIEXEC; }

void skip(const std::string& reason) {
  std::fprintf(stderr, "SKIPPED: %s\n", reason.c_str());
  std::fflush(stderr);
  std::_Exit(77);
}

std::string required_mpiexec() {
  const std::string m = mpiexec();
  if (m.empty()) throw std::runtime_error("mpiexec not found: scripts/install-deps installs it (openmpi-bin)");
  return m;
}

int run_command(const std::string& command, std::string* output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buffer{};
  std::string text;
  while (std::fgets(buffer.data(), buffer.size(), pipe)) text += buffer.data();
  const int status = pclose(pipe);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace throng::test
