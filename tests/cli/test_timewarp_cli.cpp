// `throng timewarp` run as a user would: the identity on an undeformed crowd, the warp stored in the output, the
// clamp's warning, and its errors with their exit codes and no output left behind.
#include "../graph/synthetic_crowd.h"
#include "cli.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cmath>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

std::string s(const std::filesystem::path& p) { return p.string(); }

// A 3 × 4 block walking straight east at 1.2 m/s for 81 frames of 0.1 s (ids 100..111).
CrowdFile walking() {
  CrowdFile file;
  file.motion = test::marching_grid(3, 4, 81, 1.0, 1.2, 0.1, 0.0, 0.1);
  return file;
}

}  // namespace

TEST_CASE("timewarp of an undeformed crowd is the identity, and the warp is stored") {
  const auto dir = test::scratch_dir("cli_timewarp_identity");
  write_crowd_file(dir / "walk.h5", walking());
  std::string out;
  REQUIRE(run("--quiet --json timewarp " + s(dir / "walk.h5") + " --reference " + s(dir / "walk.h5") + " -o " + s(dir / "out.h5"), &out) == 0);
  const auto report = nlohmann::json::parse(out);
  CHECK(report["frames"] == 81);
  CHECK(report["speed_deviation_before_mps"].get<double>() < 1e-12);
  const CrowdFile in = read_crowd_file(dir / "walk.h5"), warped = read_crowd_file(dir / "out.h5");
  REQUIRE(warped.motion.frame_count() == 81);
  for (std::size_t f = 0; f < 81; ++f) CHECK(warped.motion.times[f] == Approx(in.motion.times[f]).margin(1e-9));
  double gap = 0;
  for (std::size_t k = 0; k < in.motion.positions.size(); ++k) gap = std::max(gap, std::abs(warped.motion.positions[k] - in.motion.positions[k]));
  CHECK(gap <= 1e-9);
  const h5::File file = h5::File::open(dir / "out.h5");
  const h5::Group g = open_throng_parameters(file).open_group("timewarp");
  CHECK(g.read_doubles("source_time", 1).values == in.motion.times);
  const auto target = g.read_doubles("warped_time", 1).values;
  REQUIRE(target.size() == 81);
  for (std::size_t f = 0; f < 81; ++f) CHECK(target[f] == Approx(in.motion.times[f]).margin(1e-9));
  CHECK(*g.double_attribute("output_rate") == 10.0);
}

TEST_CASE("timewarp slows a crowd that was pushed ahead, warns when the clamp acts, and resamples at --output-rate") {
  const auto dir = test::scratch_dir("cli_timewarp_clamp");
  const CrowdFile original = walking();
  CrowdFile pushed = original;
  // From frame 40 on everybody is 3 m further east: interval 39 → 40 would need to last 26× longer.
  for (std::size_t f = 40; f < 81; ++f) {
    for (std::size_t a = 0; a < pushed.motion.agent_count(); ++a) pushed.motion.position(f, a).x() += 3.0;
  }
  write_crowd_file(dir / "walk.h5", original);
  write_crowd_file(dir / "pushed.h5", pushed);
  std::string out;
  // Eq. 12's warp alone (the guard off): the clamp holds the jump's interval at 5×.
  REQUIRE(run("--json timewarp " + s(dir / "pushed.h5") + " --reference " + s(dir / "walk.h5") +
              " --max-interval-ratio 5 --output-rate 20 --set guard.enabled=false -o " + s(dir / "out.h5") + " 2>&1", &out) == 0);
  CHECK_THAT(out, Contains("clamp acts on 1 of 80"));
  {
    // With the guard (the default) the jump the clamp left is slowed further, to 1.25 × the walk's speed.
    std::string guarded;
    REQUIRE(run("--json timewarp " + s(dir / "pushed.h5") + " --reference " + s(dir / "walk.h5") +
                " --max-interval-ratio 5 --output-rate 20 -o " + s(dir / "guarded.h5") + " 2>&1", &guarded) == 0);
    CHECK_THAT(guarded, Contains("\"guard_warped\": true"));
    const CrowdMotion& m = read_crowd_file(dir / "guarded.h5").motion;
    const CrowdMotion& w = original.motion;
    double fastest = 0, reference = 0;
    for (std::size_t f = 1; f < m.frame_count(); ++f)
      for (std::size_t a = 0; a < m.agent_count(); ++a)
        fastest = std::max(fastest, (m.position(f, a) - m.position(f - 1, a)).norm() / (m.times[f] - m.times[f - 1]));
    for (std::size_t f = 1; f < w.frame_count(); ++f)
      for (std::size_t a = 0; a < w.agent_count(); ++a)
        reference = std::max(reference, (w.position(f, a) - w.position(f - 1, a)).norm() / (w.times[f] - w.times[f - 1]));
    CHECK(fastest <= 1.25 * reference * 1.02);
    CHECK(m.times.back() > 8.4);
  }
  const CrowdFile warped = read_crowd_file(dir / "out.h5");
  CHECK(warped.motion.times[1] - warped.motion.times[0] == Approx(0.05).epsilon(1e-9));
  CHECK(warped.motion.times.back() == Approx(8.4).margin(0.05 + 1e-9));  // 8 s + 4 × 0.1 s for the clamped interval
  const h5::File file = h5::File::open(dir / "out.h5");
  const h5::Group g = open_throng_parameters(file).open_group("timewarp");
  CHECK(g.int_attribute("clamped_long") == std::vector<std::int64_t>{1});
  CHECK(g.read_int32("bound", 1).values[39] == 1);
}

