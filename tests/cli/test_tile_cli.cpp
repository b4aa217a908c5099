// throng tile and throng check-tiling as a user runs them: every example config (shrunk), repeatability over
// threads and MPI ranks, the exit codes of bad jobs, impossible libraries and imperfect tilings.
#include <throng/io/crowd_file.h>
#include <throng/io/tiling_job.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

#include "test_paths.h"

using namespace throng;
using Catch::Matchers::Contains;

namespace {

int run(const std::string& args, std::string* out = nullptr) {
  return test::run_command(test::throng_program().string() + " " + args, out);
}

std::string config(const std::string& name) { return (test::source_dir() / "configs" / name).string(); }

void write_file(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

bool only_inputs_left(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".yaml") return false;
  }
  return true;
}

// Every path sample and connection of a tiling file, for bitwise comparison.
std::vector<double> numbers(const std::filesystem::path& path) {
  const TilingData d = read_tiling_data(path);
  std::vector<double> v;
  for (const tiling::Instance& i : d.tiling.instances) {
    for (const tiling::Path& p : i.paths) {
      for (const auto& q : p.positions) v.insert(v.end(), {q.x(), q.y()});
      v.insert(v.end(), p.times.begin(), p.times.end());
      v.insert(v.end(), p.headings.begin(), p.headings.end());
    }
  }
  for (const tiling::Connection& c : d.tiling.connections) {
    v.insert(v.end(), {double(c.from.instance), double(c.from.fragment), double(c.to.instance), double(c.to.fragment)});
  }
  const CrowdFile crowd = read_crowd_file(path);
  v.insert(v.end(), crowd.motion.positions.begin(), crowd.motion.positions.end());
  return v;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

const char* small_job =
    "region: {min: [0, 0], max: [8, 8], time: [0, 8]}\n"
    "library: {builtin: [locomotion, interaction]}\n"
    "characters: 12\n"
    "annealing: {max_failures: 300}\n";

}  // namespace

TEST_CASE("every tile config, shrunk, gives a tiling that check-tiling passes") {
  const auto dir = test::scratch_dir("cli_tile_configs");
  const std::vector<std::pair<std::string, std::string>> configs = {
      {"tile-static.yaml", "--set characters=16"},
      {"tile-dynamic.yaml", "--set characters=16"},
      {"tile-control.yaml", "--set characters=20 --set chains=1 --set region.time=[0,12]"},
      {"tile-repeating.yaml", "--set characters=15 --set region.time=[0,10]"},
      {"tile-objects.yaml", "--set characters=12"},
      {"tile-real.yaml", "--set characters=10 --set library.real.max_pair_patches=4 --set library.real.max_single_patches=4"},
  };
  for (const auto& [name, shrink] : configs) {
    INFO(name);
    if (name == "tile-real.yaml" && test::real_data_dir().empty()) {
      WARN("no ../shared/data/real: tile-real.yaml skipped");
      continue;
    }
    const auto out = dir / (name + ".h5");
    std::string report;
    REQUIRE(run("--quiet --json tile " + config(name) + " " + shrink + " -o " + out.string(), &report) == 0);
    CHECK_THAT(report, Contains("\"dangling\": 0"));
    std::string checked;
    CHECK(run("--json check-tiling " + out.string(), &checked) == 0);
    CHECK_THAT(checked, Contains("\"perfect\": true"));
    const CrowdFile crowd = read_crowd_file(out);
    CHECK(crowd.motion.agent_count() > 0);
    CHECK(crowd.scene.region.has_value());
    if (name == "tile-real.yaml") CHECK_FALSE(crowd.provenance.credits.empty());
  }
}

TEST_CASE("the same seed gives the same tiling file for 1 and 2 threads and the seed flag changes it") {
  const auto dir = test::scratch_dir("cli_tile_threads");
  write_file(dir / "job.yaml", small_job);
  const std::string job = (dir / "job.yaml").string();
  REQUIRE(run("--quiet --threads 1 tile " + job + " -o " + (dir / "a.h5").string()) == 0);
  REQUIRE(run("--quiet --threads 2 tile " + job + " -o " + (dir / "b.h5").string()) == 0);
  REQUIRE(run("--quiet --threads 2 --seed 9 tile " + job + " -o " + (dir / "c.h5").string()) == 0);
  CHECK(same_bits(numbers(dir / "a.h5"), numbers(dir / "b.h5")));
  CHECK_FALSE(same_bits(numbers(dir / "a.h5"), numbers(dir / "c.h5")));
}

