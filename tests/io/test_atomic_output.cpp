#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <catch2/catch.hpp>

#include <fstream>

using namespace throng;

TEST_CASE("an uncommitted output leaves nothing and a committed one replaces the target") {
  const auto dir = test::scratch_dir("io_atomic");
  std::ofstream(dir / "out.txt") << "old";
  {
    AtomicOutput o(dir / "out.txt");
    CHECK(o.temporary().parent_path() == dir);
    std::ofstream(o.temporary()) << "partial";
  }
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
  std::string content;
  std::ifstream(dir / "out.txt") >> content;
  CHECK(content == "old");
  {
    AtomicOutput o(dir / "out.txt");
    std::ofstream(o.temporary()) << "new";
    o.commit();
  }
  std::ifstream(dir / "out.txt") >> content;
  CHECK(content == "new");
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
}

TEST_CASE("an output in a missing folder, or over its own input, is refused up front") {
  const auto dir = test::scratch_dir("io_atomic_refuse");
  CHECK_THROWS_AS(AtomicOutput(dir / "missing" / "x"), IoError);
  std::ofstream(dir / "in.h5") << "x";
  CHECK_THROWS_AS(check_distinct(dir / "in.h5", dir / "." / "in.h5"), ConfigError);
  CHECK_NOTHROW(check_distinct(dir / "in.h5", dir / "other.h5"));
}
