// `throng edit` with the general constraints beyond relative position, velocity and on-a-line (acceleration, sum,
// row) and with formation splits, run as a user would: the report, the output, the errors with their exit codes
// and no output left, and the paper's configs (configs/paper/editing-*.yaml) passing check-motion.
#include "../graph/synthetic_crowd.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <iterator>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

// A 4 × 5 block marching along a curve for 41 frames (ids 100..119, id 100 + 5 r + c in row r, column c).
std::filesystem::path write_input(const std::filesystem::path& dir) {
  CrowdFile file;
  file.motion = test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.6, 0.2);
  const auto path = dir / "in.h5";
  write_crowd_file(path, file);
  return path;
}

// Every new kind in one job, the paper's edit (guard off) so the request is measured on the written frames.
const char* kinds_job = R"(
guard: {enabled: false}
clip: {sample_step: 4}
drags:
  - {frames: [0, 1]}
  - {frames: [-2, end], offset: [2, -3], rotation: 0.2}
constraints:
  - {type: acceleration, agent: 107, frame: 20}
  - {type: sum, agents: [100, 101, 102], frames: [10, 14], value: [5, 1]}
  - {type: sum, agents: [110, 111], weights: [0.75, 0.25], frames: [30, 31]}
  - type: row
    terms:
      - {agent: 115, frame: 25, axis: x, coefficient: 1}
      - {agent: 116, frame: 26, axis: y, coefficient: -2}
    value: 1.5
)";

Eigen::Vector2d xy(const CrowdMotion& c, std::size_t frame, std::int64_t id) {
  return c.position(frame, static_cast<std::size_t>(id - 100)).head<2>();
}

}  // namespace

TEST_CASE("edit meets acceleration, sum and row constraints on the written frames") {
  const auto dir = test::scratch_dir("cli_edit_constraints");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "job.yaml", kinds_job);
  const auto output = dir / "out.h5";
  std::string out;
  REQUIRE(run("--json --quiet edit " + input.string() + " --job " + job.string() + " -o " + output.string(), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["constraint_rows"] == 2 + 2 * 5 + 2 * 2 + 1);
  CHECK(report["residual_after_guard"] == true);
  CHECK(report["max_constraint_residual_m"].get<double>() < 1e-9);
  const CrowdMotion in = read_crowd_file(input).motion, edited = read_crowd_file(output).motion;
  REQUIRE(edited.frame_count() == 41);
  // Zero acceleration of agent 107 at frame 20 (equal spacing: p(19) − 2 p(20) + p(21) = 0), where the input curves.
  CHECK((xy(in, 19, 107) - 2 * xy(in, 20, 107) + xy(in, 21, 107)).norm() > 1e-3);
  CHECK((xy(edited, 19, 107) - 2 * xy(edited, 20, 107) + xy(edited, 21, 107)).norm() < 1e-9);
  for (std::size_t f = 10; f <= 14; ++f) {
    CHECK(((xy(edited, f, 100) + xy(edited, f, 101) + xy(edited, f, 102)) / 3 - Eigen::Vector2d(5, 1)).norm() < 1e-9);
  }
  for (std::size_t f = 30; f <= 31; ++f) {
    const Eigen::Vector2d before = 0.75 * xy(in, f, 110) + 0.25 * xy(in, f, 111);
    CHECK((0.75 * xy(edited, f, 110) + 0.25 * xy(edited, f, 111) - before).norm() < 1e-9);
  }
  CHECK(std::abs(xy(edited, 25, 115).x() - 2 * xy(edited, 26, 116).y() - 1.5) < 1e-9);
  // The effective job in the output's provenance keeps them (it reads back as the same request).
  const CrowdFile file = read_crowd_file(output);
  CHECK_THAT(file.provenance.options, Contains("type: acceleration") && Contains("type: sum") && Contains("type: row"));
}

TEST_CASE("edit with a formation split: the job reads, runs and records the split") {
  const auto dir = test::scratch_dir("cli_edit_split");
  const auto input = write_input(dir);
  const auto job = test::write_file(dir / "job.yaml", R"(
clip: {sample_step: 2}
formation:
  splits:
    - {agents: [100, 101, 105, 106, 110, 111, 115, 116], frames: [16, end]}
drags:
  - {frames: [0, 1]}
  - {frames: [16, 16]}
  - {agents: [100, 101, 105, 106, 110, 111, 115, 116], frames: [39, end], offset: [0, 2]}
  - {agents: [102, 103, 104, 107, 108, 109, 112, 113, 114, 117, 118, 119], frames: [39, end], offset: [0, -2]}
)");
  std::string out;
  REQUIRE(run("--quiet edit " + input.string() + " --job " + job.string() + " -o " + (dir / "out.h5").string(), &out) == 0);
  CHECK_THAT(read_crowd_file(dir / "out.h5").provenance.options, Contains("splits:"));
  CHECK(run("--print-config edit " + input.string() + " --job " + job.string() + " -o " + (dir / "x.h5").string(), &out) == 0);
  CHECK_THAT(out, Contains("splits:") && Contains("[16, end]"));
}

