// Interrupted runs, as a farm sees them: `throng run` killed (SIGKILL) or stopped (SIGTERM) part-way and run again
// with --resume ends with the same bits as a run never interrupted, without running the finished steps or jobs
// again (drivers/checkpoint.h).
#include "../graph/synthetic_crowd.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

namespace fs = std::filesystem;

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

// Inputs in `dir`: a small crowd and a large one whose edit takes long enough (about a second) for a signal to
// land inside it.
void write_inputs(const fs::path& dir) {
  CrowdFile small, large;
  small.motion = test::marching_grid(4, 8, 11, 1.0, 1.2, 0.1, 0.3, 0.2);
  large.motion = test::marching_grid(12, 25, 80, 1.0, 1.2, 0.1, 0.1, 0.2);
  write_crowd_file(dir / "small.h5", small);
  write_crowd_file(dir / "large.h5", large);
}

const char* drags = "    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [1, 0]}\n";

// A pipeline of four steps whose outputs resolve against the working folder (so one job runs in two folders and
// writes the same bits in both). Step 1 makes a named crowd, written nowhere, that step 4 reads (the checkpoint
// keeps a copy); step 2 is a long one whose crowd step 3 reads as the last crowd made (the checkpoint names the file
// step 2 wrote).
fs::path write_pipeline(const fs::path& dir) {
  const fs::path job = dir / "pipeline.yaml";
  std::ofstream(job) << "steps:\n"
                        "  - step: edit\n    input: small.h5\n    name: small\n" << drags
                     << "  - step: edit\n    input: large.h5\n    output: b.h5\n" << drags
                     << "  - step: edit\n    output: c.h5\n"
                        "    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [0, 1]}\n"
                        "  - step: plot\n    input: small\n    output: d.svg\n";
  return job;
}

// Runs `throng <args>` in `folder` in the background; once `ready` (an extended regular expression) matches a
// checkpoint state (or the run ended), or after `delay` seconds when `ready` is empty, sends `signal`. Returns the
// exit status; stdout and stderr go to out.txt and err.txt in `folder`.
int run_and_stop(const fs::path& folder, const std::string& args, const std::string& ready, double delay, const std::string& signal) {
  const std::string wait_for =
      ready.empty() ? "sleep " + std::to_string(delay)
                    : "for i in $(seq 1 6000); do grep -Eqs '" + ready + "' .throng-resume/*/state.json && break; "
                      "kill -0 $pid 2>/dev/null || break; sleep 0.01; done";
  const std::string script = "cd " + folder.string() + " && { " + test::command(args) + " >out.txt 2>err.txt & pid=$!; " +
                             wait_for + "; kill -" + signal + " $pid 2>/dev/null; wait $pid; echo $? >status.txt; }";
  REQUIRE(test::run_command(script) == 0);
  return std::stoi(read_bytes(folder / "status.txt"));
}

int run_in(const fs::path& folder, const std::string& args) {
  return test::run_command("(cd " + folder.string() + " && " + test::command(args) + " >out.txt 2>err.txt)");
}

void check_same_files(const fs::path& a, const fs::path& b, const std::vector<std::string>& names) {
  for (const auto& name : names) {
    INFO(name);
    REQUIRE(fs::exists(b / name));
    CHECK(read_bytes(a / name) == read_bytes(b / name));
  }
}

// The pipeline's outputs (write_pipeline).
const std::vector<std::string> pipeline_outputs{"b.h5", "c.h5", "d.svg"};

// The inputs and the pipeline written in `dir`, and the pipeline run once, uninterrupted, in dir/reference: the
// bits every interrupted run must end with. Returns the job.
fs::path pipeline_with_reference(const fs::path& dir) {
  write_inputs(dir);
  const auto job = write_pipeline(dir);
  fs::create_directories(dir / "reference");
  REQUIRE(run_in(dir / "reference", "run " + job.string()) == 0);
  return job;
}

}  // namespace

