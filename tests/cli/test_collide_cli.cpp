// `throng collide` run as a user would: the report, the repaired file, flags over the job, the exit code and the
// kept output when collisions remain, every documented error with its exit code and no output left behind, the
// example configs (shrunk) as `throng run` pipelines, and imported real data with its walls.
#include "checker.h"
#include "scenes.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <fstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

std::string throng_cmd(const std::string& args) { return test::throng_program().string() + " " + args; }
int run(const std::string& args, std::string* out = nullptr) { return test::run_command(throng_cmd(args), out); }

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
  const auto job = write_text(dir, "walls.yaml", R"(
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
    const auto path = dir / s.config;
    std::ofstream(path) << job;
    std::string out;
    REQUIRE(test::run_command("cd " + dir.string() + " && " + throng_cmd("--quiet run " + path.string()), &out) == 0);
    const auto written = dir / (std::string(s.config).substr(0, std::string(s.config).size() - 5) + ".h5");
    REQUIRE(std::filesystem::exists(written));
    const CrowdFile result = read_crowd_file(written);
    CHECK(collide::check::min_pair_slack(result.motion, 0.0, 4) >= -1e-9);
    if (!result.scene.obstacles.empty()) CHECK(collide::check::min_obstacle_slack(result.motion, result.scene.obstacles, 0.0, 4) >= -1e-9);
  }
}

TEST_CASE("collide: imported real data with its walls") {
  const auto data = test::real_data_dir();
  if (data.empty()) {
    WARN("../shared/data/real not found: real-data collide test skipped");
    return;
  }
  const auto dir = test::scratch_dir("cli_collide_real");
  const auto imported = dir / "zara.h5";
  std::string out;
  REQUIRE(run("--quiet import " + (data / "zara01").string() + " -o " + imported.string(), &out) == 0);
  // Real pedestrians meet at the frames where they enter and leave (pinned): those contacts may stay.
  REQUIRE(run("--json --quiet collide " + imported.string() + " --allow-remaining --max-iterations 400 -o " +
                  (dir / "out.h5").string(),
              &out) == 0);
  INFO(out);
  // The report (stdout), without the warning about the contacts left (stderr).
  const auto report = nlohmann::json::parse(out.substr(out.find('{'), out.rfind('}') - out.find('{') + 1));
  CHECK(report["obstacles"].get<int>() > 0);
  CHECK(report["initial_pair_contacts"].get<int>() > 0);
  CHECK(report["pair_contacts"].get<int>() + report["obstacle_contacts"].get<int>() <=
        report["initial_pair_contacts"].get<int>() + report["initial_obstacle_contacts"].get<int>());
  if (report["converged"] == false && report["stop_reason"] == "only stuck contacts left") {
    CHECK(report["stuck_contacts"].get<int>() == report["pair_contacts"].get<int>() + report["obstacle_contacts"].get<int>());
  }
  const CrowdFile in = read_crowd_file(imported);
  const CrowdFile repaired = read_crowd_file(dir / "out.h5");
  CHECK(repaired.scene.obstacles.size() == in.scene.obstacles.size());
  // Each agent's first and last present frames are where they were.
  for (std::size_t a = 0; a < in.motion.agent_count(); ++a) {
    const auto [first, end] = in.motion.presence_span(a);
    if (end == 0) continue;
    CHECK(in.motion.position(first, a) == repaired.motion.position(first, a));
    CHECK(in.motion.position(end - 1, a) == repaired.motion.position(end - 1, a));
  }
}