TEST_CASE("timewarp errors: a reference without the crowd's agents, bad options, a missing reference") {
  const auto dir = test::scratch_dir("cli_timewarp_errors");
  CrowdFile original = walking();
  write_crowd_file(dir / "walk.h5", original);
  for (auto& id : original.motion.ids) id += 50;
  write_crowd_file(dir / "other.h5", original);
  const std::string out_h5 = s(dir / "out.h5");
  std::string out;
  CHECK(run("timewarp " + s(dir / "walk.h5") + " --reference " + s(dir / "other.h5") + " -o " + out_h5, &out) == 3);
  CHECK_THAT(out, Contains("100"));
  CHECK(run("timewarp " + s(dir / "walk.h5") + " --reference " + s(dir / "walk.h5") + " --min-interval-ratio 2 -o " + out_h5, &out) == 2);
  CHECK_THAT(out, Contains("min_interval_ratio"));
  CHECK(run("timewarp " + s(dir / "walk.h5") + " --reference " + s(dir / "walk.h5") + " --spline cubic -o " + out_h5, &out) == 2);
  CHECK(run("timewarp " + s(dir / "walk.h5") + " -o " + out_h5, &out) != 0);
  CHECK(run("timewarp " + s(dir / "walk.h5") + " --reference " + s(dir / "walk.h5") + " -o " + s(dir / "walk.h5"), &out) == 2);
  CHECK_FALSE(std::filesystem::exists(out_h5));
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++files;
  CHECK(files == 2);
}

namespace {

// 3 walkers east at 1.4 m/s, `frames` frames at 2.5 Hz (the ETH/UCY rate), and the same paths with every step
// scaled by k: the warp against the first scales every interval by k.
std::pair<CrowdFile, CrowdFile> walkers_and_scaled(std::size_t frames, double k) {
  CrowdFile walk, scaled;
  walk.motion = CrowdMotion::with_shape(frames, 3);
  for (std::size_t f = 0; f < frames; ++f) {
    walk.motion.times[f] = 0.4 * static_cast<double>(f);
    for (std::size_t a = 0; a < 3; ++a) walk.motion.position(f, a) << 1.4 * walk.motion.times[f], 0.5 * static_cast<double>(a), 0.0;
  }
  scaled = walk;
  for (double& p : scaled.motion.positions) p *= k;
  return {walk, scaled};
}

}  // namespace

TEST_CASE("timewarp reports the duration of the frames it wrote and keeps every last sample (issue 17's cases)") {
  const auto dir = test::scratch_dir("cli_timewarp_report");
  std::string out;
  SECTION("frames ending at 420.4 s warped to end at 420.52 s: duration_s 420.4") {
    const auto [walk, scaled] = walkers_and_scaled(1052, 420.52 / 420.4);
    write_crowd_file(dir / "walk.h5", walk);
    write_crowd_file(dir / "scaled.h5", scaled);
    REQUIRE(run("--quiet --json timewarp " + s(dir / "scaled.h5") + " --reference " + s(dir / "walk.h5") + " -o " + s(dir / "out.h5"), &out) == 0);
    const auto report = nlohmann::json::parse(out);
    CHECK(report["duration_s"].get<double>() == Approx(420.4).epsilon(1e-12));
    CHECK(report["warped_duration_s"].get<double>() == Approx(420.52).epsilon(1e-9));
    const CrowdFile warped = read_crowd_file(dir / "out.h5");
    CHECK(warped.motion.times.back() - warped.motion.times.front() == Approx(report["duration_s"].get<double>()).epsilon(1e-15));
  }
  SECTION("a warp of 27 ms keeps every agent's last sample") {
    const auto [walk, scaled] = walkers_and_scaled(26, (10.0 - 0.027) / 10.0);
    write_crowd_file(dir / "walk.h5", walk);
    write_crowd_file(dir / "scaled.h5", scaled);
    REQUIRE(run("--quiet --json timewarp " + s(dir / "scaled.h5") + " --reference " + s(dir / "walk.h5") + " -o " + s(dir / "out.h5"), &out) == 0);
    const auto report = nlohmann::json::parse(out);
    CHECK(report["frames"] == 26);
    CHECK(report["warped_duration_s"].get<double>() == Approx(9.973).epsilon(1e-12));
    const CrowdFile warped = read_crowd_file(dir / "out.h5");
    for (std::size_t a = 0; a < 3; ++a) {
      CHECK(warped.motion.present(25, a));
      CHECK((warped.motion.position(25, a) - scaled.motion.position(25, a)).norm() < 1e-9);
    }
  }
}