TEST_CASE("a pipeline killed during a step and resumed writes the same bits without running the finished steps again") {
  const auto dir = test::scratch_dir("cli_resume_pipeline");
  const auto job = pipeline_with_reference(dir);
  CHECK_FALSE(fs::exists(dir / "reference" / ".throng-resume"));  // a finished run leaves no checkpoint

  // Killed (SIGKILL: nothing of the program runs) while step 2 is under way: step 1 is done and checkpointed.
  const auto killed = dir / "killed";
  fs::create_directories(killed);
  REQUIRE(run_and_stop(killed, "run " + job.string(), "\"running\": 2", 0, "KILL") == 137);
  CHECK_FALSE(fs::exists(killed / "b.h5"));
  REQUIRE(run_in(killed, "run --resume " + job.string()) == 0);
  const std::string log = read_bytes(killed / "err.txt");
  INFO(log);
  CHECK_THAT(log, Contains("stopped during step 2/4 on rank 0") && Contains("resuming after step 1/4"));
  CHECK_FALSE(log.find("step 1/4 edit") != std::string::npos);  // step 1 was not run again
  CHECK_THAT(log, Contains("step 2/4 edit: wrote b.h5"));
  check_same_files(dir / "reference", killed, pipeline_outputs);
  CHECK_FALSE(fs::exists(killed / ".throng-resume"));

  // Killed at other points (before the first checkpoint, as step 1, 3 or 4 starts): the resumed run always ends with
  // the reference's bits.
  const std::vector<std::string> points{"", "\"running\": 1", "\"running\": 3", "\"running\": 4"};
  for (std::size_t p = 0; p < points.size(); ++p) {
    const auto folder = dir / ("killed-at-" + std::to_string(p));
    fs::create_directories(folder);
    const int status = run_and_stop(folder, "run " + job.string(), points[p], 0.02, "KILL");
    CHECK((status == 137 || status == 0));
    REQUIRE(run_in(folder, "run --resume " + job.string()) == 0);
    INFO("killed at " << (points[p].empty() ? "0.02 s" : points[p]) << ": " << read_bytes(folder / "err.txt"));
    check_same_files(dir / "reference", folder, pipeline_outputs);
  }
}

TEST_CASE("a run killed while it removes its finished checkpoint resumes to an end with the same bits") {
  // Killed (kill_at_unlink.c, preloaded) as the last step is done and its checkpoint goes: at the removal of its
  // state, the first thing removed, the whole checkpoint is left and the resumed run has nothing to do; at the
  // removal of step 1's crowd copy the state is already gone and the resumed run starts over. A state left naming
  // a removed copy (the order of a folder's entries is the file system's) made the resumed run fail to read it.
  const auto dir = test::scratch_dir("cli_resume_removal");
  const auto job = pipeline_with_reference(dir);
  for (const std::string removed : {"state.json", "step-1.h5"}) {
    INFO("killed at the removal of " << removed);
    const auto folder = dir / ("killed-removing-" + removed);
    fs::create_directories(folder);
    // (ASan as a shared library, GCC's, wants to come first among the libraries loaded: the preloaded one does.)
    const std::string killer = std::string("THRONG_TEST_KILL_AT_UNLINK=") + removed + " LD_PRELOAD=" + THRONG_KILL_AT_UNLINK_LIBRARY +
                               " ASAN_OPTIONS=verify_asan_link_order=0 ";
    REQUIRE(test::run_command("cd " + folder.string() + " && " + killer + test::command("run " + job.string()) +
                              " >out.txt 2>err.txt; test $? -eq 137") == 0);
    REQUIRE(fs::is_directory(folder / ".throng-resume"));
    const fs::path checkpoint = fs::directory_iterator(folder / ".throng-resume")->path();  // the job's one folder
    REQUIRE(fs::exists(checkpoint / "step-1.h5"));
    CHECK(fs::exists(checkpoint / "state.json") == (removed == "state.json"));
    check_same_files(dir / "reference", folder, pipeline_outputs);

    REQUIRE(run_in(folder, "run --resume " + job.string()) == 0);
    const std::string log = read_bytes(folder / "err.txt");
    INFO(log);
    if (removed == "state.json") {
      CHECK_THAT(log, Contains("every step was done in the run being resumed"));
      CHECK(log.find("step 1/4 edit") == std::string::npos);  // nothing ran again
    } else {
      CHECK_THAT(log, Contains("no checkpoint") && Contains("starting from the first step"));
    }
    check_same_files(dir / "reference", folder, pipeline_outputs);
    CHECK_FALSE(fs::exists(folder / ".throng-resume"));
  }
}

