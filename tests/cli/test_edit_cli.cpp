// `throng edit` run as a user would: the report, the output file, the example configs, and every documented error
// with its exit code and no output left behind.
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

TEST_CASE("edit writes the edited crowd and reports it") {
  const auto dir = test::scratch_dir("cli_edit");
  const auto input = write_input(dir);
  // The paper's edit (the guard off): the request holds on the input's frames.
  const auto job = write_job(dir, "job.yaml", std::string(drag_job) + "guard: {enabled: false}\n");
  const auto output = dir / "out.h5";
  std::string out;
  REQUIRE(run("--json --quiet edit " + input.string() + " --job " + job.string() + " -o " + output.string(), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["agents"] == 20);
  CHECK(report["frames"] == 41);
  CHECK(report["guard_warped"] == false);
  CHECK(report["residual_after_guard"] == true);
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

TEST_CASE("edit puts the edited clip back into the whole crowd: same agents, ids and frames") {
  // 41 frames of 20 agents; agent 119 leaves after frame 30; the clip is frames 10..35, so 119 is not edited
  // and frames 0..9 and 36..40 lie outside. The input has velocities and formation edges.
  const auto dir = test::scratch_dir("cli_edit_whole");
  CrowdFile file;
  file.motion = test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.3, 0.2);
  file.motion.velocities.assign(file.motion.positions.size(), 0.5);
  for (std::size_t f = 31; f < 41; ++f) file.motion.position(f, 19).setConstant(absent);
  file.formation_edges = {{0, 1}, {3, 19}, {7, 12}};
  write_crowd_file(dir / "in.h5", file);
  const auto job = write_job(dir, "job.yaml", R"(
clip: {first_frame: 10, last_frame: 35, sample_step: 3}
guard: {enabled: false}   # the paper's edit: the output's frames are the input's
drags:
  - {frames: [10, 12]}
  - {frames: [-3, end], offset: [2, 1]}
)");
  std::string out, err;
  // Warnings go to stderr, the report to stdout: keep them apart.
  REQUIRE(test::run_command("(" + test::command("-q --json edit " + (dir / "in.h5").string() + " --job " + job.string() + " -o " +
                                             (dir / "out.h5").string()) +
                                " 2>" + (dir / "err.txt").string() + ")",
                            &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["agents"] == 20);
  CHECK(report["frames"] == 41);
  CHECK(report["clip_agents"] == 19);
  CHECK(report["left_out"] == 1);
  // The tail drag reaches the clip's last frame (35), which joins unedited frame 36: a seam of the offset.
  CHECK_THAT(report["seam_jump_m"].get<double>(), Catch::Matchers::WithinAbs(std::sqrt(5.0), 1e-9));
  std::ifstream err_file(dir / "err.txt");
  const std::string warnings((std::istreambuf_iterator<char>(err_file)), {});
  CHECK_THAT(warnings, Contains("not edited (119)") && Contains("jumps there"));

  const CrowdFile in = read_crowd_file(dir / "in.h5"), edited = read_crowd_file(dir / "out.h5");
  REQUIRE(edited.motion.ids == in.motion.ids);
  REQUIRE(edited.motion.times == in.motion.times);
  CHECK(edited.formation_edges == in.formation_edges);
  REQUIRE(edited.motion.velocities.size() == in.motion.velocities.size());
  auto same_position = [&](std::size_t f, std::size_t a) {
    return in.motion.present(f, a) ? edited.motion.position(f, a) == in.motion.position(f, a) : !edited.motion.present(f, a);
  };
  auto same_velocity = [&](std::size_t f, std::size_t a) {
    const std::size_t k = in.motion.index(f, a);
    return std::equal(in.motion.velocities.begin() + static_cast<long>(k), in.motion.velocities.begin() + static_cast<long>(k + 3),
                      edited.motion.velocities.begin() + static_cast<long>(k));
  };
  bool outside_kept = true, left_out_kept = true;
  for (std::size_t f = 0; f < 41; ++f) {
    for (std::size_t a = 0; a < 20; ++a) {
      const bool in_clip = f >= 10 && f <= 35 && a != 19;
      if (!in_clip) outside_kept = outside_kept && same_position(f, a) && same_velocity(f, a);
      if (a == 19) left_out_kept = left_out_kept && same_position(f, a);
    }
  }
  CHECK(outside_kept);
  CHECK(left_out_kept);
  // Inside the clip: the drags hold on every frame, and the velocities describe the new motion.
  for (std::size_t a = 0; a < 19; ++a) {
    CHECK(edited.motion.position(11, a) == in.motion.position(11, a));
    CHECK((edited.motion.position(34, a) - in.motion.position(34, a) - Eigen::Vector3d(2, 1, 0)).norm() < 1e-9);
  }
  const double dt = in.motion.times[21] - in.motion.times[19];
  const Eigen::Vector3d central = (edited.motion.position(21, 4) - edited.motion.position(19, 4)) / dt;
  CHECK((Eigen::Map<const Eigen::Vector3d>(edited.motion.velocities.data() + edited.motion.index(20, 4)) - central).norm() < 1e-12);

  // --clip-only writes the clip: its frames, its agents, their formation edges renumbered.
  REQUIRE(run("-q --json edit " + (dir / "in.h5").string() + " --job " + job.string() + " -o " + (dir / "clip.h5").string() +
                  " --clip-only",
              &out) == 0);
  const CrowdFile clip = read_crowd_file(dir / "clip.h5");
  CHECK(clip.motion.frame_count() == 26);
  CHECK(clip.motion.agent_count() == 19);
  CHECK(clip.motion.times.front() == in.motion.times[10]);
  CHECK(clip.formation_edges == std::vector<std::array<std::int32_t, 2>>{{0, 1}, {7, 12}});
  CHECK(clip.motion.velocities.size() == clip.motion.positions.size());
  for (std::size_t f = 0; f < 26; ++f) {
    for (std::size_t a = 0; a < 19; ++a) CHECK(clip.motion.position(f, a) == edited.motion.position(10 + f, a));
  }
}

TEST_CASE("edit's guard slows a drag that is too fast and reports it") {
  // drag_job moves the tail 3.6 m in 4 s on top of a 1.2 m/s march: too fast for 1.25 × the input's fastest.
  const auto dir = test::scratch_dir("cli_edit_guard");
  const auto input = write_input(dir);
  const auto job = write_job(dir, "job.yaml", drag_job);
  std::string out;
  REQUIRE(run("--json --quiet edit " + input.string() + " --job " + job.string() + " -o " + (dir / "out.h5").string(), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  const CrowdFile in = read_crowd_file(input), edited = read_crowd_file(dir / "out.h5");
  CHECK(report["guard_warped"] == true);
  CHECK(report["guard_largest_stretch"].get<double>() > 1);
  CHECK(report["residual_after_guard"] == false);
  CHECK(report["frames"] == edited.motion.frame_count());
  CHECK(edited.motion.frame_count() > in.motion.frame_count());
  CHECK(edited.motion.ids == in.motion.ids);
  double input_fastest = 0, fastest = 0;
  for (const auto* m : {&in.motion, &edited.motion}) {
    double& top = m == &in.motion ? input_fastest : fastest;
    for (std::size_t f = 0; f + 1 < m->frame_count(); ++f)
      for (std::size_t a = 0; a < m->agent_count(); ++a)
        top = std::max(top, (m->position(f + 1, a) - m->position(f, a)).head<2>().norm() / (m->times[f + 1] - m->times[f]));
  }
  CHECK(fastest <= 1.25 * input_fastest * (1 + 1e-9));
  CHECK_THAT(report["guard_max_speed_m_s"].get<double>(), Catch::Matchers::WithinRel(fastest, 1e-9));
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
      {"drags:\n  - {frames: [0, 0]}\n  - {frames: [40, 40]}\nweights: {alpha: 0, beta: 0}\n", 5,
       "weights.alpha and weights.beta are 0"},
      {"drags:\n  - {frames: [0, 0]}\n  - {frames: [40, 40]}\nweights: {alpha_prime: 0, beta_prime: 0}\n", 5,
       "step 2 (scale compensation) is singular: weights.alpha_prime and weights.beta_prime are 0"},
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
  // The tail was moved 45 m east: the group's last centroid moved by about that much. Each crowd's own last frame:
  // the plausibility guard slows the dragged walk, so the edit has more frames than its input (2953 of 2907 on 6 December 2026).
  const CrowdFile before = read_crowd_file(dir / "paper.h5"), after = read_crowd_file(dir / "battlefield.h5");
  REQUIRE(after.motion.frame_count() >= before.motion.frame_count());
  Eigen::Vector2d shift(0, 0);
  const std::size_t last_after = after.motion.frame_count() - 1, last_before = before.motion.frame_count() - 1;
  for (std::size_t a = 0; a < 50; ++a) {
    shift += (after.motion.position(last_after, a) - before.motion.position(last_before, a)).head<2>() / 50.0;
  }
  CHECK(shift.x() > 30);
  REQUIRE(run("-q plot " + (dir / "battlefield.h5").string() + " --overlay " + (dir / "paper.h5").string() + " -o " +
                  (dir / "battlefield.svg").string(),
              &out) == 0);
  CHECK(std::filesystem::file_size(dir / "battlefield.svg") > 10000);

  // The pipeline, run from a folder where configs/ is the project's.
  std::filesystem::create_directory_symlink(configs, dir / "configs");
  REQUIRE(test::run_command("cd " + dir.string() + " && " + test::command("-q run configs/run-battlefield.yaml"), &out) == 0);
  CHECK(std::filesystem::exists(dir / "battlefield.png"));
}

TEST_CASE("a local edit reports the step across its region's edge and warns when it jumps") {
  const auto dir = test::scratch_dir("cli_edit_local_edge");
  const auto input = write_input(dir);
  // Everyone held at both ends; agents 100 and 101 dragged 3 m at frame 20 (about 15 of their steps).
  const auto job = write_job(dir, "job.yaml",
                             "drags:\n  - {frames: [0, 0]}\n  - {frames: [end, end]}\n"
                             "  - {agents: [100, 101], frames: [20, 20], offset: [3, 0]}\n");
  // Runs with the report (stdout) and the messages (stderr) apart.
  auto edit = [&](const std::string& flags, nlohmann::json& report, std::string& messages) {
    const auto err = dir / "stderr.txt";
    std::string out;
    const int code = test::run_command("(" + test::command("--json edit " + input.string() + " --job " + job.string() + " " + flags +
                                                         " -o " + (dir / "out.h5").string()) +
                                           " 2>" + err.string() + ")",
                                       &out);
    std::ifstream in(err);
    messages.assign(std::istreambuf_iterator<char>(in), {});
    INFO(out << messages);
    REQUIRE(code == 0);
    report = nlohmann::json::parse(out);
  };
  nlohmann::json report;
  std::string messages;
  // Halo 0: the drag's parts end a few frames from frame 20, so the held agents take the 3 m in a few steps.
  edit("--local-parts 8 --halo 0", report, messages);
  CHECK(report["region_edge_jump"] == true);
  CHECK(report["region_edge_step_m"].get<double>() > report["region_edge_reference_m"].get<double>());
  CHECK(report["region_edge_reference_m"].get<double>() > 0);
  CHECK_THAT(messages, Contains("the local region's edge jumps") && Contains("widen local.halo"));
  // A region covering the graph has no edge: nothing added, no warning.
  edit("--local-parts 8 --halo -1", report, messages);
  CHECK(report["region_edge_step_m"] == 0.0);
  CHECK(report["region_edge_jump"] == false);
  CHECK_THAT(messages, !Contains("edge jumps"));
  // A global edit has no region.
  edit("", report, messages);
  CHECK_FALSE(report.contains("region_edge_step_m"));
  CHECK_THAT(messages, !Contains("edge jumps"));
}
