// Every bad-input case of the crowd file reader: one test each, checking the error type (hence the exit code)
// and that the message names the dataset and the problem.
#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <array>
#include <fstream>
#include <limits>

using namespace throng;

namespace {

enum class Defect {
  none, missing_position, rank_two, last_axis_two, time_length, nan_present, times_decrease, version_two, id_changes,
  // Without an id/value dataset (presence from positions alone):
  no_ids_absent, no_ids_infinite, no_ids_partly_nan,
  // The H5MD box (as another program would write it):
  box_periodic, box_without_edges, box_bad_boundary, box_triclinic, box_disagrees
};

// A minimal H5MD crowd file (3 frames, 2 agents) written by hand, with one defect.
void write_by_hand(const std::filesystem::path& path, Defect d) {
  h5::File f = h5::File::create(path);
  {
    const h5::Group root = f.root();
    root.create_group("h5md").set_attribute("version", std::vector<std::int32_t>{1, 1});
    const h5::Group traj = root.create_group("particles").create_group("trajectory");
    const h5::Group pos = traj.create_group("position");
    std::vector<double> value{0, 0, 0, 1, 0, 0, 0.1, 0, 0, 1.1, 0, 0, 0.2, 0, 0, 1.2, 0, 0};
    if (d == Defect::nan_present) value[6] = std::nan("");
    if (d == Defect::no_ids_absent) value[9] = value[10] = value[11] = std::nan("");  // agent 6 absent at frame 1
    if (d == Defect::no_ids_infinite) value[10] = -std::numeric_limits<double>::infinity();  // agent 6, frame 1, y
    if (d == Defect::no_ids_partly_nan) value[9] = std::nan("");
    if (d == Defect::rank_two) pos.write("value", value, {3, 6});
    else if (d == Defect::last_axis_two) pos.write("value", std::vector<double>(12, 0.0), {3, 2, 2});
    else if (d != Defect::missing_position) pos.write("value", value, {3, 2, 3});
    std::vector<double> time{0, 1, 2};
    if (d == Defect::times_decrease) time = {0, 2, 1};
    if (d == Defect::time_length) time = {0, 1};
    pos.write("time", time, {time.size()});
    pos.write("step", std::vector<std::int64_t>{0, 1, 2}, {3});
    std::vector<std::int64_t> ids{5, 6, 5, 6, 5, 6};
    if (d == Defect::id_changes) ids[4] = 9;
    const bool without_ids = d == Defect::no_ids_absent || d == Defect::no_ids_infinite || d == Defect::no_ids_partly_nan;
    if (!without_ids) traj.create_group("id").write("value", ids, {3, 2});
    if (d >= Defect::box_periodic) {
      const h5::Group box = traj.create_group("box");
      box.set_attribute("dimension", std::int64_t{3});
      box.set_attribute("boundary", std::vector<std::string>{d == Defect::box_bad_boundary ? "wrapped" : "periodic",
                                                             "none", "none"});
      if (d != Defect::box_without_edges) {
        // A time-independent box: sides [3], or box vectors [3][3] (sheared in the triclinic case).
        if (d == Defect::box_triclinic) box.write("edges", std::vector<double>{4, 0, 0, 1, 3, 0, 0, 0, 1}, {3, 3});
        else box.write("edges", std::vector<double>{4, 3, 1}, {3});
      }
      box.write("offset", std::vector<double>{-1, -0.5, 0}, {3});
    }
    const h5::Group params = root.create_group("parameters").create_group("throng");
    if (d == Defect::box_disagrees) {  // a stored region 5 m wide where the box says 4
      const h5::Group scene = params.create_group("scene");
      scene.write("region", std::vector<double>{-1, -0.5, 4, 2.5, 0, 2}, {6});
      scene.write("region_periodic", std::vector<std::int32_t>{1, 0, 0}, {3});
    }
    params.set_attribute("format_version", std::int64_t{d == Defect::version_two ? 2 : 1});
    const h5::Group agents = params.create_group("agents");
    agents.write("id", std::vector<std::int64_t>{5, 6}, {2});
    agents.write("radius", std::vector<double>{0.2, 0.2}, {2});
  }
  f.close();
}

std::filesystem::path case_file(const std::string& name, Defect d) {
  const auto dir = test::scratch_dir("io_errors_" + name);
  write_by_hand(dir / "crowd.h5", d);
  return dir / "crowd.h5";
}

}  // namespace

TEST_CASE("the hand-written file without defects reads") {
  const CrowdFile f = read_crowd_file(case_file("none", Defect::none));
  CHECK(f.motion.frame_count() == 3);
  CHECK(f.motion.ids == std::vector<std::int64_t>{5, 6});
}

TEST_CASE("missing file: IoError naming the path") {
  CHECK_THROWS_AS_WITH(read_crowd_file("/nonexistent/crowd.h5"), IoError, Catch::Matchers::Contains("/nonexistent/crowd.h5: no such file"));
}

