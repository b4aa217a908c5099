// The tiling job file (io/tiling), the tiling data in the crowd file read back for check-tiling, and patches
// built from the real pedestrian data.
#include <catch2/catch.hpp>

#include <throng/core/errors.h>
#include <throng/io/crowd_file.h>
#include <throng/io/import_crowd.h>
#include <throng/io/tiling_job.h>
#include <throng/tiling/construct.h>

#include "test_paths.h"

#include <cstring>

using namespace throng;
using namespace throng::tiling;

namespace {

const char* small_job = R"(
region: {min: [0, 0], max: [8, 8], time: [0, 8], periodic: [true, false, false]}
library:
  builtin: [locomotion, meet]
  builtin_options: {walk_speed: 1.2}
  preferences: {meet: 3}
keyframes:
  - {patch: meet, position: [4, 4], angle: 30, time: 4}
sources: [{center: [1, 1], radius: 0.5, time: [0, 4]}]
preference:
  position: {target: [4, 4], sigma: 16}
  direction: {target: 90, sigma: 900}
  labels: {friendly: 1}
characters: 12
chains: 2
limits: {bend: 8}
annealing: {max_failures: 300}
search: {max_steps: 20000}
output: {frame_rate: 5, repeat: [2, 1, 1]}
)";

TilingJob parse(const std::string& text) { return read_job<TilingJob>(ConfigNode::parse(text, "job.yaml")); }

}  // namespace

TEST_CASE("a tiling job reads every part and its effective form reads back the same") {
  const TilingJob job = parse(small_job);
  const Prepared prepared = prepare(job, nullptr);  // reading builds nothing: the library is made here
  CHECK(prepared.library.types.size() == 12);
  CHECK(prepared.library.types[prepared.library.find("meet")].preference == 3.0);
  REQUIRE(prepared.keyframes.size() == 1);
  CHECK(prepared.keyframes[0].type == prepared.library.find("meet"));
  CHECK(std::abs(job.keyframes[0].transform.angle - 30 * M_PI / 180) < 1e-12);
  CHECK(job.environment.sources.size() == 1);
  CHECK(job.options.preference.position);
  CHECK(std::abs(job.options.preference.direction->sigma_rad2 - 900 * std::pow(M_PI / 180, 2)) < 1e-12);
  CHECK(std::abs(job.options.limits.bend_rad - 8 * M_PI / 180) < 1e-12);
  CHECK(job.layout.repeat == std::array<int, 3>{2, 1, 1});
  const YAML::Node effective = effective_job(job);
  CHECK(effective["chains"].as<int>() == 2);
  CHECK(effective["characters"].as<int>() == 12);
  CHECK(effective["limits"]["bend"].as<double>() == 8);
  CHECK(effective["annealing"]["alpha"].as<double>() == 0.2);
  CHECK(effective["output"]["repeat"][0].as<int>() == 2);
  CHECK(effective["library"]["builtin_options"]["walk_speed"].as<double>() == 1.2);
  CHECK(effective["region"]["periodic"][0].as<bool>());
  const std::string once = to_yaml_text(effective);
  const std::string twice = to_yaml_text(effective_job(parse(once)));
  CHECK(once == twice);
}

TEST_CASE("library.real takes import's reading options, and its effective form keeps them") {
  const std::string text = "region: {min: [0, 0], max: [8, 8], time: [0, 8]}\n"
                           "library:\n  real:\n    dataset: tracks.csv\n    fps: 25\n"
                           "    columns: \"frame=f,id=p,x=X,y=Y\"\n    units: cm\n    credit: Our lab\n    near: 2\n";
  const TilingJob job = parse(text);
  CHECK(job.real_import.fps == 25);
  CHECK(job.real_import.columns == "frame=f,id=p,x=X,y=Y");
  CHECK(job.real_import.units == "cm");
  CHECK(job.real_import.credit == "Our lab");
  CHECK(job.library.real_options.near_m == 2);
  CHECK(std::filesystem::path(job.real_dataset).is_absolute());
  const TilingJob again = parse(to_yaml_text(effective_job(job)));
  CHECK(again.real_import.fps == 25);
  CHECK(again.real_import.columns == job.real_import.columns);
  CHECK(again.real_import.units == "cm");
  CHECK(again.real_import.credit == "Our lab");
  CHECK(again.real_dataset == job.real_dataset);
  // Absent: the format's own (no rate, no map, no unit); a unit import does not know is refused with its line.
  const TilingJob plain = parse("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {real: {dataset: x}}\n");
  CHECK(plain.real_import.fps == 0);
  CHECK(plain.real_import.units.empty());
  CHECK_THROWS_WITH(parse("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {real: {dataset: x, units: ft}}\n"),
                    Catch::Contains("job.yaml:2") && Catch::Contains("ft"));
}

