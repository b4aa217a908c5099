// Working at scale, run as a user would: local edits (`throng edit --local-parts`, the job's `local:` block) and
// batches (`throng run` with several jobs or a folder; a broken job does not stop the others).
#include "../graph/synthetic_crowd.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

namespace fs = std::filesystem;

using test::run;

// Runs with stdout in *out and stderr in *err (run_command merges them otherwise).
int run_split(const fs::path& dir, const std::string& args, std::string* out, std::string* err) {
  const fs::path err_file = dir / "stderr.txt";
  const int status = test::run_command("(" + test::command(args) + " 2>" + err_file.string() + ")", out);
  std::ifstream in(err_file);
  err->assign(std::istreambuf_iterator<char>(in), {});
  return status;
}

// A wide, short crowd (8 × 16 agents, 11 frames, ids 100..227): METIS cuts it across the agents.
fs::path write_input(const fs::path& dir) {
  CrowdFile file;
  file.motion = test::marching_grid(8, 16, 11, 1.0, 1.2, 0.1, 0.3, 0.2);
  const auto path = dir / "in.h5";
  write_crowd_file(path, file);
  return path;
}

fs::path write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path;
}

const char* corner_drag = R"(
drags:
  - {frames: [0, 0]}
  - {frames: [end, end]}
  - {agents: [100, 101, 102], frames: [6, 6], offset: [0.8, 0.4]}
)";

double max_gap(const CrowdMotion& a, const CrowdMotion& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  double gap = 0;
  for (std::size_t k = 0; k < a.positions.size(); ++k) gap = std::max(gap, std::abs(a.positions[k] - b.positions[k]));
  return gap;
}

}  // namespace

TEST_CASE("a local edit solves part of the crowd, and with a full halo gives the global edit") {
  const auto dir = test::scratch_dir("cli_scale_local");
  const auto input = write_input(dir);
  // The guard off: the local edit is compared with the input and the global edit frame by frame.
  const auto job = write_text(dir / "job.yaml", std::string(corner_drag) + "guard: {enabled: false}\n");
  const std::string base = "--json --quiet edit " + input.string() + " --job " + job.string();
  std::string out;
  REQUIRE(run(base + " -o " + (dir / "global.h5").string(), &out) == 0);
  std::string err;  // halo 0 stops this drag within a sample or two of its frame: a jump warning on stderr
  REQUIRE(run_split(dir, base + " --local-parts 8 --halo 0 -o " + (dir / "local.h5").string(), &out, &err) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["parts"] == 8);
  CHECK(report["region_parts"].get<int>() >= 1);
  CHECK(report["region_parts"].get<int>() < 8);
  CHECK(report["region_vertices"].get<std::size_t>() < report["unknowns"].get<std::size_t>() / 2);
  REQUIRE(run(base + " --local-parts 8 --halo -1 -o " + (dir / "full.h5").string(), &out) == 0);
  CHECK(nlohmann::json::parse(out)["region_vertices"] == nlohmann::json::parse(out)["unknowns"].get<std::size_t>() / 2);

  const CrowdFile in = read_crowd_file(input), global = read_crowd_file(dir / "global.h5");
  const CrowdFile local = read_crowd_file(dir / "local.h5"), full = read_crowd_file(dir / "full.h5");
  CHECK(max_gap(full.motion, global.motion) < 1e-9);
  CHECK(max_gap(local.motion, in.motion) > 0.5);  // the drag happened
  // Some agents are bit-identical to the input at every frame in the local edit, none in the global one.
  std::size_t untouched = 0;
  for (std::size_t j = 0; j < in.motion.agent_count(); ++j) {
    bool same = true;
    for (std::size_t f = 0; f < in.motion.frame_count(); ++f) {
      same = same && std::memcmp(local.motion.position(f, j).data(), in.motion.position(f, j).data(), 3 * sizeof(double)) == 0;
    }
    untouched += same;
  }
  CHECK(untouched > in.motion.agent_count() / 2);
  // The job's local block does what the flags do, bit for bit.
  const auto job_local = write_text(dir / "job_local.yaml", std::string(corner_drag) + "guard: {enabled: false}\nlocal: {parts: 8, halo: 0}\n");
  REQUIRE(run("--quiet edit " + input.string() + " --job " + job_local.string() + " -o " + (dir / "local2.h5").string()) == 0);
  CHECK(read_crowd_file(dir / "local2.h5").motion.positions == local.motion.positions);
  // One and two threads give the same bits.
  REQUIRE(run("--quiet --threads 1 edit " + input.string() + " --job " + job_local.string() + " -o " + (dir / "t1.h5").string()) == 0);
  REQUIRE(run("--quiet --threads 2 edit " + input.string() + " --job " + job_local.string() + " -o " + (dir / "t2.h5").string()) == 0);
  CHECK(read_crowd_file(dir / "t1.h5").motion.positions == read_crowd_file(dir / "t2.h5").motion.positions);
  // --print-config shows the effective local block.
  REQUIRE(run("--print-config edit " + input.string() + " --job " + job.string() + " --local-parts 5 -o x.h5", &out) == 0);
  CHECK_THAT(out, Contains("local:") && Contains("parts: 5") && Contains("halo: 1"));
}

