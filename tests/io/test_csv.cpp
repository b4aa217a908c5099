#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/csv.h>

#include <catch2/catch.hpp>

#include <fstream>

using namespace throng;

TEST_CASE("CSV export lists present agents only and reads back to the same motion") {
  const auto dir = test::scratch_dir("io_csv");
  const CrowdMotion m = test::rich_crowd().motion;
  write_csv(dir / "crowd.csv", m);
  std::ifstream in(dir / "crowd.csv");
  std::string header;
  std::getline(in, header);
  CHECK(header == "time,id,x,y,z");
  std::size_t rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  CHECK(rows == 5 * 4 - 3);  // three absent samples

  const CrowdMotion back = read_csv(dir / "crowd.csv", 0.3);
  CHECK(back.times == m.times);
  // Ids come back sorted: map each agent by id.
  for (std::size_t n = 0; n < m.agent_count(); ++n) {
    const auto k = static_cast<std::size_t>(std::find(back.ids.begin(), back.ids.end(), m.ids[n]) - back.ids.begin());
    REQUIRE(k < back.agent_count());
    for (std::size_t t = 0; t < m.frame_count(); ++t) {
      REQUIRE(back.present(t, k) == m.present(t, n));
      if (m.present(t, n)) CHECK(back.position(t, k) == m.position(t, n));  // shortest round-trip form: exact
    }
  }
}

TEST_CASE("malformed CSV rows name their line") {
  const auto dir = test::scratch_dir("io_csv_bad");
  std::ofstream(dir / "a.csv") << "time,id,x,y,z\n0,1,0,0,0\n0.5,1,zero,0,0\n";
  CHECK_THROWS_WITH(read_csv(dir / "a.csv"), Catch::Contains("a.csv:3: x 'zero' is not a number"));
  std::ofstream(dir / "b.csv") << "t,i,x,y,z\n";
  CHECK_THROWS_WITH(read_csv(dir / "b.csv"), Catch::Contains("expected time,id,x,y,z"));
  std::ofstream(dir / "c.csv") << "time,id,x,y,z\n0,1,0,0,0\n0,1,1,0,0\n";
  CHECK_THROWS_WITH(read_csv(dir / "c.csv"), Catch::Contains("two rows"));
}
