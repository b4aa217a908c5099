// The PedPy / Pedestrian Dynamics Data Archive layout checked with h5py (and shapely for the walkable area) the way
// PedPy's loaders read it: /trajectory with the columns id, frame, x, y (and z, ox, oy) and an fps attribute,
// wkt_geometry at the root; every row against the crowd file it came from.
#include "direct_write_driver.h"
#include "direct_writes.h"
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/export/pedpy.h>

#include <catch2/catch.hpp>
#include <hdf5.h>

#include <cstdint>
#include <fstream>
#include <vector>

using namespace throng;

namespace {

// argv: the export, the crowd file it came from. Checks the loaders' requirements, then every row.
const char* check_script = R"(
import sys, h5py, numpy as np, shapely.wkt, shapely.geometry
out, crowd = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r')
# What pedpy.load_trajectory_from_ped_data_archive_hdf5 needs.
assert 'trajectory' in out, list(out)
ds = out['trajectory']
assert ds.dtype.names == ('frame', 'id', 'x', 'y', 'z', 'ox', 'oy'), ds.dtype.names
assert {'id', 'frame', 'x', 'y'} <= set(ds.dtype.names)
assert 'fps' in ds.attrs and ds.attrs['fps'] == 25.0, dict(ds.attrs)
rows = ds[:]
# Every present agent and frame, once, frame-major; values equal to the crowd file's.
t = crowd['particles/trajectory']
position, ids, times = t['position/value'][:], t['id/value'][:], t['position/time'][:]
present = ids >= 0
assert len(rows) == present.sum(), (len(rows), present.sum())
frames, columns = np.nonzero(present)
assert (rows['frame'] == frames).all() and (rows['id'] == ids[frames, columns]).all()
for axis, name in enumerate('xyz'):
    assert (rows[name] == position[frames, columns, axis]).all(), name
assert np.allclose(rows['frame'] / ds.attrs['fps'] + times[0], times[rows['frame']], atol=1e-12)
assert np.allclose(rows['ox'] ** 2 + rows['oy'] ** 2, 1, atol=1e-14)
if 'orientation' in t:
    q = t['orientation/value'][:][frames, columns]          # x, y, z, w
    x, y, z, w = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    forward = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y + w * z)], axis=1)
    forward /= np.linalg.norm(forward, axis=1)[:, None]
    assert np.allclose(rows['ox'], forward[:, 0], atol=1e-14) and np.allclose(rows['oy'], forward[:, 1], atol=1e-14)
# What pedpy.load_walkable_area_from_ped_data_archive_hdf5 needs: one valid polygon holding every agent.
if sys.argv[3] == 'area':
    area = shapely.wkt.loads(out.attrs['wkt_geometry'])
    assert area.geom_type == 'Polygon' and area.is_valid and area.area > 0, area.geom_type
    print('holes', len(area.interiors))
    assert all(area.contains(shapely.geometry.Point(p)) for p in zip(rows['x'], rows['y']))
    for name, (x, y) in {'pillar': (4, 6), 'kiosk': (9.5, 3.4), 'fence': (5, -5), 'fence end': (13.05, -5)}.items():
        assert not area.contains(shapely.geometry.Point(x, y)), name
else:
    assert 'wkt_geometry' not in out.attrs
print('ok')
)";

void check_export(const std::filesystem::path& dir, const std::string& area) {
  std::ofstream(dir / "check.py") << check_script;
  const std::string out = test::run_tool(test::system_python() + " " + (dir / "check.py").string() + " " + (dir / "out.h5").string() +
                                         " " + (dir / "crowd.h5").string() + " " + area + " 2>&1");
  CHECK_THAT(out, Catch::Matchers::Contains("ok"));
  if (area == "area") CHECK_THAT(out, Catch::Matchers::Contains("holes 3"));
}

}  // namespace

TEST_CASE("the pedpy export has the archive's layout, every row of the crowd and its walkable area") {
  const auto dir = test::scratch_dir("export_pedpy");
  for (const bool posed : {true, false}) {
    INFO((posed ? "stored facing" : "derived facing"));
    const CrowdFile crowd = posed ? test::posed_export_crowd() : test::export_crowd();
    write_crowd_file(dir / "crowd.h5", crowd);
    export_pedpy(dir / "crowd.h5", dir / "out.h5");
    check_export(dir, "area");
  }
}

