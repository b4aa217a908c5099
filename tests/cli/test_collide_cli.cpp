// `throng collide` run as a user would: the report, the repaired file, flags over the job, the exit code and the
// kept output when collisions remain, every documented error with its exit code and no output left behind, the
// example configs (shrunk) as `throng run` pipelines, and imported real data with its walls.
#include "checker.h"
#include "scenes.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <cstring>
#include <fstream>
#include <tuple>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

std::filesystem::path write_crowd(const std::filesystem::path& dir, const collide::scenes::CollideScene& scene,
                                  const std::string& name = "in.h5") {
  CrowdFile file;
  file.motion = scene.crowd;
  file.scene.obstacles = scene.obstacles;
  const auto path = dir / name;
  write_crowd_file(path, file);
  return path;
}

std::filesystem::path write_text(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// Two agents 0.1 m apart over all 20 frames: their pinned first and last frames collide.
collide::scenes::CollideScene stuck_pair() {
  collide::scenes::CollideScene s;
  s.crowd = CrowdMotion::with_shape(20, 2, 0.25);
  for (std::size_t f = 0; f < 20; ++f) {
    s.crowd.times[f] = 0.1 * static_cast<double>(f);
    s.crowd.position(f, 0) = Eigen::Vector3d(0.1 * static_cast<double>(f), 0, 0);
    s.crowd.position(f, 1) = Eigen::Vector3d(0.1 * static_cast<double>(f), 0.1, 0);
  }
  return s;
}

bool leftovers(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.find("out") != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("collide repairs a crowd and reports it") {
  const auto dir = test::scratch_dir("cli_collide");
  const auto scene = collide::scenes::bump(3, 90);
  const auto input = write_crowd(dir, scene);
  const auto output = dir / "out.h5";
  std::string out;
  REQUIRE(run("--json --quiet collide " + input.string() + " -o " + output.string(), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["converged"] == true);
  CHECK(report["pair_contacts"] == 0);
  CHECK(report["initial_pair_contacts"].get<int>() > 5);
  CHECK(report["iterations"].get<int>() > 0);
  CHECK(report["min_pair_gap_m"].get<double>() >= 0.0);

  const CrowdFile repaired = read_crowd_file(output);
  CHECK(repaired.motion.ids == scene.crowd.ids);
  CHECK(collide::check::min_pair_slack(repaired.motion, 0.0) >= -1e-9);
  CHECK(collide::check::changed_vertices(scene.crowd, repaired.motion, {0, 89}) == 0);
  CHECK_THAT(repaired.provenance.options, Contains("push_fraction"));
  const h5::File file = h5::File::open(output);
  const h5::Group g = open_throng_parameters(file).open_group("collide");
  CHECK(g.read_int64("history", 1).values.size() == report["iterations"].get<std::size_t>());
}

TEST_CASE("collide: flags override the job, --set overrides both, --print-config writes nothing") {
  const auto dir = test::scratch_dir("cli_collide_print");
  const auto input = write_crowd(dir, collide::scenes::bump(2, 30));
  const auto job = write_text(dir, "job.yaml", "margin: 0.3\nspread: 9\nfixed_agents: [1]\n");
  std::string out;
  REQUIRE(run("collide " + input.string() + " --job " + job.string() + " --margin 0.1 --obstacle-pull nearest " +
                  "--set max_iterations=77 --print-config -o " + (dir / "out.h5").string(),
              &out) == 0);
  const YAML::Node effective = YAML::Load(out);
  CHECK(effective["margin"].as<double>() == 0.1);
  CHECK(effective["spread"].as<double>() == 9);
  CHECK(effective["max_iterations"].as<int>() == 77);
  CHECK(effective["obstacle_pull"].as<std::string>() == "nearest");
  CHECK(effective["fixed_agents"][0].as<int>() == 1);
  CHECK(!leftovers(dir));
}

TEST_CASE("collide: collisions left at pinned frames exit 5 and keep the output, unless allowed") {
  const auto dir = test::scratch_dir("cli_collide_stuck");
  const auto input = write_crowd(dir, stuck_pair());
  std::string out;
  CHECK(run("--json collide " + input.string() + " -o " + (dir / "out.h5").string(), &out) == 5);
  CHECK_THAT(out, Contains("\"converged\": false"));
  CHECK_THAT(out, Contains("stuck at pinned frames"));
  REQUIRE(std::filesystem::exists(dir / "out.h5"));
  const CrowdFile kept = read_crowd_file(dir / "out.h5");
  CHECK(kept.motion.agent_count() == 2);
  CHECK(run("--quiet collide " + input.string() + " --allow-remaining -o " + (dir / "out2.h5").string(), &out) == 0);
  CHECK(std::filesystem::exists(dir / "out2.h5"));
}

TEST_CASE("collide: bad jobs, flags and inputs exit with their codes and write nothing") {
  const auto dir = test::scratch_dir("cli_collide_errors");
  const auto input = write_crowd(dir, collide::scenes::bump(2, 30));
  const std::string o = " -o " + (dir / "out.h5").string();
  std::string out;
  const auto unknown = write_text(dir, "unknown.yaml", "margin: 0.1\npush: 0.2\n");
  CHECK(run("collide " + input.string() + " --job " + unknown.string() + o, &out) == 2);
  CHECK_THAT(out, Contains("push"));
  const auto range = write_text(dir, "range.yaml", "push_fraction: 1.5\n");
  CHECK(run("collide " + input.string() + " --job " + range.string() + o, &out) == 2);
  CHECK_THAT(out, Contains("push_fraction"));
  const auto pull = write_text(dir, "pull.yaml", "obstacle_pull: around\n");
  CHECK(run("collide " + input.string() + " --job " + pull.string() + o, &out) == 2);
  CHECK(run("collide " + input.string() + " --margin -1" + o, &out) == 2);
  CHECK(run("collide " + input.string() + " --fixed-agents 999" + o, &out) == 2);
  CHECK_THAT(out, Contains("999"));
  CHECK(run("collide " + input.string() + " -o " + input.string(), &out) == 2);
  CHECK(run("collide " + (dir / "missing.h5").string() + o, &out) == 4);
  const auto not_h5 = write_text(dir, "bad.h5", "not a crowd");
  CHECK(run("collide " + not_h5.string() + o, &out) != 0);
  CHECK(!leftovers(dir));
}

TEST_CASE("collide: the job's obstacles are added to the crowd's and avoided") {
  const auto dir = test::scratch_dir("cli_collide_walls");
  const auto input = write_crowd(dir, collide::scenes::bump(2, 60));
  // The limits off (max_speed_ratio, max_acceleration: 0): a 2-s clip of groups passing through each other and
  // the obstacles, which no walker could repair within them; here the point is that the job's obstacles count.
  const auto job = write_text(dir, "walls.yaml", R"(
max_speed_ratio: 0
max_acceleration: 0
obstacles:
  - circle: {center: [0, 0.6], radius: 0.3}
    name: post
  - wall: {from: [-0.5, -2], to: [0.5, -0.8], thickness: 0.2}
)");
  std::string out;
  REQUIRE(run("--json --quiet collide " + input.string() + " --job " + job.string() + " -o " + (dir / "out.h5").string(), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["obstacles"] == 2);
  CHECK(report["initial_obstacle_contacts"].get<int>() > 0);
  CHECK(report["obstacle_contacts"] == 0);
  const CrowdFile repaired = read_crowd_file(dir / "out.h5");
  REQUIRE(repaired.scene.obstacles.size() == 2);
  CHECK(collide::check::min_obstacle_slack(repaired.motion, repaired.scene.obstacles, 0.0) >= -1e-9);
}

TEST_CASE("collide: the example configs run as pipelines (shrunk)") {
  struct Shrink {
    const char* config;
    int agents;       // per sketch step with a count
    double duration;  // seconds
  };
  for (const Shrink& s : {Shrink{"collide-bump.yaml", 9, 16}, Shrink{"collide-narrow-opening.yaml", 0, 20},
                          Shrink{"collide-crossing.yaml", 40, 60}}) {
    INFO(s.config);
    const auto dir = test::scratch_dir(std::string("cli_collide_config_") + s.config);
    YAML::Node job = YAML::LoadFile((test::source_dir() / "configs" / s.config).string());
    for (YAML::Node step : job["steps"]) {
      if (step["step"].as<std::string>() == "sketch" && s.agents > 0) step["agents"]["count"] = s.agents;
    }
    // Keep the crowd the collide step reads (the step before it), to check the pins against.
    job["steps"][job["steps"].size() - 2]["output"] = "before.h5";
    const auto path = dir / s.config;
    std::ofstream(path) << job;
    std::string out;
    REQUIRE(test::run_command("cd " + dir.string() + " && " + test::command("--quiet run " + path.string()), &out) == 0);
    const auto written = dir / (std::string(s.config).substr(0, std::string(s.config).size() - 5) + ".h5");
    REQUIRE(std::filesystem::exists(written));
    const CrowdFile result = read_crowd_file(written);
    CHECK(collide::check::min_pair_slack(result.motion, 0.0, 4) >= -1e-9);
    if (!result.scene.obstacles.empty()) CHECK(collide::check::min_obstacle_slack(result.motion, result.scene.obstacles, 0.0, 4) >= -1e-9);
    // Every config keeps the default pins: the first and last frames are the input's, bit for bit.
    const CrowdFile before = read_crowd_file(dir / "before.h5");
    REQUIRE(before.motion.frame_count() == result.motion.frame_count());
    CHECK(collide::check::changed_vertices(before.motion, result.motion, {0, result.motion.frame_count() - 1}) == 0);
    CHECK(collide::check::changed_vertices(before.motion, result.motion) > 0);
  }
}

// The report (stdout) of a run that may also warn (stderr).
nlohmann::json report_of(const std::string& out) {
  return nlohmann::json::parse(out.substr(out.find('{'), out.rfind('}') - out.find('{') + 1));
}

TEST_CASE("collide: imported real data with its walls, at the defaults") {
  const auto data = test::real_data_dir();
  const auto dir = test::scratch_dir("cli_collide_real");
  // hotel: agents tracked inside the pillars at their first and last frames (audit: the old loop dragged one
  // 255 m away in 10,000 iterations); eth and zara have walls, univ is the densest. Each takes well under 1 s.
  for (const char* name : {"hotel", "eth", "zara01", "univ_students03"}) {
    INFO(name);
    const auto imported = dir / (std::string(name) + ".h5");
    const auto repaired_path = dir / (std::string(name) + "-out.h5");
    std::string out;
    REQUIRE(run("--quiet import " + (data / name).string() + " -o " + imported.string(), &out) == 0);
    // Real pedestrians overlap at the frames where they enter and leave (pinned): those contacts stay, exit 5.
    const int code = run("--json --quiet collide " + imported.string() + " -o " + repaired_path.string(), &out);
    INFO(out);
    const auto report = report_of(out);
    CHECK(report["initial_pair_contacts"].get<int>() > 0);
    const int remaining = report["pair_contacts"].get<int>() + report["obstacle_contacts"].get<int>();
    CHECK(code == (remaining > 0 ? 5 : 0));
    CHECK(report["iterations"].get<int>() < 1000);  // stops long before the cap (10,000)
    if (remaining > 0) {
      CHECK(report["stop_reason"] == "only stuck or abandoned contacts left");
      CHECK(report["stuck_contacts"].get<int>() == remaining);  // what is left is what the pins hold
    }
    // Bounded repair: nobody is moved more than out of a pillar or past a neighbour (measured ≤ 2.4 m), nor
    // made much faster than the fastest pedestrian recorded (measured ≤ 1.4×).
    CHECK(report["max_displacement_m"].get<double>() <= 4.0);
    CHECK(report["max_speed_out_m_s"].get<double>() <= 2.0 * report["max_speed_in_m_s"].get<double>());
    const CrowdFile in = read_crowd_file(imported);
    const CrowdFile repaired = read_crowd_file(repaired_path);
    CHECK(repaired.scene.obstacles.size() == in.scene.obstacles.size());
    // Each agent's first and last present frames are where they were.
    for (std::size_t a = 0; a < in.motion.agent_count(); ++a) {
      const auto [first, end] = in.motion.presence_span(a);
      if (end == 0) continue;
      CHECK(in.motion.position(first, a) == repaired.motion.position(first, a));
      CHECK(in.motion.position(end - 1, a) == repaired.motion.position(end - 1, a));
    }
  }
}

namespace {

std::vector<double> positions(const std::filesystem::path& path) { return read_crowd_file(path).motion.positions; }

using test::same_bits;

}  // namespace

TEST_CASE("collide: 1 and 2 threads give the same bits, with obstacles") {
  const auto dir = test::scratch_dir("cli_collide_threads");
  const auto input = write_crowd(dir, collide::scenes::narrow_opening(19, 2.4, 300));
  REQUIRE(run("--quiet --threads 1 collide " + input.string() + " -o " + (dir / "one.h5").string()) == 0);
  REQUIRE(run("--quiet --threads 2 collide " + input.string() + " -o " + (dir / "two.h5").string()) == 0);
  const auto one = positions(dir / "one.h5");
  CHECK(!same_bits(one, positions(input)));
  CHECK(same_bits(one, positions(dir / "two.h5")));
}

TEST_CASE("collide: 1 and 2 MPI ranks give the same bits, and only rank 0 writes and reports", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_collide_ranks");
  const auto input = write_crowd(dir, collide::scenes::narrow_opening(19, 2.4, 300));
  REQUIRE(run("--quiet collide " + input.string() + " -o " + (dir / "one.h5").string()) == 0);
  std::string out;
  REQUIRE(test::run_command(mpiexec + " -n 2 --oversubscribe " + test::throng_program().string() + " --json --quiet collide " +
                                input.string() + " -o " + (dir / "two.h5").string(),
                            &out) == 0);
  INFO(out);
  CHECK(same_bits(positions(dir / "one.h5"), positions(dir / "two.h5")));
  // One report, from rank 0, saying the solves were spread over 2 ranks.
  std::size_t reports = 0;
  for (std::size_t at = out.find("\"ranks\""); at != std::string::npos; at = out.find("\"ranks\"", at + 1)) ++reports;
  CHECK(reports == 1);
  CHECK_THAT(out, Contains("\"ranks\": 2"));
}

TEST_CASE("collide: edit -> collide and stitch -> collide pipelines repair and keep the pins") {
  const auto dir = test::scratch_dir("cli_collide_pipelines");
  const std::string configs = (test::source_dir() / "configs").string();
  // The battlefield edit (edit output), with a margin that makes its closest pairs collide.
  const auto edit = write_text(dir, "edit.yaml", "steps:\n"
      "  - {step: sketch, job: " + configs + "/sketch-paper.yaml}\n"
      "  - {step: edit, job: " + configs + "/edit-battlefield.yaml, output: before-edit.h5}\n"
      "  - {step: collide, margin: 0.4, output: after-edit.h5}\n");
  // Two sketched clips stitched (stitch output), with a post in the stitched group's way.
  const auto stitch = write_text(dir, "stitch.yaml", "steps:\n"
      "  - {step: sketch, name: a, agents: {count: 12, radius: 0.25}, output_rate: 10,\n"
      "     strokes: {main: [[0, 0, 0], [10, 0, 8]], auxiliary: [[[0, 2], [10, 2]], [[0, -2], [10, -2]]]}}\n"
      "  - {step: sketch, name: b, agents: {count: 12, radius: 0.25}, output_rate: 10,\n"
      "     strokes: {main: [[10, 0, 0], [10, 10, 8]], auxiliary: [[[8, 0], [8, 10]], [[12, 0], [12, 10]]]}}\n"
      "  - {step: stitch, inputs: [a, b], output: before-stitch.h5}\n"
      "  - {step: collide, obstacles: [{circle: {center: [12.5, 0], radius: 0.5}}], output: after-stitch.h5}\n");
  for (const auto& [job, name, margin] : {std::tuple{edit, "edit", 0.4}, std::tuple{stitch, "stitch", 0.0}}) {
    INFO(name);
    std::string out;
    REQUIRE(test::run_command("cd " + dir.string() + " && " + test::command("--quiet run " + job.string()), &out) == 0);
    const CrowdFile before = read_crowd_file(dir / ("before-" + std::string(name) + ".h5"));
    const CrowdFile after = read_crowd_file(dir / ("after-" + std::string(name) + ".h5"));
    CHECK(collide::check::changed_vertices(before.motion, after.motion) > 0);  // there was something to repair
    CHECK(collide::check::changed_vertices(before.motion, after.motion, {0, after.motion.frame_count() - 1}) == 0);
    CHECK(collide::check::min_pair_slack(after.motion, margin, 4) >= -1e-9);
    if (!after.scene.obstacles.empty()) CHECK(collide::check::min_obstacle_slack(after.motion, after.scene.obstacles, 0.0, 8) >= -1e-9);
  }
}

TEST_CASE("collide: a missing output folder and a periodic region fail before any solving") {
  const auto dir = test::scratch_dir("cli_collide_early");
  const auto input = write_crowd(dir, collide::scenes::crossing(200, 300));
  std::string out;
  CHECK(run("collide " + input.string() + " -o " + (dir / "no" / "such" / "out.h5").string(), &out) == 4);
  CHECK_THAT(out, Contains("cannot write"));
  CHECK_THAT(out, !Contains("iterations"));  // failed before the repair ran (no report, no summary)
  const auto periodic = write_text(dir, "periodic.yaml", "region: {min: [0, 0], max: [8, 8], time: [0, 8], periodic: [true, false, false]}\n");
  CHECK(run("collide " + input.string() + " --job " + periodic.string() + " -o " + (dir / "out.h5").string(), &out) == 2);
  CHECK_THAT(out, Contains("periodic"));
  CHECK(!leftovers(dir));
}