TEST_CASE("bad local options are config errors (exit 2) and leave no output") {
  const auto dir = test::scratch_dir("cli_scale_local_errors");
  const auto input = write_input(dir);
  const auto output = dir / "out.h5";
  std::string out;
  const auto bad = write_text(dir / "bad.yaml", std::string(corner_drag) + "local: {parts: -1}\n");
  CHECK(run("edit " + input.string() + " --job " + bad.string() + " -o " + output.string(), &out) == 2);
  CHECK_THAT(out, Contains("bad.yaml:6") && Contains("parts"));
  const auto halo = write_text(dir / "halo.yaml", std::string(corner_drag) + "local: {parts: 4, halo: -3}\n");
  CHECK(run("edit " + input.string() + " --job " + halo.string() + " -o " + output.string(), &out) == 2);
  CHECK_THAT(out, Contains("halo"));
  const auto job = write_text(dir / "job.yaml", corner_drag);
  CHECK(run("edit " + input.string() + " --job " + job.string() + " --local-parts 100000 -o " + output.string(), &out) == 2);
  CHECK_THAT(out, Contains("local.parts 100000"));
  CHECK_FALSE(fs::exists(output));
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
}

TEST_CASE("parts by size: --local-parts auto and local.vertices_per_part, bad values naming the key (exit 2)") {
  const auto dir = test::scratch_dir("cli_scale_parts_by_size");
  const auto input = write_input(dir);  // 128 agents × 11 frames = 1,408 vertices
  const auto job = write_text(dir / "job.yaml", corner_drag);
  const auto output = dir / "out.h5";
  const std::string base = "--json --quiet edit " + input.string() + " --job " + job.string();
  std::string out;
  REQUIRE(run(base + " --local-parts auto --set local.vertices_per_part=200 --halo 0 -o " + output.string(), &out) == 0);
  // partition_time_blocks: one block (11 samples, against 2∛200 ≈ 12 a block) of 128 × 11 / 200 ≈ 7 groups.
  CHECK(nlohmann::json::parse(out)["parts"] == 7);
  // The job's block does the same, and --print-config shows it.
  const auto job_auto = write_text(dir / "job_auto.yaml", std::string(corner_drag) + "local: {parts: auto, vertices_per_part: 200, halo: 0}\n");
  REQUIRE(run("--quiet edit " + input.string() + " --job " + job_auto.string() + " -o " + (dir / "auto.h5").string()) == 0);
  CHECK(read_crowd_file(dir / "auto.h5").motion.positions == read_crowd_file(output).motion.positions);
  REQUIRE(run("--print-config edit " + input.string() + " --job " + job_auto.string() + " -o x.h5", &out) == 0);
  CHECK_THAT(out, Contains("parts: auto") && Contains("vertices_per_part: 200"));
  // A given count wins over the size.
  REQUIRE(run(base + " --local-parts 4 --set local.vertices_per_part=200 -o " + output.string(), &out) == 0);
  CHECK(nlohmann::json::parse(out)["parts"] == 4);

  fs::remove(output);
  const auto zero = write_text(dir / "zero.yaml", std::string(corner_drag) + "local:\n  parts: auto\n  vertices_per_part: 0\n");
  CHECK(run("edit " + input.string() + " --job " + zero.string() + " -o " + output.string(), &out) == 2);
  CHECK_THAT(out, Contains("zero.yaml:8") && Contains("local.vertices_per_part") && Contains("out of range"));
  CHECK(run("edit " + input.string() + " --job " + job.string() + " --local-parts auto --set local.vertices_per_part=-4 -o " +
                output.string(),
            &out) == 2);
  CHECK_THAT(out, Contains("local.vertices_per_part"));
  const auto words = write_text(dir / "words.yaml", std::string(corner_drag) + "local: {parts: lots}\n");
  CHECK(run("edit " + input.string() + " --job " + words.string() + " -o " + output.string(), &out) == 2);
  CHECK_THAT(out, Contains("local.parts") && Contains("'lots'"));
  CHECK(run("edit " + input.string() + " --job " + job.string() + " --local-parts lots -o " + output.string(), &out) == 2);
  CHECK_THAT(out, Contains("--local-parts") && Contains("auto"));
  CHECK_FALSE(fs::exists(output));
  for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().find(".tmp") == std::string::npos);
}