TEST_CASE("a second run of a job under way leaves the first's checkpoint alone and resuming it meanwhile is refused") {
  const auto dir = test::scratch_dir("cli_resume_concurrent");
  const auto job = pipeline_with_reference(dir);

  // The first run is stopped (SIGSTOP: it holds its checkpoint's lock) during step 2; a second run of the job in the
  // same folder runs without a checkpoint, and a --resume meanwhile is refused (exit 2); then the first is killed.
  const auto work = dir / "work";
  fs::create_directories(work);
  const std::string script =
      "cd " + work.string() + " && { " + test::command("run " + job.string()) + " >a-out.txt 2>a-err.txt & pid=$!; "
      "for i in $(seq 1 6000); do grep -qs '\"running\": 2' .throng-resume/*/state.json && break; sleep 0.01; done; "
      "kill -STOP $pid; cp .throng-resume/*/state.json held.json; " +
      test::command("run " + job.string()) + " >b-out.txt 2>b-err.txt; echo $? >b-status.txt; " +
      test::command("run --resume " + job.string()) + " >c-out.txt 2>c-err.txt; echo $? >c-status.txt; "
      "cp .throng-resume/*/state.json after.json; kill -KILL $pid; wait $pid; echo $? >a-status.txt; }";
  REQUIRE(test::run_command(script) == 0);
  CHECK(read_bytes(work / "a-status.txt") == "137\n");
  CHECK(read_bytes(work / "b-status.txt") == "0\n");
  CHECK_THAT(read_bytes(work / "b-err.txt"), Contains("another run of this job is under way") && Contains("not checkpointed"));
  CHECK(read_bytes(work / "c-status.txt") == "2\n");
  CHECK_THAT(read_bytes(work / "c-err.txt"), Contains("another run of") && Contains("is under way"));
  CHECK(read_bytes(work / "after.json") == read_bytes(work / "held.json"));  // neither touched the first's checkpoint

  // Killed, the first run resumes from its own checkpoint.
  REQUIRE(run_in(work, "run --resume " + job.string()) == 0);
  INFO(read_bytes(work / "err.txt"));
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("resuming after step 1/4"));
  check_same_files(dir / "reference", work, pipeline_outputs);
  CHECK_FALSE(fs::exists(work / ".throng-resume"));
}

TEST_CASE("a crowd file a later step writes again is copied into the checkpoint and one changed since is refused") {
  const auto dir = test::scratch_dir("cli_resume_rewritten");
  write_inputs(dir);
  // Step 1's crowd, read by step 3 as `a`, is written to x.h5, which step 2 overwrites with its own crowd.
  const fs::path job = dir / "rewrite.yaml";
  std::ofstream(job) << "steps:\n"
                        "  - step: edit\n    input: large.h5\n    name: a\n    output: x.h5\n" << drags
                     << "  - step: edit\n    output: x.h5\n"
                        "    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [0, 2]}\n"
                        "  - step: edit\n    input: a\n    output: y.h5\n"
                        "    drags:\n      - {frames: [0, 0]}\n      - {frames: [end, end], offset: [-1, 0]}\n";
  fs::create_directories(dir / "reference");
  REQUIRE(run_in(dir / "reference", "run " + job.string()) == 0);
  const auto work = dir / "work";
  fs::create_directories(work);
  REQUIRE(run_and_stop(work, "run " + job.string(), "\"running\": 3", 0, "KILL") == 137);
  REQUIRE(run_in(work, "run --resume " + job.string()) == 0);
  INFO(read_bytes(work / "err.txt"));
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("resuming after step 2/3"));
  check_same_files(dir / "reference", work, {"x.h5", "y.h5"});

  // A crowd file the checkpoint names (b.h5, step 2's output, read by step 3) changed after the run wrote it: resuming
  // is refused (exit 2) naming it, and nothing is written.
  const auto pipeline = write_pipeline(dir);
  const auto changed = dir / "changed";
  fs::create_directories(changed);
  REQUIRE(run_and_stop(changed, "run " + pipeline.string(), "\"running\": 3", 0, "KILL") == 137);
  REQUIRE(fs::exists(changed / "b.h5"));
  fs::copy_file(dir / "reference" / "x.h5", changed / "b.h5", fs::copy_options::overwrite_existing);
  CHECK(run_in(changed, "run --resume " + pipeline.string()) == 2);
  CHECK_THAT(read_bytes(changed / "err.txt"), Contains("b.h5") && Contains("changed after the run being resumed wrote it"));
  CHECK_FALSE(fs::exists(changed / "c.h5"));
}

