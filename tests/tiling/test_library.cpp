// The built-in library: every patch valid, walking ends facing along the path, the documented pose classes.
#include <catch2/catch.hpp>

#include <throng/core/errors.h>
#include <throng/tiling/library.h>

#include <algorithm>
#include <cmath>

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
