// throng formation: the spectral formation job as a user runs it — every example config, keyframes hit in the
// output file, keyframes from a crowd, the `formation` step of `throng run`, bad jobs and their exit codes.
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

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
    if (e.path().extension() != ".yaml" && e.path().filename() != "input.h5") return false;
  }
  return true;
}

// Checks that every individual is at its keyframe position at its keyframe frame, as stored in the file, and
// that the stored keyframes are those of the job (the first row of keyframe 0 when given).
void check_keyframes_hit(const std::filesystem::path& path, std::size_t individuals, std::size_t keyframes) {
  const CrowdFile f = read_crowd_file(path);
  REQUIRE(f.motion.agent_count() == individuals);
  CHECK_NOTHROW(f.motion.validate(path.filename().string()));
  CHECK_FALSE(f.formation_edges.empty());
  const h5::File file = h5::File::open(path);
  const h5::Group g = open_throng_parameters(file).open_group("formation").open_group("keyframes");
  const auto frames = g.read_int64("frame", 1);
  const auto position = g.read_doubles("position", 3);
  REQUIRE(frames.shape == std::vector<std::uint64_t>{keyframes});
  REQUIRE(position.shape[0] == keyframes);
  REQUIRE(position.shape[1] == individuals);
  const std::uint64_t d = position.shape[2];
  double worst = 0.0;
  for (std::size_t k = 0; k < keyframes; ++k) {
    const auto frame = static_cast<std::size_t>(frames.values[k]);
    REQUIRE(frame < f.motion.frame_count());
    for (std::size_t i = 0; i < individuals; ++i)
      for (std::uint64_t a = 0; a < d; ++a)
        worst = std::max(worst, std::abs(f.motion.position(frame, i)(static_cast<Eigen::Index>(a)) -
                                         position.values[(k * individuals + i) * d + a]));
  }
  CHECK(worst < 1e-6);
  CHECK(frames.values.front() == 0);
  CHECK(static_cast<std::size_t>(frames.values.back()) == f.motion.frame_count() - 1);
}

// A valid small job; `extra` is appended.
std::string small_job(const std::string& extra = {}) {
  return "keyframes:\n"
         "  - {time: 0, positions: [[0, 0], [2, 0], [0, 2], [2, 2.5], [1, 4]]}\n"
         "  - {time: 2, positions: [[10, 0], [12, 0], [10, 2], [12, 2], [11, 3]]}\n"
         "  - {time: 4, shapes: [{circle: {count: 5, radius: 2, center: [20, 0]}}]}\n" +
         extra;
}

}  // namespace

TEST_CASE("every formation config runs and reads back with its keyframes hit") {
  const auto dir = test::scratch_dir("cli_formation_configs");
  struct Case {
    const char* file;
    const char* set;  // shrinks large configs
    std::size_t individuals, keyframes;
    int dimension;
  };
  for (const Case& c : {Case{"formation-marching-band.yaml", "", 25, 4, 2}, Case{"formation-offside-trap.yaml", "", 14, 4, 2},
                        Case{"formation-airshow.yaml", "--set frame_rate=5", 10, 6, 3},
                        Case{"formation-hierarchy-1260.yaml", "--set frame_rate=2", 1260, 4, 2}}) {
    INFO(c.file);
    const auto out = dir / (std::string(c.file) + ".h5");
    std::string report;
    REQUIRE(run("--quiet --json " + std::string(c.set) + " formation " + config(c.file) + " -o " + out.string(), &report) == 0);
    CHECK_THAT(report, Contains("\"agents\": " + std::to_string(c.individuals)) &&
                           Contains("\"dimension\": " + std::to_string(c.dimension)));
    if (std::string(c.file).find("band") != std::string::npos || std::string(c.file).find("offside") != std::string::npos)
      CHECK_THAT(report, Contains("\"collision_satisfied\": true"));
    check_keyframes_hit(out, c.individuals, c.keyframes);
    const CrowdFile f = read_crowd_file(out);
    CHECK_THAT(f.provenance.options, Contains("tension: 0.5") && Contains("reordering: greedy"));
    if (c.dimension == 3) CHECK(f.motion.position(0, 0).z() > 100);
  }

  // The pictures: formation edges drawn at the keyframes; a 3-D crowd seen from the front (x, z).
  const auto airshow = dir / "formation-airshow.yaml.h5";
  REQUIRE(run("--quiet plot " + airshow.string() + " -o " + (dir / "front.svg").string() + " --view front --frames 0,-1") == 0);
  REQUIRE(run("--quiet plot " + airshow.string() + " -o " + (dir / "top.svg").string() + " --frames 0,-1") == 0);
  auto text = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  CHECK_THAT(text(dir / "front.svg"), Contains("<line"));
  // The vertical spread of the drawn discs (frames 0 and last): letters stand up in the front view (120 m
  // tall) and lie flat from above (every plane at y = 0 at those frames).
  auto disc_spread = [&](const std::filesystem::path& p) {
    const std::string svg = text(p);
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) {
      const std::size_t cy = svg.find("cy=\"", at);
      const double y = std::stod(svg.substr(cy + 4));
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    return hi - lo;
  };
  CHECK(disc_spread(dir / "front.svg") > 50);
  CHECK(disc_spread(dir / "top.svg") < 1);
  CHECK(run("--quiet plot " + airshow.string() + " -o " + (dir / "bad.svg").string() + " --view diagonal") != 0);
  CHECK_FALSE(std::filesystem::exists(dir / "bad.svg"));
}

