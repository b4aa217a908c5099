// Files open in readers nobody here wrote: h5py and MDAnalysis' H5MD reader (Debian's python3 packages).
#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>

#include <fstream>

using namespace throng;

namespace {

// A crowd without absent agents (MDAnalysis has no notion of presence): 4 frames × 3 agents.
CrowdFile full_crowd() {
  CrowdFile f;
  f.motion = CrowdMotion::with_shape(4, 3);
  f.motion.times = {0.0, 0.4, 0.8, 1.2};
  for (std::size_t t = 0; t < 4; ++t) {
    for (std::size_t n = 0; n < 3; ++n) f.motion.position(t, n) = Eigen::Vector3d(n + 0.25 * t, 2.0 * n - t, 0.0);
  }
  return f;
}

std::string python_check(const std::filesystem::path& dir, const std::string& script) {
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());  // installed by scripts/install-deps (python3-h5py, python3-mdanalysis)
  std::ofstream(dir / "check.py") << script;
  std::string output;
  const int status = test::run_command(python + " " + (dir / "check.py").string(), &output);
  INFO(output);
  CHECK(status == 0);
  return output;
}

}  // namespace

TEST_CASE("h5py reads frame count, agent count, positions, absent agents and ids") {
  const auto dir = test::scratch_dir("io_h5py");
  write_crowd_file(dir / "crowd.h5", test::rich_crowd());
  const std::string out = python_check(dir, R"(
import h5py, numpy as np, sys
f = h5py.File(sys.argv[0].replace('check.py', 'crowd.h5'), 'r')
assert list(f['h5md'].attrs['version']) == [1, 1]
p = f['particles/trajectory/position/value']
assert p.shape == (5, 4, 3), p.shape
ids = f['particles/trajectory/id/value'][:]
assert ids[0, 2] == -1 and np.isnan(p[0, 2, 0])
assert ids[2, 2] == 11
assert abs(p[3, 1, 0] - (0.1 * 3 + 1)) < 1e-15
assert list(f['particles/trajectory/position/time'][:]) == [0.0, 0.5, 1.25, 2.0, 3.5]
assert f['particles/trajectory/velocity/time'][:].tolist() == f['particles/trajectory/position/time'][:].tolist()
assert f['parameters/throng'].attrs['format_version'] == 1
print('ok')
)");
  CHECK_THAT(out, Catch::Matchers::Contains("ok"));
}

TEST_CASE("MDAnalysis' H5MD reader reads frame count, agent count and positions") {
  const auto dir = test::scratch_dir("io_mdanalysis");
  const CrowdFile f = full_crowd();
  write_crowd_file(dir / "crowd.h5", f);
  const std::string out = python_check(dir, R"(
import sys, warnings
warnings.filterwarnings('ignore')
import numpy as np
from MDAnalysis.coordinates.H5MD import H5MDReader
r = H5MDReader(sys.argv[0].replace('check.py', 'crowd.h5'), convert_units=False)
assert r.n_frames == 4, r.n_frames
assert r.n_atoms == 3, r.n_atoms
for i, ts in enumerate(r):
    for n in range(3):
        expected = np.array([n + 0.25 * i, 2.0 * n - i, 0.0])
        assert np.allclose(ts.positions[n], expected, atol=1e-5), (i, n, ts.positions[n])
    assert abs(ts.time - 0.4 * i) < 1e-9, ts.time
print('ok')
)");
  CHECK_THAT(out, Catch::Matchers::Contains("ok"));
}

TEST_CASE("MDAnalysis and h5py read a file whose region is periodic (box edges and boundary)") {
  const auto dir = test::scratch_dir("io_other_periodic");
  CrowdFile f = full_crowd();
  f.scene.region = Region{{-1, -2}, {9, 6}, 0.0, 1.2, {true, true, false}};
  write_crowd_file(dir / "crowd.h5", f);
  const std::string out = python_check(dir, R"(
import sys, warnings
warnings.filterwarnings('ignore')
import h5py, numpy as np
from MDAnalysis.coordinates.H5MD import H5MDReader
path = sys.argv[0].replace('check.py', 'crowd.h5')
box = h5py.File(path, 'r')['particles/trajectory/box']
assert [b.decode() if isinstance(b, bytes) else b for b in box.attrs['boundary']] == ['periodic', 'periodic', 'none']
assert box['edges/value'].shape == (4, 3, 3)
assert np.array_equal(box['edges/value'][2], np.diag([10.0, 8.0, 0.0]))
assert list(box['offset'][:]) == [-1.0, -2.0, 0.0]
r = H5MDReader(path, convert_units=False)
assert r.n_frames == 4 and r.n_atoms == 3
for i, ts in enumerate(r):
    assert np.allclose(ts.positions[2], [2 + 0.25 * i, 4.0 - i, 0.0], atol=1e-5), ts.positions[2]
print('ok')
)");
  CHECK_THAT(out, Catch::Matchers::Contains("ok"));
}