TEST_CASE("tiling job errors are configuration errors naming the place") {
  // Read, then prepared (the library built and the resources bounded), as a run does before tiling.
  const auto fails = [](const std::string& text, const std::string& needle) {
    try {
      (void)prepare(parse(text), nullptr);
    } catch (const ConfigError& e) {
      INFO(e.what());
      CHECK(std::string(e.what()).find(needle) != std::string::npos);
      return;
    }
    FAIL("no ConfigError for: " << text);
  };
  fails("library: {builtin: [walk]}\n", "region");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [moonwalk]}\n", "moonwalk");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\nchans: 2\n", "chans");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\nkeyframes: [{patch: bow, position: [1, 1], time: 1}]\n", "bow");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\noutput: {repeat: [2, 1, 1]}\n", "periodic");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\nmatch: {distance: -1}\n", "distance");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {}\n", "builtin");
  // Resources are bounded before anything is allocated (a dense deformation system per type, the index grid),
  // named by the key that sets them.
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk], builtin_options: {sample_rate: 100000}}\n",
        "sample_rate");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [locomotion, interaction], "
        "builtin_options: {sample_rate: 500}}\n",
        "library.builtin_options.sample_rate = 500 Hz");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\nindex: {cell: 1e-6}\n", "index.cell");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\nindex: {cell_time: 1e-9}\n", "index.cell");
  // A keyframe's centroid and middle time inside the region (not on a periodic axis: it wraps).
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\n"
        "keyframes: [{patch: walk, position: [400, 4], time: 4}]\n", "keyframes[0].position");
  fails("region: {min: [0, 0], max: [8, 8], time: [0, 8]}\nlibrary: {builtin: [walk]}\n"
        "keyframes: [{patch: walk, position: [4, 4], time: -3}]\n", "keyframes[0].time");
  CHECK_NOTHROW(prepare(parse("region: {min: [0, 0], max: [8, 8], time: [0, 8], periodic: [true, false, false]}\n"
                              "library: {builtin: [walk]}\nkeyframes: [{patch: walk, position: [12, 4], time: 4}]\n"),
                        nullptr));
}

TEST_CASE("the tiling data written with the characters reads back bit for bit and checks perfect") {
  TilingJob job = parse(small_job);
  NoProgress quiet;
  const tiling::Run run = tiling::run({}, job, quiet, Communicator::single());
  const TilingResult& result = run.result;
  REQUIRE(result.report.perfect());
  const Characters& laid = run.characters;
  CrowdFile crowd;
  static_cast<Crowd&>(crowd) = run.crowd;
  const auto path = test::scratch_dir("tiling_job") / "tiling.h5";
  write_crowd_file(path, crowd, [&](const h5::Group& g) { write_data(g.create_group("tiling"), run); });
  // The crowd's scene covers both laid copies along the periodic x axis; the tiling keeps the tile.
  const CrowdFile read = read_crowd_file(path);
  REQUIRE(read.scene.region);
  CHECK(read.scene.region->max.x() == 16.0);
  CHECK(read.scene.region->max.y() == 8.0);
  CHECK(read.scene.region->periodic == std::array<bool, 3>{true, false, false});
  CHECK(has_tiling_data(path));
  const TilingData back = read_tiling_data(path);
  REQUIRE(back.environment.scene.region);
  CHECK(back.environment.scene.region->max.x() == 8.0);
  CHECK(back.repeat == job.layout.repeat);
  REQUIRE(back.pieces.size() == laid.pieces.size());
  for (std::size_t a = 0; a < laid.pieces.size(); ++a) {
    REQUIRE(back.pieces[a].size() == laid.pieces[a].size());
    for (std::size_t k = 0; k < laid.pieces[a].size(); ++k) {
      CHECK(back.pieces[a][k].fragment == laid.pieces[a][k].fragment);
      CHECK(back.pieces[a][k].copy == laid.pieces[a][k].copy);
    }
  }
  REQUIRE(back.tiling.instances.size() == result.tiling.instances.size());
  REQUIRE(back.tiling.connections.size() == result.tiling.connections.size());
  for (std::size_t i = 0; i < back.tiling.instances.size(); ++i) {
    const Instance& a = back.tiling.instances[i];
    const Instance& b = result.tiling.instances[i];
    CHECK(a.type == b.type);
    CHECK(a.keyframed == b.keyframed);
    for (std::size_t f = 0; f < a.paths.size(); ++f) {
      CHECK(std::memcmp(a.paths[f].times.data(), b.paths[f].times.data(), a.paths[f].times.size() * sizeof(double)) == 0);
      CHECK(a.paths[f].positions == b.paths[f].positions);
    }
  }
  CHECK(back.library.types.size() == run.library.types.size());
  CHECK(back.environment.sources.size() == 1);
  CHECK(back.check.limits.bend_rad == job.options.limits.bend_rad);
  const CheckReport c = check_tiling(back.library, back.tiling, back.environment, back.check);
  CHECK(c.perfect());
  // A file without tiling data is an input error.
  const auto plain = test::scratch_dir("tiling_job") / "plain.h5";
  write_crowd_file(plain, crowd);
  CHECK_FALSE(has_tiling_data(plain));
  CHECK_THROWS_AS(read_tiling_data(plain), InputError);
}

