// Exports are formatted in parallel over agent ranges: the same crowd gives the same bytes whatever the number
// of threads.
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/core/parallel.h>
#include <throng/io/export/csv_table.h>
#include <throng/io/export/gltf.h>
#include <throng/io/export/pedpy.h>
#include <throng/io/export/usd.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <sstream>

using namespace throng;

namespace {

std::string bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("every export writes the same bytes on one thread and on several") {
  const auto dir = test::scratch_dir("export_repeatable");
  // Enough agents for every one of the 16 agent ranges to hold several.
  CrowdFile crowd = test::export_crowd();
  CrowdMotion big = CrowdMotion::with_shape(crowd.motion.frame_count(), 100);
  big.times = crowd.motion.times;
  for (std::size_t t = 0; t < big.frame_count(); ++t) {
    for (std::size_t n = 0; n < 100; ++n) {
      if (crowd.motion.present(t, n % 6)) big.position(t, n) = crowd.motion.position(t, n % 6) + Eigen::Vector3d(0.0, 3.0 * static_cast<double>(n / 6), 0.0);
    }
  }
  crowd.motion = big;
  std::map<std::string, std::string> first;
  for (const std::size_t threads : {std::size_t{1}, std::size_t{4}}) {
    const ThreadLimit limit(threads);
    export_gltf(crowd, dir / "crowd.glb");
    export_usd(crowd, dir / "crowd.usda");
    export_csv(crowd, dir / "crowd.csv");
    export_pedpy(crowd, dir / "crowd.h5");
    for (const char* name : {"crowd.glb", "crowd.usda", "crowd.csv", "crowd.h5"}) {
      INFO(name << " on " << threads << " threads");
      if (threads == 1) first[name] = bytes(dir / name);
      else CHECK(bytes(dir / name) == first[name]);
    }
  }
}