TEST_CASE("pedpy: a crowd without obstacles exports without a walkable area, and refuses to when one is required") {
  const auto dir = test::scratch_dir("export_pedpy_no_obstacles");
  CrowdFile crowd = test::export_crowd();
  crowd.scene.obstacles.clear();
  write_crowd_file(dir / "crowd.h5", crowd);
  export_pedpy(dir / "crowd.h5", dir / "out.h5");
  check_export(dir, "none");
  std::filesystem::remove(dir / "out.h5");
  PedpyOptions required;
  required.walkable_area = PedpyOptions::WalkableArea::required;
  CHECK_THROWS_AS(export_pedpy(crowd, dir / "out.h5", required), ConfigError);
  CHECK_THROWS_WITH(export_pedpy(crowd, dir / "out.h5", required), Catch::Contains("the crowd has no obstacles"));
  CHECK(test::files_in(dir) == std::vector<std::string>{"check.py", "crowd.h5"});
}

TEST_CASE("pedpy: a crowd whose frames are not evenly spaced is refused, leaving no file") {
  const auto dir = test::scratch_dir("export_pedpy_uneven");
  CrowdFile crowd = test::export_crowd();
  crowd.motion.times[7] += 0.01;
  CHECK_THROWS_AS(export_pedpy(crowd, dir / "out.h5"), InputError);
  CHECK_THROWS_WITH(export_pedpy(crowd, dir / "out.h5"), Catch::Contains("not evenly spaced"));
  CHECK(test::files_in(dir).empty());
}

TEST_CASE("pedpy: whole chunks of rows go straight to the disk, and every row reads back in order") {
  // 1,000 agents × 140 frames: 140,000 rows, two whole chunks of 65,536 rows (3,670,016 bytes each) and a last
  // one of 8,928 (under the driver's 1 MiB minimum, so through the page cache). Without the aligned rows, or with
  // libhdf5 filling each new chunk through its cache first (a fill value), nothing went straight to the disk.
  const auto dir = test::scratch_dir("export_pedpy_direct");
  constexpr std::size_t T = 140, N = 1000;
  CrowdFile crowd;
  CrowdMotion& m = crowd.motion;
  m = CrowdMotion::with_shape(T, N);
  for (std::size_t n = 0; n < N; ++n) {
    m.ids[n] = static_cast<std::int64_t>(5 * n + 3);
    m.radii[n] = 0.25;
    m.species[n] = 0;
  }
  for (std::size_t t = 0; t < T; ++t) {
    m.times[t] = 0.1 * static_cast<double>(t);
    for (std::size_t n = 0; n < N; ++n) m.position(t, n) = Eigen::Vector3d(0.01 * t + n, 0.5 * n, 0.0);
  }
  crowd.provenance.program_version = "test";
  const bool direct = test::takes_direct_writes(dir);
  INFO("the scratch folder's file system takes O_DIRECT: " << direct);
  const std::size_t before = h5::detail::direct_write_bytes();
  export_pedpy(crowd, dir / "out.h5");
  CHECK(h5::detail::direct_write_bytes() - before == (direct ? 2 * 3670016 : 0));

  struct Row {
    std::int64_t frame, id;
    double x, y, z, ox, oy;
  };
  const hid_t file = H5Fopen((dir / "out.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  REQUIRE(file >= 0);
  const hid_t set = H5Dopen2(file, "/trajectory", H5P_DEFAULT);
  const hid_t type = H5Tcreate(H5T_COMPOUND, sizeof(Row));
  H5Tinsert(type, "frame", HOFFSET(Row, frame), H5T_NATIVE_INT64);
  H5Tinsert(type, "id", HOFFSET(Row, id), H5T_NATIVE_INT64);
  H5Tinsert(type, "x", HOFFSET(Row, x), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "y", HOFFSET(Row, y), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "z", HOFFSET(Row, z), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "ox", HOFFSET(Row, ox), H5T_NATIVE_DOUBLE);
  H5Tinsert(type, "oy", HOFFSET(Row, oy), H5T_NATIVE_DOUBLE);
  std::vector<Row> rows(T * N + 1);
  const hid_t space = H5Dget_space(set);
  CHECK(H5Sget_simple_extent_npoints(space) == static_cast<hssize_t>(T * N));
  CHECK(H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, rows.data()) >= 0);
  H5Sclose(space);
  H5Tclose(type);
  H5Dclose(set);
  H5Fclose(file);
  std::size_t wrong = 0;
  for (std::size_t t = 0; t < T; ++t) {
    for (std::size_t n = 0; n < N; ++n) {
      const Row& r = rows[t * N + n];
      // Every agent creeps at 0.1 m/s, below the standing speed: it never walks, so it faces +x (1, 0).
      if (r.frame != static_cast<std::int64_t>(t) || r.id != m.ids[n] || r.x != m.position(t, n).x() || r.y != m.position(t, n).y() ||
          r.z != 0.0 || r.ox != 1.0 || r.oy != 0.0) {
        ++wrong;
      }
    }
  }
  CHECK(wrong == 0);
}