TEST_CASE("patches from two synthetic walkers: a pair episode tied at its closest approach, and single pieces") {
  // Two people walk toward each other along y = ±0.4 at 1.2 m/s, pass at t = 5 s (0.8 m apart), sampled at
  // 2.5 Hz like the recorded data.
  CrowdMotion m = CrowdMotion::with_shape(26, 2);
  for (std::size_t f = 0; f < 26; ++f) {
    const double t = 0.4 * static_cast<double>(f);
    m.times[f] = t;
    m.position(f, 0) = Eigen::Vector3d(-6 + 1.2 * t, 0.4, 0);
    m.position(f, 1) = Eigen::Vector3d(6 - 1.2 * t, -0.4, 0);
  }
  RealPatchOptions o;
  o.reaction_min_m2ps2 = 0;  // straight walkers do not react: keep the episode anyway
  const PatchLibrary lib = patches_from_trajectories(m, o);
  std::size_t pairs = 0, singles = 0;
  for (const PatchType& t : lib.types) {
    if (t.character_count() == 2) {
      ++pairs;
      CHECK(!t.constraints.empty());
      CHECK(t.label == "pair");
    } else {
      ++singles;
    }
  }
  CHECK(pairs == 1);
  CHECK(singles >= 2);
  // Nothing to make patches from: an input error saying why.
  CHECK_THROWS_AS(patches_from_trajectories(CrowdMotion::with_shape(3, 1), o), InputError);
}

TEST_CASE("patches from the real zara01 data tile a box perfectly") {
  const auto dir = test::real_data_dir();
  const CrowdFile data = import_crowd(dir / "zara01").crowd;
  RealPatchOptions o;
  o.max_episode_patches = 6;
  o.max_single_patches = 6;
  PatchLibrary lib = patches_from_trajectories(data.motion, o);
  std::size_t pairs = 0;
  for (const PatchType& t : lib.types) pairs += t.character_count() == 2;
  CHECK(pairs >= 1);
  merge_into(lib, builtin_library({"walk", "turn_left", "turn_right", "stop", "start", "wait"}));
  Environment env;
  env.scene.region = Region{{0, 0}, {8, 8}, 0, 8, {false, false, false}};
  Options opts;
  opts.annealing.max_failures = 300;
  opts.search.max_steps = 20000;
  NoProgress quiet;
  const TilingResult r = tile(lib, env, {}, opts, quiet);
  CHECK(r.report.perfect());
  CHECK(check_tiling(lib, r.tiling, env, check_options_for(opts)).perfect());
  std::size_t real_used = 0;
  for (const Instance& i : r.tiling.instances) real_used += lib.types[i.type].name.rfind("real_", 0) == 0;
  CHECK(real_used > 0);
}
