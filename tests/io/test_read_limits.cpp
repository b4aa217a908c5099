// Bounded reading: overflow-checked sizes, whole-number conversions, the memory budget and its estimate, and
// every reader refusing, before it allocates, what exceeds its ReadLimits.
#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/crowd_file.h>
#include <throng/io/csv.h>
#include <throng/io/hdf5.h>
#include <throng/io/read_limits.h>
#include <throng/io/real_dataset.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <fstream>
#include <limits>

using namespace throng;
using Catch::Matchers::Contains;

TEST_CASE("sizes multiply with overflow checks: [2^62+1][4] does not wrap to 4") {
  const std::uint64_t big = (std::uint64_t{1} << 62) + 1;
  CHECK_FALSE(checked_product({big, 4}).has_value());
  CHECK(checked_product({big, 3}).value() == 3 * big);  // 3·2^62 + 3 < 2^64
  CHECK(checked_product({big, 0, big}).value() == 0);   // an empty side: nothing to hold, whatever the others
  CHECK(checked_product(std::span<const std::uint64_t>{}).value() == 1);
  CHECK_FALSE(checked_sum(std::numeric_limits<std::uint64_t>::max(), 1).has_value());
}

TEST_CASE("a double becomes an integer only when it is a whole number in range") {
  CHECK(whole_number_in(3.0, 0, 10).value() == 3);
  CHECK(whole_number_in(-0.0, 0, 10).value() == 0);
  CHECK_FALSE(whole_number_in(1e19, 0, std::numeric_limits<std::int64_t>::max()).has_value());  // a cast gives −2^63
  CHECK_FALSE(whole_number_in(2.5, 0, 10).has_value());
  CHECK_FALSE(whole_number_in(-1.0, 0, 10).has_value());
  CHECK_FALSE(whole_number_in(11.0, 0, 10).has_value());
  CHECK_FALSE(whole_number_in(std::nan(""), 0, 10).has_value());
  CHECK_FALSE(whole_number_in(std::numeric_limits<double>::infinity(), 0, 10).has_value());
  CHECK_FALSE(whole_number_in(largest_exact_integer * 2, 0, std::numeric_limits<std::int64_t>::max()).has_value());
}

TEST_CASE("a memory budget adds what is charged and refuses past its limit with the estimate") {
  MemoryBudget budget(ReadLimits{1000});
  budget.charge(600, "first");
  CHECK(budget.used() == 600);
  CHECK_THROWS_AS_WITH(budget.charge(500, "file.h5:/big", "5 frames × 4 agents"), InputError,
                       Contains("file.h5:/big") && Contains("500 bytes") && Contains("5 frames × 4 agents") &&
                           Contains("600 bytes already read") && Contains("memory limit of 1.0 KB"));
  CHECK(budget.used() == 600);  // a refused charge leaves the budget as it was
  CHECK_NOTHROW(budget.charge(400, "last"));
  CHECK_THROWS_AS(budget.charge(std::numeric_limits<std::uint64_t>::max(), "overflow"), InputError);
}

TEST_CASE("working memory is checked beside what is charged without being charged") {
  MemoryBudget budget(ReadLimits{1000});
  budget.charge(600, "held");
  CHECK_NOTHROW(budget.require(400, "one chunk"));
  CHECK(budget.used() == 600);
  CHECK_THROWS_AS_WITH(budget.require(401, "file.h5:/set", "one chunk"), InputError,
                       Contains("file.h5:/set") && Contains("401 bytes") && Contains("600 bytes already read"));
  CHECK_THROWS_AS(budget.require(std::numeric_limits<std::uint64_t>::max(), "overflow"), InputError);
}

