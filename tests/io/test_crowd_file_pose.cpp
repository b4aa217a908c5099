// Facing and action in the crowd file: the H5MD elements beside position round-trip, older files (without them)
// still read, h5py and MDAnalysis read files with them, and every malformed element is refused by name.
#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <cmath>
#include <cstring>
#include <fstream>

using namespace throng;

namespace {

// rich_crowd with a facing per present agent and frame (a yaw that turns with time, one agent pitched) and actions
// from a table with a tiled patch's label and a prop.
CrowdFile posed_crowd() {
  CrowdFile f = test::rich_crowd();
  CrowdMotion& m = f.motion;
  const std::size_t T = m.frame_count(), N = m.agent_count();
  m.orientations.assign(T * N * 4, absent);
  m.actions.assign(T * N, -1);
  m.action_table = standard_actions();
  m.action_table.push_back({"bow", ""});
  m.action_table.push_back({"walk", "umbrella"});
  for (std::size_t t = 0; t < T; ++t) {
    for (std::size_t n = 0; n < N; ++n) {
      if (!m.present(t, n)) continue;
      m.orientation(t, n) = facing_along(Eigen::Vector3d(std::cos(0.7 * t + n), std::sin(0.7 * t + n), n == 1 ? 0.4 : 0.0));
      m.action(t, n) = static_cast<std::int32_t>((t + n) % m.action_table.size());
    }
  }
  return f;
}

std::string python_check(const std::filesystem::path& dir, const std::string& script) {
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());  // installed by scripts/install-deps (python3-h5py, python3-mdanalysis)
  std::ofstream(dir / "check.py") << script;
  std::string output;
  const int status = test::run_command(python + " " + (dir / "check.py").string() + " " + dir.string(), &output);
  INFO(output);
  CHECK(status == 0);
  return output;
}

enum class Defect { none, orientation_shape, orientation_not_unit, orientation_nan, foreign_orientation, bad_components,
                    action_out_of_table, action_names_missing, action_props_short, action_shape };

// 2 frames × 2 agents by hand, agent 6 absent at frame 1, with orientation and action elements and one defect.
void write_by_hand(const std::filesystem::path& path, Defect d) {
  h5::File f = h5::File::create(path);
  {
    const h5::Group root = f.root();
    root.create_group("h5md").set_attribute("version", std::vector<std::int32_t>{1, 1});
    const h5::Group traj = root.create_group("particles").create_group("trajectory");
    const h5::Group pos = traj.create_group("position");
    const double nan = std::nan("");
    pos.write("value", std::vector<double>{0, 0, 0, 1, 0, 0, 0.1, 0, 0, nan, nan, nan}, {2, 2, 3});
    pos.write("time", std::vector<double>{0, 1}, {2});
    pos.write("step", std::vector<std::int64_t>{0, 1}, {2});
    traj.create_group("id").write("value", std::vector<std::int64_t>{5, 6, 5, -1}, {2, 2});
    const h5::Group o = traj.create_group("orientation");
    if (d != Defect::foreign_orientation) {
      o.set_attribute("components", d == Defect::bad_components ? std::vector<std::string>{"w", "x", "y", "z"}
                                                                 : std::vector<std::string>{"x", "y", "z", "w"});
    }
    std::vector<double> q{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, std::sin(0.2), std::cos(0.2), nan, nan, nan, nan};
    if (d == Defect::orientation_not_unit) q[10] = 0.5;
    if (d == Defect::orientation_nan) q[0] = nan;
    if (d == Defect::foreign_orientation) q[3] = 7;  // not ours: never read, so never refused
    if (d == Defect::orientation_shape) o.write("value", std::vector<double>(12, 0.0), {2, 2, 3});
    else o.write("value", q, {2, 2, 4});
    const h5::Group a = traj.create_group("action");
    if (d != Defect::action_names_missing) a.set_attribute("names", std::vector<std::string>{"walk", "stand", "run"});
    a.set_attribute("props", d == Defect::action_props_short ? std::vector<std::string>{"", ""} : std::vector<std::string>{"", "", ""});
    std::vector<std::int32_t> actions{0, 1, 2, -1};
    if (d == Defect::action_out_of_table) actions[2] = 3;
    if (d == Defect::action_shape) a.write("value", std::vector<std::int32_t>{0, 1}, {2});
    else a.write("value", actions, {2, 2});
  }
  f.close();
}

}  // namespace

TEST_CASE("facing and actions round-trip through the crowd file, bit for bit where present") {
  const auto dir = test::scratch_dir("io_pose_roundtrip");
  const CrowdFile f = posed_crowd();
  write_crowd_file(dir / "crowd.h5", f);
  const CrowdFile g = read_crowd_file(dir / "crowd.h5");
  CHECK(test::same_crowd(f, g));
  REQUIRE(g.motion.orientations.size() == f.motion.orientations.size());
  REQUIRE(g.motion.actions.size() == f.motion.actions.size());
  CHECK(g.motion.action_table == f.motion.action_table);
  const CrowdMotion &m = f.motion, &r = g.motion;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      INFO("frame " << t << " agent " << n);
      if (m.present(t, n)) {
        CHECK(std::memcmp(r.orientation(t, n).coeffs().data(), m.orientation(t, n).coeffs().data(), 4 * sizeof(double)) == 0);
        CHECK(r.action(t, n) == m.action(t, n));
      } else {
        CHECK(std::isnan(r.orientation(t, n).w()));  // stored masked as positions are
        CHECK(r.action(t, n) == -1);
      }
    }
  }
}

