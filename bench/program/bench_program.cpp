// How long `throng --version` takes from start to exit: the cost every command pays before its work, almost all of
// it the dynamic loader bringing in the program's 65 shared libraries (113 before the petsc backend became a plugin
// loaded only by the solves that ask for it: solver/linalg/src/petsc_plugin.h). Three ways of starting:
//   launcher    `throng` as users run it: the launcher sets glibc's huge-page tunable and executes throng-main once
//   restarting  throng-main alone, which restarts itself to set the tunable (every command before the launcher)
//   one_load    throng-main with THRONG_HUGE_PAGES=0: one load, no huge pages (the floor)
// Each child gets this process's environment without GLIBC_TUNABLES and the restart marker, which this benchmark's
// own start set (common/main.cpp), so it starts as from a shell.
//
// Run: build/release/bench/program/bench_program --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace {

// This process's environment without the variables named in `drop` (NAME=...), with `add` appended.
std::vector<std::string> environment(const std::vector<std::string>& drop, const std::vector<std::string>& add) {
  std::vector<std::string> out;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry(*e);
    bool dropped = false;
    for (const std::string& name : drop) dropped = dropped || entry.rfind(name + "=", 0) == 0;
    if (!dropped) out.push_back(entry);
  }
  out.insert(out.end(), add.begin(), add.end());
  return out;
}

// Runs `program --version` with `env`, its output to /dev/null; throws unless it exits 0.
void run_version(const std::string& program, std::vector<std::string> env) {
  std::string path = program, flag = "--version";
  char* argv[] = {path.data(), flag.data(), nullptr};
  std::vector<char*> envp;
  for (std::string& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  const int started = posix_spawn(&pid, path.c_str(), &actions, nullptr, argv, envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (started != 0) throw std::runtime_error(program + ": cannot start (" + std::strerror(started) + ")");
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error(program + " --version failed");
  }
}

void BM_Start(benchmark::State& state) {
  const std::vector<std::string> drop{"GLIBC_TUNABLES", "THRONG_HUGE_PAGES_RESTARTED", "THRONG_HUGE_PAGES"};
  const auto way = state.range(0);
  const std::string program = way == 0 ? THRONG_PROGRAM : THRONG_PROGRAM_MAIN;
  const std::vector<std::string> env = environment(drop, way == 2 ? std::vector<std::string>{"THRONG_HUGE_PAGES=0"} : std::vector<std::string>{});
  for (auto _ : state) run_version(program, env);
  state.SetLabel(way == 0 ? "launcher" : way == 1 ? "restarting" : "one_load");
}
BENCHMARK(BM_Start)->ArgName("way")->DenseRange(0, 2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