TEST_CASE("the hierarchy config's groups are stored and used as species") {
  const auto dir = test::scratch_dir("cli_formation_groups");
  const auto out = dir / "band.h5";
  REQUIRE(run("--quiet formation " + config("formation-marching-band.yaml") + " -o " + out.string()) == 0);
  const CrowdFile f = read_crowd_file(out);
  const h5::File file = h5::File::open(out);
  const h5::Group groups = open_throng_parameters(file).open_group("formation").open_group("groups");
  const std::vector<std::string> names = groups.read_strings("name");
  REQUIRE(names.size() == 7);
  CHECK(names[0] == "band");
  CHECK(names[2] == "trumpets");
  CHECK(names[f.motion.species[3]] == "trumpets");
  CHECK(names[f.motion.species[24]] == "guard_right");
  CHECK(groups.read_int64("parent", 1).values == std::vector<std::int64_t>{-1, 0, 0, 0, 0, 0, 0});
}

TEST_CASE("print-config shows the effective job and writes nothing, and one and two threads give the same bits") {
  const auto dir = test::scratch_dir("cli_formation_print");
  write_file(dir / "job.yaml", small_job());
  std::string printed;
  REQUIRE(run("--print-config formation " + (dir / "job.yaml").string() + " -o " + (dir / "out.h5").string(), &printed) == 0);
  CHECK_THAT(printed, Contains("tension: 0.5") && Contains("orientation: pca") && Contains("circle:") &&
                          Contains("min_distance: 0.6"));
  CHECK_FALSE(std::filesystem::exists(dir / "out.h5"));

  const std::string job = config("formation-hierarchy-1260.yaml");
  REQUIRE(run("--quiet --threads 1 --set frame_rate=1 formation " + job + " -o " + (dir / "one.h5").string()) == 0);
  REQUIRE(run("--quiet --threads 2 --set frame_rate=1 formation " + job + " -o " + (dir / "two.h5").string()) == 0);
  const CrowdFile one = read_crowd_file(dir / "one.h5"), two = read_crowd_file(dir / "two.h5");
  REQUIRE(one.motion.positions.size() == two.motion.positions.size());
  CHECK(std::memcmp(one.motion.positions.data(), two.motion.positions.data(), one.motion.positions.size() * sizeof(double)) == 0);
}

TEST_CASE("keyframes from a crowd file, and the formation step of throng run") {
  const auto dir = test::scratch_dir("cli_formation_crowd");
  write_file(dir / "job.yaml", small_job());
  REQUIRE(run("--quiet formation " + (dir / "job.yaml").string() + " -o " + (dir / "input.h5").string()) == 0);

  // Back from the last frame to the first, taken from the file: the path reverses, keyframes hit.
  // The guard off: the job's own times exactly (with it, the reversal would be re-timed to 4.4 s).
  write_file(dir / "back.yaml", "from_crowd: {file: " + (dir / "input.h5").string() + ", frames: [-1, 0], times: [0, 4]}\n"
                                "guard: {enabled: false}\n");
  std::string report;
  REQUIRE(run("--quiet formation " + (dir / "back.yaml").string() + " -o " + (dir / "back.h5").string(), &report) == 0);
  const CrowdFile input = read_crowd_file(dir / "input.h5"), back = read_crowd_file(dir / "back.h5");
  REQUIRE(back.motion.agent_count() == 5);
  for (std::size_t i = 0; i < 5; ++i) {
    CHECK((back.motion.position(0, i) - input.motion.position(input.motion.frame_count() - 1, i)).norm() < 1e-9);
    CHECK((back.motion.position(back.motion.frame_count() - 1, i) - input.motion.position(0, i)).norm() < 1e-9);
  }
  CHECK(back.motion.times.back() == 4.0);

  // A pipeline: make the crowd, then a formation step taking its keyframes from it (no file), then a picture.
  write_file(dir / "pipeline.yaml",
             "steps:\n"
             "  - step: formation\n"
             "    job: " + (dir / "job.yaml").string() + "\n"
             "  - step: formation\n"
             "    from_crowd: {frames: [0, 40, -1]}\n"
             "    tension: 1\n"
             "    output: " + (dir / "again.h5").string() + "\n"
             "  - step: plot\n"
             "    frames: [0, 40, -1]\n"
             "    output: " + (dir / "again.svg").string() + "\n");
  REQUIRE(run("--quiet run " + (dir / "pipeline.yaml").string(), &report) == 0);
  check_keyframes_hit(dir / "again.h5", 5, 3);
  CHECK(std::filesystem::file_size(dir / "again.svg") > 1000);

  // The step needs its crowd.
  write_file(dir / "lonely.yaml", "steps:\n  - step: formation\n    from_crowd: {frames: [0, 1]}\n    output: " +
                                      (dir / "lonely.h5").string() + "\n");
  CHECK(run("--quiet run " + (dir / "lonely.yaml").string(), &report) == 2);
  CHECK_FALSE(std::filesystem::exists(dir / "lonely.h5"));
}