TEST_CASE("not HDF5: InputError") {
  const auto dir = test::scratch_dir("io_errors_text");
  std::ofstream(dir / "notes.h5") << "time,id,x,y,z\n0,1,0,0,0\n";
  CHECK_THROWS_AS_WITH(read_crowd_file(dir / "notes.h5"), InputError, Catch::Matchers::Contains("is not an HDF5 file"));
}

TEST_CASE("truncated file: InputError") {
  const auto dir = test::scratch_dir("io_errors_truncated");
  write_crowd_file(dir / "whole.h5", test::rich_crowd());
  const auto size = std::filesystem::file_size(dir / "whole.h5");
  std::filesystem::copy_file(dir / "whole.h5", dir / "cut.h5");
  std::filesystem::resize_file(dir / "cut.h5", size / 2);
  CHECK_THROWS_AS_WITH(read_crowd_file(dir / "cut.h5"), InputError, Catch::Matchers::Contains("truncated"));
}

TEST_CASE("missing dataset: InputError naming it") {
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("missing", Defect::missing_position)), InputError,
                       Catch::Matchers::Contains("/particles/trajectory/position/value: missing dataset"));
}

TEST_CASE("wrong rank: InputError naming the dataset and the ranks") {
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("rank", Defect::rank_two)), InputError,
                       Catch::Matchers::Contains("position/value: has rank 2, expected 3"));
}

TEST_CASE("wrong shape: InputError for a last axis other than 3 and for a time length mismatch") {
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("axis", Defect::last_axis_two)), InputError,
                       Catch::Matchers::Contains("expected [frames][agents][3]"));
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("time", Defect::time_length)), InputError,
                       Catch::Matchers::Contains("position/time: has 2 entries for 3 frames"));
}

TEST_CASE("NaN for a present agent: InputError naming agent and frame") {
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("nan", Defect::nan_present)), InputError,
                       Catch::Matchers::Contains("NaN position for present agent 5 (column 0) at frame 1"));
}

TEST_CASE("without id/value only NaN means absent: an infinite position is an InputError naming it") {
  const CrowdFile absent = read_crowd_file(case_file("no_ids_absent", Defect::no_ids_absent));
  CHECK(absent.motion.present(0, 1));
  CHECK_FALSE(absent.motion.present(1, 1));
  CHECK(absent.motion.present(2, 1));
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("no_ids_inf", Defect::no_ids_infinite)), InputError,
                       Catch::Matchers::Contains("/particles/trajectory/position/value: infinite position for present "
                                                 "agent 6 (column 1) at frame 1"));
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("no_ids_partly_nan", Defect::no_ids_partly_nan)), InputError,
                       Catch::Matchers::Contains("position/value: NaN position for present agent 6 (column 1) at frame 1") &&
                           Catch::Matchers::Contains("only NaN in all three coordinates means absent"));
}

TEST_CASE("times not increasing: InputError naming the frame") {
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("times", Defect::times_decrease)), InputError,
                       Catch::Matchers::Contains("times not increasing at frame 2"));
}

TEST_CASE("unknown format version: InputError naming both versions") {
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("version", Defect::version_two)), InputError,
                       Catch::Matchers::Contains("unknown format version 2 (this throng reads version 1)"));
}

TEST_CASE("an id that changes within a column: InputError") {
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("ids", Defect::id_changes)), InputError,
                       Catch::Matchers::Contains("column 0 holds id 9 at frame 2"));
}

TEST_CASE("a periodic H5MD box from another program becomes the region, and a bad box is an InputError naming it") {
  const CrowdFile f = read_crowd_file(case_file("box_periodic", Defect::box_periodic));
  REQUIRE(f.scene.region.has_value());
  const Region& r = *f.scene.region;
  CHECK(r.periodic == std::array<bool, 3>{true, false, false});
  CHECK(r.min == Eigen::Vector2d(-1, -0.5));
  CHECK(r.max == Eigen::Vector2d(3, 2.5));  // offset + sides
  CHECK(r.t0 == 0);
  CHECK(r.t1 == 2);
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("box_no_edges", Defect::box_without_edges)), InputError,
                       Catch::Matchers::Contains("/particles/trajectory/box/edges: missing dataset"));
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("box_boundary", Defect::box_bad_boundary)), InputError,
                       Catch::Matchers::Contains("box: attribute boundary[0] is 'wrapped'"));
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("box_triclinic", Defect::box_triclinic)), InputError,
                       Catch::Matchers::Contains("box/edges: a triclinic box"));
  CHECK_THROWS_AS_WITH(read_crowd_file(case_file("box_disagrees", Defect::box_disagrees)), InputError,
                       Catch::Matchers::Contains("box: axis x disagrees with /parameters/throng/scene/region"));
}
