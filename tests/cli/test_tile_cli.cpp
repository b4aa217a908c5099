// throng tile and throng check-tiling as a user runs them: every example config (shrunk), repeatability over
// threads and MPI ranks, the exit codes of bad jobs, impossible libraries and imperfect tilings.
#include <throng/io/crowd_file.h>
#include <throng/io/tiling_job.h>
#include <throng/io/tiling_plot.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "cli.h"
#include "test_paths.h"

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

using test::config;

using test::write_file;

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

using test::same_bits;

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
      {"tile-control.yaml", "--set characters=20 --set chains=1 --set region.time=[0,12] "
                            "--set 'keyframes=[{patch: bow_rows, position: [6, 6], angle: 0, time: 4.5}]'"},
      {"tile-repeating.yaml", "--set characters=15 --set region.time=[0,10]"},
      {"tile-objects.yaml", "--set characters=12"},
      {"tile-real.yaml", "--set characters=10 --set library.real.max_episode_patches=4 --set library.real.max_single_patches=4"},
  };
  for (const auto& [name, shrink] : configs) {
    INFO(name);
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
    if (name == "tile-real.yaml") {
      CHECK_FALSE(crowd.provenance.credits.empty());
      // The dataset is named by its resolved folder, not relative to the job file.
      const std::filesystem::path dataset = std::filesystem::weakly_canonical(test::real_data_dir() / "zara01");
      bool named = false;
      for (const std::string& in : crowd.provenance.inputs) {
        named = named || std::filesystem::weakly_canonical(in) == dataset;
      }
      CHECK(named);
      CHECK_THAT(crowd.provenance.options, !Contains("../data/real"));
    }
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
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_tile_ranks");
  write_file(dir / "job.yaml", std::string(small_job) + "chains: 3\n");
  const std::string job = (dir / "job.yaml").string();
  REQUIRE(run("--quiet tile " + job + " -o " + (dir / "one.h5").string()) == 0);
  REQUIRE(test::run_command(mpiexec + " -n 2 --oversubscribe " + test::throng_program().string() + " --quiet tile " + job + " -o " +
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
    CHECK_THAT(text, Contains("dangling") && Contains("search.max_steps = 0"));
    REQUIRE(std::filesystem::exists(out));
    CHECK(run("--json check-tiling " + out.string(), &text) == 5);
    CHECK_THAT(text, Contains("\"perfect\": false") && Contains("dangles"));
  }
  SECTION("check-tiling of a crowd file without a tiling: exit 3; of no file: exit 4 naming it") {
    write_file(dir / "job.yaml", small_job);
    REQUIRE(run("--quiet tile " + (dir / "job.yaml").string() + " -o " + out.string()) == 0);
    write_crowd_file(dir / "plain.h5", read_crowd_file(out));  // the characters alone, no tiling data
    CHECK(run("check-tiling " + (dir / "plain.h5").string(), &text) == 3);
    CHECK_THAT(text, Contains("tiling"));
    CHECK(run("check-tiling " + (dir / "missing.h5").string(), &text) == 4);
    CHECK_THAT(text, Contains("missing.h5"));
  }
  SECTION("an output folder that does not exist: exit 4 before any tiling") {
    // A job that would take minutes: the folder is checked first, so the error comes at once.
    const auto started = std::chrono::steady_clock::now();
    CHECK(run("tile " + config("tile-static.yaml") + " -o " + (dir / "no" / "such" / "x.h5").string(), &text) == 4);
    CHECK_THAT(text, Contains("no/such"));
    CHECK(std::chrono::steady_clock::now() - started < std::chrono::seconds(10));
  }
  SECTION("a keyframe outside the region: exit 2 naming the keyframe") {
    write_file(dir / "job.yaml", "region: {min: [0, 0], max: [12, 12], time: [0, 20]}\n"
                                 "library: {builtin: [locomotion, interaction]}\n"
                                 "keyframes: [{patch: meet, position: [400, 4], time: 5}]\n");
    CHECK(run("tile " + (dir / "job.yaml").string() + " -o " + out.string(), &text) == 2);
    CHECK_THAT(text, Contains("keyframes[0].position") && Contains("400"));
    CHECK(only_inputs_left(dir));
  }
  SECTION("a keyframe of a patch that can never be used: exit 2 at once naming the keyframe and its end") {
    // box_pickup exits carrying, and nothing in [locomotion, box_pickup] enters carrying.
    write_file(dir / "job.yaml", "region: {min: [0, 0], max: [12, 12], time: [0, 20]}\n"
                                 "library: {builtin: [locomotion, box_pickup]}\n"
                                 "keyframes: [{patch: box_pickup, position: [6, 6], time: 5}]\n");
    const auto started = std::chrono::steady_clock::now();
    CHECK(run("tile " + (dir / "job.yaml").string() + " -o " + out.string(), &text) == 2);
    CHECK_THAT(text, Contains("keyframe 0") && Contains("box_pickup") && Contains("carrying"));
    CHECK(std::chrono::steady_clock::now() - started < std::chrono::seconds(5));
    CHECK(only_inputs_left(dir));
  }
}

namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t occurrences(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (auto p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("throng plot of a tiling colours the patches by type and marks the connections and seams") {
  const auto dir = test::scratch_dir("cli_tile_plot");
  const auto tiled = dir / "tiled.h5";
  REQUIRE(run("--quiet tile " + config("tile-repeating.yaml") + " --set characters=15 --set region.time=[0,10] -o " +
              tiled.string()) == 0);
  const TilingData data = read_tiling_data(tiled);
  std::size_t seams = 0, joins = 0;
  for (const tiling::Connection& c : data.tiling.connections) (c.image == std::array<int, 3>{0, 0, 0} ? joins : seams) += 1;
  REQUIRE(seams > 0);
  REQUIRE(joins > 0);
  std::map<std::size_t, std::size_t> used;
  for (const tiling::Instance& i : data.tiling.instances) ++used[i.type];
  REQUIRE(used.size() >= 3);

  REQUIRE(run("plot " + tiled.string() + " -o " + (dir / "tiling.svg").string()) == 0);
  const std::string svg = read_text(dir / "tiling.svg");
  // A legend entry per type used, with its count, and a colour of its own (at most 20 types: no colour is
  // shared) drawn on every fragment path of its instances in each of the 2 × 2 laid copies.
  REQUIRE(used.size() <= 20);
  std::size_t rank = 0;
  for (const auto& [type, count] : used) {
    INFO(data.library.types[type].name);
    CHECK(svg.find(">" + data.library.types[type].name + " (" + std::to_string(count) + ")</text>") != std::string::npos);
    const std::string colour = patch_type_colour(rank++);
    CHECK(occurrences(svg, "<polyline fill=\"none\" stroke-linejoin=\"round\" stroke=\"" + colour + "\"") ==
          4 * count * data.library.types[type].fragments.size());
  }
  // Connections: a dot at each within the tile, two rings at each seam crossing, in each of the 2 × 2 copies.
  CHECK(occurrences(svg, "fill=\"#202020\" stroke=\"white\"") == 4 * joins);
  CHECK(occurrences(svg, "fill=\"none\" stroke=\"#000000\" stroke-width=\"1.5\"/>") == 4 * 2 * seams + 1);  // + legend
  CHECK(svg.find(">connection (" + std::to_string(joins) + ")</text>") != std::string::npos);
  CHECK(svg.find(">seam connection (" + std::to_string(seams) + ")</text>") != std::string::npos);

  // --no-tiling: the plain crowd, one colour per species, no patch legend.
  REQUIRE(run("plot " + tiled.string() + " --no-tiling -o " + (dir / "plain.svg").string()) == 0);
  const std::string plain = read_text(dir / "plain.svg");
  CHECK(plain.find("connection (") == std::string::npos);
  CHECK(occurrences(plain, "<polyline stroke=\"") >= read_crowd_file(tiled).motion.agent_count());
}

namespace {

// zara01's obsmat.txt (frame id x z y ...; frames at 25 per second) rewritten as another layout: `row` gets the
// frame, the id, x and y (metres) and returns the line.
template <class Row>
std::filesystem::path rewrite_zara01(const std::filesystem::path& path, const std::string& header, Row row) {
  std::ifstream in(test::real_data_dir() / "zara01" / "obsmat.txt");
  std::ofstream out(path);
  out << header;
  double frame = 0, id = 0, x = 0, z = 0, y = 0, vx = 0, vz = 0, vy = 0;
  while (in >> frame >> id >> x >> z >> y >> vx >> vz >> vy) out << row(frame, id, x, y) << "\n";
  return path;
}

std::string real_job(const std::string& dataset, const std::string& more = "") {
  return "region: {min: [0, 0], max: [12, 12], time: [0, 20]}\n"
         "library:\n  builtin: [locomotion]\n  real:\n    dataset: " + dataset + "\n"
         "    max_episode_patches: 4\n    max_single_patches: 4\n" + more +
         "characters: 10\nchains: 2\nannealing: {max_failures: 2000}\n";
}

}  // namespace

TEST_CASE("a tiling library reads its recorded crowd in any format throng import reads") {
  const auto dir = test::scratch_dir("cli_tile_real_formats");
  std::string text;
  auto tile_ok = [&](const std::string& job_text, const std::string& flags, const std::string& name) {
    write_file(dir / (name + ".yaml"), job_text);
    const auto out = dir / (name + ".h5");
    INFO(name);
    REQUIRE(run("--quiet --json tile " + (dir / (name + ".yaml")).string() + " " + flags + " -o " + out.string(), &text) == 0);
    CHECK_THAT(text, Contains("\"dangling\": 0"));
    std::string checked;
    CHECK(run("--json check-tiling " + out.string(), &checked) == 0);
    return read_crowd_file(out);
  };
  SECTION("an ETH/UCY folder, and the crowd file throng import made of it") {
    const CrowdFile from_folder = tile_ok(real_job(test::real_data_dir().string() + "/zara01/"), "", "folder");
    CHECK_FALSE(from_folder.provenance.credits.empty());
    REQUIRE(run("--quiet import " + (test::real_data_dir() / "zara01").string() + " -o " + (dir / "zara.h5").string()) == 0);
    const CrowdFile from_crowd = tile_ok(real_job("zara.h5"), "", "crowd");  // relative to the job's folder
    CHECK(from_crowd.provenance.credits == from_folder.provenance.credits);
    CHECK_THAT(from_crowd.provenance.options, Contains((dir / "zara.h5").string()));
  }
  SECTION("a CSV table with its own column names in centimetres: library.real.columns and units") {
    rewrite_zara01(dir / "zara.csv", "t_s,person,X_cm,Y_cm\n", [](double f, double id, double x, double y) {
      std::ostringstream row;
      row.precision(10);
      row << f / 25 << "," << id << "," << 100 * x << "," << 100 * y;
      return row.str();
    });
    // Without the column map the importer cannot find x and y: exit 3 (bad input data) saying what to give.
    write_file(dir / "bare.yaml", real_job("zara.csv"));
    CHECK(run("tile " + (dir / "bare.yaml").string() + " -o " + (dir / "bare.h5").string(), &text) == 3);
    CHECK_THAT(text, Contains("zara.csv") && Contains("--columns"));
    CHECK_FALSE(std::filesystem::exists(dir / "bare.h5"));
    const CrowdFile tiled = tile_ok(real_job("zara.csv", "    columns: \"time=t_s,id=person,x=X_cm,y=Y_cm\"\n"
                                                         "    units: cm\n    credit: \"UCY zara01, as a CSV\"\n"),
                                    "", "csv");
    CHECK(std::find(tiled.provenance.credits.begin(), tiled.provenance.credits.end(), "UCY zara01, as a CSV") !=
          tiled.provenance.credits.end());
  }
  SECTION("the 4-column frame id x y layout needs a frame rate: library.real.fps or --fps") {
    rewrite_zara01(dir / "zara.txt", "", [](double f, double id, double x, double y) {
      std::ostringstream row;
      row.precision(10);
      row << f << " " << id << " " << x << " " << y;
      return row.str();
    });
    write_file(dir / "rate.yaml", real_job("zara.txt"));
    CHECK(run("tile " + (dir / "rate.yaml").string() + " -o " + (dir / "rate.h5").string(), &text) == 2);
    CHECK_THAT(text, Contains("per second") && Contains("library.real.fps"));
    CHECK_FALSE(std::filesystem::exists(dir / "rate.h5"));
    (void)tile_ok(real_job("zara.txt"), "--fps 25", "rate_flag");
    (void)tile_ok(real_job("zara.txt", "    fps: 25\n"), "", "rate_key");
    // The flag's value is checked as the command line is read.
    CHECK(run("tile " + (dir / "rate.yaml").string() + " --fps -3 -o " + (dir / "rate.h5").string(), &text) == 2);
    CHECK_THAT(text, Contains("--fps") && Contains("library.real.fps"));
  }
}

TEST_CASE("a library built from the shipped recorded crowd holds groups of three or more and tiles perfectly within human limits") {
  const auto dir = test::scratch_dir("cli_tile_real_groups");
  const auto out = dir / "real.h5";
  REQUIRE(run("--quiet tile " + config("tile-real.yaml") + " -o " + out.string()) == 0);
  CHECK(run("check-tiling " + out.string()) == 0);
  std::string motion;
  CHECK(run("check-motion " + out.string(), &motion) == 0);
  INFO(motion);
  // Episodes merged into groups: patches labelled "group" with three or more characters, used by the tiling.
  const TilingData d = read_tiling_data(out);
  std::size_t groups = 0, used = 0;
  for (std::size_t k = 0; k < d.library.types.size(); ++k) {
    const tiling::PatchType& t = d.library.types[k];
    if (t.label != "group") continue;
    CHECK(t.fragments.size() >= 3);
    ++groups;
    for (const tiling::Instance& i : d.tiling.instances) used += i.type == k ? 1 : 0;
  }
  CHECK(groups >= 3);
  CHECK(used >= 1);
}
