// throng tile with `window:` as a user runs it (issue 15): the horizon tiled window by window and streamed to a
// crowd file in reused slots that check-tiling, check-motion and every reader open; the same data for any
// thread count; a run stopped by SIGTERM or SIGINT and resumed with --resume ending with the same data as one
// never stopped (h5diff, dataset by dataset and attribute by attribute); the options it cannot take refused.
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>
#include <throng/io/tiling_data.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "test_paths.h"

using namespace throng;
using Catch::Matchers::Contains;

namespace {

// A 16 m × 16 m plaza for 90 s at 0.05 characters per m², in windows of 15 s: six windows, slots reused.
const char* plaza_job =
    "region: {min: [0, 0], max: [16, 16], time: [0, 90]}\n"
    "library: {builtin: [walk, walk_slow, turn_left, turn_right, stop, start, wait, meet, pass]}\n"
    "density: {per_m2: 0.05, report_window: 15}\n"
    "annealing: {max_failures: 500}\n"
    "window: 15\n";

int shell(const std::string& line) {
  const int status = std::system(line.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// h5diff's verdict: 0 when both files hold the same objects, data and attributes.
int h5diff(const std::filesystem::path& a, const std::filesystem::path& b) {
  return shell("h5diff -q " + a.string() + " " + b.string() + " >/dev/null 2>&1");
}

// Tiles the plaza job in `folder` (cwd there, output plaza.h5), extra flags `flags`.
int tile_in(const std::filesystem::path& folder, const std::string& flags = "") {
  return shell("cd " + folder.string() + " && " + test::command("--quiet tile plaza.yaml -o plaza.h5 " + flags) + " >log.txt 2>&1");
}

// A longer plaza (30 m × 30 m for 300 s, twenty windows, about a second), for runs stopped half-way.
const char* long_job =
    "region: {min: [0, 0], max: [30, 30], time: [0, 300]}\n"
    "library: {builtin: [walk, walk_slow, turn_left, turn_right, stop, start, wait, meet, pass]}\n"
    "density: {per_m2: 0.05, report_window: 15}\n"
    "annealing: {max_failures: 500}\n"
    "window: 15\n";

// Starts `throng --quiet tile plaza.yaml -o plaza.h5` in `folder` with SIGINT and SIGTERM at their defaults
// (a test started in the background inherits SIGINT ignored, and throng keeps an ignored signal ignored), sends it
// `signal` as soon as its first window's resume record is on disk, and returns its exit status (128 + n when a
// signal ended it, as a shell reports).
int stop_after_first_window(const std::filesystem::path& folder, int signal) {
  const pid_t pid = test::spawn(folder, "--quiet tile plaza.yaml -o plaza.h5");
  int status = 0;
  bool ended = false;
  while (!std::filesystem::exists(folder / ".plaza.h5.partial.state") && !ended) {
    ended = waitpid(pid, &status, WNOHANG) == pid;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (!ended) {
    kill(pid, signal);
    waitpid(pid, &status, 0);
  }
  return test::exit_status(status);
}

std::filesystem::path fresh(const std::string& name, const char* job = plaza_job) {
  const auto dir = test::scratch_dir(name);
  test::write_file(dir / "plaza.yaml", job);
  return dir;
}

}  // namespace

TEST_CASE("a windowed tile streams a crowd in reused slots that check-tiling check-motion and info accept") {
  const auto dir = fresh("cli_tile_windowed");
  std::string report;
  REQUIRE(test::run("--quiet --json tile " + (dir / "plaza.yaml").string() + " -o " + (dir / "plaza.h5").string(), &report) == 0);
  CHECK_THAT(report, Contains("\"windows\": 6") && Contains("\"dangling\": 0") && Contains("\"density_met\": true"));
  CHECK_FALSE(std::filesystem::exists(dir / ".plaza.h5.partial"));
  CHECK_FALSE(std::filesystem::exists(dir / ".plaza.h5.partial.state"));

  std::string out;
  CHECK(test::run("check-tiling " + (dir / "plaza.h5").string(), &out) == 0);
  INFO(out);
  CHECK(test::run("check-motion " + (dir / "plaza.h5").string(), &out) == 0);
  CHECK(test::run("info " + (dir / "plaza.h5").string(), &out) == 0);

  // Slots: fewer columns than agents, every agent read back with its frames.
  const h5::File file = h5::File::open(dir / "plaza.h5");
  const auto slots = file.root().shape("particles/trajectory/position/value");
  const auto agents = file.root().shape("parameters/throng/agents/id");
  REQUIRE(slots.size() == 3);
  CHECK(slots[0] == 901);  // 90 s at 10 Hz, both ends
  CHECK(slots[1] < agents[0]);
  const CrowdFile crowd = read_crowd_file(dir / "plaza.h5");
  CHECK(crowd.motion.agent_count() == agents[0]);
  CHECK(crowd.motion.frame_count() == 901);
  for (std::size_t a = 0; a < crowd.motion.agent_count(); ++a) {
    const auto [first, last] = crowd.motion.presence_span(a);
    CHECK(last > first);
    for (std::size_t t = first; t < last; ++t) CHECK(crowd.motion.present(t, a));  // one present run per agent
  }
  const TilingData tiling = read_tiling_data(dir / "plaza.h5");
  CHECK(tiling.pieces.size() == agents[0]);
}

TEST_CASE("a windowed tile writes the same data for 1 and 2 threads") {
  const auto one = fresh("cli_tile_windowed_t1"), two = fresh("cli_tile_windowed_t2");
  REQUIRE(shell("cd " + one.string() + " && " + test::command("--quiet --threads 1 tile plaza.yaml -o plaza.h5") + " >log.txt 2>&1") == 0);
  REQUIRE(shell("cd " + two.string() + " && " + test::command("--quiet --threads 2 tile plaza.yaml -o plaza.h5") + " >log.txt 2>&1") == 0);
  // The command lines differ by --threads: every dataset and every other attribute is the same.
  CHECK(shell("h5diff -q --exclude-attribute=/parameters/throng " + (one / "plaza.h5").string() + " " + (two / "plaza.h5").string() +
              " >/dev/null 2>&1") == 0);
}

TEST_CASE("a windowed tile stopped by a signal and resumed ends with the same data as one never stopped") {
  const auto whole = fresh("cli_tile_resume_whole", long_job);
  REQUIRE(tile_in(whole) == 0);
  for (const int signal : {SIGTERM, SIGINT}) {
    INFO("signal " << signal);
    const auto dir = fresh("cli_tile_resume_" + std::to_string(signal), long_job);
    const int status = stop_after_first_window(dir, signal);
    CHECK(status == 128 + signal);
    CHECK_FALSE(std::filesystem::exists(dir / "plaza.h5"));  // no output until the last window
    REQUIRE(std::filesystem::exists(dir / ".plaza.h5.partial"));
    REQUIRE(std::filesystem::exists(dir / ".plaza.h5.partial.state"));
    REQUIRE(tile_in(dir, "--resume") == 0);
    CHECK(h5diff(whole / "plaza.h5", dir / "plaza.h5") == 0);
    CHECK_FALSE(std::filesystem::exists(dir / ".plaza.h5.partial"));
    CHECK(test::run("check-tiling " + (dir / "plaza.h5").string()) == 0);
  }
}

TEST_CASE("a resumed windowed tile cuts back what a killed run wrote past its last record") {
  const auto whole = fresh("cli_tile_cutback_whole", long_job);
  REQUIRE(tile_in(whole) == 0);
  const auto dir = fresh("cli_tile_cutback", long_job);
  REQUIRE(stop_after_first_window(dir, SIGTERM) == 128 + SIGTERM);
  // What a run killed while writing a window leaves: rows past the record in the per-frame, per-agent and
  // tiling datasets (here appended by h5py, filled with garbage).
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());
  test::write_file(dir / "grow.py",
                   "import sys, h5py, numpy as np\n"
                   "f = h5py.File(sys.argv[1], 'r+')\n"
                   "for name in ['particles/trajectory/position/value', 'particles/trajectory/id/value',\n"
                   "             'parameters/throng/agents/id', 'parameters/throng/tiling/instances/type',\n"
                   "             'parameters/throng/tiling/connections', 'parameters/throng/tiling/agents/pieces']:\n"
                   "    d = f[name]\n"
                   "    n = d.shape[0]\n"
                   "    d.resize(n + 7, axis=0)\n"
                   "    d[n:] = 3\n"
                   "f.close()\n");
  REQUIRE(shell(python + " " + (dir / "grow.py").string() + " " + (dir / ".plaza.h5.partial").string()) == 0);
  REQUIRE(tile_in(dir, "--resume") == 0);
  CHECK(h5diff(whole / "plaza.h5", dir / "plaza.h5") == 0);
}

TEST_CASE("a windowed tile refuses what it cannot do with a clear message") {
  const auto dir = fresh("cli_tile_windowed_refusals", long_job);
  const std::string job = (dir / "plaza.yaml").string(), out = (dir / "x.h5").string();
  std::string message;
  // A resume record of another job.
  REQUIRE(stop_after_first_window(dir, SIGTERM) == 128 + SIGTERM);
  REQUIRE(std::filesystem::exists(dir / ".plaza.h5.partial.state"));
  CHECK(test::run("tile " + job + " --set density.per_m2=0.04 --resume -o " + (dir / "plaza.h5").string(), &message) == 2);
  CHECK_THAT(message, Contains("another job") && Contains("without --resume"));
  // --resume on a job without a window.
  CHECK(test::run("tile " + job + " --set window=0 --resume -o " + out, &message) == 2);
  CHECK_THAT(message, Contains("--resume continues a windowed tiling"));
  // Keyframes, repeat, a loop in time, and a run step.
  CHECK(test::run("tile " + job + " --set 'keyframes=[{patch: meet, position: [8, 8], angle: 0, time: 40}]' -o " + out, &message) == 2);
  CHECK_THAT(message, Contains("keyframes"));
  CHECK(test::run("tile " + job + " --set region.periodic=[true,false,false] --set output.repeat=[2,1,1] -o " + out, &message) == 2);
  CHECK_THAT(message, Contains("output.repeat"));
  CHECK(test::run("tile " + job + " --set region.periodic=[false,false,true] -o " + out, &message) == 2);
  CHECK_THAT(message, Contains("periodic in time"));
  CHECK(test::run("tile " + job + " --set 'density.zones=[{min: [100, 100], max: [104, 104], per_m2: 0.2}]' -o " + out, &message) == 2);
  CHECK_THAT(message, Contains("outside the region"));
  test::write_file(dir / "run.yaml", "steps:\n  - {step: tile, job: plaza.yaml, output: t.h5}\n");
  CHECK(test::run("run " + (dir / "run.yaml").string(), &message) == 2);
  CHECK_THAT(message, Contains("window"));
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("shots of a batch share a library saved by an earlier tile and a failed shot stops no other") {
  const auto dir = fresh("cli_tile_batch_library");
  // The library, built once (its output holds it).
  REQUIRE(test::run("--quiet tile " + (dir / "plaza.yaml").string() + " --set region.time=[0,15] --set window=0 -o " +
                    (dir / "library.h5").string()) == 0);
  const std::string shot =
      "steps:\n"
      "  - step: tile\n"
      "    region: {min: [0, 0], max: [12, 12], time: [0, 20]}\n"
      "    library: {file: library.h5}\n"
      "    density: {per_m2: 0.05, report_window: 20}\n"
      "    annealing: {max_failures: 300}\n"
      "    output: OUT\n";
  // A step's output is relative to the working folder (docs/commands/run.md): given whole.
  const auto with_output = [&](const std::string& out) { return shot.substr(0, shot.find("OUT")) + (dir / out).string() + "\n"; };
  test::write_file(dir / "shot-a.yaml", with_output("a.h5"));
  test::write_file(dir / "shot-b.yaml", with_output("b.h5"));
  test::write_file(dir / "shot-c.yaml", with_output("c.h5") + "    limits: {stretch: -1}\n");  // refused: exit 2
  std::string out;
  CHECK(test::run("--quiet run " + (dir / "shot-a.yaml").string() + " " + (dir / "shot-b.yaml").string() + " " +
                      (dir / "shot-c.yaml").string(),
                  &out) == 2);
  CHECK_THAT(out, Contains("succeeded: 2") && Contains("failed: 1") && Contains("limits.stretch"));
  for (const char* name : {"a.h5", "b.h5"}) {
    INFO(name);
    CHECK(test::run("check-tiling " + (dir / name).string()) == 0);
    const h5::File file = h5::File::open(dir / name);
    const auto types = file.root().open_group("parameters/throng/tiling/library").read_strings("type_name");
    CHECK(types == h5::File::open(dir / "library.h5").root().open_group("parameters/throng/tiling/library").read_strings("type_name"));
  }
  CHECK_FALSE(std::filesystem::exists(dir / "c.h5"));
}
