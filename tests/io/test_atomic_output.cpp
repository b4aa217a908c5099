#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <fstream>
#include <string>
#include <vector>

using namespace throng;
using Catch::Matchers::Contains;

TEST_CASE("an uncommitted output leaves nothing and a committed one replaces the target") {
  const auto dir = test::scratch_dir("io_atomic");
  std::ofstream(dir / "out.txt") << "old";
  {
    AtomicOutput o(dir / "out.txt");
    CHECK(o.temporary().parent_path() == dir);
    std::ofstream(o.temporary()) << "partial";
  }
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
  std::string content;
  std::ifstream(dir / "out.txt") >> content;
  CHECK(content == "old");
  {
    AtomicOutput o(dir / "out.txt");
    std::ofstream(o.temporary()) << "new";
    o.commit();
  }
  std::ifstream(dir / "out.txt") >> content;
  CHECK(content == "new");
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
}

TEST_CASE("an output in a missing folder, or over its own input, is refused up front") {
  const auto dir = test::scratch_dir("io_atomic_refuse");
  CHECK_THROWS_AS(AtomicOutput(dir / "missing" / "x"), IoError);
  std::ofstream(dir / "in.h5") << "x";
  CHECK_THROWS_AS(check_distinct(dir / "in.h5", dir / "." / "in.h5"), ConfigError);
  CHECK_NOTHROW(check_distinct(dir / "in.h5", dir / "other.h5"));
}

namespace {

// The folder's entries other than `keep`.
std::vector<std::string> others(const std::filesystem::path& dir, const std::string& keep) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().filename() != keep) names.push_back(e.path().filename().string());
  }
  return names;
}

std::string content(const std::filesystem::path& p) {
  std::string s;
  std::getline(std::ifstream(p), s);
  return s;
}

}  // namespace

TEST_CASE("the temporary file is created exclusively, under an unpredictable name, and written by descriptor") {
  const auto dir = test::scratch_dir("io_atomic_exclusive");
  std::ofstream(dir / "victim.txt") << "victim";
  // The names the old scheme used (.NAME.tmp-PID-N), planted as links to a file the run must not touch.
  for (int n = 0; n < 8; ++n) {
    std::filesystem::create_symlink(dir / "victim.txt", dir / (".out.txt.tmp-" + std::to_string(::getpid()) + "-" + std::to_string(n)));
  }
  AtomicOutput a(dir / "out.txt"), b(dir / "out.txt");
  CHECK(a.temporary() != b.temporary());
  for (const AtomicOutput* o : {&a, &b}) {
    const std::string name = o->temporary().filename().string();
    REQUIRE(name.rfind(".out.txt.tmp-", 0) == 0);
    const std::string suffix = name.substr(std::string(".out.txt.tmp-").size());
    CHECK(suffix.size() == 16);
    CHECK(suffix.find_first_not_of("0123456789abcdef") == std::string::npos);
    CHECK(std::filesystem::is_regular_file(std::filesystem::symlink_status(o->temporary())));  // exists already
  }
  a.write("new");
  a.commit();
  CHECK(content(dir / "out.txt") == "new");
  CHECK(content(dir / "victim.txt") == "victim");
  CHECK(std::filesystem::is_regular_file(std::filesystem::symlink_status(dir / "out.txt")));
}

TEST_CASE("only a regular file is ever replaced: devices, links, folders and pipes are refused up front") {
  const auto dir = test::scratch_dir("io_atomic_kinds");
  std::ofstream(dir / "real.txt") << "real";
  std::filesystem::create_symlink(dir / "real.txt", dir / "link.txt");
  std::filesystem::create_directory(dir / "folder.txt");
  REQUIRE(::mkfifo((dir / "pipe.txt").c_str(), 0600) == 0);
  CHECK_THROWS_AS_WITH(AtomicOutput(dir / "link.txt"), IoError, Contains("is a symbolic link") && Contains("only regular files"));
  CHECK_THROWS_AS_WITH(AtomicOutput(dir / "folder.txt"), IoError, Contains("is a folder"));
  CHECK_THROWS_AS_WITH(AtomicOutput(dir / "pipe.txt"), IoError, Contains("is a pipe"));
  CHECK_THROWS_AS(AtomicOutput("/dev/null"), IoError);  // "is a device" as root, "not writable" otherwise
  if (::geteuid() == 0) CHECK_THROWS_WITH(AtomicOutput("/dev/null"), Contains("is a device"));
  CHECK_THROWS_AS_WITH(AtomicOutput(""), ConfigError, Contains("output file name is empty"));
  CHECK(content(dir / "link.txt") == "real");
  CHECK(others(dir, "").size() == 4);  // no temporary left behind by a refusal
}

