// Loops: a tile periodic in time (with or without x and y) at a density per area is perfect and holds its
// density; on a tile periodic on every axis every character is a closed loop, present at every time.
// (Twenty seeds of the 10 m × 10 m × 20 s x+y+t tile at the documented density: bench/tiling, BM_LoopSeeds.)
#include <catch2/catch.hpp>

#include <throng/tiling/characters.h>
#include <throng/tiling/check.h>
#include <throng/tiling/density.h>

#include "tiling_scenes.h"

#include <cmath>

using namespace throng;
using namespace throng::tiling;
using namespace throng::tiling::test;

namespace {

CheckOptions check_options(const Options& o) {
  CheckOptions c;
  c.limits = o.limits;
  c.match = o.match;
  return c;
}

std::string failures(const CheckReport& r) {
  std::string s;
  for (const Failure& f : r.failures) s += std::string(to_string(f.kind)) + ": " + f.message + "\n";
  return s;
}

// The loop density documented in options.h (SearchOptions::restarts) and bench/tiling.
constexpr double loop_density = 0.1;

}  // namespace

TEST_CASE("a tile periodic in x, y and t at the documented density closes every loop") {
  const PatchLibrary lib = builtin_library(builtin_patch_group("locomotion"));
  const Environment env = box(10, 10, 20, {true, true, true});
  NoProgress quiet;
  for (const std::uint64_t seed : {1, 2, 3, 4}) {
    INFO("seed " << seed);
    Options o;
    o.seed = seed;
    o.annealing.max_failures = 2000;
    o.density.per_m2 = loop_density;
    o.density.report_window_s = 20;
    const TilingResult r = tile(lib, env, {}, o, quiet);
    const CheckReport c = check_tiling(lib, r.tiling, env, check_options(o));
    INFO(failures(c));
    REQUIRE(c.perfect());
    // Every character is a closed loop: as many chains as loops, and every fragment has a predecessor.
    CHECK(r.tiling.connections.size() == r.tiling.instances.size());
    // The count of characters present is the same at every time (loops neither start nor end) and within the
    // tolerance of the target.
    const DensityReport d = measure_density(lib, r.tiling, env, o.density, 0, 20);
    REQUIRE(d.windows.size() == 1);
    const AreaDensity& a = d.windows[0].areas[0];
    CHECK(a.target == Approx(10.0));
    CHECK(std::abs(a.error()) <= o.density.tolerance);
    CHECK(a.highest - a.lowest < 1e-6);
    CHECK(std::abs(a.mean - std::round(a.mean)) < 1e-6);
  }
}

TEST_CASE("a tile periodic in time, alone or with x, holds its density and repeats without a seam") {
  const PatchLibrary lib = builtin_library(builtin_patch_group("locomotion"));
  NoProgress quiet;
  for (const std::array<bool, 3> periodic : {std::array<bool, 3>{false, false, true}, std::array<bool, 3>{true, false, true}}) {
    INFO("periodic x " << periodic[0]);
    const Environment env = box(16, 16, 20, periodic);
    Options o = quick_options(8);
    o.density.per_m2 = 0.05;
    o.density.report_window_s = 10;
    const TilingResult r = tile(lib, env, {}, o, quiet);
    const CheckReport c = check_tiling(lib, r.tiling, env, check_options(o));
    INFO(failures(c));
    REQUIRE(c.perfect());
    std::size_t time_seams = 0;
    for (const Connection& k : r.tiling.connections) time_seams += k.image[2] != 0;
    CHECK(time_seams > 0);
    const DensityReport d = measure_density(lib, r.tiling, env, o.density, 0, 20);
    for (const DensityWindow& w : d.windows) CHECK(std::abs(w.areas[0].error()) <= o.density.tolerance);
  }
}
