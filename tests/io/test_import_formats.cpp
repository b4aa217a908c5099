// Each text layout import_crowd reads, on samples generated from data/real/zara01 (tests/data/import, see
// make_samples.py there): positions equal to the recording's within float precision, times from the frame rate
// the file states or is given, and the exit code and message for each way a file or option can be wrong.
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/import_crowd.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <fstream>
#include <map>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

struct SourceRow {
  std::int64_t frame, id;
  double x, y;
};

// The first `count` rows of zara01's obsmat.txt (frame id x z y ...), the samples' source.
std::vector<SourceRow> zara01_rows(std::size_t count = 300) {
  std::ifstream in(test::real_data_dir() / "zara01" / "obsmat.txt");
  std::vector<SourceRow> rows;
  double v[8];
  while (rows.size() < count && in >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7]) {
    rows.push_back({static_cast<std::int64_t>(v[0]), static_cast<std::int64_t>(v[1]), v[2], v[4]});
  }
  return rows;
}

std::filesystem::path sample(const std::string& name) { return test::source_dir() / "tests" / "data" / "import" / name; }

// Every source row is present at time time_of(frame) with the source's position: exactly, or within a few ulps
// where the file holds centimetres or millimetres (one multiplication by 0.01 or 0.001). Nobody else is present.
template <class TimeOf>
void check_same_as_source(const CrowdMotion& m, const std::vector<SourceRow>& rows, TimeOf time_of, double relative) {
  std::map<std::int64_t, std::size_t> column;
  for (std::size_t n = 0; n < m.agent_count(); ++n) column[m.ids[n]] = n;
  std::size_t present = 0;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) present += m.present(t, n);
  }
  CHECK(present == rows.size());
  for (const SourceRow& r : rows) {
    const double time = time_of(r.frame);
    const auto t = static_cast<std::size_t>(std::lower_bound(m.times.begin(), m.times.end(), time - 1e-9) - m.times.begin());
    REQUIRE(t < m.frame_count());
    REQUIRE(m.times[t] == Approx(time).epsilon(1e-12));
    REQUIRE(column.count(r.id) == 1);
    const std::size_t n = column[r.id];
    REQUIRE(m.present(t, n));
    CHECK(m.position(t, n).x() == Approx(r.x).epsilon(relative).margin(0));
    CHECK(m.position(t, n).y() == Approx(r.y).epsilon(relative).margin(0));
    CHECK(m.position(t, n).z() == 0.0);
  }
}

constexpr double exact = 0.0;
constexpr double a_few_ulps = 4e-16;

}  // namespace

TEST_CASE("the benchmarks' frame id x y layout: tab-separated, frames at the given rate") {
  const auto rows = zara01_rows();
  const auto path = sample("zara01_frame_id_x_y.txt");
  CHECK(detect_import_format(path) == ImportFormat::frame_id_x_y);
  CHECK_THROWS_AS_WITH(import_crowd(path), ConfigError, Contains("zara01_frame_id_x_y.txt") && Contains("give the rate with --fps"));
  ImportOptions o;
  o.fps = 25;
  const ImportedCrowd got = import_crowd(path, o);
  CHECK(got.format == ImportFormat::frame_id_x_y);
  check_same_as_source(got.crowd.motion, rows, [](std::int64_t f) { return f / 25.0; }, exact);

  const auto dir = test::scratch_dir("import_frame_id_x_y");
  std::ofstream(dir / "spaces.txt") << "# a comment\n0 1 0.5 1.5\n\n10 1 0.75 1.25\n";
  const ImportedCrowd spaces = import_crowd(dir / "spaces.txt", o);
  CHECK(spaces.crowd.motion.position(1, 0).y() == 1.25);
  std::ofstream(dir / "bad.txt") << "0 1 0.5 1.5\n10 1 0.75\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "bad.txt", o), InputError, Contains("bad.txt:2: expected 4 numbers (frame id x y), found 3"));
  std::ofstream(dir / "frac.txt") << "0.5 1 0.5 1.5\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "frac.txt", o), InputError, Contains("frac.txt:1: frame '0.5' is not a whole number"));
  std::ofstream(dir / "twice.txt") << "0 1 0.5 1.5\n0 1 0.5 1.5\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "twice.txt", o), InputError, Contains("agent 1 has two rows at frame 0"));
  std::ofstream(dir / "nan.txt") << "0 1 nan 1.5\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "nan.txt", o), InputError, Contains("nan.txt:1: x 'nan' is not finite"));
}

TEST_CASE("Jülich/PeTrack id frame x y z: centimetres, CRLF, the header's frame rate, z is not a ground position") {
  const auto rows = zara01_rows();
  const auto path = sample("zara01_petrack.txt");
  CHECK(detect_import_format(path) == ImportFormat::petrack);
  const ImportedCrowd got = import_crowd(path);  // 25 fps and cm from the header
  check_same_as_source(got.crowd.motion, rows, [](std::int64_t f) { return f / 25.0; }, a_few_ulps);
  REQUIRE(got.notes.size() == 1);
  CHECK_THAT(got.notes[0], Contains("z"));
  ImportOptions o;
  o.fps = 16;
  CHECK_THROWS_AS_WITH(import_crowd(path, o), ConfigError, Contains("its header states 25 frames per second") && Contains("--fps 16"));
  o = {};
  o.units = "m";
  CHECK_THROWS_AS_WITH(import_crowd(path, o), ConfigError, Contains("its header gives positions in cm") && Contains("--units m"));

  const auto dir = test::scratch_dir("import_petrack");
  // No rate in the header: --fps; no unit: centimetres; 4 columns named id frame x y in the header.
  std::ofstream(dir / "bare.txt") << "# id frame x y\r\n7 100 150 -20\r\n7 101 160 -20\r\n";
  CHECK(detect_import_format(dir / "bare.txt") == ImportFormat::petrack);
  CHECK_THROWS_AS_WITH(import_crowd(dir / "bare.txt"), ConfigError, Contains("give the rate with --fps"));
  o = {};
  o.fps = 16;
  const CrowdMotion bare = import_crowd(dir / "bare.txt", o).crowd.motion;
  CHECK(bare.ids == std::vector<std::int64_t>{7});
  CHECK(bare.times[1] - bare.times[0] == Approx(1.0 / 16));
  CHECK(bare.position(1, 0).x() == Approx(1.6));
  // A header in metres.
  std::ofstream(dir / "metres.txt") << "# framerate: 16 fps\n# X,Y,Z: position (in m)\n1 5 1.5 2.5 1.7\n";
  CHECK(import_crowd(dir / "metres.txt").crowd.motion.position(0, 0).x() == 1.5);
  std::ofstream(dir / "short.txt") << "# framerate: 16 fps\n1 5 150 250 170\n1 6 150 250\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "short.txt"), InputError, Contains("short.txt:3: expected 5 numbers (id frame x y z), found 4"));
}