TEST_CASE("a write that fails (a full disk, a file size limit) is an IoError and leaves nothing behind") {
  const auto dir = test::scratch_dir("io_atomic_full");
  std::ofstream(dir / "out.bin") << "old";
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    // In the child: writes past 4 KiB fail with EFBIG, the file-level equivalent of ENOSPC.
    ::signal(SIGXFSZ, SIG_IGN);
    const struct rlimit limit {4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      AtomicOutput o(dir / "out.bin");
      o.write(std::string(64 * 1024, 'x'));
      o.commit();
    } catch (const IoError& e) {
      ::_exit(std::string(e.what()).find("write failed") != std::string::npos ? 4 : 1);
    } catch (...) {
      ::_exit(2);
    }
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 4);
  CHECK(content(dir / "out.bin") == "old");
  CHECK(others(dir, "out.bin").empty());
}

TEST_CASE("background flushes between writes keep the bytes as written, and an abandoned output still leaves nothing") {
  const auto dir = test::scratch_dir("io_atomic_background_flush");
  std::string expected;
  {
    AtomicOutput o(dir / "out.bin");
    for (int k = 0; k < 8; ++k) {
      const std::string block(std::size_t{1} << 20, static_cast<char>('a' + k));
      o.write(block);
      expected += block;
      o.flush_in_background();
      o.flush_in_background();  // while the first may still run: nothing more starts, nothing is lost
    }
    o.write("tail");  // after the last flush: commit's own flush takes it
    expected += "tail";
    o.commit();
  }
  CHECK(content(dir / "out.bin") == expected);
  CHECK(others(dir, "out.bin").empty());
  {
    AtomicOutput o(dir / "out.bin");
    o.write(std::string(std::size_t{4} << 20, 'z'));
    o.flush_in_background();
  }  // destroyed without commit, its flush perhaps still running: the temporary goes, the target stays
  CHECK(content(dir / "out.bin") == expected);
  CHECK(others(dir, "out.bin").empty());
}

TEST_CASE("every termination signal removes the pending temporary file, and an ignored one stays ignored") {
  const auto dir = test::scratch_dir("io_atomic_signals");
  const auto run = [&](int signal, bool ignore_hup_first) {
    int ready[2];
    REQUIRE(::pipe(ready) == 0);
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      ::close(ready[0]);
      for (int s : {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGUSR1, SIGXCPU}) ::signal(s, SIG_DFL);  // whatever the runner set
      if (ignore_hup_first) ::signal(SIGHUP, SIG_IGN);  // as nohup starts a program
      install_interrupt_cleanup();
      AtomicOutput o(dir / "out.h5");
      o.write("partial");
      (void)!::write(ready[1], "x", 1);
      for (;;) ::pause();
    }
    ::close(ready[1]);
    char c = 0;
    REQUIRE(::read(ready[0], &c, 1) == 1);
    ::close(ready[0]);
    CHECK(others(dir, "").size() == 1);  // the temporary, being written
    if (ignore_hup_first) {
      ::kill(child, SIGHUP);
      ::usleep(100 * 1000);
      CHECK(::waitpid(child, nullptr, WNOHANG) == 0);  // still running
    }
    ::kill(child, signal);
    int status = 0;
    ::waitpid(child, &status, 0);
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 128 + signal);
    CHECK(others(dir, "").empty());
  };
  for (int s : {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGUSR1, SIGXCPU}) {
    INFO("signal " << s);
    run(s, false);
  }
  run(SIGTERM, true);
}