TEST_CASE("resuming checks the checkpoint: another job is refused and a damaged one named while none starts over") {
  const auto dir = test::scratch_dir("cli_resume_checks");
  write_inputs(dir);
  const auto job = write_pipeline(dir);
  const auto work = dir / "work";
  fs::create_directories(work);
  REQUIRE(run_and_stop(work, "run " + job.string(), "\"running\": 2", 0, "KILL") == 137);

  // The job changed since: resuming would mix two jobs (exit 2, the checkpoint and the way out named).
  const std::string original = read_bytes(job);
  std::ofstream(job, std::ios::app) << "  - step: info\n";
  CHECK(run_in(work, "run --resume " + job.string()) == 2);
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("was made by another version of") && Contains("run without --resume"));
  std::ofstream(job) << original;
  // So does another seed.
  CHECK(run_in(work, "--seed 7 run --resume " + job.string()) == 2);

  // A damaged checkpoint: exit 3 naming the file; nothing else is touched.
  fs::path state;
  for (const auto& e : fs::directory_iterator(work / ".throng-resume")) state = e.path() / "state.json";
  const std::string good_state = read_bytes(state);
  std::ofstream(state) << "{\"format\": 1, \"fingerprint\": ";
  CHECK(run_in(work, "run --resume " + job.string()) == 3);
  CHECK_THAT(read_bytes(work / "err.txt"), Contains(state.string()) && Contains("damaged checkpoint"));
  CHECK_FALSE(fs::exists(work / "b.h5"));
  std::ofstream(state) << good_state;
  fs::remove(state.parent_path() / "step-1.h5");
  CHECK(run_in(work, "run --resume " + job.string()) == 4);  // the crowd it keeps is missing: an I/O error naming it
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("step 1's crowd") && Contains("step-1.h5"));

  // Without a checkpoint --resume starts from the first step and says so; without --resume a run starts over.
  const auto fresh = dir / "fresh";
  fs::create_directories(fresh);
  REQUIRE(run_in(fresh, "run --resume " + job.string()) == 0);
  CHECK_THAT(read_bytes(fresh / "err.txt"), Contains("no checkpoint") && Contains("starting from the first step"));
  REQUIRE(run_in(work, "run " + job.string()) == 0);
  CHECK_FALSE(fs::exists(work / ".throng-resume"));

  // A checkpoint folder that cannot be written (/proc, even for root) never fails the run: one warning.
  const auto unwritable = dir / "unwritable";
  fs::create_directories(unwritable);
  REQUIRE(run_in(unwritable, "run --checkpoint-dir /proc/throng-checkpoints " + job.string()) == 0);
  CHECK_THAT(read_bytes(unwritable / "err.txt"), Contains("/proc/throng-checkpoints") && Contains("cannot be resumed if it is interrupted"));
  CHECK(read_bytes(unwritable / "c.h5") == read_bytes(fresh / "c.h5"));

  // --checkpoint-dir puts them elsewhere; neither flag is recorded in the outputs (a resumed run writes the bits of
  // an uninterrupted one).
  const auto elsewhere = dir / "elsewhere";
  fs::create_directories(elsewhere);
  const std::string ckpt = (dir / "ckpt").string();
  REQUIRE(test::run_command("cd " + elsewhere.string() + " && { " + test::command("run --checkpoint-dir " + ckpt + " " + job.string()) +
                            " >out.txt 2>err.txt & pid=$!; for i in $(seq 1 6000); do grep -qs '\"running\": 2' " + ckpt +
                            "/*/state.json && break; sleep 0.01; done; kill -KILL $pid; wait $pid; }") == 137);
  CHECK_FALSE(fs::exists(elsewhere / ".throng-resume"));
  REQUIRE(run_in(elsewhere, "run --checkpoint-dir=" + ckpt + " --resume " + job.string()) == 0);
  CHECK_THAT(read_bytes(elsewhere / "err.txt"), Contains("resuming after step 1/4"));
  CHECK_FALSE(fs::exists(dir / "ckpt"));
  CHECK(read_crowd_file(elsewhere / "c.h5").provenance.command_line == read_crowd_file(fresh / "c.h5").provenance.command_line);
  CHECK_THAT(read_crowd_file(elsewhere / "c.h5").provenance.command_line, !Contains("--resume") && !Contains("--checkpoint-dir"));
}

