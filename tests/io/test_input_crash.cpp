// A fault while libhdf5 reads an input (io/include/throng/io/input_crash.h): a fault in library code (here the C
// library's memcpy reading an unmapped page, as libhdf5's copies fault) while an input is being read removes the
// pending temporary outputs, names the input opened last and exits 3; a fault in throng's own code, a signal sent
// with kill, or a fault with no input open removes the pending outputs and takes the default action (a defect of
// throng stays a crash). Each case runs in a child process (fork).
#include <throng/io/atomic_output.h>
#include <throng/io/input_crash.h>

#include <catch2/catch.hpp>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "test_paths.h"

using namespace throng;

// Under AddressSanitizer the program leaves faults to it (install_input_crash_report does nothing), and its
// interceptors (memcpy) and instrumented stores fault in its own code: the forked fault cases are for the other
// builds, and the sanitizer build checks that the program's install leaves the fault handlers alone.
#if defined(__SANITIZE_ADDRESS__)
#define THRONG_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define THRONG_TEST_UNDER_ASAN 1
#endif
#endif

#if defined(THRONG_TEST_UNDER_ASAN)
TEST_CASE("under AddressSanitizer the program's crash report leaves the fault handlers to it") {
  for (int fault : {SIGSEGV, SIGBUS, SIGFPE, SIGILL}) {
    struct sigaction before {}, after {};
    REQUIRE(::sigaction(fault, nullptr, &before) == 0);
    install_input_crash_report();
    REQUIRE(::sigaction(fault, nullptr, &after) == 0);
    CHECK(after.sa_sigaction == before.sa_sigaction);
    CHECK(after.sa_flags == before.sa_flags);
  }
}
#else

namespace {

struct Child {
  int status = 0;
  std::string stderr_text;
};

// Runs `body` in a child whose stderr goes to dir/stderr.txt, armed as the program is: the interrupt cleanup and
// the crash handlers installed, and one pending output, dir/out/result.h5, whose temporary exists when `body`
// starts (exit 93 otherwise). The child's wait status and what it printed.
template <class Body>
Child run_armed_child(const std::filesystem::path& dir, Body body) {
  std::filesystem::create_directories(dir / "out");
  const auto log = dir / "stderr.txt";
  std::fflush(nullptr);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::FILE* err = std::freopen(log.c_str(), "w", stderr);
    if (err == nullptr) ::_exit(90);
    const rlimit no_core{0, 0};  // the crash this child may end in leaves no core file behind
    ::setrlimit(RLIMIT_CORE, &no_core);
    try {
      install_interrupt_cleanup();
      detail::install_input_crash_handlers();
      AtomicOutput output(dir / "out" / "result.h5");
      if (!std::filesystem::exists(output.temporary())) ::_exit(93);
      body();
    } catch (...) {
      ::_exit(92);  // never back into the test runner from a child
    }
    ::_exit(0);
  }
  Child child;
  REQUIRE(::waitpid(pid, &child.status, 0) == pid);
  std::ifstream in(log);
  child.stderr_text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return child;
}

// A fault inside the C library: memcpy reading an unmapped page (the size read at run time, so the copy is
// libc's, not inlined).
void fault_in_library() {
  static volatile std::size_t size = 4096;
  static volatile std::uintptr_t unmapped = 64;
  std::vector<char> into(size);
  std::memcpy(into.data(), reinterpret_cast<const void*>(unmapped), size);
}

// A fault in our own code: a store through a null pointer.
void fault_in_own_code() {
  static int* volatile nowhere = nullptr;
  *nowhere = 1;
}

std::size_t files_in(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), {}));
}

}  // namespace

TEST_CASE("a fault in library code while an input is read is reported as its damage: message, exit 3, outputs removed") {
  const auto dir = test::scratch_dir("input_crash_reading");
  const Child child = run_armed_child(dir, [&] {
    auto first = std::make_unique<ReadingInput>(dir / "first.h5");
    const ReadingInput second(dir / "second.h5");
    first.reset();  // its slot is taken again by the input opened next, which is the one named
    const ReadingInput last(dir / "damaged.h5");
    fault_in_library();
    ::_exit(91);  // not reached: the handler exits
  });
  REQUIRE(WIFEXITED(child.status));
  CHECK(WEXITSTATUS(child.status) == 3);
  CHECK(child.stderr_text.find("damaged.h5: libhdf5 ") != std::string::npos);
  CHECK(child.stderr_text.find("crashed while reading it") != std::string::npos);
  CHECK(child.stderr_text.find("first.h5") == std::string::npos);
  CHECK(child.stderr_text.find("second.h5") == std::string::npos);
  CHECK(files_in(dir / "out") == 0);  // the temporary output removed
}

TEST_CASE("a fault in throng's own code, or a signal sent with kill, stays a crash while an input is read") {
  const auto dir = test::scratch_dir("input_crash_own_fault");
  for (int sent : {0, 1}) {
    INFO((sent ? "SIGSEGV sent with raise" : "a null store in our code"));
    const Child child = run_armed_child(dir, [&] {
      const ReadingInput input(dir / "input.h5");
      if (sent) std::raise(SIGSEGV);
      else fault_in_own_code();
      ::_exit(91);
    });
    REQUIRE(WIFSIGNALED(child.status));
    CHECK(WTERMSIG(child.status) == SIGSEGV);
    CHECK(child.stderr_text.find("crashed while reading") == std::string::npos);
    CHECK(files_in(dir / "out") == 0);  // the pending output removed all the same
  }
}

TEST_CASE("a fault while no input is read stays a crash, its pending outputs removed") {
  const auto dir = test::scratch_dir("input_crash_not_reading");
  const Child child = run_armed_child(dir, [&] {
    {
      const ReadingInput ended(dir / "read_before.h5");
    }
    fault_in_library();
    ::_exit(91);
  });
  REQUIRE(WIFSIGNALED(child.status));
  CHECK(WTERMSIG(child.status) == SIGSEGV);
  CHECK(child.stderr_text.find("libhdf5 crashed") == std::string::npos);
  CHECK(files_in(dir / "out") == 0);
}
#endif