TEST_CASE("a batch with a broken job finishes the others and reports the broken one") {
  const auto dir = test::scratch_dir("cli_scale_batch");
  const auto input = write_input(dir);
  const auto jobs = dir / "jobs";
  fs::create_directories(jobs);
  auto edit_job = [&](const std::string& name, const std::string& extra) {
    return write_text(jobs / (name + ".yaml"), "steps:\n  - step: edit\n    input: " + input.string() + "\n    output: " +
                                                   (dir / (name + ".h5")).string() +
                                                   "\n    drags:\n      - {frames: [0, 0]}\n"
                                                   "      - {frames: [end, end], offset: [1, 0]}\n" + extra);
  };
  edit_job("a", "");
  edit_job("b", "    sample_stpe: 2\n");  // a typo: the job fails with a config error
  edit_job("c", "    local: {parts: 4}\n");
  write_text(jobs / "notes.txt", "not a job");  // ignored: not *.yaml / *.yml

  std::string out, err;
  const int status = run_split(dir, "--json --quiet run " + jobs.string(), &out, &err);
  CHECK(status == 2);  // the broken job's exit code
  const auto summary = nlohmann::json::parse(out);
  CHECK(summary["jobs"] == 3);
  CHECK(summary["succeeded"] == 2);
  CHECK(summary["failed"] == 1);
  REQUIRE(summary["results"].size() == 3);
  CHECK(summary["results"][0]["status"] == "ok");
  CHECK(summary["results"][1]["status"] == "failed");
  CHECK(summary["results"][1]["exit_code"] == 2);
  CHECK_THAT(summary["results"][1]["job"].get<std::string>(), Contains("b.yaml"));
  CHECK_THAT(summary["results"][1]["error"].get<std::string>(), Contains("sample_stpe"));
  CHECK(summary["results"][2]["status"] == "ok");
  CHECK(summary["results"][2]["report"]["crowd_files_written"] == 1);
  CHECK_THAT(err, Contains("1 of 3 jobs failed") && Contains("b.yaml"));
  // The good jobs wrote complete files; the broken one wrote nothing.
  CHECK(read_crowd_file(dir / "a.h5").motion.agent_count() == 128);
  CHECK(read_crowd_file(dir / "c.h5").motion.agent_count() == 128);
  CHECK_FALSE(fs::exists(dir / "b.h5"));

  // Jobs named one by one run in the order given; all good: exit 0, a readable human summary.
  fs::remove(dir / "a.h5");
  REQUIRE(run("--quiet run " + (jobs / "c.yaml").string() + " " + (jobs / "a.yaml").string(), &out) == 0);
  CHECK_THAT(out, Contains("succeeded: 2") && Contains("failed: 0"));
  CHECK(fs::exists(dir / "a.h5"));
}

TEST_CASE("a batch naming a missing job or an empty folder fails before running anything") {
  const auto dir = test::scratch_dir("cli_scale_batch_errors");
  std::string out;
  const auto good = write_text(dir / "good.yaml", "steps:\n  - step: info\n    input: nowhere.h5\n");
  CHECK(run("run " + good.string() + " " + (dir / "missing.yaml").string(), &out) == 4);
  CHECK_THAT(out, Contains("missing.yaml does not exist"));
  fs::create_directories(dir / "empty");
  CHECK(run("run " + (dir / "empty").string(), &out) == 2);
  CHECK_THAT(out, Contains("holds no job file"));
  CHECK(run("--print-config run " + good.string() + " " + good.string(), &out) == 2);
}