TEST_CASE("a batch stopped by SIGTERM prints its summary so far and --resume runs only what did not finish") {
  const auto dir = test::scratch_dir("cli_resume_batch");
  write_inputs(dir);
  const auto jobs = dir / "jobs";
  fs::create_directories(jobs);
  auto edit_job = [&](const std::string& name, const std::string& input) {
    std::ofstream(jobs / (name + ".yaml")) << "steps:\n  - step: edit\n    input: " << (dir / input).string()
                                           << "\n    output: " << name << ".h5\n" << drags;
  };
  edit_job("j1", "small.h5");
  edit_job("j2", "large.h5");
  edit_job("j3", "small.h5");
  const std::vector<std::string> outputs{"j1.h5", "j2.h5", "j3.h5"};
  fs::create_directories(dir / "reference");
  REQUIRE(run_in(dir / "reference", "--json run " + jobs.string()) == 0);

  const auto work = dir / "work";
  fs::create_directories(work);
  // Stopped while j2 runs (its checkpoint says step 1 is under way): exit 143, the summary on stdout.
  REQUIRE(run_and_stop(work, "--json run " + jobs.string(), "j2.yaml", 0, "TERM") == 143);
  const auto summary = nlohmann::json::parse(read_bytes(work / "out.txt"));
  CHECK(summary["interrupted"] == true);
  CHECK(summary["succeeded"] == 1);
  CHECK(summary["not_finished"] == 2);
  REQUIRE(summary["results"].size() == 3);
  CHECK(summary["results"][0]["status"] == "ok");
  CHECK(summary["results"][1]["status"] == "interrupted");
  CHECK(summary["results"][2]["status"] == "not run");
  CHECK_THAT(summary["continue"].get<std::string>(), Contains("--resume"));
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("j2.yaml: running on rank 0 (pid "));
  CHECK_FALSE(fs::exists(work / "j2.h5"));  // the interrupted job left nothing half-written

  REQUIRE(run_in(work, "--json run --resume " + jobs.string()) == 0);
  const std::string log = read_bytes(work / "err.txt");
  INFO(log);
  CHECK_THAT(log, Contains("j1.yaml: finished in the run being resumed"));
  CHECK_THAT(log, Contains("j2.yaml: the run being resumed stopped during step 1/1 on rank 0"));
  const auto resumed = nlohmann::json::parse(read_bytes(work / "out.txt"));
  CHECK(resumed["succeeded"] == 3);
  CHECK(resumed["results"][0]["report"] == nlohmann::json::parse(read_bytes(dir / "reference" / "out.txt"))["results"][0]["report"]);
  check_same_files(dir / "reference", work, outputs);
  CHECK_FALSE(fs::exists(work / ".throng-resume"));  // a batch that succeeded leaves nothing to resume
}

