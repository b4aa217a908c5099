// The importer on the recorded datasets shipped in data/real.
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/real_dataset.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace throng;

namespace {
struct Sample {
  double frame, id, x, y;
};
std::vector<Sample> obsmat_rows(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<Sample> rows;
  double v[8];
  while (in >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7]) rows.push_back({v[0], v[1], v[2], v[4]});
  return rows;
}
}  // namespace

TEST_CASE("hotel: every annotated row lands at its frame, walls and pillars become obstacles, groups species") {
  const auto data = test::real_data_dir();
  const CrowdFile f = import_real_dataset(data / "hotel", {});
  const CrowdMotion& m = f.motion;
  const auto rows = obsmat_rows(data / "hotel" / "obsmat.txt");
  std::set<double> ids;
  for (const auto& r : rows) ids.insert(r.id);
  CHECK(m.agent_count() == ids.size());
  CHECK(m.agent_count() == 390);
  // One frame per annotated video frame (1,168), 0.4 s apart wherever an agent stays present (every 10th frame of
  // a 25 fps video).
  CHECK(m.frame_count() == 1168);
  for (std::size_t n = 0; n < m.agent_count(); ++n) {
    const auto [first, last] = m.presence_span(n);
    for (std::size_t t = first + 1; t < last; ++t) REQUIRE(m.times[t] - m.times[t - 1] == Catch::Detail::Approx(0.4));
  }
  std::size_t present = 0;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) present += m.present(t, n);
  }
  CHECK(present == rows.size());
  for (std::size_t i = 0; i < rows.size(); i += 97) {
    const auto& r = rows[i];
    const auto t = static_cast<std::size_t>(std::find_if(m.times.begin(), m.times.end(), [&](double x) { return std::abs(x - r.frame / 25.0) < 1e-9; }) - m.times.begin());
    REQUIRE(t < m.frame_count());
    const auto n = static_cast<std::size_t>(std::find(m.ids.begin(), m.ids.end(), static_cast<std::int64_t>(r.id)) - m.ids.begin());
    REQUIRE(m.present(t, n));
    CHECK(m.position(t, n).x() == r.x);
    CHECK(m.position(t, n).y() == r.y);
    CHECK(m.position(t, n).z() == 0.0);
  }
  std::size_t walls = 0, circles = 0;
  for (const auto& o : f.scene.obstacles) {
    walls += std::holds_alternative<Wall>(o.shape);
    circles += std::holds_alternative<Circle>(o.shape);
  }
  CHECK(walls == 4);
  CHECK(circles == 3);
  std::set<std::int32_t> groups(m.species.begin(), m.species.end());
  groups.erase(0);
  CHECK(groups.size() == 41);
  // Members of the first group in groups.txt ("14 15") share a species.
  const auto a = std::find(m.ids.begin(), m.ids.end(), 14) - m.ids.begin();
  const auto b = std::find(m.ids.begin(), m.ids.end(), 15) - m.ids.begin();
  CHECK(m.species[static_cast<std::size_t>(a)] == m.species[static_cast<std::size_t>(b)]);
  CHECK(m.species[static_cast<std::size_t>(a)] != 0);
  REQUIRE(f.provenance.credits.size() == 1);
  CHECK_THAT(f.provenance.credits[0], Catch::Contains("Pellegrini"));
}

TEST_CASE("eth uses 15 fps, students03 has no map, each dataset imports") {
  const auto data = test::real_data_dir();
  const CrowdFile eth = import_real_dataset(data / "eth", {});
  CHECK(eth.motion.times[1] - eth.motion.times[0] == Catch::Detail::Approx(0.4));  // 6 frames at 15 fps
  CHECK(eth.motion.frame_count() == 1448);
  CHECK(eth.motion.agent_count() == 360);
  const CrowdFile students = import_real_dataset(data / "univ_students03" / "obsmat.txt", {});
  CHECK(students.scene.obstacles.empty());
  CHECK(students.motion.agent_count() == 428);
  CHECK_THAT(students.provenance.credits.at(0), Catch::Contains("Lerner"));
  const CrowdFile zara = import_real_dataset(data / "zara01", {});
  CHECK(zara.scene.obstacles.size() == 7);
}

TEST_CASE("importer errors: missing folder, malformed row, unknown frame rate") {
  const auto dir = test::scratch_dir("io_import_bad");
  CHECK_THROWS_AS(import_real_dataset(dir / "nothing", {}), IoError);
  std::filesystem::create_directories(dir / "mine");
  std::ofstream(dir / "mine" / "obsmat.txt") << "1 1 0 0 0 0 0 0\n2 1 0 0 zero 0 0 0\n";
  RealDatasetOptions o;
  o.video_fps = 10;
  CHECK_THROWS_WITH(import_real_dataset(dir / "mine", o), Catch::Contains("obsmat.txt:2: 'zero' is not a number"));
  std::ofstream(dir / "mine" / "obsmat.txt") << "1 1 0 0 0 0 0 0\n";
  CHECK_THROWS_AS(import_real_dataset(dir / "mine", {}), ConfigError);
  CHECK(import_real_dataset(dir / "mine", o).motion.agent_count() == 1);
}
