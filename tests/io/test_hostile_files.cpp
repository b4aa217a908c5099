// Hostile and damaged files met by the readers (issue 18): each refused with InputError or IoError naming what
// and where, never a crash, a hang or an unbounded allocation. The reproducers as files are replayed by
// tests/fuzz (every reader) and run through the program by tests/cli/test_hostile_inputs.cpp (exit codes).
#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/crowd_file.h>
#include <throng/io/csv.h>
#include <throng/io/hdf5.h>
#include <throng/io/real_dataset.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <cstring>
#include <fstream>
#include <iterator>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

std::string read_bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void put_u64(std::string& bytes, std::size_t at, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) bytes[at + static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xff);
}

}  // namespace

TEST_CASE("a damaged global heap is refused before libhdf5 walks it (it looped forever in `info`)") {
  const auto dir = test::scratch_dir("io_hostile_heap");
  write_crowd_file(dir / "good.h5", test::rich_crowd());
  const std::string good = read_bytes(dir / "good.h5");
  const std::size_t heap = good.find(std::string("GCOL\1", 5));
  REQUIRE(heap != std::string::npos);  // our variable-length strings live there
  const std::size_t first_object = heap + 16;  // after signature, version, reserved and the collection's size

  // (a) the first object made free space of size 0: libhdf5 1.10 never advances past it.
  std::string free_zero = good;
  free_zero[first_object] = free_zero[first_object + 1] = 0;
  put_u64(free_zero, first_object + 8, 0);
  write_bytes(dir / "free_zero.h5", free_zero);
  CHECK_THROWS_AS_WITH(read_crowd_file(dir / "free_zero.h5"), InputError,
                       Contains("global heap collection at byte " + std::to_string(heap)) && Contains("damaged"));

  // (b) an object size whose padded sum wraps to 0 (2^64 − 16), and (c) one past the collection's end.
  for (const std::uint64_t size : {~std::uint64_t{0} - 15, std::uint64_t{1} << 20}) {
    std::string bad = good;
    put_u64(bad, first_object + 8, size);
    write_bytes(dir / "bad_size.h5", bad);
    CHECK_THROWS_AS_WITH(read_crowd_file(dir / "bad_size.h5"), InputError, Contains("global heap collection"));
  }
  CHECK_NOTHROW(read_crowd_file(dir / "good.h5"));
}

TEST_CASE("a number attribute holding several values is refused, not read into one double") {
  const auto dir = test::scratch_dir("io_hostile_attribute");
  {
    h5::File f = h5::File::create(dir / "a.h5");
    const h5::Group root = f.root();
    root.set_attribute("one", 2.5);
    root.set_attribute("many", std::vector<std::int32_t>(100, 7));  // overflowed the stack as a double
    root.set_attribute("text", std::string("x"));
    f.close();
  }
  const h5::File f = h5::File::open(dir / "a.h5");
  const h5::Group root = f.root();
  CHECK(root.double_attribute("one").value() == 2.5);
  CHECK_FALSE(root.double_attribute("absent").has_value());
  CHECK_THROWS_AS_WITH(root.double_attribute("many"), InputError, Contains("attribute many") && Contains("holds 100 values"));
  CHECK_THROWS_AS_WITH(root.double_attribute("text"), InputError, Contains("is not a number"));
  CHECK(root.int_attribute("many").size() == 100);
}

TEST_CASE("seeds of 2^63 and more are stored unsigned and read back exactly, as are older signed seeds") {
  const auto dir = test::scratch_dir("io_hostile_seed");
  CrowdFile crowd = test::rich_crowd();
  crowd.provenance.seed = ~std::uint64_t{0} - 1;
  write_crowd_file(dir / "c.h5", crowd);
  CHECK(read_crowd_file(dir / "c.h5").provenance.seed == ~std::uint64_t{0} - 1);
  {
    h5::File f = h5::File::create(dir / "old.h5");
    f.root().set_attribute("seed", std::int64_t{-2});  // how 2^64 − 2 was stored before
    f.close();
  }
  const h5::File f = h5::File::open(dir / "old.h5");
  CHECK(f.root().unsigned_attribute("seed").value() == ~std::uint64_t{0} - 1);
}

TEST_CASE("a folder, a device or a missing path given as a file is an I/O error (exit 4)") {
  const auto dir = test::scratch_dir("io_hostile_kinds");
  std::filesystem::create_directory(dir / "folder.h5");
  std::filesystem::create_directory(dir / "folder.csv");
  CHECK_THROWS_AS_WITH(read_crowd_file(dir / "folder.h5"), IoError, Contains("is a folder"));
  CHECK_THROWS_AS_WITH(read_csv(dir / "folder.csv"), IoError, Contains("is a folder"));
  CHECK_THROWS_AS_WITH(read_csv("/dev/zero"), IoError, Contains("not a regular file"));
  CHECK_THROWS_AS_WITH(read_crowd_file("/dev/zero"), IoError, Contains("not a regular file"));
  CHECK_THROWS_AS_WITH(read_crowd_file(dir / "missing.h5"), IoError, Contains("no such file"));
  const auto dataset = dir / "hotel";
  std::filesystem::create_directories(dataset / "obsmat.txt");  // a folder where obsmat.txt should be
  CHECK_THROWS_AS_WITH(import_real_dataset(dataset, {}), IoError, Contains("is a folder"));
}

TEST_CASE("CSV and obsmat numbers are read whole: trailing characters are an error naming the line") {
  const auto dir = test::scratch_dir("io_hostile_numbers");
  std::ofstream(dir / "a.csv") << "time,id,x,y,z\n0,1,0,0,0\n0.5,1,1.5xyz,0,0\n";
  CHECK_THROWS_AS_WITH(read_csv(dir / "a.csv"), InputError, Contains("a.csv:3") && Contains("x '1.5xyz' is not a number"));
  std::ofstream(dir / "b.csv") << "time,id,x,y,z\n0,99999999999999999999,0,0,0\n";
  CHECK_THROWS_AS_WITH(read_csv(dir / "b.csv"), InputError, Contains("b.csv:2") && Contains("out of range"));
  std::ofstream(dir / "c.csv") << "time,id,x,y,z\n 0 ,1, 2,3 ,0\r\n";  // spaces around a number are fine
  CHECK(read_csv(dir / "c.csv").position(0, 0).x() == 2.0);

  const auto dataset = dir / "hotel";
  std::filesystem::create_directory(dataset);
  std::ofstream(dataset / "obsmat.txt") << "1e19 1 0 0 0 0 0 0\n";  // became time −3.7e17 s
  CHECK_THROWS_AS_WITH(import_real_dataset(dataset, {}), InputError, Contains("obsmat.txt:1") && Contains("whole numbers"));
  std::ofstream(dataset / "obsmat.txt") << "10 1 0 0 0 0 0 1.5xyz\n";
  CHECK_THROWS_AS_WITH(import_real_dataset(dataset, {}), InputError, Contains("obsmat.txt:1") && Contains("'1.5xyz' is not a number"));
  std::ofstream(dataset / "obsmat.txt") << "10 1 0 0 0 0 0 1\n";
  std::ofstream(dataset / "groups.txt") << "1 2x\n";
  CHECK_THROWS_AS_WITH(import_real_dataset(dataset, {}), InputError, Contains("groups.txt:1") && Contains("'2x' is not an agent id"));
}
