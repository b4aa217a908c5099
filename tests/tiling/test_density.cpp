// Density per area: the measure (exact on hand-built chains whose presence is known in closed form) and the
// tiler holding it (every reported window within the tolerance, the tiling still perfect).
#include <catch2/catch.hpp>

#include <throng/core/errors.h>
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

// A static square block [lo, hi]².
Obstacle block(double lo, double hi) {
  Obstacle o;
  o.shape = ConvexPolygon{{{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}}};
  o.name = "block";
  return o;
}

// The locomotion patches and the two-character ones: a plaza's crowd.
PatchLibrary plaza_library() {
  return builtin_library({"walk", "walk_slow", "walk_fast", "turn_left", "turn_right", "turn_left_90", "turn_right_90",
                          "stop", "start", "wait", "turn_in_place", "meet", "pass", "handshake", "bump"});
}

}  // namespace

TEST_CASE("the density measure counts a walker exactly while it is inside each area") {
  // Five walks along +x at y = 6, 1.3 m/s, from x = −1 at t = 2 s: inside the 12 m box (x in (0, 12)) from
  // t = 2 + 1 / 1.3 s until the chain ends at x = 12, t = 12 s.
  const PatchLibrary lib = walk_library();
  const Environment env = box(12, 12, 20);
  const Tiling chain = walk_chain(lib, 5, -1.0, 6.0, 2.0);
  DensityOptions o;
  o.per_m2 = 1.0 / 144.0;                           // target: one character in the box
  o.zones.push_back({{6, 0}, {12, 12}, 1.0 / 72.0});  // the right half: one character there
  o.report_window_s = 5;
  o.bin_s = 1;
  const DensityReport r = measure_density(lib, chain, env, o, 0, 20);
  REQUIRE(r.windows.size() == 4);
  const double enter = 2 + 1 / 1.3, half = 2 + 7 / 1.3;  // into the box, into the right half
  const double box_means[4] = {(5 - enter) / 5, 1.0, 2.0 / 5, 0.0};
  const double half_means[4] = {0.0, (10 - half) / 5, 2.0 / 5, 0.0};
  for (std::size_t w = 0; w < 4; ++w) {
    INFO("window " << w);
    CHECK(r.windows[w].t0 == Approx(5.0 * static_cast<double>(w)));
    REQUIRE(r.windows[w].areas.size() == 2);
    CHECK(r.windows[w].areas[0].target == Approx(1.0));
    CHECK(r.windows[w].areas[1].target == Approx(1.0));
    CHECK(r.windows[w].areas[0].mean == Approx(box_means[w]).margin(1e-9));
    CHECK(r.windows[w].areas[1].mean == Approx(half_means[w]).margin(1e-9));
  }
  // Bins of 1 s: in the first window the box is empty in [0, 2) and full in [3, 5).
  CHECK(r.windows[0].areas[0].lowest == Approx(0.0).margin(1e-12));
  CHECK(r.windows[0].areas[0].highest == Approx(1.0));
  CHECK(r.worst_error() == Approx(1.0));  // the last window is empty
  CHECK_FALSE(r.met());

  // Periodic in x: the zone [0, 2] also counts its image [12, 14], which the walker crosses from t = 4 / 1.3 s.
  const Environment wrapped = box(12, 12, 20, {true, false, false});
  DensityOptions z;
  z.zones.push_back({{0, 0}, {2, 12}, 1.0 / 24.0});
  z.report_window_s = 20;
  const DensityReport p = measure_density(lib, walk_chain(lib, 3, 8.0, 6.0, 0.0), wrapped, z, 0, 20);
  REQUIRE(p.windows.size() == 1);
  CHECK(p.windows[0].areas[0].mean == Approx((2 / 1.3) / 20).margin(1e-9));
}

