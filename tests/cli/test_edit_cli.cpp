// `throng edit` run as a user would: the report, the output file, the example configs, and every documented error
// with its exit code and no output left behind.
#include "../graph/synthetic_crowd.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

std::string throng_cmd(const std::string& args) { return test::throng_program().string() + " " + args; }
int run(const std::string& args, std::string* out = nullptr) { return test::run_command(throng_cmd(args), out); }

// A 4 × 5 block marching for 41 frames (ids 100..119), written as a crowd file.
std::filesystem::path write_input(const std::filesystem::path& dir) {
  CrowdFile file;
  file.motion = test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.3, 0.2);
  const auto path = dir / "in.h5";
  write_crowd_file(path, file);
  return path;
}

std::filesystem::path write_job(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}

const char* drag_job = R"(
clip: {sample_step: 2}
drags:
  - {frames: [0, 1]}
  - {frames: [-2, end], offset: [3, -2], rotation: 0.3}
constraints:
  - {type: velocity, agent: 103, frame: 20, velocity: [1.0, 0.4]}
)";

}  // namespace

TEST_CASE("edit writes the edited clip and reports it") {
  const auto dir = test::scratch_dir("cli_edit");
  const auto input = write_input(dir);
  const auto job = write_job(dir, "job.yaml", drag_job);
  const auto output = dir / "out.h5";
  std::string out;
  REQUIRE(run("--json --quiet edit " + input.string() + " --job " + job.string() + " -o " + output.string(), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["agents"] == 20);
  CHECK(report["frames"] == 41);
  CHECK(report["samples"] == 24);  // 0, 2, ..., 40, and the frames the request names: 1, 21 (velocity), 39
  CHECK(report["constraint_rows"] == 2);
  CHECK(report["max_constraint_residual_m"].get<double>() < 1e-9);

  const CrowdFile in = read_crowd_file(input);
  const CrowdFile edited = read_crowd_file(output);
  CHECK(edited.motion.ids == in.motion.ids);
  CHECK(edited.motion.times == in.motion.times);
  // The held head is where it was, the velocity constraint holds on the output frames.
  CHECK(edited.motion.position(0, 7) == in.motion.position(0, 7));
  const double dt = edited.motion.times[21] - edited.motion.times[20];
  const Eigen::Vector2d v = (edited.motion.position(21, 3) - edited.motion.position(20, 3)).head<2>() / dt;
  CHECK((v - Eigen::Vector2d(1.0, 0.4)).norm() < 1e-8);
  CHECK_THAT(edited.provenance.options, Contains("velocity"));

  // The method data.
  const h5::File file = h5::File::open(output);
  const h5::Group g = open_throng_parameters(file).open_group("edit");
  CHECK(g.read_int64("sample_frames", 1).values.size() == 24);
}

TEST_CASE("edit --print-config prints the effective job and writes nothing") {
  const auto dir = test::scratch_dir("cli_edit_print");
  const auto input = write_input(dir);
  const auto job = write_job(dir, "job.yaml", drag_job);
  std::string out;
  REQUIRE(run("--print-config edit " + input.string() + " --job " + job.string() + " -o " + (dir / "x.h5").string() +
                  " --backend petsc",
              &out) == 0);
  CHECK_THAT(out, Contains("backend: petsc") && Contains("sample_step: 2") && Contains("type: velocity"));
  CHECK_FALSE(std::filesystem::exists(dir / "x.h5"));
}

TEST_CASE("the petsc backend gives the eigen backend's result through the program") {
  const auto dir = test::scratch_dir("cli_edit_petsc");
  const auto input = write_input(dir);
  const auto job = write_job(dir, "job.yaml", drag_job);
  std::string out;
  REQUIRE(run("-q edit " + input.string() + " --job " + job.string() + " -o " + (dir / "e.h5").string(), &out) == 0);
  REQUIRE(run("-q edit " + input.string() + " --job " + job.string() + " -o " + (dir / "p.h5").string() + " --backend petsc", &out) == 0);
  const CrowdFile e = read_crowd_file(dir / "e.h5"), p = read_crowd_file(dir / "p.h5");
  double gap = 0;
  for (std::size_t k = 0; k < e.motion.positions.size(); ++k) gap = std::max(gap, std::abs(e.motion.positions[k] - p.motion.positions[k]));
  // PETSc stops at relative residual 1e-12; cond ≈ 1e2 here: measured gaps are ~1e-11 m.
  CHECK(gap < 1e-8);
}

TEST_CASE("bad edits exit with their documented codes and leave no output") {
  const auto dir = test::scratch_dir("cli_edit_errors");
  const auto input = write_input(dir);
  const auto output = dir / "out.h5";
  struct Case {
    const char* job;
    int code;
    const char* message;
  };
  const Case cases[] = {
      {"drags:\n  - {frames: [0, 0]}\nweights: {gamma: 1}\n", 2, "gamma"},
      {"pins:\n  - {agent: 555, frame: 3}\n", 2, "pins[0].agent: no agent with id 555"},
      {"drags:\n  - {frames: [0, 0]}\npins:\n  - {agent: 100, frame: 70}\n", 2, "pins[0].frame 70 is outside the clip [0, 40]"},
      {"drags:\n  - {frames: [0, 0]}\n  - {frames: [40, 40]}\nconstraints:\n"
       "  - {type: relative_position, agent: 100, other: 101, frames: [10, 10], offset: [1, 0]}\n"
       "  - {type: relative_position, agent: 100, other: 101, frames: [10, 10], offset: [2, 0]}\n",
       5, "contradictory constraints: constraints[0]"},
      {"pins:\n  - {agent: 100, frame: 0}\n", 5, "the system is singular"},
  };
  for (const Case& c : cases) {
    const auto job = write_job(dir, "job.yaml", c.job);
    std::string out;
    CAPTURE(c.job);
    CHECK(run("-q edit " + input.string() + " --job " + job.string() + " -o " + output.string(), &out) == c.code);
    CHECK_THAT(out, Contains(c.message));
    CHECK_FALSE(std::filesystem::exists(output));
  }
  std::string out;
  CHECK(run("-q edit " + (dir / "absent.h5").string() + " --job " + (dir / "job.yaml").string() + " -o " + output.string(), &out) == 4);
  CHECK(run("-q edit " + input.string() + " --job " + (dir / "job.yaml").string() + " -o " + input.string(), &out) == 2);
  CHECK(run("-q edit " + input.string() + " --job " + (dir / "job.yaml").string() + " -o " + output.string() + " --backend cuda", &out) == 2);
  // Only the input, the job and nothing else (no temporary) are left.
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 2);
}

