#include "cli.h"

#include "test_paths.h"

#include <catch2/catch.hpp>

#include <spawn.h>
#include <sys/wait.h>

#include <csignal>
#include <cstring>
#include <fstream>

namespace throng::test {

std::string command(const std::string& args) { return throng_program().string() + " " + args; }

int run(const std::string& args, std::string* output) { return run_command(command(args), output); }

int spawn(const std::filesystem::path& folder, const std::string& args, const std::string& environment) {
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGINT);
  sigaddset(&defaults, SIGTERM);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  std::string line = "cd " + folder.string() + " && " + environment + (environment.empty() ? "" : " ") + "exec " +
                     command(args) + " >log.txt 2>&1";
  std::string shell_path = "/bin/sh", dash_c = "-c";
  char* argv[] = {shell_path.data(), dash_c.data(), line.data(), nullptr};
  pid_t pid = 0;
  REQUIRE(posix_spawn(&pid, "/bin/sh", nullptr, &attributes, argv, environ) == 0);
  posix_spawnattr_destroy(&attributes);
  return pid;
}

int exit_status(int status) { return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : WEXITSTATUS(status); }

std::string config(const std::string& name) { return (source_dir() / "configs" / name).string(); }

std::filesystem::path write_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace throng::test