TEST_CASE("the density measure's free area leaves out what obstacles cover") {
  Environment env = box(20, 20, 10);
  env.scene.obstacles.push_back(block(8, 12));
  DensityOptions o;
  o.per_m2 = 0.1;
  o.free_area = true;
  o.report_window_s = 10;
  const DensityReport r = measure_density(walk_library(), Tiling{}, env, o, 0, 10);
  REQUIRE(r.windows.size() == 1);
  // (400 − 16) m² on a 0.1 m raster whose cells the block's sides cut exactly.
  CHECK(r.windows[0].areas[0].target == Approx(0.1 * 384).epsilon(1e-9));
  o.free_area = false;
  CHECK(measure_density(walk_library(), Tiling{}, env, o, 0, 10).windows[0].areas[0].target == Approx(40.0));
}

TEST_CASE("the tiler holds a density per area in every window, and the tiling stays perfect") {
  const PatchLibrary lib = plaza_library();
  NoProgress quiet;
  for (const double per_m2 : {0.03, 0.06}) {
    for (const std::uint64_t seed : {1, 2}) {
      INFO("density " << per_m2 << " /m², seed " << seed);
      const Environment env = box(24, 24, 40);
      Options o = quick_options(seed);
      o.density.per_m2 = per_m2;
      o.density.report_window_s = 10;
      const TilingResult r = tile(lib, env, {}, o, quiet);
      CHECK(r.report.perfect());
      CHECK(check_tiling(lib, r.tiling, env, check_options(o)).perfect());
      const DensityReport d = measure_density(lib, r.tiling, env, o.density, 0, 40);
      REQUIRE(d.windows.size() == 4);
      for (const DensityWindow& w : d.windows) {
        INFO("window [" << w.t0 << ", " << w.t1 << "] target " << w.areas[0].target << " mean " << w.areas[0].mean);
        CHECK(std::abs(w.areas[0].error()) <= o.density.tolerance);
      }
    }
  }
}

TEST_CASE("the tiler holds a zone's density and the obstacle-free area's") {
  const PatchLibrary lib = builtin_library(builtin_patch_group("locomotion"));
  Environment env = box(24, 24, 30);
  env.scene.obstacles.push_back(block(9, 15));
  NoProgress quiet;
  SECTION("free area") {
    Options o = quick_options(1);
    o.density.per_m2 = 0.05;
    o.density.free_area = true;
    o.density.report_window_s = 10;
    const TilingResult r = tile(lib, env, {}, o, quiet);
    CHECK(check_tiling(lib, r.tiling, env, check_options(o)).perfect());
    const DensityReport d = measure_density(lib, r.tiling, env, o.density, 0, 30);
    for (const DensityWindow& w : d.windows) {
      CHECK(w.areas[0].target == Approx(0.05 * (576 - 36)));
      CHECK(std::abs(w.areas[0].error()) <= o.density.tolerance);
    }
  }
  SECTION("a zone alone (the rest of the region is filled freely)") {
    Options o = quick_options(1);
    o.density.zones.push_back({{0, 0}, {8, 24}, 0.1});
    o.density.report_window_s = 10;
    const TilingResult r = tile(lib, env, {}, o, quiet);
    CHECK(check_tiling(lib, r.tiling, env, check_options(o)).perfect());
    const DensityReport d = measure_density(lib, r.tiling, env, o.density, 0, 30);
    for (const DensityWindow& w : d.windows) {
      REQUIRE(w.areas.size() == 1);
      CHECK(w.areas[0].target == Approx(19.2));
      CHECK(std::abs(w.areas[0].error()) <= o.density.tolerance);
    }
  }
}

TEST_CASE("impossible density options are configuration errors naming the option") {
  const auto message = [](const Options& o) {
    try {
      validate(o);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  Options o;
  o.density.per_m2 = -0.1;
  CHECK(message(o).find("density.per_m2") != std::string::npos);
  o = Options{};
  o.density.tolerance = 0;
  CHECK(message(o).find("density.tolerance") != std::string::npos);
  o = Options{};
  o.density.zones.push_back({{4, 4}, {2, 8}, 0.1});
  CHECK(message(o).find("density.zones[0]") != std::string::npos);
  o = Options{};
  o.density.bin_s = 90;  // longer than the reported window (60 s)
  CHECK(message(o).find("density.report_window") != std::string::npos);
}