TEST_CASE("bad formation jobs give their exit codes and leave no output") {
  // `place`: the job's line the message must name ("job.yaml:5:" = the edits, the hierarchy, or keyframe 2's
  // line), also when the solver finds the problem; empty: the message names no line (from_crowd, the file).
  const auto dir = test::scratch_dir("cli_formation_errors");
  struct Bad {
    const char* name;
    std::string job;
    int code;
    const char* message;
    const char* place;
  };
  const std::vector<Bad> cases = {
      {"disconnected", small_job("edits: {remove: [[0, 1], [0, 2]]}\n"), 3, "not connected", "job.yaml:2:"},
      {"count", "keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0], [0, 1]]}\n  - {time: 1, positions: [[0, 0], [1, 0]]}\n",
       3, "keyframe 1 has 2 individuals, keyframe 0 has 3", "job.yaml:3:"},
      {"duplicate", "keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0], [0, 1]]}\n  - {time: 1, positions: [[3, 3], [1, 0], [3, 3]]}\n",
       3, "both at (3, 3)", "job.yaml:3:"},
      {"times", "keyframes:\n  - {time: 1, positions: [[0, 0], [1, 0]]}\n  - {time: 1, positions: [[0, 1], [1, 1]]}\n", 3,
       "must increase strictly", "job.yaml:3:"},
      {"nan position", "keyframes:\n  - {time: 0, positions: [[0, 0], [1, .nan]]}\n  - {time: 1, positions: [[0, 1], [1, 1]]}\n", 3,
       "individual 1's coordinate is '.nan', not a finite number", "job.yaml:2:"},
      {"infinite time", "keyframes:\n  - {time: 0, positions: [[0, 0], [1, 0]]}\n  - {time: .inf, positions: [[0, 1], [1, 1]]}\n", 3,
       "keyframe 1's time is '.inf'", "job.yaml:3:"},
      {"spacing", small_job("collision: {enabled: true, min_distance: 3}\n"), 3, "closer than collision.min_distance", "job.yaml:2:"},
      {"unknown key", small_job("tensoin: 0.5\n"), 2, "tensoin", "job.yaml:5:"},
      {"range", small_job("tension: 1.5\n"), 2, "tension", "job.yaml:5:"},
      {"non-edge", small_job("edits: {remove: [[0, 4]]}\n"), 2, "remove[0]", "job.yaml:5:"},
      {"unknown individual", small_job("edits: {remove: [[0, 5]]}\n"), 2, "edits.remove[0]: individual 5 does not exist", "job.yaml:5:"},
      {"bad hierarchy", small_job("hierarchy: {name: all, members: [0, 1, 2, 3]}\n"), 2, "individual 4", "job.yaml:5:"},
      {"bad shape", "keyframes:\n  - {time: 0, shapes: [{spiral: {count: 3}}]}\n  - {time: 1, positions: [[0, 1]]}\n", 2,
       "unknown shape 'spiral'", "job.yaml:2:"},
      {"missing crowd", "from_crowd: {file: " + (dir / "nowhere.h5").string() + ", frames: [0, 1]}\n", 4, "nowhere.h5", ""},
  };
  for (const Bad& b : cases) {
    INFO(b.name);
    write_file(dir / "job.yaml", b.job);
    std::string output;
    CHECK(run("formation " + (dir / "job.yaml").string() + " -o " + (dir / "out.h5").string(), &output) == b.code);
    CHECK_THAT(output, Contains(b.message));
    if (*b.place) CHECK_THAT(output, Contains(b.place));
    CHECK(only_inputs_left(dir));
  }
}
