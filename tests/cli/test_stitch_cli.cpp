// `throng split`, `merge`, `transform` and `stitch` run as a user would, alone and as steps of `throng run`:
// the split-and-stitch round trip, frame counts and times through a pipeline, the town job, and every documented
// error with its exit code and no output left behind.
#include "../graph/synthetic_crowd.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

std::string s(const std::filesystem::path& p) { return p.string(); }

// A 4 × 5 block turning on an arc at a constant rate for 61 frames of 0.1 s (ids 100..119). Every temporal
// feature is the same at every frame, so the stitch of its halves is the original exactly (tests/stitch).
std::filesystem::path write_arc(const std::filesystem::path& dir, const std::string& name = "arc.h5") {
  CrowdFile file;
  file.motion = test::marching_grid(4, 5, 61, 1.0, 1.3, 0.1, 0.25, 0.15);
  write_crowd_file(dir / name, file);
  return dir / name;
}

std::set<std::string> files_in(const std::filesystem::path& dir) {
  std::set<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

// The largest speed (m/s) of the agents `keep` selects, over every pair of frames where the agent is present.
template <typename Keep>
double max_speed(const CrowdMotion& c, Keep keep) {
  double speed = 0;
  for (std::size_t f = 0; f + 1 < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) {
      if (!keep(a) || !c.present(f, a) || !c.present(f + 1, a)) continue;
      speed = std::max(speed, (c.position(f + 1, a) - c.position(f, a)).head<2>().norm() / (c.times[f + 1] - c.times[f]));
    }
  }
  return speed;
}

double max_gap(const CrowdMotion& a, const CrowdMotion& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  double gap = 0;
  for (std::size_t k = 0; k < a.positions.size(); ++k) gap = std::max(gap, std::abs(a.positions[k] - b.positions[k]));
  return gap;
}

}  // namespace