TEST_CASE("a compressed chunk's decoding buffers count against the limit: one 24 MB chunk of zeros needs 96 MB") {
  // The fuzzers' out-of-memory finding: a 1 MB file whose one deflated chunk decodes to nearly 1 GB passed the
  // budget (which held the result only) while libhdf5 grew its own decoding buffer to twice the chunk.
  const auto dir = test::scratch_dir("io_limits_chunk");
  const std::uint64_t count = 3'000'000;  // 24 MB of doubles in one chunk, deflated to a few tens of KB
  {
    h5::File f = h5::File::create(dir / "bomb.h5");
    f.root().write("zeros", std::vector<double>(count, 0.0), {count}, h5::Layout{true, count});
    f.close();
  }
  REQUIRE(std::filesystem::file_size(dir / "bomb.h5") < 1'000'000);
  {
    const h5::File f = h5::File::open(dir / "bomb.h5", ReadLimits{80'000'000});  // the result alone would fit
    CHECK_THROWS_AS_WITH(f.root().read_doubles("zeros", 1), InputError,
                         Contains("bomb.h5:/zeros") && Contains("libhdf5's buffers") && Contains("72 MB") && Contains("already read"));
  }
  const h5::File f = h5::File::open(dir / "bomb.h5", ReadLimits{100'000'000});
  CHECK(f.root().read_doubles("zeros", 1).values.size() == count);
}

TEST_CASE("the default limit is the machine's memory, lowered by the process's own limits") {
  CHECK(default_memory_limit() <= physical_memory_bytes());
  CHECK(default_memory_limit() > 0);
  CHECK(ReadLimits{}.memory_bytes == default_memory_limit());
  CHECK(format_bytes(999) == "999 bytes");
  CHECK(format_bytes(4'600'000'000) == "4.6 GB");
  CHECK(format_bytes(52'000) == "52 KB");
}

TEST_CASE("a crowd file whose arrays exceed the limit is refused with frames × agents before it is read") {
  const auto dir = test::scratch_dir("io_limits_crowd");
  const CrowdFile crowd = test::rich_crowd();  // 5 frames × 4 agents, ids and velocities
  write_crowd_file(dir / "c.h5", crowd);
  // 5 · 4 entries × (24 positions + 8 ids + 24 velocities) + 4 agents × 20 bytes = 1200 bytes.
  CHECK_THROWS_AS_WITH(read_crowd_file(dir / "c.h5", ReadLimits{1199}), InputError,
                       Contains("position/value") && Contains("5 frames × 4 agents × 56 bytes") && Contains("1.2 KB"));
  // Enough for the arrays and the scene, strings and attributes read with them.
  CHECK(test::same_crowd(read_crowd_file(dir / "c.h5", ReadLimits{1 << 20}), crowd));
}

TEST_CASE("a CSV table whose frames × agents array exceeds the limit is refused with the estimate") {
  const auto dir = test::scratch_dir("io_limits_csv");
  {
    // Every row a new time and a new id: 200 rows make a 200 × 200 array (960 KB) from a 6 KB file.
    std::ofstream out(dir / "sparse.csv");
    out << "time,id,x,y,z\n";
    for (int i = 0; i < 200; ++i) out << i << ',' << i << ",1,2,0\n";
  }
  CHECK_THROWS_AS_WITH(read_csv(dir / "sparse.csv", 0.25, ReadLimits{500'000}), InputError,
                       Contains("200 distinct times × 200 distinct ids × 24 bytes") && Contains("960 KB") &&
                           Contains("memory limit of 500 KB"));
  CHECK(read_csv(dir / "sparse.csv", 0.25, ReadLimits{2'000'000}).frame_count() == 200);
}

TEST_CASE("a recorded dataset whose frames × agents arrays exceed the limit is refused with the estimate") {
  const auto dir = test::scratch_dir("io_limits_obsmat") / "hotel";
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "obsmat.txt");
    for (int i = 0; i < 100; ++i) out << 10 * i << ' ' << i << " 1 0 2 0 0 0\n";
  }
  CHECK_THROWS_AS_WITH(import_real_dataset(dir, {}, ReadLimits{400'000}), InputError,
                       Contains("100 frames × 100 agents × 48 bytes") && Contains("480 KB"));
  // Not a recording throng knows by its rows (the folder's name says nothing): the frame rate is given.
  RealDatasetOptions at_25_fps;
  at_25_fps.video_fps = 25;
  CHECK(import_real_dataset(dir, at_25_fps, ReadLimits{4'000'000}).motion.agent_count() == 100);
}