TEST_CASE("the same seed gives the same tiling file for 1 and 2 MPI ranks", "[mpi]") {
  const std::string mpiexec = test::mpiexec();
  if (mpiexec.empty()) {
    WARN("no mpiexec: skipped");
    return;
  }
  const auto dir = test::scratch_dir("cli_tile_ranks");
  write_file(dir / "job.yaml", std::string(small_job) + "chains: 3\n");
  const std::string job = (dir / "job.yaml").string();
  REQUIRE(run("--quiet tile " + job + " -o " + (dir / "one.h5").string()) == 0);
  REQUIRE(test::run_command(mpiexec + " -n 2 " + test::throng_program().string() + " --quiet tile " + job + " -o " +
                            (dir / "two.h5").string()) == 0);
  CHECK(same_bits(numbers(dir / "one.h5"), numbers(dir / "two.h5")));
}

TEST_CASE("a tile step of throng run writes a tiling that check-tiling passes") {
  const auto dir = test::scratch_dir("cli_tile_run");
  const auto out = dir / "tiled.h5";
  write_file(dir / "run.yaml", "steps:\n"
                               "  - step: tile\n"
                               "    region: {min: [0, 0], max: [8, 8], time: [0, 8]}\n"
                               "    library: {builtin: [locomotion]}\n"
                               "    characters: 8\n"
                               "    output: " + out.string() + "\n");
  REQUIRE(run("--quiet run " + (dir / "run.yaml").string()) == 0);
  CHECK(run("--quiet check-tiling " + out.string()) == 0);
}

TEST_CASE("tile and check-tiling exit codes") {
  const auto dir = test::scratch_dir("cli_tile_errors");
  const auto out = dir / "out.h5";
  std::string text;
  SECTION("a bad job: exit 2 naming the key, no output") {
    write_file(dir / "job.yaml", std::string(small_job) + "chans: 2\n");
    CHECK(run("tile " + (dir / "job.yaml").string() + " -o " + out.string(), &text) == 2);
    CHECK_THAT(text, Contains("chans"));
    CHECK(only_inputs_left(dir));
  }
  SECTION("a library whose ends never match: exit 5 at once, no output") {
    write_file(dir / "job.yaml", "region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [stop, box_pickup]}\n");
    CHECK(run("tile " + (dir / "job.yaml").string() + " -o " + out.string(), &text) == 5);
    CHECK_THAT(text, Contains("no patch type can ever be placed"));
    CHECK(only_inputs_left(dir));
  }
  SECTION("dangling ends remain: the tiling is written, exit 5; check-tiling lists them, exit 5") {
    write_file(dir / "job.yaml", std::string(small_job) + "search: {max_steps: 0}\n");
    CHECK(run("--quiet tile " + (dir / "job.yaml").string() + " -o " + out.string(), &text) == 5);
    CHECK_THAT(text, Contains("dangling"));
    REQUIRE(std::filesystem::exists(out));
    CHECK(run("--json check-tiling " + out.string(), &text) == 5);
    CHECK_THAT(text, Contains("\"perfect\": false") && Contains("dangles"));
  }
  SECTION("check-tiling of a crowd file without a tiling: exit 3; of no file: an error") {
    write_file(dir / "job.yaml", small_job);
    REQUIRE(run("--quiet tile " + (dir / "job.yaml").string() + " -o " + out.string()) == 0);
    write_crowd_file(dir / "plain.h5", read_crowd_file(out));  // the characters alone, no tiling data
    CHECK(run("check-tiling " + (dir / "plain.h5").string(), &text) == 3);
    CHECK_THAT(text, Contains("tiling"));
    CHECK(run("check-tiling " + (dir / "missing.h5").string()) != 0);
  }
}