TEST_CASE("a rank killed inside a batch over 2 MPI ranks is reported with the job it held", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_resume_batch_mpi");
  write_inputs(dir);
  std::string jobs;
  for (const std::string name : {"m0", "m1"}) {
    std::ofstream(dir / (name + ".yaml")) << "steps:\n  - step: edit\n    input: " << (dir / "large.h5").string()
                                          << "\n    output: " << name << ".h5\n" << drags;
    jobs += " " + (dir / (name + ".yaml")).string();
  }
  const std::string mpi = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec + " -np 2 --oversubscribe ";
  const auto work = dir / "work";
  fs::create_directories(work);
  // Rank 1 holds m1: kill that process alone (its pid is in m1's checkpoint) once it is under way.
  const std::string script =
      "cd " + work.string() + " && { " + mpi + test::throng_program().string() + " --json run" + jobs +
      " >out.txt 2>err.txt & pid=$!; f=; for i in $(seq 1 6000); do for s in .throng-resume/*/state.json; do "
      "grep -qs '\"rank\": 1' $s && grep -qs '\"running\": 1' $s && f=$s; done; [ -n \"$f\" ] && break; sleep 0.01; done; "
      "[ -n \"$f\" ] || { kill -KILL $pid; wait $pid; exit 1; }; rank1=$(grep -E '\"pid\"' $f | tr -dc 0-9); kill -KILL $rank1; wait $pid; echo $? >status.txt; echo $rank1 >rank1.txt; }";
  REQUIRE(test::run_command(script) == 0);
  const std::string rank1 = read_bytes(work / "rank1.txt").substr(0, read_bytes(work / "rank1.txt").find('\n'));
  INFO(read_bytes(work / "err.txt"));
  CHECK(read_bytes(work / "status.txt") != "0\n");
  // The killed run's log says which job rank 1 held ...
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("m1.yaml: running on rank 1 (pid " + rank1 + ")"));
  // ... and so does the resumed run, which finishes the batch.
  REQUIRE(test::run_command("(cd " + work.string() + " && " + mpi + test::throng_program().string() + " --json run --resume" + jobs +
                            " >out.txt 2>err.txt)") == 0);
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("m1.yaml: the run being resumed stopped during step 1/1 on rank 1 (pid " + rank1));
  CHECK(read_crowd_file(work / "m1.h5").motion.agent_count() == 300);
}

TEST_CASE("one pipeline run by 2 MPI ranks, stopped and resumed by 2 ranks, writes the bits of an uninterrupted run", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_resume_collective_mpi");
  write_inputs(dir);
  const auto job = write_pipeline(dir);
  const std::string mpi = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec + " -np 2 --oversubscribe " +
                          test::throng_program().string();
  fs::create_directories(dir / "reference");
  REQUIRE(test::run_command("(cd " + (dir / "reference").string() + " && " + mpi + " run " + job.string() + " >out.txt 2>err.txt)") == 0);

  // SIGTERM to mpiexec (as a scheduler stops a job) while step 2 is under way: it passes the signal to both ranks.
  const auto work = dir / "work";
  fs::create_directories(work);
  REQUIRE(test::run_command("cd " + work.string() + " && { " + mpi + " run " + job.string() + " >out.txt 2>err.txt & pid=$!; "
                            "for i in $(seq 1 6000); do grep -qs '\"running\": 2' .throng-resume/*/state.json && break; "
                            "kill -0 $pid 2>/dev/null || break; sleep 0.01; done; kill -TERM $pid; wait $pid; echo $? >status.txt; }") == 0);
  INFO(read_bytes(work / "err.txt"));
  CHECK(read_bytes(work / "status.txt") != "0\n");
  CHECK_FALSE(fs::exists(work / "c.h5"));

  // Resumed by 2 ranks: rank 0 reads the checkpoint, both ranks its crowds; the same bits as the reference.
  REQUIRE(test::run_command("(cd " + work.string() + " && " + mpi + " run --resume " + job.string() + " >out.txt 2>err.txt)") == 0);
  const std::string log = read_bytes(work / "err.txt");
  INFO(log);
  // (mpiexec passes the signal on a moment later: the ranks may have finished step 2 by then.)
  CHECK_THAT(log, Contains("resuming after step 1/4") || Contains("resuming after step 2/4"));
  check_same_files(dir / "reference", work, pipeline_outputs);
  CHECK_FALSE(fs::exists(work / ".throng-resume"));

  // Another number of ranks computes another run: refused (exit 2) rather than mixed.
  REQUIRE(test::run_command("cd " + work.string() + " && { " + mpi + " run " + job.string() + " >out.txt 2>err.txt & pid=$!; "
                            "for i in $(seq 1 6000); do grep -qs '\"running\": 2' .throng-resume/*/state.json && break; "
                            "kill -0 $pid 2>/dev/null || break; sleep 0.01; done; kill -TERM $pid; wait $pid; }") != 0);
  CHECK(run_in(work, "run --resume " + job.string()) == 2);
  CHECK_THAT(read_bytes(work / "err.txt"), Contains("the number of MPI ranks"));
}
