// throng sketch writes its crowd file as the simulation goes (issue 19, io/crowd_stream.h): the streamed file
// holds the same datasets, values, attributes and chunk shapes as the file written from memory (h5diff), for any
// thread count and whether or not the frame count is known in advance; a run with far more frames than it could
// hold in memory keeps its memory flat; plain storage (--compression none) holds the same values unfiltered; a
// run stopped by a signal leaves the previous output (or none) and no temporary.
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/io/crowd_file.h>
#include <throng/io/crowd_stream.h>
#include <throng/io/hdf5.h>
#include <throng/io/sketch_stream.h>
#include <throng/sketch/runner.h>

#include <catch2/catch.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <thread>

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cli.h"
#include "scenes.h"
#include "test_paths.h"

using namespace throng;
using namespace throng::sketch;

namespace {

int shell(const std::string& line) {
  const int status = std::system(line.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The chunk shapes and filters of every dataset, as h5dump shows them.
std::string storage_layout(const std::filesystem::path& file) {
  const auto text = file.string() + ".layout";
  shell("h5dump -p -H " + file.string() + " | grep -E 'DATASET |CHUNKED|SHUFFLE|DEFLATE|LEVEL' > " + text);
  return read_text(text);
}


CrowdFile crowd_of(SimulationResult& r, const Scene& scene) {
  CrowdFile f;
  f.motion = std::move(r.motion);
  f.scene = scene;
  f.provenance.program_version = "0.1.0";
  f.provenance.command_line = "throng sketch job.yaml -o out.h5";
  f.provenance.options = "duration: 0\n";
  f.provenance.seed = 7;
  f.provenance.inputs = {"job.yaml"};
  return f;
}

const ExtraWriter record = [](const h5::Group& parameters) {
  parameters.create_group("sketch").set_attribute("issue", std::int64_t{19});
};

// A layout from storage_layout() without its filter lines: what the same datasets stored plain show.
std::string without_filters(const std::string& layout) {
  std::string kept;
  std::istringstream lines(layout);
  for (std::string line; std::getline(lines, line);) {
    if (line.find("SHUFFLE") == std::string::npos && line.find("DEFLATE") == std::string::npos &&
        line.find("LEVEL") == std::string::npos) {
      kept += line + "\n";
    }
  }
  return kept;
}

// A layout from storage_layout() with the chunks of [frames][agents][components] datasets taken whole along the
// last axis, as plain storage keeps them: "CHUNKED ( 163, 50, 1 )" of a 4-component dataset reads
// "CHUNKED ( 163, 50, 4 )". `components`: each dataset's last axis, in the layout's order (the scenes have many
// agents, so no two-axis chunk ends in ", 1 )").
std::string whole_components(const std::string& layout, const std::vector<int>& components) {
  std::string kept;
  std::istringstream lines(layout);
  std::size_t next = 0;
  for (std::string line; std::getline(lines, line);) {
    const auto at = line.find(", 1 )");
    if (line.find("CHUNKED") != std::string::npos && at != std::string::npos && next < components.size()) {
      line.replace(at, 5, ", " + std::to_string(components[next++]) + " )");
    }
    kept += line + "\n";
  }
  return kept;
}

// The scene written from memory (write_crowd_file, compressed) and streamed (on `threads` threads, with or without
// the writer thread, stored as `storage` says); both files must hold the same objects, data and attributes, in
// the same chunks: compressed alike, or the streamed ones unfiltered in chunks of whole rows (`throng
// --compression none`).
void compare(const scenes::SketchScene& s, const std::string& name, std::size_t threads, bool background,
             CrowdStorage storage = CrowdStorage::compressed) {
  const auto dir = test::scratch_dir("cli_sketch_stream_" + name);
  {
    const ThreadLimit limit(2);
    SimulationResult memory = simulate(s.drawing, s.scene, s.options);
    write_crowd_file(dir / "memory.h5", crowd_of(memory, s.scene), record);
  }
  {
    const ThreadLimit limit(threads);
    SketchFileSink sink(dir / "streamed.h5", background, storage);
    NoProgress quiet;
    SimulationResult streamed = simulate(s.drawing, s.scene, s.options, sink, quiet);
    CHECK(streamed.motion.positions.empty());
    CHECK(streamed.motion.orientations.empty());
    CHECK(streamed.motion.actions.empty());
    sink.take()->finish(crowd_of(streamed, s.scene), record);
  }
  const bool plain = storage == CrowdStorage::plain;
  INFO(name << " on " << threads << " threads" << (background ? " with a writer thread" : "") << (plain ? ", plain" : ""));
  CHECK(shell("h5diff " + (dir / "memory.h5").string() + " " + (dir / "streamed.h5").string() + " > " +
              (dir / "h5diff.txt").string() + " 2>&1") == 0);
  INFO(read_text(dir / "h5diff.txt"));
  const std::string memory_layout = storage_layout(dir / "memory.h5");
  CHECK(memory_layout.find("DEFLATE") != std::string::npos);
  // Compressed, one component per chunk; plain, whole rows (crowd_stream.cpp): orientation (4), then position (3).
  CHECK(storage_layout(dir / "streamed.h5") ==
        (plain ? whole_components(without_filters(memory_layout), {4, 3}) : memory_layout));
  if (plain) CHECK(std::filesystem::file_size(dir / "streamed.h5") > std::filesystem::file_size(dir / "memory.h5"));
  const CrowdFile a = read_crowd_file(dir / "memory.h5"), b = read_crowd_file(dir / "streamed.h5");
  CHECK(test::same_bits(a.motion.positions, b.motion.positions));
  CHECK(test::same_bits(a.motion.orientations, b.motion.orientations));
  CHECK(a.motion.actions == b.motion.actions);
  CHECK(a.motion.times == b.motion.times);
  CHECK(a.motion.frame_count() > 0);
}

using test::exit_status;
using test::spawn;

// The temporary file `throng` writes `name` through (atomic_output.h), if there is one.
std::filesystem::path temporary_of(const std::filesystem::path& folder, const std::string& name) {
  for (const auto& e : std::filesystem::directory_iterator(folder)) {
    if (e.path().filename().string().rfind("." + name + ".tmp-", 0) == 0) return e.path();
  }
  return {};
}

}  // namespace

TEST_CASE("a streamed sketch file equals the one written from memory") {
  scenes::SketchScene paper = scenes::paper_experiment();
  SECTION("the paper experiment until everyone arrives: frame count not known, datasets created at the end") {
    compare(paper, "paper", 2, false);
  }
  SECTION("the same at 100 frames per second: full blocks before the end, extendible datasets") {
    paper.options.output_rate_hz = 100;
    compare(paper, "paper_100hz", 2, false);
    compare(paper, "paper_100hz_t1", 1, false);
    compare(paper, "paper_100hz_writer", 2, true);
  }
  SECTION("agents removed at the end of their path: absent entries") {
    paper.options.end_of_path = EndOfPath::remove;
    paper.options.output_rate_hz = 50;
    compare(paper, "paper_remove", 2, true);
  }
  SECTION("the large crowd for a fixed duration: every dataset created with its final shape") {
    scenes::SketchScene large = scenes::large_crowd();
    large.options.duration_s = 20;
    compare(large, "large", 2, false);
    compare(large, "large_t1", 1, true);
  }
  SECTION("41 frames with the writer thread: blocks of about a quarter of the run, an action chunk larger than that") {
    // 2,000 agents: position blocks of 15 rows (3 chunks of 5), the last one 11; orientation 12, 12, 12 and 5;
    // action chunks of 32 rows, so one block of a chunk (more than a quarter) and an edge block of 9 rows at the
    // end; id 16, 16 and 9.
    scenes::SketchScene large = scenes::large_crowd();
    large.options.duration_s = 4;
    compare(large, "large_41", 2, true);
    compare(large, "large_41_t1", 1, true);
  }
}

TEST_CASE("a sketch streamed with plain storage holds the same values, unfiltered") {
  scenes::SketchScene paper = scenes::paper_experiment();
  SECTION("until everyone arrives at 100 frames per second: extendible datasets, an edge chunk padded") {
    paper.options.output_rate_hz = 100;
    compare(paper, "plain_paper_100hz", 2, false, CrowdStorage::plain);
    compare(paper, "plain_paper_100hz_writer", 2, true, CrowdStorage::plain);
  }
  SECTION("the large crowd for a fixed duration: final shapes") {
    scenes::SketchScene large = scenes::large_crowd();
    large.options.duration_s = 20;
    compare(large, "plain_large", 1, false, CrowdStorage::plain);
  }
}

TEST_CASE("throng --compression none: every crowd file it writes is unfiltered, with the same values") {
  const auto dir = test::scratch_dir("cli_compression_none");
  const auto s = [](const std::filesystem::path& p) { return p.string(); };
  const std::string job = test::config("sketch-paper.yaml") + " --set agents.count=60 --set output_rate=50";
  REQUIRE(test::run("--quiet sketch " + job + " -o " + s(dir / "deflate.h5")) == 0);
  REQUIRE(test::run("--quiet --compression none sketch " + job + " -o " + s(dir / "none.h5")) == 0);
  // A method command that writes from memory (method_command.h), the flag after the command.
  REQUIRE(test::run("--quiet transform " + s(dir / "deflate.h5") + " --rotate 90 -o " + s(dir / "turned_deflate.h5")) == 0);
  REQUIRE(test::run("--quiet transform " + s(dir / "deflate.h5") + " --rotate 90 --compression none -o " + s(dir / "turned_none.h5")) == 0);
  for (const auto& [deflated, plain] : {std::pair{"deflate.h5", "none.h5"}, std::pair{"turned_deflate.h5", "turned_none.h5"}}) {
    INFO(deflated << " against " << plain);
    // h5diff compares values and attributes: the frames (the provenance's command line differs by the flag).
    CHECK(shell("h5diff " + s(dir / deflated) + " " + s(dir / plain) + " /particles /particles > " + s(dir / "h5diff.txt") +
                " 2>&1") == 0);
    INFO(read_text(dir / "h5diff.txt"));
    const std::string deflated_layout = storage_layout(dir / deflated), plain_layout = storage_layout(dir / plain);
    CHECK(deflated_layout.find("DEFLATE") != std::string::npos);
    CHECK(plain_layout.find("DEFLATE") == std::string::npos);
    CHECK(plain_layout.find("SHUFFLE") == std::string::npos);
    CHECK(std::filesystem::file_size(dir / plain) > std::filesystem::file_size(dir / deflated));
  }
  // An unknown codec is a usage error (exit 2) naming the choices, and writes nothing.
  std::string output;
  CHECK(test::run("--compression zstd sketch " + job + " -o " + s(dir / "zstd.h5"), &output) == 2);
  CHECK_THAT(output, Catch::Matchers::Contains("--compression") && Catch::Matchers::Contains("deflate"));
  CHECK_FALSE(std::filesystem::exists(dir / "zstd.h5"));
}

TEST_CASE("a streamed run holds its times and a few blocks and not its frames") {
  Options o;
  o.agent_count = 200;
  o.duration_s = 200;
  o.output_rate_hz = 100;  // 20,001 frames: 288 MB held in memory, 0.3 MB of times when streamed
  CHECK_THROWS_AS(check_memory(o, 200e6), ConfigError);
  CHECK_NOTHROW(check_streamed_memory(o, static_cast<double>(CrowdStreamWriter::held_bytes(200, false)), 200e6));
  CHECK(CrowdStreamWriter::held_bytes(200, false) < 20'000'000);
  CHECK(CrowdStreamWriter::held_bytes(1'000'000, false) == 2 * 68'000'000);  // two frames per block at most
  o.duration_s = 0;
  o.max_duration_s = 1e9;  // the frames' times alone do not fit
  CHECK_THROWS_WITH(check_streamed_memory(o, 1e6, 200e9), Catch::Matchers::Contains("while written as they go"));

  // The command: its peak resident memory stays far below what the frames would take in memory.
  const auto dir = test::scratch_dir("cli_sketch_stream_memory");
  // Two threads and no huge pages (huge_pages.h), so what is measured is the frames' storage, not a many-core
  // machine's per-thread arenas rounded up to 2 MB pages.
  const pid_t pid = spawn(dir, "--quiet --threads 2 sketch " + test::config("sketch-paper.yaml") +
                                   " --set agents.count=200 --set duration=200 --set output_rate=100 -o paper.h5",
                          "THRONG_HUGE_PAGES=0");
  int status = 0;
  rusage usage{};
  REQUIRE(wait4(pid, &status, 0, &usage) == pid);
  INFO(read_text(dir / "log.txt"));
  REQUIRE(exit_status(status) == 0);
  const double frames_bytes = 20001.0 * 200 * 72;
  const double peak_bytes = static_cast<double>(usage.ru_maxrss) * 1024;
  INFO("peak resident " << peak_bytes / 1e6 << " MB; the frames in memory: " << frames_bytes / 1e6 << " MB");
  CHECK(peak_bytes < 0.5 * frames_bytes);
  const h5::File file = h5::File::open(dir / "paper.h5");
  CHECK(file.root().shape("particles/trajectory/position/value") == std::vector<std::uint64_t>{20001, 200, 3});
  CHECK(file.root().shape("particles/trajectory/orientation/value") == std::vector<std::uint64_t>{20001, 200, 4});
  CHECK(temporary_of(dir, "paper.h5").empty());
}

TEST_CASE("a disk that fills while a sketch streams exits 4, leaving the previous output and no temporary") {
  // A file size limit (ulimit -f, 512-byte blocks; SIGXFSZ ignored, so writes past it fail with EFBIG as with a
  // full disk): the writer thread's first blocks fail and the failure reaches the command through the frames.
  const auto dir = test::scratch_dir("cli_sketch_stream_full_disk");
  test::write_file(dir / "large.h5", "the previous output\n");
  std::string out;
  const std::string command = test::throng_program().string() + " sketch " + test::config("sketch-large.yaml") +
                              " --set duration=20 -o " + (dir / "large.h5").string();
  const int status = test::run_command("sh -c \"trap '' XFSZ; ulimit -f 2048; exec " + command + "\"", &out);
  INFO(out);
  CHECK(status == 4);
  CHECK_THAT(out, Catch::Contains("large.h5"));
  CHECK(read_text(dir / "large.h5") == "the previous output\n");
  CHECK(temporary_of(dir, "large.h5").empty());
}

TEST_CASE("a streamed sketch stopped by a signal leaves the previous output or none and no temporary") {
  for (const int signal : {SIGTERM, SIGINT}) {
    for (const bool previous : {true, false}) {
      const auto dir = test::scratch_dir("cli_sketch_stream_stop_" + std::to_string(signal) + (previous ? "_previous" : ""));
      if (previous) test::write_file(dir / "paper.h5", "the previous output\n");
      // Far longer than the test waits: stopped once blocks of frames are in the temporary file.
      const pid_t pid = spawn(dir, "--quiet sketch " + test::config("sketch-paper.yaml") +
                                       " --set agents.count=200 --set duration=100000 --set output_rate=100 -o paper.h5");
      int status = 0;
      bool ended = false;
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::minutes(2);
      for (;;) {
        ended = waitpid(pid, &status, WNOHANG) == pid;
        if (ended || std::chrono::steady_clock::now() > give_up) break;
        const auto temporary = temporary_of(dir, "paper.h5");
        std::error_code error;
        if (!temporary.empty() && std::filesystem::file_size(temporary, error) > 8'000'000 && !error) break;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      REQUIRE_FALSE(ended);
      kill(pid, signal);
      waitpid(pid, &status, 0);
      INFO("signal " << signal << (previous ? ", a previous output" : ", no previous output"));
      CHECK(exit_status(status) == 128 + signal);
      CHECK(temporary_of(dir, "paper.h5").empty());
      if (previous) {
        CHECK(read_text(dir / "paper.h5") == "the previous output\n");
      } else {
        CHECK_FALSE(std::filesystem::exists(dir / "paper.h5"));
      }
    }
  }
}
