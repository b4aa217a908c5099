// A fault while libhdf5 reads an input (io/include/throng/io/input_crash.h): with an input being read, the pending
// temporary outputs are removed, a message naming the input is printed and the program exits 3; with none, the
// pending outputs are removed and the fault takes its default action (a defect of throng stays a crash). Each case
// runs in a child process (fork), which raises the fault itself.
#include <throng/io/atomic_output.h>
#include <throng/io/input_crash.h>

#include <catch2/catch.hpp>

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_paths.h"

using namespace throng;

namespace {

struct Child {
  int status = 0;
  std::string stderr_text;
};

// Runs `body` in a child whose stderr goes to `log`; the child's wait status and what it printed.
template <class Body>
Child run_child(const std::filesystem::path& log, Body body) {
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::FILE* err = std::freopen(log.c_str(), "w", stderr);
    if (err == nullptr) ::_exit(90);
    const rlimit no_core{0, 0};  // the crash this child may end in leaves no core file behind
    ::setrlimit(RLIMIT_CORE, &no_core);
    body();
    ::_exit(0);
  }
  Child child;
  REQUIRE(::waitpid(pid, &child.status, 0) == pid);
  std::ifstream in(log);
  child.stderr_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return child;
}

std::size_t files_in(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

}  // namespace

TEST_CASE("a fault while an input is read is reported as its damage: message, exit 3, pending outputs removed") {
  const auto dir = test::scratch_dir("input_crash_reading");
  const auto out_dir = dir / "out";
  std::filesystem::create_directories(out_dir);
  for (int fault : {SIGSEGV, SIGBUS}) {
    INFO("signal " << fault);
    const Child child = run_child(dir / "stderr.txt", [&] {
      install_interrupt_cleanup();
      install_input_crash_report();
      AtomicOutput output(out_dir / "result.h5");
      const ReadingInput first(dir / "first.h5");
      {
        const ReadingInput ended(dir / "ended.h5");
      }
      const ReadingInput last(dir / "damaged.h5");
      std::raise(fault);
      ::_exit(91);  // not reached: the handler exits
    });
    REQUIRE(WIFEXITED(child.status));
    CHECK(WEXITSTATUS(child.status) == 3);
    CHECK(child.stderr_text.find("damaged.h5: libhdf5 crashed while reading it") != std::string::npos);
    CHECK(child.stderr_text.find("first.h5") == std::string::npos);  // the input opened last is named
    CHECK(child.stderr_text.find("ended.h5") == std::string::npos);
    CHECK(files_in(out_dir) == 0);  // the temporary output removed
  }
}

TEST_CASE("a fault while no input is read stays a crash, its pending outputs removed") {
  const auto dir = test::scratch_dir("input_crash_not_reading");
  const auto out_dir = dir / "out";
  std::filesystem::create_directories(out_dir);
  const Child child = run_child(dir / "stderr.txt", [&] {
    install_interrupt_cleanup();
    install_input_crash_report();
    AtomicOutput output(out_dir / "result.h5");
    {
      const ReadingInput ended(dir / "read_before.h5");
    }
    std::raise(SIGSEGV);  // the handler returns with the default action restored
    std::raise(SIGSEGV);  // as a real fault's instruction, run again
    ::_exit(91);
  });
  REQUIRE(WIFSIGNALED(child.status));
  CHECK(WTERMSIG(child.status) == SIGSEGV);
  CHECK(child.stderr_text.find("libhdf5 crashed") == std::string::npos);
  CHECK(files_in(out_dir) == 0);
}
