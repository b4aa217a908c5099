#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>

using namespace throng;

namespace {
std::string bytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}
}  // namespace

TEST_CASE("a crowd file round-trips every field exactly") {
  const auto dir = test::scratch_dir("io_round_trip");
  const CrowdFile original = test::rich_crowd();
  write_crowd_file(dir / "rich.h5", original);
  const CrowdFile back = read_crowd_file(dir / "rich.h5");
  CHECK(test::same_crowd(original, back));
  // Absent agents come back absent, present ones bit-identical.
  CHECK_FALSE(back.motion.present(0, 2));
  CHECK(back.motion.present(2, 2));
  CHECK_FALSE(back.motion.present(4, 3));
}

TEST_CASE("the same data gives the same file bytes") {
  const auto dir = test::scratch_dir("io_same_bytes");
  const CrowdFile f = test::rich_crowd();
  write_crowd_file(dir / "a.h5", f);
  write_crowd_file(dir / "b.h5", f);
  CHECK(bytes(dir / "a.h5") == bytes(dir / "b.h5"));
}

TEST_CASE("method data written through the extra callback reads back") {
  const auto dir = test::scratch_dir("io_extra");
  write_crowd_file(dir / "x.h5", test::rich_crowd(), [](const h5::Group& g) {
    const h5::Group s = g.create_group("sketch");
    s.write("stroke_points", std::vector<double>{1, 2, 3, 4, 5, 6}, {3, 2});
    s.set_attribute("strokes", std::int64_t{1});
  });
  const h5::File f = h5::File::open(dir / "x.h5");
  const h5::Group s = open_throng_parameters(f).open_group("sketch");
  const auto points = s.read_doubles("stroke_points", 2);
  CHECK(points.shape == std::vector<std::uint64_t>{3, 2});
  CHECK(points.values[5] == 6);
  CHECK(s.int_attribute("strokes") == std::vector<std::int64_t>{1});
}

TEST_CASE("a large crowd is chunked and compressed and reads back") {
  const auto dir = test::scratch_dir("io_large");
  CrowdFile f;
  f.motion = CrowdMotion::with_shape(200, 500);
  for (std::size_t t = 0; t < 200; ++t) {
    for (std::size_t n = 0; n < 500; ++n) f.motion.position(t, n) = Eigen::Vector3d(n * 0.5, t * 0.1, 0);
  }
  write_crowd_file(dir / "large.h5", f);
  // Regular data compresses well below its raw size (200 × 500 × 3 doubles = 2.4 MB).
  CHECK(std::filesystem::file_size(dir / "large.h5") < 1200000);
  CHECK(read_crowd_file(dir / "large.h5").motion.positions == f.motion.positions);
}

TEST_CASE("writing never leaves a partial file or touches an existing target on failure") {
  const auto dir = test::scratch_dir("io_no_partial");
  SECTION("missing folder") {
    CHECK_THROWS_AS(write_crowd_file(dir / "no" / "such" / "x.h5", test::rich_crowd()), IoError);
  }
  SECTION("invalid data leaves the old file as it was") {
    write_crowd_file(dir / "keep.h5", test::rich_crowd());
    const std::string before = bytes(dir / "keep.h5");
    CrowdFile bad = test::rich_crowd();
    bad.motion.times[3] = bad.motion.times[2];
    CHECK_THROWS_AS(write_crowd_file(dir / "keep.h5", bad), InputError);
    CHECK(bytes(dir / "keep.h5") == before);
  }
  SECTION("an exception inside the extra writer removes the temporary file") {
    CHECK_THROWS_AS(write_crowd_file(dir / "x.h5", test::rich_crowd(), [](const h5::Group&) { throw IoError("disk full"); }), IoError);
    CHECK_FALSE(std::filesystem::exists(dir / "x.h5"));
  }
  std::size_t leftovers = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) leftovers += e.path().filename().string().find(".tmp-") != std::string::npos;
  CHECK(leftovers == 0);
}

TEST_CASE("a periodic region becomes the H5MD box: periodic axes, edges and offset, and reads back") {
  const auto dir = test::scratch_dir("io_periodic_box");
  CrowdFile f = test::rich_crowd();  // region [-2, 6] × [-2, 6], periodic in x (and in time), not in y
  write_crowd_file(dir / "x.h5", f);
  {
    const h5::File file = h5::File::open(dir / "x.h5");
    const h5::Group box = file.root().open_group("particles/trajectory/box");
    CHECK(box.string_array_attribute("boundary") == std::vector<std::string>{"periodic", "none", "none"});
    const auto edges = box.read_doubles("edges/value", 3);
    REQUIRE(edges.shape == std::vector<std::uint64_t>{f.motion.frame_count(), 3, 3});
    for (std::size_t t = 0; t < f.motion.frame_count(); ++t) {
      const std::vector<double> frame(edges.values.begin() + 9 * t, edges.values.begin() + 9 * (t + 1));
      CHECK(frame == std::vector<double>{8, 0, 0, 0, 8, 0, 0, 0, 0});
    }
    CHECK(box.read_doubles("offset", 1).values == std::vector<double>{-2, -2, 0});
    CHECK(box.read_doubles("edges/time", 1).values == f.motion.times);  // shares position's time
  }
  CHECK(test::same_crowd(f, read_crowd_file(dir / "x.h5")));

  // Both axes periodic; and no region at all gives a box with no periodic axis and no edges.
  f.scene.region->periodic = {true, true, false};
  write_crowd_file(dir / "xy.h5", f);
  {
    const h5::File xy = h5::File::open(dir / "xy.h5");
    CHECK(xy.root().open_group("particles/trajectory/box").string_array_attribute("boundary") ==
          std::vector<std::string>{"periodic", "periodic", "none"});
  }
  CHECK(test::same_crowd(f, read_crowd_file(dir / "xy.h5")));
  f.scene.region.reset();
  write_crowd_file(dir / "none.h5", f);
  const h5::File none_file = h5::File::open(dir / "none.h5");
  const h5::Group none = none_file.root().open_group("particles/trajectory/box");
  CHECK(none.string_array_attribute("boundary") == std::vector<std::string>{"none", "none", "none"});
  CHECK_FALSE(none.has("edges"));
  CHECK_FALSE(read_crowd_file(dir / "none.h5").scene.region.has_value());
}
