// The built-in library: every patch valid, walking ends facing along the path, the documented pose classes.
#include <catch2/catch.hpp>

#include <throng/core/errors.h>
#include <throng/tiling/library.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace throng;
using namespace throng::tiling;

TEST_CASE("the built-in library is valid and its patches look as documented") {
  const PatchLibrary lib = builtin_library(builtin_patch_group("all"));
  REQUIRE(lib.types.size() == builtin_patch_names().size());
  const auto walking = static_cast<std::size_t>(
      std::find(lib.pose_classes.begin(), lib.pose_classes.end(), "walking") - lib.pose_classes.begin());
  REQUIRE(walking < lib.pose_classes.size());
  for (const PatchType& t : lib.types) {
    INFO(t.name);
    CHECK(t.preference == static_cast<double>(t.character_count()));
    for (const Fragment& f : t.fragments) {
      if (!f.is_character()) continue;
      // Walking ends face along the path.
      const auto along = [&](std::size_t a, std::size_t b, double heading) {
        const Eigen::Vector2d d = f.positions[b] - f.positions[a];
        return std::abs(std::remainder(std::atan2(d.y(), d.x()) - heading, 2 * M_PI)) < 0.05;
      };
      if (f.entry_class == walking) CHECK(along(0, 1, f.headings.front()));
      if (f.exit_class == walking) CHECK(along(f.sample_count() - 2, f.sample_count() - 1, f.headings.back()));
    }
  }
  // Canonical frames: the centroid of every sample at the origin, time centred.
  for (const PatchType& t : lib.types) {
    Eigen::Vector2d c(0, 0);
    std::size_t n = 0;
    for (const Fragment& f : t.fragments) {
      for (const auto& p : f.positions) c += p;
      n += f.sample_count();
    }
    CHECK((c / static_cast<double>(n)).norm() < 1e-9);
    CHECK(std::abs(t.start_time() + t.end_time()) < 1e-9);
  }
  const PatchType& walk = lib.types[lib.find("walk")];
  CHECK(walk.fragments[0].sample_count() == 21);
  CHECK_THAT((walk.fragments[0].positions.back() - walk.fragments[0].positions.front()).norm(),
             Catch::Matchers::WithinAbs(2.6, 1e-6));
  CHECK(lib.types[lib.find("bow_rows")].character_count() == 10);
  CHECK(lib.types[lib.find("meet")].constraints.size() == 2);
  CHECK(lib.pose_classes[lib.types[lib.find("stop")].fragments[0].exit_class] == "standing");
}

TEST_CASE("unknown built-in names are configuration errors naming the known ones") {
  CHECK_THROWS_AS(builtin_library({"walk", "moonwalk"}), ConfigError);
  CHECK_THROWS_AS(builtin_patch_group("dances"), ConfigError);
  try {
    (void)builtin_library({"moonwalk"});
  } catch (const ConfigError& e) {
    CHECK(std::string(e.what()).find("handshake") != std::string::npos);
  }
}

namespace {

// Where fragment f of a patch is at time t (linear between samples); false outside its time span.
bool at_time(const Fragment& f, double t, Eigen::Vector2d& p) {
  if (t < f.times.front() || t > f.times.back()) return false;
  std::size_t k = 0;
  while (k + 2 < f.times.size() && f.times[k + 1] < t) ++k;
  const double u = (t - f.times[k]) / (f.times[k + 1] - f.times[k]);
  p = f.positions[k] + std::clamp(u, 0.0, 1.0) * (f.positions[k + 1] - f.positions[k]);
  return true;
}

}  // namespace

TEST_CASE("the characters and props of every built-in patch keep clear of each other") {
  // Sampled every millisecond: between samples the relative motion of two linearly interpolated paths is
  // linear, and at walking speeds 1 ms moves a pair at most 3 mm closer than what is sampled; the clearance
  // asked for is the radii sum plus 5 mm, so a sampled pass means the exact distance is at least the radii.
  const PatchLibrary lib = builtin_library(builtin_patch_group("all"));
  for (const PatchType& t : lib.types) {
    for (std::size_t a = 0; a < t.fragments.size(); ++a) {
      for (std::size_t b = a + 1; b < t.fragments.size(); ++b) {
        const Fragment& fa = t.fragments[a];
        const Fragment& fb = t.fragments[b];
        double closest = std::numeric_limits<double>::infinity(), when = 0;
        for (double time = t.start_time(); time <= t.end_time(); time += 1e-3) {
          Eigen::Vector2d p, q;
          if (!at_time(fa, time, p) || !at_time(fb, time, q)) continue;
          if ((p - q).norm() < closest) {
            closest = (p - q).norm();
            when = time;
          }
        }
        INFO(t.name << " fragments " << a << " and " << b << ": closest " << closest << " m at " << when << " s, radii "
                    << fa.radius_m + fb.radius_m << " m");
        CHECK(closest >= fa.radius_m + fb.radius_m + 0.005);
      }
    }
  }
}