TEST_CASE("bad constraint and split entries exit with their documented codes and leave no output") {
  const auto dir = test::scratch_dir("cli_edit_constraints_errors");
  const auto input = write_input(dir);
  const auto output = dir / "out.h5";
  const std::string held = "drags:\n  - {frames: [0, 0]}\n  - {frames: [40, 40]}\n";
  struct Case {
    std::string job;
    int code;
    const char* message;
  };
  const Case cases[] = {
      {held + "constraints:\n  - {type: acceleration, agent: 555, frame: 3}\n", 2, "constraints[0].agent: no agent with id 555"},
      {held + "constraints:\n  - {type: acceleration, agent: 100, frame: 70}\n", 2, "constraints[0].frame 70 is outside the clip [0, 40]"},
      {held + "constraints:\n  - {type: sum, agents: [100, 555]}\n", 2, "constraints[0].agents[1]: no agent with id 555"},
      {held + "constraints:\n  - {type: sum, agents: [100, 101], weights: [1]}\n", 2, "1 weights for 2 agents"},
      {held + "constraints:\n  - {type: row, terms: [{agent: 100, frame: 3, axis: x}, {agent: 555, frame: 3, axis: x}], value: 0}\n",
       2, "constraints[0].terms[1].agent: no agent with id 555"},
      {held + "constraints:\n  - {type: row, terms: [{agent: 100, frame: 40, axis: y}, {agent: 100, frame: -1, axis: y}], value: 0}\n",
       2, "constraints[0].terms[1]: the same coordinate as constraints[0].terms[0] (agent 100, frame 40, y)"},
      {held + "constraints:\n  - {type: row, terms: [{agent: 100, frame: 3, axis: x, coefficient: 0}], value: 1}\n", 2,
       "every coefficient is 0"},
      {held + "constraints:\n  - {type: row, terms: [{agent: 100, frame: 3, axis: w}], value: 1}\n", 2, "unknown axis 'w'"},
      {held + "formation:\n  splits:\n    - {agents: [100, 555]}\n", 2, "formation.splits[0].agents[1]: agent 555 is not in the clip"},
      {held + "formation:\n  splits:\n    - {agents: [100], frames: [50, end]}\n", 2, "formation.splits[0]: frames [50, end] hold no sample"},
      {held + "constraints:\n  - {type: row, terms: [{agent: 100, frame: 10, axis: x}], value: 5}\n"
              "  - {type: row, terms: [{agent: 100, frame: 10, axis: x, coefficient: 2}], value: 12}\n",
       5, "contradictory constraints: constraints[0] (row of 1 term from agent 100 at frame 10) and constraints[1]"},
      {"drags:\n  - {frames: [0, 2]}\n  - {frames: [40, 40]}\nconstraints:\n"
       "  - {type: acceleration, agent: 100, frame: 1, acceleration: [1, 0]}\n",
       5, "constraints[0] (acceleration of agent 100 at frame 1) cannot be met together with the pins and drags"},
  };
  for (const Case& c : cases) {
    const auto job = test::write_file(dir / "job.yaml", c.job);
    std::string out;
    CAPTURE(c.job);
    CHECK(run("-q edit " + input.string() + " --job " + job.string() + " -o " + output.string(), &out) == c.code);
    CHECK_THAT(out, Contains(c.message));
    CHECK_FALSE(std::filesystem::exists(output));
  }
  // Only the input and the job are left (no temporary).
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 2);
}

TEST_CASE("the paper's branch split and constraint configs run and pass check-motion against their input") {
  // As scripts/run-paper-config runs them: `throng run` from a scratch folder holding paper-out/.
  const auto dir = test::scratch_dir("cli_edit_paper_configs");
  std::filesystem::create_directory(dir / "paper-out");
  const auto configs = test::source_dir() / "configs" / "paper";
  std::string out;
  for (const std::string stem : {"editing-figure-12-branch-split", "editing-constraints"}) {
    CAPTURE(stem);
    REQUIRE(test::run_command("cd " + dir.string() + " && " + test::command("-q run " + (configs / (stem + ".yaml")).string()), &out) == 0);
    const auto edited = dir / "paper-out" / (stem + ".h5"), input = dir / "paper-out" / (stem + "-input.h5");
    CHECK(std::filesystem::exists(dir / "paper-out" / (stem + ".png")));
    CHECK(run("-q check-motion " + edited.string() + " --reference " + input.string(), &out) == 0);
    CHECK(read_crowd_file(edited).motion.agent_count() == 50);
  }
  // The split drives the two branches' last centroids apart: north-east and east-south-east of the input's end,
  // about 50 m apart (the input's lanes end gathered together).
  const CrowdMotion in = read_crowd_file(dir / "paper-out" / "editing-figure-12-branch-split-input.h5").motion;
  const CrowdMotion split = read_crowd_file(dir / "paper-out" / "editing-figure-12-branch-split.h5").motion;
  auto branches_apart = [](const CrowdMotion& c) {
    Eigen::Vector2d north(0, 0), south(0, 0);
    const std::size_t last = c.frame_count() - 1;
    for (std::size_t a = 0; a < c.agent_count(); ++a) (c.ids[a] % 2 ? north : south) += c.position(last, a).head<2>() / 25.0;
    return (north - south).norm();
  };
  CHECK(branches_apart(in) < 5.0);
  CHECK(branches_apart(split) > 40.0);
}
