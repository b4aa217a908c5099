// CSV tables through import_crowd: columns found by name or given by --columns (names or indices), units from
// --units or the header, species and radius columns, extra columns reported; each mistake with its exit code.
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

std::filesystem::path sample(const std::string& name) { return test::source_dir() / "tests" / "data" / "import" / name; }

std::size_t column_of(const CrowdMotion& m, std::int64_t id) {
  return static_cast<std::size_t>(std::find(m.ids.begin(), m.ids.end(), id) - m.ids.begin());
}

}  // namespace

TEST_CASE("a CSV with renamed, reordered columns in millimetres imports zara01's rows, species from its group column") {
  // The reference: the same 300 rows through the obsmat reader (their positions are checked against the source
  // in test_import_formats and test_real_dataset).
  std::ifstream in(test::real_data_dir() / "zara01" / "obsmat.txt");
  std::map<std::pair<std::int64_t, std::int64_t>, std::pair<double, double>> source;  // (frame, id) -> (x, y)
  double v[8];
  while (source.size() < 300 && in >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7]) {
    source[{static_cast<std::int64_t>(v[0]), static_cast<std::int64_t>(v[1])}] = {v[2], v[4]};
  }
  const auto path = sample("zara01_renamed.csv");
  CHECK(detect_import_format(path) == ImportFormat::csv);
  CHECK_THROWS_AS_WITH(import_crowd(path), ConfigError, Contains("give the rate with --fps"));  // a frame column
  ImportOptions o;
  o.fps = 25;
  const ImportedCrowd got = import_crowd(path, o);  // "X [mm]": millimetres from the header
  const CrowdMotion& m = got.crowd.motion;
  std::size_t present = 0;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) present += m.present(t, n);
  }
  CHECK(present == source.size());
  for (const auto& [key, xy] : source) {
    const auto t = static_cast<std::size_t>(std::lower_bound(m.times.begin(), m.times.end(), key.first / 25.0 - 1e-9) - m.times.begin());
    REQUIRE(t < m.frame_count());
    const std::size_t n = column_of(m, key.second);
    REQUIRE(m.present(t, n));
    CHECK(m.position(t, n).x() == Approx(xy.first).epsilon(4e-16).margin(0));
    CHECK(m.position(t, n).y() == Approx(xy.second).epsilon(4e-16).margin(0));
  }
  // zara01's groups.txt: "1 2" is the first group, "3 4" the second.
  CHECK(m.species[column_of(m, 1)] == 1);
  CHECK(m.species[column_of(m, 2)] == 1);
  CHECK(m.species[column_of(m, 3)] == 2);
  // The speed column is not dropped silently.
  REQUIRE(got.notes.size() == 1);
  CHECK_THAT(got.notes[0], Contains("'speed'") && Contains("not imported"));
  o.species_from = "none";
  CHECK(import_crowd(path, o).crowd.motion.species[column_of(m, 1)] == 0);
  o.species_from = (test::real_data_dir() / "zara01" / "groups.txt").string();  // a groups file: the same species
  CHECK(import_crowd(path, o).crowd.motion.species == m.species);
  o = {};
  o.fps = 25;
  o.units = "cm";
  CHECK_THROWS_AS_WITH(import_crowd(path, o), ConfigError, Contains("header gives positions in mm") && Contains("--units cm"));
}

TEST_CASE("CSV columns by --columns (names or indices), times in seconds, radius, the old time,id,x,y,z header") {
  const auto dir = test::scratch_dir("import_csv_columns");
  std::ofstream(dir / "plain.csv") << "time,id,x,y,z\n0,1,0.5,0.25,0\n0.4,1,1,0.5,0\n0.4,2,3,4,0\n";
  const CrowdMotion plain = import_crowd(dir / "plain.csv").crowd.motion;
  CHECK(plain.times == std::vector<double>{0.0, 0.4});
  CHECK(plain.position(1, 1).y() == 4.0);
  CHECK_FALSE(plain.present(0, 1));
  // As a spreadsheet saves it: a UTF-8 byte order mark before the header, CRLF line ends.
  std::ofstream(dir / "excel.csv") << "\xEF\xBB\xBFTime,ID,X,Y\r\n0,1,0.5,0.25\r\n0.4,1,1,0.5\r\n";
  CHECK(import_crowd(dir / "excel.csv").crowd.motion.position(1, 0).x() == 1.0);

  std::ofstream(dir / "odd.csv") << "when;who;east;north;size;kind\n0.0;5;100;200;30;2\n0.5;5;150;200;30;2\n";
  ImportOptions o;
  o.columns = "time=when,id=who,x=east,y=north,radius=size,species=kind";
  o.units = "cm";
  const CrowdMotion odd = import_crowd(dir / "odd.csv", o).crowd.motion;
  CHECK(odd.position(1, 0).x() == Approx(1.5));
  CHECK(odd.radii[0] == Approx(0.3));
  CHECK(odd.species[0] == 2);
  o.fps = 10;
  CHECK_THROWS_AS_WITH(import_crowd(dir / "odd.csv", o), ConfigError, Contains("'when' gives times in seconds") && Contains("--fps"));

  std::ofstream(dir / "bare.csv") << "3,0,1.5,2.5\n3,10,1.75,2.5\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "bare.csv"), ConfigError, Contains("no header row") && Contains("--columns"));
  o = {};
  o.columns = "id=0,frame=1,x=2,y=3";
  o.fps = 20;
  const CrowdMotion bare = import_crowd(dir / "bare.csv", o).crowd.motion;
  CHECK(bare.ids == std::vector<std::int64_t>{3});
  CHECK(bare.times[1] == Approx(0.5));
  o.columns = "id=0,frame=1,x=2,y=9";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "bare.csv", o), ConfigError, Contains("y=9 is not a column") && Contains("4 columns"));
  o.columns = "id=0,frame=1,x=2,height=3";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "bare.csv", o), ConfigError, Contains("unknown role 'height'"));
  o.columns = "id=0,frame=1,x=2,y=name";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "bare.csv", o), ConfigError, Contains("no header row"));
}

TEST_CASE("CSV mistakes: missing columns, ragged rows, bad numbers, species that change") {
  const auto dir = test::scratch_dir("import_csv_errors");
  std::ofstream(dir / "noid.csv") << "time,x,y\n0,1,2\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "noid.csv"), InputError, Contains("cannot find the column(s) id") && Contains("--columns"));
  std::ofstream(dir / "ragged.csv") << "t,id,x,y\n0,1,2,3\n1,1,2\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "ragged.csv"), InputError, Contains("ragged.csv:3: expected 4 values"));
  std::ofstream(dir / "word.csv") << "t,id,x,y\n0,1,2,3\n1,1,two,3\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "word.csv"), InputError, Contains("word.csv:3: x 'two' is not a number"));
  std::ofstream(dir / "species.csv") << "t,id,x,y,group\n0,1,2,3,1\n1,1,2,3,2\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "species.csv"), InputError, Contains("agent 1 changes its species"));
  std::ofstream(dir / "twice.csv") << "t,id,x,y\n0,1,2,3\n0,1,2,3\n";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "twice.csv"), InputError, Contains("agent 1 has two rows at time 0"));
  ImportOptions o;
  o.species_from = "colour";
  CHECK_THROWS_AS_WITH(import_crowd(dir / "species.csv", o), ConfigError, Contains("--species-from colour: not a column"));
}