TEST_CASE("a batch over 2 MPI ranks spreads the jobs round-robin, with either backend", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_scale_batch_mpi");
  const auto input = write_input(dir);
  std::string jobs;
  // Jobs 1 and 2 use the petsc backend: in a farm PETSc runs on each rank alone (on rank 1 too).
  for (int k = 0; k < 3; ++k) {
    const std::string solver = k == 0 ? "" : "    solver: {backend: petsc}\n";
    const auto job = write_text(dir / ("j" + std::to_string(k) + ".yaml"),
                                "steps:\n  - step: edit\n    input: " + input.string() + "\n    output: " +
                                    (dir / ("j" + std::to_string(k) + ".h5")).string() + "\n" + solver +
                                    "    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [1, 0]}\n");
    jobs += " " + job.string();
  }
  std::string out, err;
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec +
                              " -np 2 --oversubscribe " + test::throng_program().string() + " --json --quiet run" + jobs;
  const int status = test::run_command("(" + command + " 2>" + (dir / "stderr.txt").string() + ")", &out);
  INFO(command << "\n" << out);
  REQUIRE(status == 0);
  const auto summary = nlohmann::json::parse(out);  // printed once, by rank 0
  CHECK(summary["ranks"] == 2);
  CHECK(summary["succeeded"] == 3);
  for (int k = 0; k < 3; ++k) {
    CHECK(summary["results"][k]["rank"] == k % 2);
    CHECK(fs::exists(dir / ("j" + std::to_string(k) + ".h5")));
  }
  // The same edit with either backend: CG stops at a relative residual of 1e-12 on a well-posed edit system,
  // measured ~1e-11 m apart (as in the MPI edit test); 1e-8 m.
  const CrowdFile eigen = read_crowd_file(dir / "j0.h5"), petsc = read_crowd_file(dir / "j1.h5");
  CHECK(max_gap(eigen.motion, petsc.motion) < 1e-8);
}

TEST_CASE("a batch keeps stdout for its summary, refuses two jobs writing one file, and reports runtime failures") {
  const auto dir = test::scratch_dir("cli_scale_batch_details");
  const auto input = write_input(dir);
  std::string out, err;
  // An info step prints a report: in a batch it goes to stderr, stdout holds one JSON document.
  const auto info = write_text(dir / "info.yaml", "steps:\n  - step: info\n    input: " + input.string() + "\n");
  const auto edit = [&](const std::string& name, const std::string& output, const std::string& extra) {
    return write_text(dir / (name + ".yaml"), "steps:\n  - step: edit\n    input: " + input.string() + "\n    output: " +
                                                  output + "\n    drags:\n      - {frames: [0, 0]}\n"
                                                  "      - {frames: [end, end], offset: [1, 0]}\n" + extra);
  };
  const auto a = edit("a", (dir / "a.h5").string(), "");
  REQUIRE(run_split(dir, "--json --quiet run " + info.string() + " " + a.string(), &out, &err) == 0);
  const auto summary = nlohmann::json::parse(out);  // throws if stdout holds two documents
  CHECK(summary["succeeded"] == 2);
  CHECK_THAT(err, Contains("\"agents\": 128"));

  // Two jobs writing the same file (spelled differently): refused before anything runs.
  fs::remove(dir / "a.h5");
  const auto twin = edit("twin", (dir / "." / "a.h5").string(), "");
  CHECK(run_split(dir, "--quiet run " + a.string() + " " + twin.string(), &out, &err) == 2);
  CHECK_THAT(err, Contains("a.yaml") && Contains("twin.yaml") && Contains("both write"));
  CHECK_FALSE(fs::exists(dir / "a.h5"));

  // A solve that does not converge (exit 5) in the middle of a batch: the others finish, the exit code is 5.
  const auto stuck = edit("stuck", (dir / "stuck.h5").string(), "    solver: {backend: petsc, max_iterations: 1}\n");
  const auto c = edit("c", (dir / "c.h5").string(), "");
  CHECK(run_split(dir, "--json --quiet run " + a.string() + " " + stuck.string() + " " + c.string(), &out, &err) == 5);
  const auto failed = nlohmann::json::parse(out);
  CHECK(failed["failed"] == 1);
  CHECK(failed["results"][1]["exit_code"] == 5);
  CHECK_THAT(failed["results"][1]["error"].get<std::string>(), Contains("step 1/1 edit") && Contains("did not converge"));
  CHECK(fs::exists(dir / "a.h5"));
  CHECK(fs::exists(dir / "c.h5"));
  CHECK_FALSE(fs::exists(dir / "stuck.h5"));
}