TEST_CASE("split a clip at frame k and stitch the halves: the original comes back") {
  const auto dir = test::scratch_dir("cli_stitch_roundtrip");
  const auto input = write_arc(dir);
  std::string out;
  REQUIRE(run("--quiet --json split " + s(input) + " --at-frame 25 -o " + s(dir / "a.h5") + " --other " + s(dir / "b.h5"), &out) == 0);
  const auto split = nlohmann::json::parse(out);
  CHECK(split["frames"] == 26);
  CHECK(split["other"]["frames"] == 36);
  const CrowdFile a = read_crowd_file(dir / "a.h5"), b = read_crowd_file(dir / "b.h5");
  CHECK(a.motion.times.back() == b.motion.times.front());  // the halves share the cut frame

  REQUIRE(run("--quiet --json stitch " + s(dir / "a.h5") + " " + s(dir / "b.h5") + " -o " + s(dir / "c.h5"), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["frames"] == 61);  // t + t′ − 1
  CHECK(report["joints"][0]["frame"] == 25);
  CHECK(report["joints"][0]["matched_same_id"] == 20);
  const CrowdFile original = read_crowd_file(input), stitched = read_crowd_file(dir / "c.h5");
  CHECK(stitched.motion.times == original.motion.times);
  CHECK(stitched.motion.ids == original.motion.ids);
  // Tolerance: 1e-9 m — a least-squares solve of ~2,500 unknowns with positions of ~10 m rounds far below it,
  // while any real fault (a misplaced feature, a wrong alignment) moves agents by centimetres or more.
  CHECK(max_gap(stitched.motion, original.motion) <= 1e-9);

  // The joint is stored: the matching, the alignment, the frame.
  const h5::File file = h5::File::open(dir / "c.h5");
  const h5::Group j = open_throng_parameters(file).open_group("stitch").open_group("joint_1");
  CHECK(j.int_attribute("frame") == std::vector<std::int64_t>{25});
  CHECK(j.read_int64("first_ids", 1).values == original.motion.ids);
  CHECK(j.read_int64("second_ids", 1).values == original.motion.ids);
  CHECK(std::abs(*j.double_attribute("rotation")) < 1e-12);
}

TEST_CASE("stitch gives the same bits with one thread and with two") {
  const auto dir = test::scratch_dir("cli_stitch_threads");
  const auto input = write_arc(dir);
  REQUIRE(run("--quiet split " + s(input) + " --at-frame 30 -o " + s(dir / "a.h5") + " --other " + s(dir / "b.h5")) == 0);
  // Move the second half so the stitch has real work: a rotated, shifted copy.
  REQUIRE(run("--quiet transform " + s(dir / "b.h5") + " --rotate 20 --translate 3,-2 -o " + s(dir / "b2.h5")) == 0);
  const std::string clips = s(dir / "a.h5") + " " + s(dir / "b2.h5");
  REQUIRE(run("--quiet --threads 1 stitch " + clips + " --alignment translation -o " + s(dir / "one.h5")) == 0);
  REQUIRE(run("--quiet --threads 2 stitch " + clips + " --alignment translation -o " + s(dir / "two.h5")) == 0);
  const CrowdFile one = read_crowd_file(dir / "one.h5"), two = read_crowd_file(dir / "two.h5");
  CHECK(one.motion.positions == two.motion.positions);
  CHECK(one.motion.frame_count() == 61);
}

TEST_CASE("split by agents, transform and merge keep every agent and time") {
  const auto dir = test::scratch_dir("cli_stitch_agents");
  const auto input = write_arc(dir);
  std::string out;
  REQUIRE(run("--quiet --json split " + s(input) + " --agents 100,101,102 -o " + s(dir / "few.h5") + " --other " + s(dir / "rest.h5"), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["agents"] == 3);
  CHECK(report["other"]["agents"] == 17);
  const CrowdFile few = read_crowd_file(dir / "few.h5");
  CHECK(few.motion.ids == std::vector<std::int64_t>{100, 101, 102});

  // A quarter turn about the origin, 10 s later, new ids.
  REQUIRE(run("--quiet transform " + s(dir / "rest.h5") + " --rotate 90 --pivot 0,0 --time-shift 0 --id-offset 1000 -o " + s(dir / "moved.h5")) == 0);
  const CrowdFile rest = read_crowd_file(dir / "rest.h5"), moved = read_crowd_file(dir / "moved.h5");
  CHECK(moved.motion.ids.front() == rest.motion.ids.front() + 1000);
  const Eigen::Vector3d p = rest.motion.position(10, 4), q = moved.motion.position(10, 4);
  CHECK(q.x() == Approx(-p.y()).margin(1e-12));
  CHECK(q.y() == Approx(p.x()).margin(1e-12));

  REQUIRE(run("--quiet --json merge " + s(dir / "few.h5") + " " + s(dir / "moved.h5") + " -o " + s(dir / "merged.h5"), &out) == 0);
  const auto merged_report = nlohmann::json::parse(out);
  CHECK(merged_report["agents"] == 20);
  CHECK(merged_report["frames"] == 61);
  CHECK(merged_report["interpolated_frames"] == 0);
  const CrowdFile merged = read_crowd_file(dir / "merged.h5");
  CHECK(merged.motion.times == few.motion.times);
  CHECK(merged.formation_edges.size() > 0);
  const h5::File file = h5::File::open(dir / "merged.h5");
  const auto group = open_throng_parameters(file).open_group("merge").read_int32("group", 1).values;
  CHECK(std::count(group.begin(), group.end(), 0) == 3);
  CHECK(std::count(group.begin(), group.end(), 1) == 17);
}

TEST_CASE("every clip command prints its effective job and writes nothing with --print-config") {
  const auto dir = test::scratch_dir("cli_stitch_print");
  const auto input = write_arc(dir);
  const std::string o = " -o " + s(dir / "out.h5");
  std::string out;
  REQUIRE(run("--print-config split " + s(input) + " --at-time 2.5 --keep second" + o, &out) == 0);
  CHECK_THAT(out, Contains("at_time: 2.5") && Contains("keep: second"));
  REQUIRE(run("--print-config merge " + s(input) + " " + s(input) + " --span union" + o, &out) == 0);
  CHECK_THAT(out, Contains("span: union") && Contains("on_id_clash: shift"));
  REQUIRE(run("--print-config transform " + s(input) + " --rotate 90 --place-at 1,2" + o, &out) == 0);
  CHECK_THAT(out, Contains("rotate: 90") && Contains("place_at: [1, 2]"));
  REQUIRE(run("--print-config stitch " + s(input) + " " + s(input) + " --blend-window 1.5 --set weights.alpha=2" + o, &out) == 0);
  CHECK_THAT(out, Contains("blend_window: 1.5") && Contains("alpha: 2") && Contains("max_blend_vertices: 60000"));
  // Formation edits as in the edit job (by agent id, frames of the stitched output).
  const auto job = dir / "edits.yaml";
  std::ofstream(job) << "formation:\n  edits:\n    - {remove: [100, 101], frames: [20, end]}\n    - {add: [100, 119]}\n";
  REQUIRE(run("--print-config stitch " + s(input) + " " + s(input) + " --job " + s(job) + o, &out) == 0);
  CHECK_THAT(out, Contains("remove: [100, 101]") && Contains("[20, end]") && Contains("add: [100, 119]"));
  std::ofstream(job) << "formation:\n  edits:\n    - {remove: [100]}\n";
  CHECK(run("--print-config stitch " + s(input) + " " + s(input) + " --job " + s(job) + o, &out) == 2);
  CHECK_THAT(out, Contains("two agent ids"));
  std::filesystem::remove(job);
  CHECK(files_in(dir) == std::set<std::string>{"arc.h5"});
}

TEST_CASE("mismatched agent counts, non-overlapping spans and empty selections are errors that leave nothing") {
  const auto dir = test::scratch_dir("cli_stitch_errors");
  const auto input = write_arc(dir);
  REQUIRE(run("--quiet split " + s(input) + " --frames 0,20 -o " + s(dir / "early.h5")) == 0);
  REQUIRE(run("--quiet split " + s(input) + " --frames 30,60 -o " + s(dir / "late.h5")) == 0);
  REQUIRE(run("--quiet split " + s(input) + " --frames 20,40 --agents 100,101 --keep-agents rest -o " + s(dir / "fewer.h5")) == 0);
  const std::set<std::string> before = files_in(dir);
  const std::string out_h5 = s(dir / "out.h5");
  std::string out;

  SECTION("stitching clips of 20 and 18 agents: InputError (3)") {
    CHECK(run("stitch " + s(dir / "early.h5") + " " + s(dir / "fewer.h5") + " -o " + out_h5, &out) == 3);
    CHECK_THAT(out, Contains("joint 1") && Contains("20") && Contains("18") && Contains("same number"));
  }
  SECTION("merging crowds whose times do not overlap: InputError (3); with --span union it works") {
    CHECK(run("merge " + s(dir / "early.h5") + " " + s(dir / "late.h5") + " -o " + out_h5, &out) == 3);
    CHECK_THAT(out, Contains("overlap"));
    CHECK(files_in(dir) == before);
    REQUIRE(run("--quiet --json merge " + s(dir / "early.h5") + " " + s(dir / "late.h5") + " --span union -o " + out_h5, &out) == 0);
    CHECK(nlohmann::json::parse(out)["frames"] == 52);  // frames 0..20 and 30..60 at their own times
    std::filesystem::remove(out_h5);
  }
  SECTION("an empty agent list: ConfigError (2) naming the key") {
    CHECK(run("split " + s(input) + " --agents '' -o " + out_h5, &out) == 2);
    CHECK_THAT(out, Contains("agents") && Contains("selects nobody"));
  }
  SECTION("an id the crowd does not have: ConfigError (2)") {
    CHECK(run("split " + s(input) + " --agents 7 -o " + out_h5, &out) == 2);
    CHECK_THAT(out, Contains("7"));
  }
  SECTION("the rest of everybody is nobody: InputError (3), and --other leaves nothing either") {
    std::string all;
    for (int id = 100; id < 120; ++id) all += (all.empty() ? "" : ",") + std::to_string(id);
    CHECK(run("split " + s(input) + " --agents " + all + " --keep-agents rest -o " + out_h5, &out) == 3);
    CHECK(run("split " + s(input) + " --agents " + all + " -o " + out_h5 + " --other " + s(dir / "other.h5"), &out) == 3);
  }
  SECTION("a split frame out of range, a range with no single other part: ConfigError (2)") {
    CHECK(run("split " + s(input) + " --at-frame 60 -o " + out_h5, &out) == 2);
    CHECK_THAT(out, Contains("[1, 59]"));
    CHECK(run("split " + s(input) + " --frames 10,20 -o " + out_h5 + " --other " + s(dir / "other.h5"), &out) == 2);
  }
  SECTION("one clip to stitch, an unknown key, a bad choice: ConfigError (2)") {
    CHECK(run("stitch " + s(input) + " -o " + out_h5, &out) != 0);
    const auto job = dir / "job.yaml";
    std::ofstream(job) << "blend_windw: 3\n";
    CHECK(run("stitch " + s(input) + " " + s(input) + " --job " + s(job) + " -o " + out_h5, &out) == 2);
    CHECK_THAT(out, Contains("blend_windw"));
    std::filesystem::remove(job);
    CHECK(run("stitch " + s(input) + " " + s(input) + " --alignment shear -o " + out_h5, &out) == 2);
    CHECK_THAT(out, Contains("alignment") && Contains("rigid"));
  }
  SECTION("a pipeline whose stitch step fails keeps the earlier step's file and writes nothing for the failing one") {
    const auto job = dir / "job.yaml";
    std::ofstream(job) << "steps:\n"
                          "  - {step: split, input: " << s(input) << ", frames: [0, 20], name: early, output: " << s(dir / "kept.h5") << "}\n"
                          "  - {step: split, input: " << s(input) << ", frames: [20, 40], agents: [100], keep_agents: rest, name: fewer}\n"
                          "  - {step: stitch, inputs: [early, fewer], output: " << out_h5 << "}\n";
    CHECK(run("run " + s(job), &out) == 3);
    CHECK_THAT(out, Contains("step 3/3 stitch"));
    CHECK(std::filesystem::exists(dir / "kept.h5"));
    std::filesystem::remove(dir / "kept.h5");
    std::filesystem::remove(job);
  }
  CHECK(files_in(dir) == before);
}

TEST_CASE("an output folder that does not exist fails before any work, and a singular stitch exits 5 leaving nothing") {
  const auto dir = test::scratch_dir("cli_stitch_io_singular");
  const auto input = write_arc(dir);
  REQUIRE(run("--quiet split " + s(input) + " --frames 0,20 -o " + s(dir / "early.h5")) == 0);
  REQUIRE(run("--quiet split " + s(input) + " --frames 20,40 --agents 100,101 --keep-agents rest -o " + s(dir / "fewer.h5")) == 0);
  const std::string missing = s(dir / "no_such_folder" / "out.h5");
  std::string out;
  // These clips do not fit (20 and 18 agents: exit 3 after reading them); the folder is checked first: exit 4.
  CHECK(run("stitch " + s(dir / "early.h5") + " " + s(dir / "fewer.h5") + " -o " + missing, &out) == 4);
  CHECK_THAT(out, Contains("no_such_folder"));
  // The other clip commands on an input that is not HDF5 (exit 3 once read): exit 4, so the folder came first.
  const auto bad = dir / "not_hdf5.h5";
  { std::ofstream(bad) << "not an HDF5 file\n"; }
  const std::string b = s(bad);
  CHECK(run("split " + b + " --at-frame 10 -o " + s(dir / "a.h5") + " --other " + missing, &out) == 4);
  CHECK(run("merge " + b + " " + b + " -o " + missing, &out) == 4);
  CHECK(run("transform " + b + " --rotate 10 -o " + missing, &out) == 4);
  CHECK(run("timewarp " + b + " --reference " + b + " -o " + missing, &out) == 4);
  CHECK(run("merge " + b + " " + b + " -o " + s(dir / "m.h5"), &out) == 3);  // what reading it first gives
  CHECK_FALSE(std::filesystem::exists(dir / "a.h5"));
  CHECK_FALSE(std::filesystem::exists(dir / "m.h5"));
  std::filesystem::remove(bad);

  // One agent (no formation neighbour) with the temporal and spatiotemporal weights 0: nothing ties its free
  // samples to the pinned ends, the system is singular (exit 5) and nothing is written.
  REQUIRE(run("--quiet split " + s(input) + " --agents 100 -o " + s(dir / "one.h5")) == 0);
  CHECK(run("stitch " + s(dir / "one.h5") + " " + s(dir / "one.h5") +
                " --set weights.alpha=0 --set weights.beta=0 --set scale_compensation=false -o " + s(dir / "out.h5"), &out) == 5);
  CHECK_THAT(out, Contains("singular"));
  CHECK_FALSE(std::filesystem::exists(dir / "out.h5"));
}

TEST_CASE("stitch under mpiexec with the petsc backend matches eigen on 1 and 2 ranks, one file and one report", "[mpi]") {
  const std::string mpiexec = test::required_mpiexec();
  const auto dir = test::scratch_dir("cli_stitch_mpi");
  const auto input = write_arc(dir);
  REQUIRE(run("--quiet split " + s(input) + " --at-frame 30 -o " + s(dir / "a.h5") + " --other " + s(dir / "b.h5")) == 0);
  REQUIRE(run("--quiet transform " + s(dir / "b.h5") + " --rotate 20 --translate 3,-2 -o " + s(dir / "b2.h5")) == 0);
  const std::string clips = s(dir / "a.h5") + " " + s(dir / "b2.h5");
  REQUIRE(run("--quiet stitch " + clips + " -o " + s(dir / "eigen.h5")) == 0);
  const CrowdFile eigen = read_crowd_file(dir / "eigen.h5");
  for (int ranks : {1, 2}) {
    INFO(ranks << " rank(s)");
    const auto output = dir / ("petsc" + std::to_string(ranks) + ".h5");
    std::string out;
    const std::string command = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 " + mpiexec + " -np " +
                                std::to_string(ranks) + " --oversubscribe " + test::throng_program().string() +
                                " --quiet --json stitch " + clips + " --set solver.backend=petsc -o " + s(output);
    REQUIRE(test::run_command("(" + command + " 2>" + s(dir / "stderr.txt") + ")", &out) == 0);
    // One report (from rank 0): the JSON parses as one object.
    const auto report = nlohmann::json::parse(out);
    CHECK(report["frames"] == 61);
    const CrowdFile petsc = read_crowd_file(output);
    REQUIRE(petsc.motion.positions.size() == eigen.motion.positions.size());
    // The petsc solve is iterative to a relative residual of 1e-12 (solver.relative_tolerance): on a system of
    // ~2,500 unknowns with positions of ~10 m the positions agree far below 1 µm; a wrong share of the system
    // between ranks moves them by centimetres or more.
    CHECK(max_gap(petsc.motion, eigen.motion) <= 1e-6);
  }
  const std::set<std::string> names = files_in(dir);
  CHECK(std::none_of(names.begin(), names.end(), [](const std::string& n) { return n.find(".tmp") != std::string::npos; }));
}

TEST_CASE("frame counts and times stay consistent through a pipeline: sketch, split, transform, merge, stitch, edit, timewarp, plot") {
  const auto dir = test::scratch_dir("cli_stitch_pipeline");
  const auto configs = test::source_dir() / "configs";
  const auto job = dir / "pipeline.yaml";
  // 12 agents for 20 s at 10 fps: 201 frames. Each half is duplicated 30 m north and merged with itself; the
  // two pairs are stitched back (201 frames again), the tail is dragged 10 m on, and the time warp slows the
  // stretched end down.
  std::ofstream(job) << "steps:\n"
                        "  - {step: sketch, job: " << s(configs / "sketch-paper.yaml") << ", agents: {count: 12, radius: 0.25},"
                        " duration: 20, output_rate: 10, name: crowd}\n"
                        "  - {step: split, input: crowd, at_frame: 100, name: head}\n"
                        "  - {step: split, input: crowd, at_frame: 100, keep: second, name: tail}\n"
                        "  - {step: transform, input: head, translate: [0, 30], id_offset: 1000, name: head2}\n"
                        "  - {step: transform, input: tail, translate: [0, 30], id_offset: 1000, name: tail2}\n"
                        "  - {step: merge, inputs: [head, head2], name: heads}\n"
                        "  - {step: merge, inputs: [tail, tail2], name: tails}\n"
                        "  - {step: stitch, inputs: [heads, tails], name: both, output: " << s(dir / "both.h5") << "}\n"
                        "  - {step: edit, clip: {sample_step: 5}, guard: {enabled: false},"  // the timewarp step restores the speeds
                        " drags: [{frames: [0, 0]}, {frames: [-10, end], offset: [10, 0]}],"
                        " name: dragged, output: " << s(dir / "dragged.h5") << "}\n"
                        "  - {step: timewarp, inputs: [dragged, both], output: " << s(dir / "warped.h5") << "}\n"
                        "  - {step: plot, inputs: [both, dragged], output: " << s(dir / "town.svg") << "}\n";
  std::string out;
  REQUIRE(run("--quiet --json run " + s(job), &out) == 0);
  CHECK(nlohmann::json::parse(out)["crowd_files_written"] == 3);

  const CrowdFile both = read_crowd_file(dir / "both.h5");
  CHECK(both.motion.frame_count() == 201);  // 101 + 101 − 1
  CHECK(both.motion.agent_count() == 24);
  REQUIRE(both.motion.times.size() == 201);
  for (std::size_t f = 0; f < 201; ++f) CHECK(both.motion.times[f] == Approx(0.1 * static_cast<double>(f)).margin(1e-9));
  const CrowdFile dragged = read_crowd_file(dir / "dragged.h5");
  CHECK(dragged.motion.times == both.motion.times);

  // The warp runs from the dragged crowd's times to new ones and the output is sampled on them at 10 fps.
  const CrowdFile warped = read_crowd_file(dir / "warped.h5");
  const h5::File file = h5::File::open(dir / "warped.h5");
  const h5::Group g = open_throng_parameters(file).open_group("timewarp");
  const auto source = g.read_doubles("source_time", 1).values, target = g.read_doubles("warped_time", 1).values;
  CHECK(source == dragged.motion.times);
  REQUIRE(target.size() == source.size());
  CHECK(target.front() == source.front());
  for (std::size_t i = 1; i < target.size(); ++i) CHECK(target[i] > target[i - 1]);
  CHECK(warped.motion.times.front() == source.front());
  // The last output frame is the one nearest the warped end (within half a frame, before or after it).
  CHECK(std::abs(warped.motion.times.back() - target.back()) <= 0.05 + 1e-9);
  CHECK(warped.motion.times[1] - warped.motion.times[0] == Approx(0.1).epsilon(1e-9));
  CHECK(warped.motion.frame_count() == static_cast<std::size_t>(std::floor((target.back() - target.front()) / 0.1 + 0.5 + 1e-9)) + 1);
  CHECK(*g.double_attribute("duration_s") == Approx(warped.motion.times.back() - warped.motion.times.front()).epsilon(1e-12));
  CHECK(*g.double_attribute("warped_duration_s") == Approx(target.back() - target.front()).epsilon(1e-12));
  CHECK(warped.motion.ids == dragged.motion.ids);
  // The drag stretched the end; the warp lengthens it and brings the speeds back towards the original's.
  CHECK(target.back() > source.back());
  CHECK(*g.double_attribute("speed_deviation_after_mps") < *g.double_attribute("speed_deviation_before_mps"));
  CHECK(std::filesystem::file_size(dir / "town.svg") > 1000);
}

TEST_CASE("the town job runs end to end: 300+ characters from 10+ cut clips, duplicated, placed, deformed, stitched, merged") {
  const auto data = test::real_data_dir();
  const auto dir = test::scratch_dir("cli_stitch_town");
  std::ifstream in(test::source_dir() / "configs" / "run-town.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string job = text.str();
  // The job names its files relative to its own folder (configs/); this copy lives in a scratch folder.
  auto replace_all = [&](const std::string& from, const std::string& to) {
    for (std::size_t at = job.find(from); at != std::string::npos; at = job.find(from, at + to.size())) job.replace(at, from.size(), to);
  };
  replace_all("job: ", "job: " + (test::source_dir() / "configs").string() + "/");
  replace_all("../data/real/", data.string() + "/");
  // The two march sources are written too, for their speeds.
  replace_all("name: paper,", "name: paper, output: paper.h5,");
  replace_all("name: battlefield,", "name: battlefield, output: battlefield.h5,");
  std::size_t cuts = 0, stitches = 0, transforms = 0, edits = 0;
  for (std::size_t at = job.find("step: "); at != std::string::npos; at = job.find("step: ", at + 1)) {
    const std::string word = job.substr(at + 6, job.find_first_of(",}\n", at) - at - 6);
    cuts += word == "split";
    stitches += word == "stitch";
    transforms += word == "transform";
    edits += word == "edit";
  }
  CHECK(cuts >= 10);
  CHECK(stitches >= 1);
  CHECK(transforms >= 1);
  CHECK(edits >= 2);  // the battlefield source and a deformed copy
  std::ofstream(dir / "town.yaml") << job;

  std::string out;
  REQUIRE(test::run_command("cd " + dir.string() + " && " + test::throng_program().string() + " --quiet --json run town.yaml", &out) == 0);
  CHECK(nlohmann::json::parse(out)["crowd_files_written"] == 3);
  const CrowdFile town = read_crowd_file(dir / "town.h5");
  CHECK(town.motion.agent_count() >= 300);
  CHECK(town.motion.frame_count() == 481);  // 20 s at 24 fps: every group on one timeline
  CHECK(town.motion.times.back() == Approx(20.0).margin(1e-6));
  const std::set<std::int64_t> ids(town.motion.ids.begin(), town.motion.ids.end());
  CHECK(ids.size() == town.motion.agent_count());
  const std::set<std::int32_t> species(town.motion.species.begin(), town.motion.species.end());
  CHECK(species.size() >= 10);
  REQUIRE_FALSE(town.provenance.credits.empty());
  CHECK_THAT(town.provenance.credits.front(), Contains("Pellegrini"));
  CHECK(std::filesystem::file_size(dir / "town.svg") > 10000);
  // The stitched, placed, dragged and warped march groups (ids below 100000) move no faster than 3× the fastest
  // walker of their sources: each joint spreads its gap (up to ~20 m here) over the blended clips, which adds
  // speed, but nothing may jump (a jump at a joint showed as 50-1,000 m/s).
  const auto all = [](std::size_t) { return true; };
  const double source = std::max(max_speed(read_crowd_file(dir / "paper.h5").motion, all),
                                 max_speed(read_crowd_file(dir / "battlefield.h5").motion, all));
  const double marching = max_speed(town.motion, [&](std::size_t a) { return town.motion.ids[a] < 100000; });
  INFO("source max speed " << source << " m/s, town march groups " << marching << " m/s");
  CHECK(source > 1.0);
  CHECK(marching <= 3 * source);
}
