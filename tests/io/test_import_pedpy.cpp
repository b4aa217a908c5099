// JuPedSim/PedPy HDF5 through import_crowd: a file written as JuPedSim writes it (h5py, tests/data/import) and a
// round trip through io/export's writer; throng's own crowd files; each damaged or incomplete file's message.
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/export/pedpy.h>
#include <throng/io/hdf5.h>
#include <throng/io/import_crowd.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <fstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

std::filesystem::path sample(const std::string& name) { return test::source_dir() / "tests" / "data" / "import" / name; }

// zara01's first 300 rows (tests/data/import, frame id x y at 25 fps).
CrowdFile zara01_sample(const std::filesystem::path& obstacles = {}) {
  ImportOptions o;
  o.fps = 25;
  o.obstacles = obstacles;
  return import_crowd(sample("zara01_frame_id_x_y.txt"), o).crowd;
}

}  // namespace

TEST_CASE("a JuPedSim HDF5 file: rows, fps and the walkable area's holes as obstacles") {
  const CrowdFile reference = zara01_sample();
  const auto path = sample("zara01_pedpy.h5");
  CHECK(detect_import_format(path) == ImportFormat::pedpy);
  const ImportedCrowd got = import_crowd(path);
  const CrowdMotion& m = got.crowd.motion;
  const CrowdMotion& r = reference.motion;
  // Frames counted from 0 at 2.5 per second: reference time − 1/25 (zara01's first frame is video frame 1).
  REQUIRE(m.frame_count() == r.frame_count());
  REQUIRE(m.ids == r.ids);
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    CHECK(m.times[t] == Approx(r.times[t] - 1.0 / 25).margin(1e-12));
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      REQUIRE(m.present(t, n) == r.present(t, n));
      if (m.present(t, n)) CHECK(m.position(t, n) == r.position(t, n));
    }
  }
  // The square area with one square hole: four boundary walls and one convex obstacle, the hole itself.
  std::size_t walls = 0, polygons = 0;
  for (const auto& o : got.crowd.scene.obstacles) {
    walls += std::holds_alternative<Wall>(o.shape);
    polygons += std::holds_alternative<ConvexPolygon>(o.shape);
  }
  CHECK(walls == 4);
  REQUIRE(polygons == 1);
  CHECK(distance_to(got.crowd.scene.obstacles.back(), {0.5, 0.5}, 0).signed_distance == Approx(-0.5));
  // The facing columns are reported, not dropped silently.
  CHECK(got.notes.size() == 2);
  CHECK_THAT(got.notes[0], Contains("'ox'"));
  ImportOptions o;
  o.fps = 25;
  CHECK_THROWS_AS_WITH(import_crowd(path, o), ConfigError, Contains("attribute fps states 2.5") && Contains("--fps 25"));
}

TEST_CASE("round trip through io/export's PedPy writer: the same people at the same places, walls still blocking") {
  const auto dir = test::scratch_dir("import_pedpy_round_trip");
  // zara01's rows with zara01's map.xml (seven walls) given as the obstacles.
  const CrowdFile crowd = zara01_sample(test::real_data_dir() / "zara01" / "map.xml");
  REQUIRE(crowd.scene.obstacles.size() == 7);
  export_pedpy(crowd, dir / "zara.h5");
  const ImportedCrowd back = import_crowd(dir / "zara.h5");
  CHECK(back.format == ImportFormat::pedpy);
  const CrowdMotion& m = back.crowd.motion;
  REQUIRE(m.ids == crowd.motion.ids);
  REQUIRE(m.frame_count() == crowd.motion.frame_count());
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    // PedPy counts frames from 0: times keep their steps, not their origin.
    CHECK(m.times[t] == Approx(crowd.motion.times[t] - crowd.motion.times[0]).margin(1e-12));
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      REQUIRE(m.present(t, n) == crowd.motion.present(t, n));
      if (m.present(t, n)) CHECK(m.position(t, n) == crowd.motion.position(t, n));
    }
  }
  // Every point of every original wall's centre line is blocked by the imported obstacles: inside a hole's
  // polygon or within an imported wall (the area's boundary drawn 1/cos(π/32) outside each capsule: 0.25 mm).
  REQUIRE_FALSE(back.crowd.scene.obstacles.empty());
  for (const auto& o : crowd.scene.obstacles) {
    const Wall& w = std::get<Wall>(o.shape);
    for (int k = 0; k <= 20; ++k) {
      const Eigen::Vector2d p = w.a + (w.b - w.a) * (k / 20.0);
      double nearest = 1e9;
      for (const auto& imported : back.crowd.scene.obstacles) nearest = std::min(nearest, distance_to(imported, p, 0).signed_distance);
      CHECK(nearest <= 1e-3);
    }
  }
}

TEST_CASE("crowd files import as they are, and HDF5 files of other layouts are refused naming what is missing") {
  const auto dir = test::scratch_dir("import_hdf5_other");
  const CrowdFile crowd = zara01_sample();
  write_crowd_file(dir / "crowd.h5", crowd);
  const ImportedCrowd back = import_crowd(dir / "crowd.h5");
  CHECK(back.format == ImportFormat::crowd);
  CHECK(back.crowd.motion.positions.size() == crowd.motion.positions.size());
  ImportOptions o;
  o.fps = 25;
  CHECK_THROWS_AS_WITH(import_crowd(dir / "crowd.h5", o), ConfigError, Contains("--fps does not apply"));
  {
    h5::File f = h5::File::create(dir / "other.h5");
    f.root().write("numbers", std::vector<double>{1, 2, 3}, {3});
    f.close();
  }
  CHECK_THROWS_AS_WITH(import_crowd(dir / "other.h5"), InputError, Contains("neither /trajectory") && Contains("throng imports:"));
  {
    h5::File f = h5::File::create(dir / "plain.h5");
    f.root().write("trajectory", std::vector<double>{1, 2, 3}, {3});
    f.close();
  }
  CHECK_THROWS_AS_WITH(import_crowd(dir / "plain.h5"), InputError, Contains("plain.h5:/trajectory: is not a compound dataset"));
  std::ofstream(dir / "cut.h5", std::ios::binary) << std::string("\x89HDF\r\n\x1a\n", 8) << "truncated";
  CHECK_THROWS_AS(import_crowd(dir / "cut.h5"), InputError);
}

TEST_CASE("a PedPy table's columns and the rows built from them share the file's one memory limit") {
  // Each had a budget of its own, so a table of columns just under the limit could hold twice the limit.
  const auto dir = test::scratch_dir("import_pedpy_limit");
  const CrowdFile crowd = zara01_sample();
  export_pedpy(crowd, dir / "zara.h5");
  std::uint64_t rows = 0;
  for (std::size_t t = 0; t < crowd.motion.frame_count(); ++t) {
    for (std::size_t n = 0; n < crowd.motion.agent_count(); ++n) rows += crowd.motion.present(t, n) ? 1 : 0;
  }
  // Five columns (frame, id, x, y, z) of 8 bytes are read before the rows (40 bytes each) are built: 80 per row.
  CHECK_THROWS_AS_WITH(import_crowd(dir / "zara.h5", {}, ReadLimits{80 * rows - 1}), InputError,
                       Contains(std::to_string(rows) + " rows") && Contains(format_bytes(40 * rows) + " already read"));
  CHECK(import_crowd(dir / "zara.h5", {}, ReadLimits{1 << 20}).crowd.motion.ids == crowd.motion.ids);
}