TEST_CASE("the battlefield example configs run: the edit job and the pipeline") {
  const auto dir = test::scratch_dir("cli_edit_battlefield");
  const auto configs = test::source_dir() / "configs";
  std::string out;
  REQUIRE(run("-q sketch " + (configs / "sketch-paper.yaml").string() + " -o " + (dir / "paper.h5").string(), &out) == 0);
  REQUIRE(run("-q --json edit " + (dir / "paper.h5").string() + " --job " + (configs / "edit-battlefield.yaml").string() +
                  " -o " + (dir / "battlefield.h5").string(),
              &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["agents"] == 50);
  // The tail was moved 45 m east: the group's last centroid moved by about that much.
  const CrowdFile before = read_crowd_file(dir / "paper.h5"), after = read_crowd_file(dir / "battlefield.h5");
  Eigen::Vector2d shift(0, 0);
  const std::size_t last = after.motion.frame_count() - 1;
  for (std::size_t a = 0; a < 50; ++a) shift += (after.motion.position(last, a) - before.motion.position(last, a)).head<2>() / 50.0;
  CHECK(shift.x() > 30);
  REQUIRE(run("-q plot " + (dir / "battlefield.h5").string() + " --overlay " + (dir / "paper.h5").string() + " -o " +
                  (dir / "battlefield.svg").string(),
              &out) == 0);
  CHECK(std::filesystem::file_size(dir / "battlefield.svg") > 10000);

  // The pipeline, run from a folder where configs/ is the project's.
  std::filesystem::create_directory_symlink(configs, dir / "configs");
  REQUIRE(test::run_command("cd " + dir.string() + " && " + throng_cmd("-q run configs/run-battlefield.yaml"), &out) == 0);
  CHECK(std::filesystem::exists(dir / "battlefield.png"));
}