TEST_CASE("a crowd without facing or actions writes neither element and reads back without them") {
  const auto dir = test::scratch_dir("io_pose_absent");
  write_crowd_file(dir / "crowd.h5", test::rich_crowd());
  const CrowdFile g = read_crowd_file(dir / "crowd.h5");
  CHECK(g.motion.orientations.empty());
  CHECK(g.motion.actions.empty());
  CHECK(g.motion.action_table.empty());
  const h5::File file = h5::File::open(dir / "crowd.h5");
  CHECK_FALSE(file.root().has("particles/trajectory/orientation"));
  CHECK_FALSE(file.root().has("particles/trajectory/action"));
}

TEST_CASE("h5py reads the pose elements as documented: shared step and time, masked where absent, one name table") {
  const auto dir = test::scratch_dir("io_pose_h5py");
  write_crowd_file(dir / "crowd.h5", posed_crowd());
  const std::string out = python_check(dir, R"(
import h5py, numpy as np, sys
f = h5py.File(sys.argv[1] + '/crowd.h5', 'r')
t = f['particles/trajectory']
o, a, ids = t['orientation/value'], t['action/value'], t['id/value'][:]
assert o.shape == (5, 4, 4) and o.dtype == np.float64, (o.shape, o.dtype)
assert a.shape == (5, 4) and a.dtype == np.int32, (a.shape, a.dtype)
for name in ('orientation', 'action'):
    for link in ('step', 'time'):
        assert t[name + '/' + link] == t['position/' + link], (name, link)   # the same object: hard links
assert [s.decode() if isinstance(s, bytes) else s for s in t['orientation'].attrs['components']] == ['x', 'y', 'z', 'w']
names = [s.decode() if isinstance(s, bytes) else s for s in t['action'].attrs['names']]
props = [s.decode() if isinstance(s, bytes) else s for s in t['action'].attrs['props']]
assert names == ['walk', 'stand', 'run', 'bow', 'walk'] and props == ['', '', '', '', 'umbrella'], (names, props)
absent = ids < 0
assert absent.sum() == 3
assert np.isnan(o[:][absent]).all() and (a[:][absent] == -1).all()
q = o[:][~absent]
assert np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-15)
assert ((a[:][~absent] >= 0) & (a[:][~absent] < len(names))).all()
print('ok')
)");
  CHECK_THAT(out, Catch::Matchers::Contains("ok"));
}

TEST_CASE("MDAnalysis reads files with the pose elements and files without them alike") {
  const auto dir = test::scratch_dir("io_pose_mdanalysis");
  // MDAnalysis has no notion of presence: every agent present at every frame.
  CrowdFile with = posed_crowd();
  CrowdMotion& m = with.motion;
  for (std::size_t t = 0; t < m.frame_count(); ++t) {
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      m.position(t, n) = Eigen::Vector3d(n + 0.25 * t, 2.0 * n - t, 0.0);
      m.orientation(t, n) = facing_along(Eigen::Vector3d(1, static_cast<double>(n), 0));
      m.action(t, n) = action_walk;
    }
  }
  m.velocities.clear();
  write_crowd_file(dir / "with.h5", with);
  CrowdFile without = with;
  without.motion.orientations.clear();
  without.motion.actions.clear();
  without.motion.action_table.clear();
  write_crowd_file(dir / "without.h5", without);
  const std::string out = python_check(dir, R"(
import sys, warnings
warnings.filterwarnings('ignore')
import numpy as np
from MDAnalysis.coordinates.H5MD import H5MDReader
for name in ('with.h5', 'without.h5'):
    r = H5MDReader(sys.argv[1] + '/' + name, convert_units=False)
    assert r.n_frames == 5 and r.n_atoms == 4, (name, r.n_frames, r.n_atoms)
    for i, ts in enumerate(r):
        for n in range(4):
            assert np.allclose(ts.positions[n], [n + 0.25 * i, 2.0 * n - i, 0.0], atol=1e-5), (name, i, n, ts.positions[n])
print('ok')
)");
  CHECK_THAT(out, Catch::Matchers::Contains("ok"));
}

TEST_CASE("a file's pose elements are read where present and refused by name where malformed") {
  const auto dir = test::scratch_dir("io_pose_errors");
  const auto path = dir / "crowd.h5";

  write_by_hand(path, Defect::none);
  const CrowdFile good = read_crowd_file(path);
  REQUIRE(good.motion.orientations.size() == 16);
  CHECK(good.motion.orientation(1, 0).z() == std::sin(0.2));
  CHECK(good.motion.actions == std::vector<std::int32_t>{0, 1, 2, -1});
  CHECK(good.motion.action_table == standard_actions());

  write_by_hand(path, Defect::foreign_orientation);
  CHECK(read_crowd_file(path).motion.orientations.empty());  // another program's convention: not read

  const std::vector<std::pair<Defect, std::string>> cases{
      {Defect::orientation_shape, "orientation/value: has shape [2][2][3], expected [2][2][4]"},
      {Defect::orientation_not_unit, "orientation/value: agent 5 (column 0) at frame 1 is present but its orientation is not a finite unit quaternion"},
      {Defect::orientation_nan, "orientation/value: agent 5 (column 0) at frame 0"},
      {Defect::bad_components, "orientation: attribute components is not"},
      {Defect::action_out_of_table, "action/value: agent 5 (column 0) at frame 1 has action 3, expected 0..2"},
      {Defect::action_names_missing, "action: attribute names (the action table) is missing"},
      {Defect::action_props_short, "action: attribute props has 2 entries for 3 names"},
      {Defect::action_shape, "action/value: has rank 1, expected 2"},
  };
  for (const auto& [defect, message] : cases) {
    INFO(message);
    write_by_hand(path, defect);
    CHECK_THROWS_AS_WITH(read_crowd_file(path), InputError, Catch::Contains(message));
  }
}