TEST_CASE("a batch over 2 MPI ranks with a job failing on rank 1 reports it once, from rank 0", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_scale_batch_mpi_failure");
  const auto input = write_input(dir);
  std::string jobs;
  for (int k = 0; k < 3; ++k) {
    // Job 1 (rank 1) cannot converge in one iteration: exit 5.
    const std::string solver = k == 1 ? "    solver: {backend: petsc, max_iterations: 1}\n" : "";
    const auto job = write_text(dir / ("j" + std::to_string(k) + ".yaml"),
                                "steps:\n  - step: edit\n    input: " + input.string() + "\n    output: " +
                                    (dir / ("j" + std::to_string(k) + ".h5")).string() + "\n" + solver +
                                    "    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [1, 0]}\n");
    jobs += " " + job.string();
  }
  std::string out;
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec +
                              " -np 2 --oversubscribe " + test::throng_program().string() + " --json --quiet run" + jobs;
  const int status = test::run_command("(" + command + " 2>" + (dir / "stderr.txt").string() + ")", &out);
  std::ifstream in(dir / "stderr.txt");
  const std::string err((std::istreambuf_iterator<char>(in)), {});
  INFO(command << "\n" << out << "\n" << err);
  CHECK(status == 5);
  const auto summary = nlohmann::json::parse(out);
  CHECK(summary["failed"] == 1);
  CHECK(summary["results"][1]["rank"] == 1);
  CHECK(summary["results"][1]["exit_code"] == 5);
  const auto first = err.find("1 of 3 jobs failed");
  CHECK(first != std::string::npos);
  CHECK(err.find("1 of 3 jobs failed", first + 1) == std::string::npos);
  CHECK(fs::exists(dir / "j0.h5"));
  CHECK(fs::exists(dir / "j2.h5"));
  CHECK_FALSE(fs::exists(dir / "j1.h5"));
}

TEST_CASE("one pipeline under mpiexec -np 2 prints its report and writes its file once", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_scale_pipeline_mpi");
  const auto input = write_input(dir);
  const auto job = write_text(dir / "job.yaml", "steps:\n  - step: edit\n    input: " + input.string() + "\n    output: " +
                                                    (dir / "out.h5").string() + "\n    solver: {backend: petsc}\n" +
                                                    "    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [1, 0]}\n");
  std::string out;
  const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec +
                              " -np 2 --oversubscribe " + test::throng_program().string() + " --json --quiet run " + job.string();
  REQUIRE(test::run_command("(" + command + " 2>/dev/null)", &out) == 0);
  INFO(out);
  const auto report = nlohmann::json::parse(out);  // one document: rank 1 printed nothing
  CHECK(report["crowd_files_written"] == 1);
  CHECK(read_crowd_file(dir / "out.h5").motion.agent_count() == 128);
}

TEST_CASE("one pipeline under mpiexec -np 2 draws its plot once, from rank 0, and a failing plot stops both ranks", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_scale_pipeline_plot_mpi");
  const auto input = write_input(dir);
  const auto picture = dir / "edited.svg";
  auto job = [&](const std::string& plot_keys) {
    return write_text(dir / "job.yaml", "steps:\n  - step: edit\n    input: " + input.string() +
                                            "\n    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [1, 0]}\n"
                                            "  - step: plot\n    output: " + picture.string() + "\n" + plot_keys);
  };
  // Without --quiet every rank logs to stderr: the plot step's "wrote" line shows which ranks drew.
  const std::string launch = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 timeout 300 " + mpiexec +
                             " -np 2 --oversubscribe " + test::throng_program().string() + " --json run ";
  std::string out, err;
  const int status = test::run_command("(" + launch + job("").string() + " 2>" + (dir / "err.txt").string() + ")", &out);
  {
    std::ifstream in(dir / "err.txt");
    err.assign(std::istreambuf_iterator<char>(in), {});
  }
  INFO(out << err);
  REQUIRE(status == 0);
  const std::string wrote = "wrote " + picture.string();
  const auto first = err.find(wrote);
  CHECK(first != std::string::npos);
  CHECK(err.find(wrote, first + 1) == std::string::npos);  // once: rank 1 did not draw
  CHECK(fs::exists(picture));
  fs::remove(picture);
  // An unknown plot key: rank 0's ConfigError reaches rank 1, both leave with exit 2 (no hang, no picture).
  const int failed = test::run_command("(" + launch + job("    colour: red\n").string() + " 2>" + (dir / "err.txt").string() + ")", &out);
  {
    std::ifstream in(dir / "err.txt");
    err.assign(std::istreambuf_iterator<char>(in), {});
  }
  INFO(out << err);
  CHECK(failed == 2);
  CHECK_THAT(err, Contains("colour"));
  CHECK_FALSE(fs::exists(picture));
}
