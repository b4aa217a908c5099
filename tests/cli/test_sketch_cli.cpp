// throng sketch: the stroke-driven crowd job as a user runs it, its job file, and the example configs.
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>
#include <throng/io/sketch_job.h>

#include <catch2/catch.hpp>
#include <cstring>
#include <fstream>

#include "scenes.h"
#include "cli.h"
#include "test_paths.h"

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

using test::config;

// A small valid job: a 20 m course, 8 agents, a pillar; `extra` is appended (more keys).
std::string small_job(const std::string& extra = {}) {
  return "strokes:\n"
         "  main: [[0, 0, 0], [10, 0, 8], [20, 0, 16]]\n"
         "  auxiliary:\n"
         "    - [[0, 3], [20, 3]]\n"
         "    - [[0, -3], [20, -3]]\n"
         "agents: {count: 8}\n"
         "duration: 6\n"
         "obstacles:\n"
         "  - circle: {center: [12, 0], radius: 1}\n" +
         extra;
}

using test::write_file;

bool only_inputs_left(const std::filesystem::path& dir) {
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".yaml") return false;
  }
  return true;
}

using test::same_bits;

}  // namespace

TEST_CASE("the paper experiment config makes a crowd file that reads back with its strokes and parameters") {
  const auto dir = test::scratch_dir("cli_sketch_paper");
  const auto out = dir / "paper.h5";
  std::string report;
  REQUIRE(run("--quiet --json sketch " + config("sketch-paper.yaml") + " -o " + out.string(), &report) == 0);
  CHECK_THAT(report, Contains("\"agents\": 50") && Contains("\"arrived\": 50"));
  const CrowdFile f = read_crowd_file(out);
  CHECK(f.motion.agent_count() == 50);
  CHECK(f.motion.frame_count() > 24 * 60);
  CHECK_NOTHROW(f.motion.validate("paper.h5"));
  CHECK_THAT(f.provenance.options, Contains("smoothing_window: 5") && Contains("end_of_path: stop"));
  const h5::File file = h5::File::open(out);
  const h5::Group sketch = open_throng_parameters(file).open_group("sketch");
  const auto speed = sketch.open_group("course").read_doubles("speed", 1);
  const auto main = sketch.open_group("strokes").read_doubles("main", 2);
  CHECK(speed.shape == std::vector<std::uint64_t>{main.shape[0]});  // one speed per drawn main-line point here
  CHECK(sketch.open_group("agents").read_doubles("weights", 2).shape == std::vector<std::uint64_t>{50, 3});
}

TEST_CASE("a real sketch output opens in h5py and MDAnalysis, and keeps auxiliary time stamps") {
  // Auxiliary lines given with times keep them in the file ([x, y, t]); lines without stay [x, y]. The crowd is
  // read by readers nobody here wrote: frame and agent counts, positions (against our reader), times.
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());  // python3-h5py and python3-mdanalysis, installed by scripts/install-deps
  const auto dir = test::scratch_dir("cli_sketch_readers");
  write_file(dir / "job.yaml",
             "strokes:\n"
             "  main: [[0, 0, 0], [10, 0, 8], [20, 0, 16]]\n"
             "  auxiliary:\n"
             "    - [[0, 3, 0.5], [10, 3.5, 7], [20, 3, 15.25]]\n"
             "    - [[0, -3], [20, -3]]\n"
             "agents: {count: 8}\n"
             "duration: 6\n"
             "output_rate: 5\n");
  const auto out = dir / "crowd.h5";
  REQUIRE(run("--quiet sketch " + (dir / "job.yaml").string() + " -o " + out.string()) == 0);
  {
    const h5::File file = h5::File::open(out);
    const h5::Group strokes = open_throng_parameters(file).open_group("sketch").open_group("strokes");
    const auto timed = strokes.read_doubles("auxiliary_0", 2);
    CHECK(timed.shape == std::vector<std::uint64_t>{3, 3});
    CHECK(timed.values == std::vector<double>{0, 3, 0.5, 10, 3.5, 7, 20, 3, 15.25});
    CHECK(strokes.read_doubles("auxiliary_1", 2).shape == std::vector<std::uint64_t>{2, 2});
  }
  const CrowdFile ours = read_crowd_file(out);
  REQUIRE(ours.motion.frame_count() == 31);
  // Our reader's positions of agent 3 at frames 0, 10 and 30, for the other readers to match.
  std::string expected;
  for (std::size_t f : {0, 10, 30}) {
    const Eigen::Vector3d p = ours.motion.position(f, 3);
    expected += "(" + std::to_string(f) + ", [" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", 0]), ";
  }
  std::ofstream(dir / "check.py") << "import sys, warnings\nwarnings.filterwarnings('ignore')\n"
                                     "import h5py, numpy as np\n"
                                     "from MDAnalysis.coordinates.H5MD import H5MDReader\n"
                                     "path = sys.argv[1]\n"
                                     "expected = [" + expected + "]\n"
                                     R"(
f = h5py.File(path, 'r')
p = f['particles/trajectory/position/value']
assert p.shape == (31, 8, 3), p.shape
assert np.allclose(f['particles/trajectory/position/time'][:], np.arange(31) / 5.0)
assert (f['particles/trajectory/id/value'][:] == np.arange(8)).all()
for frame, position in expected:
    assert np.allclose(p[frame, 3], position, atol=1e-5), (frame, p[frame, 3], position)
r = H5MDReader(path, convert_units=False)
assert r.n_frames == 31 and r.n_atoms == 8, (r.n_frames, r.n_atoms)
for frame, position in expected:
    ts = r[frame]
    assert np.allclose(ts.positions[3], position, atol=1e-4), (frame, ts.positions[3], position)
    assert abs(ts.time - frame / 5.0) < 1e-9, ts.time
print('ok')
)";
  std::string output;
  CHECK(test::run_command(python + " " + (dir / "check.py").string() + " " + out.string(), &output) == 0);
  INFO(output);
  CHECK_THAT(output, Contains("ok"));
}

TEST_CASE("throng sketch on the shipped paper config writes facing and actions that h5py reads") {
  // The simulation's facing (sketch.h "Facing and actions") in the file: particles/trajectory/orientation and
  // action beside position, read with h5py: unit quaternions about +z, a standing agent's facing unchanged,
  // walking agents facing the way they move over the second around the frame, actions walk/stand/run.
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());  // python3-h5py, installed by scripts/install-deps
  const auto dir = test::scratch_dir("cli_sketch_facing");
  const auto out = dir / "paper.h5";
  REQUIRE(run("--quiet sketch " + config("sketch-paper.yaml") + " -o " + out.string()) == 0);
  std::ofstream(dir / "check.py") << R"(import sys, h5py, numpy as np
f = h5py.File(sys.argv[1], 'r')
t = f['particles/trajectory']
p = t['position/value'][:]
q = t['orientation/value'][:]
a = t['action/value'][:]
assert q.shape == p.shape[:2] + (4,), q.shape
assert a.shape == p.shape[:2], a.shape
assert list(t['orientation'].attrs['components']) in (['x', 'y', 'z', 'w'], [b'x', b'y', b'z', b'w'])
names = [n.decode() if isinstance(n, bytes) else n for n in t['action'].attrs['names']]
assert names[:3] == ['walk', 'stand', 'run'], names
present = np.isfinite(p[:, :, 0])
assert np.allclose(np.linalg.norm(q[present], axis=1), 1, atol=1e-9)
assert np.allclose(q[present][:, :2], 0)
assert ((a[present] >= 0) & (a[present] <= 2)).all()
yaw = 2 * np.arctan2(q[..., 2], q[..., 3])
turn = np.angle(np.exp(1j * (yaw[1:] - yaw[:-1])))
standing = (a[1:] == 1) & present[1:] & present[:-1]
assert standing.sum() > 1000, standing.sum()
assert np.abs(turn[standing]).max() < 1e-9, np.abs(turn[standing]).max()
rate = float(1 / (f['particles/trajectory/position/time'][1] - f['particles/trajectory/position/time'][0]))
k = int(round(rate / 2))  # the walking direction: where the agent goes over the second around the frame
ahead = p[2 * k:] - p[:-2 * k]
walking = (a[k:-k] == 0) & present[2 * k:] & present[:-2 * k] & (np.linalg.norm(ahead[..., :2], axis=2) > 0.3 * 2 * k / rate)
heading = np.arctan2(ahead[..., 1], ahead[..., 0])
off = np.abs(np.angle(np.exp(1j * (yaw[k:-k] - heading))))[walking]
assert walking.sum() > 10000, walking.sum()
# Jostled agents in the dense parts turn their facing slowly (by design), hence the percentile, not the maximum.
assert np.median(off) < np.radians(3) and np.percentile(off, 90) < np.radians(15), (np.median(off), np.percentile(off, 90))
print('ok', walking.sum(), standing.sum(), np.degrees(np.median(off)))
)";
  std::string output;
  CHECK(test::run_command(python + " " + (dir / "check.py").string() + " " + out.string(), &output) == 0);
  INFO(output);
  CHECK_THAT(output, Contains("ok"));
}

TEST_CASE("facing written by sketch goes through transform, edit and collide") {
  // The sketch's facing and actions carried by the commands that change paths (issue 13): transform turns every
  // facing by its rotation; edit and collide keep each agent's angle between facing and path where it moves, at
  // most 270°/s (carried_max_turn_rate).
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());  // python3-h5py, installed by scripts/install-deps
  const auto dir = test::scratch_dir("cli_sketch_facing_carried");
  write_file(dir / "job.yaml", small_job());
  // The guard off: the facing is compared with the input's at the same frames (edit's guard would slow the 4 m
  // drag of the last frame down, adding frames).
  write_file(dir / "edit.yaml", "guard: {enabled: false}\ndrags:\n  - {frames: [0, 0]}\n  - {frames: [end, end], offset: [0, 4]}\n");
  const auto crowd = dir / "crowd.h5";
  REQUIRE(run("--quiet sketch " + (dir / "job.yaml").string() + " -o " + crowd.string()) == 0);
  REQUIRE(run("--quiet transform " + crowd.string() + " --rotate 90 -o " + (dir / "turned.h5").string()) == 0);
  REQUIRE(run("--quiet edit " + crowd.string() + " --job " + (dir / "edit.yaml").string() + " -o " + (dir / "edited.h5").string()) == 0);
  REQUIRE(run("--quiet collide " + crowd.string() + " --margin 0.6 --allow-remaining -o " + (dir / "collided.h5").string()) == 0);
  std::ofstream(dir / "check.py") << R"(import sys, h5py, numpy as np
def load(path):
    t = h5py.File(path, 'r')['particles/trajectory']
    p, q = t['position/value'][:], t['orientation/value'][:]
    return p, 2 * np.arctan2(q[..., 2], q[..., 3]), t['action/value'][:], t['position/time'][:]
def wrap(x):
    return np.angle(np.exp(1j * x))
def to_path(p, yaw, time):
    v = (p[2:] - p[:-2]) / (time[2:] - time[:-2])[:, None, None]
    moving = np.linalg.norm(v[..., :2], axis=2) >= 0.3
    return wrap(yaw[1:-1] - np.arctan2(v[..., 1], v[..., 0])), moving
d = sys.argv[1]
p, yaw, a, time = load(d + '/crowd.h5')
angle, moving = to_path(p, yaw, time)
tp, tyaw, ta, _ = load(d + '/turned.h5')
assert np.abs(wrap(tyaw - yaw - np.pi / 2)).max() < 1e-9
assert (ta == a).all()
for name, least_bend in (("edited", 0.1), ("collided", 0.01)):
    ep, eyaw, ea, etime = load(d + '/' + name + '.h5')
    eangle, emoving = to_path(ep, eyaw, etime)
    both = moving & emoving
    assert both.sum() > 500, (name, both.sum())
    # The angle to the path is kept where the carried turn is no faster than a person turns (270 deg/s); where
    # the path's direction swings faster the facing follows at that rate and catches up.
    kept = np.abs(wrap(eangle - angle))[both] < 1e-6
    assert kept.mean() > 0.9, (name, kept.mean())
    rate = np.abs(wrap(eyaw[1:] - eyaw[:-1])) / np.diff(etime)[:, None]
    assert rate.max() <= 1.5 * np.pi * (1 + 1e-6), (name, rate.max())
    assert np.abs(wrap(eyaw - yaw)).max() >= least_bend, (name, np.abs(wrap(eyaw - yaw)).max())
    assert ((ea >= 0) & (ea <= 2)).all()
print('ok')
)";
  std::string output;
  CHECK(test::run_command(python + " " + (dir / "check.py").string() + " " + dir.string(), &output) == 0);
  INFO(output);
  CHECK_THAT(output, Contains("ok"));
}

TEST_CASE("the sketch configs are the test scenes") {
  for (const auto& [file, scene] : {std::pair{"sketch-paper.yaml", sketch::scenes::paper_experiment()},
                                    std::pair{"sketch-large.yaml", sketch::scenes::large_crowd()}}) {
    INFO(file);
    const sketch::Job job = read_job<sketch::Job>(ConfigNode::load_file(config(file)));
    REQUIRE(job.drawing.strokes.size() == scene.drawing.strokes.size());
    for (std::size_t i = 0; i < job.drawing.strokes.size(); ++i) {
      CHECK(job.drawing.strokes[i].points == scene.drawing.strokes[i].points);
      if (i == 0) CHECK(job.drawing.strokes[i].times == scene.drawing.strokes[i].times);
    }
    CHECK(job.scene.obstacles.size() == scene.scene.obstacles.size());
    const sketch::Options& a = job.options;
    const sketch::Options& b = scene.options;
    CHECK(a.agent_count == b.agent_count);
    CHECK(a.narrow_width_m == b.narrow_width_m);
    CHECK(a.wide_width_m == b.wide_width_m);
    CHECK(a.narrow_distance_m == b.narrow_distance_m);
    CHECK(a.wide_distance_m == b.wide_distance_m);
    CHECK(a.irregularity_max == b.irregularity_max);
    CHECK(a.output_rate_hz == b.output_rate_hz);
    CHECK(a.duration_s == b.duration_s);
    CHECK(a.smoothing_window == b.smoothing_window);
  }
}

TEST_CASE("the effective job reads back to the same job") {
  const sketch::Job job =
      read_job<sketch::Job>(ConfigNode::parse(small_job("end_of_path: remove\nweights: {avoid: 1.5}\n"), "job"));
  const sketch::Job again = read_job<sketch::Job>(ConfigNode::parse(to_yaml_text(effective_job(job)), "effective"));
  CHECK(again.options.end_of_path == sketch::EndOfPath::remove);
  CHECK(again.options.avoid_weight == 1.5);
  CHECK(again.options.duration_s == 6);
  CHECK(again.drawing.strokes[0].points == job.drawing.strokes[0].points);
  CHECK(again.drawing.strokes[0].times == job.drawing.strokes[0].times);
  CHECK(again.scene.obstacles.size() == 1);
}

TEST_CASE("1 thread and 2 threads give identical crowds from the large config") {
  const auto dir = test::scratch_dir("cli_sketch_threads");
  const std::string job = config("sketch-large.yaml") + " --set duration=3";
  REQUIRE(run("--quiet --threads 1 sketch " + job + " -o " + (dir / "one.h5").string()) == 0);
  REQUIRE(run("--quiet --threads 2 sketch " + job + " -o " + (dir / "two.h5").string()) == 0);
  const CrowdFile one = read_crowd_file(dir / "one.h5"), two = read_crowd_file(dir / "two.h5");
  CHECK(one.motion.agent_count() == 2000);
  CHECK(one.scene.obstacles.size() == 6);
  CHECK(same_bits(one.motion.positions, two.motion.positions));
}

TEST_CASE("1 thread and 2 threads write identical files for whole runs of the large config, stop and remove") {
  // Until every agent has arrived (past the pillars, kiosk, gate and cart; standing or removed at the end),
  // 1,000 agents (two parallel tasks per step). Every dataset and attribute must agree, bit for bit, except the
  // command line (it names the thread count and the output).
  const std::string python = test::system_python();
  REQUIRE_FALSE(python.empty());  // python3-h5py, installed by scripts/install-deps
  const auto dir = test::scratch_dir("cli_sketch_threads_whole");
  std::ofstream(dir / "compare.py") << R"(
import sys, h5py, numpy as np
a, b = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r')
def objects(f):
    names = ['/']
    f.visit(lambda name: names.append('/' + name))
    return names
def same(x, y):
    x, y = np.asarray(x), np.asarray(y)
    if x.dtype.kind in 'OSU' or y.dtype.kind in 'OSU':
        return x.shape == y.shape and x.tolist() == y.tolist()
    return x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()
problems, datasets, attributes = [], 0, 0
if objects(a) != objects(b):
    problems.append('objects differ: %s' % sorted(set(objects(a)) ^ set(objects(b))))
for name in objects(a):
    if name not in b:
        continue
    x, y = a[name], b[name]
    if isinstance(x, h5py.Dataset):
        datasets += 1
        if not same(x[()], y[()]):
            problems.append('dataset %s differs' % name)
    if sorted(x.attrs) != sorted(y.attrs):
        problems.append('attributes of %s differ: %s / %s' % (name, sorted(x.attrs), sorted(y.attrs)))
    for key in x.attrs:
        if key == 'command_line' or key not in y.attrs:
            continue
        attributes += 1
        if isinstance(x.attrs[key], h5py.Reference):
            continue  # object references point into their own file
        if not same(x.attrs[key], y.attrs[key]):
            problems.append('attribute %s of %s differs' % (key, name))
print('\n'.join(problems) if problems else 'identical: %d datasets, %d attributes' % (datasets, attributes))
)";
  for (const char* mode : {"stop", "remove"}) {
    INFO(mode);
    const std::string job = config("sketch-large.yaml") +
                            " --set duration=0 --set output_rate=2 --set agents.count=1000 --set end_of_path=" + mode;
    const auto one = dir / (std::string(mode) + "-1.h5"), two = dir / (std::string(mode) + "-2.h5");
    std::string report;
    REQUIRE(run("--quiet --json --threads 1 sketch " + job + " -o " + one.string(), &report) == 0);
    CHECK_THAT(report, Contains("\"arrived\": 1000"));
    REQUIRE(run("--quiet --threads 2 sketch " + job + " -o " + two.string()) == 0);
    std::string output;
    CHECK(test::run_command(python + " " + (dir / "compare.py").string() + " " + one.string() + " " + two.string(),
                            &output) == 0);
    INFO(output);
    CHECK_THAT(output, Contains("identical: "));
  }
  // The comparison can fail: the stop and remove runs differ in positions (NaN once removed) and options.
  std::string output;
  test::run_command(python + " " + (dir / "compare.py").string() + " " + (dir / "stop-1.h5").string() + " " +
                        (dir / "remove-1.h5").string(),
                    &output);
  CHECK_THAT(output, Contains("dataset /particles/trajectory/position/value differs") &&
                         Contains("attribute options of /parameters/throng differs"));
}

TEST_CASE("with --print-config the effective job is printed and nothing is written") {
  const auto dir = test::scratch_dir("cli_sketch_print");
  write_file(dir / "job.yaml", small_job());
  std::string out;
  REQUIRE(run("sketch " + (dir / "job.yaml").string() + " -o " + (dir / "out.h5").string() + " --print-config", &out) ==
          0);
  CHECK_THAT(out,
             Contains("time_step: 0.04") && Contains("follow_radius: 1") && Contains("main:") && Contains("circle:"));
  CHECK(only_inputs_left(dir));
}

TEST_CASE("bad jobs are config errors naming the key and line, and leave no output") {
  const auto dir = test::scratch_dir("cli_sketch_errors");
  struct Case {
    const char* name;
    std::string job;
    std::string message;
  };
  const std::vector<Case> cases{
      {"unknown key", small_job("smoothing_windw: 3\n"), "job.yaml:10:1: unknown key 'smoothing_windw'"},
      {"out of range", small_job("time_step: -1\n"), "job.yaml:10:12"},
      {"one point", "strokes: {main: [[0, 0, 0]], auxiliary: [[[0, 1], [5, 1]]]}\n", "the main line has 1 point(s)"},
      {"time not increasing",
       "strokes:\n  main: [[0, 0, 0], [5, 0, 2],\n         [9, 0, 2]]\n  auxiliary: [[[0, 1], [9, 1]]]\n",
       "job.yaml:3:10 (strokes.main[2]): the main line point 2 is drawn at 2 s, not after 2 s"},
      {"NaN", "strokes:\n  main: [[0, 0, 0], [5, .nan, 2]]\n  auxiliary: [[[0, 1], [9, 1]]]\n",
       "job.yaml:2:25 (strokes.main[1][1]): expected a finite number"},
      {"missing times", "strokes:\n  main: [[0, 0], [5, 0]]\n  auxiliary: [[[0, 1], [9, 1]]]\n",
       "expected 3 numbers, found 2"},
      {"zero-length stroke", "strokes:\n  main: [[0, 0, 0], [5, 0, 2]]\n  auxiliary: [[[1, 1], [1, 1]]]\n",
       "stroke 1 (auxiliary line) has zero length"},
      {"agent in an obstacle",
       "strokes: {main: [[0, 0, 0], [9, 0, 5]], auxiliary: [[[0, 2], [9, 2]]]}\n"
       "agents: {positions: [[3, 3], [0, 0.2]]}\n"
       "obstacles: [{circle: {center: [0, 0], radius: 0.5}, name: post}]\n",
       "agent 1 starts inside obstacle 0 ('post')"},
      {"bad end of path", small_job("end_of_path: vanish\n"), "unknown value 'vanish', expected one of: stop, remove"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    write_file(dir / "job.yaml", c.job);
    std::string out;
    CHECK(run("--quiet sketch " + (dir / "job.yaml").string() + " -o " + (dir / "out.h5").string(), &out) == 2);
    CHECK_THAT(out, Contains(c.message));
    CHECK(only_inputs_left(dir));
  }
}

TEST_CASE("a crowd that cannot finish within max_duration is written, and the exit code says so") {
  const auto dir = test::scratch_dir("cli_sketch_unfinished");
  const auto out = dir / "short.h5";
  std::string report;
  CHECK(run("--quiet sketch " + config("sketch-paper.yaml") + " --set max_duration=5 -o " + out.string(), &report) ==
        5);
  CHECK_THAT(report, Contains("had not reached the end of their path"));
  const CrowdFile f = read_crowd_file(out);
  CHECK(f.motion.times.back() == Approx(5.0));
  // With --json the report says what was missed, in a field of its own.
  std::string json;
  CHECK(run("--quiet --json sketch " + config("sketch-paper.yaml") + " --set max_duration=5 -o " + out.string(),
            &json) == 5);
  CHECK_THAT(json, Contains("\"arrived\": 0") &&
                       Contains("\"shortfall\": \"50 of 50 agents had not reached the end of their path after "
                                "max_duration = 5 s"));
}

TEST_CASE("job errors found only when the job is run still name the file and line, or the --set argument") {
  const auto dir = test::scratch_dir("cli_sketch_late_errors");
  const auto job = dir / "job.yaml";
  const auto out = dir / "out.h5";
  std::string message;
  SECTION("more agents than the course holds: at agents.count") {
    write_file(job, small_job("agents: {count: 5000}\n").replace(small_job().find("agents: {count: 8}\n"), 19, ""));
    CHECK(run("--quiet sketch " + job.string() + " -o " + out.string(), &message) == 2);
    CHECK_THAT(message, Contains("job.yaml:9:17 (agents.count): sketch option agent_count = 5000: only"));
    write_file(job, small_job());
    CHECK(run("--quiet sketch " + job.string() + " --set agents.count=5000 -o " + out.string(), &message) == 2);
    CHECK_THAT(message, Contains("--set agents.count=5000: sketch option agent_count = 5000: only"));
  }
  SECTION("frames that cannot fit in memory are refused before the run, naming the keys to change") {
    // 10^14 frames: 16 bytes each (their time and step) are 1.6 PB even written as they go, beyond any machine.
    write_file(job, small_job("output_rate: 1e7\nduration: 1e7\n").replace(small_job().find("duration: 6\n"), 12, ""));
    CHECK(run("--quiet sketch " + job.string() + " -o " + out.string(), &message) == 2);
    CHECK_THAT(message, Contains("job.yaml: up to 100000000000001 frames (duration 1e+07 s × output_rate 1e+07 Hz) of 8 "
                                 "agents need about 1.6e+06 GB of memory while written as they go") &&
                            Contains("lower output_rate, duration or agents.count"));
    CHECK(run("--quiet sketch " + config("sketch-paper.yaml") + " --set output_rate=1e7 --set max_duration=1e7 -o " +
                  out.string(),
              &message) == 2);
    CHECK_THAT(message, Contains("max_duration 1e+07 s") && Contains("lower output_rate, max_duration (or set a duration)"));
  }
  SECTION("values from --set are named as such, and unknown keys are offered only keys sketch takes") {
    write_file(job, small_job());
    CHECK(run("--quiet sketch " + job.string() + " --set time_step=-1 -o " + out.string(), &message) == 2);
    CHECK_THAT(message, Contains("--set time_step=-1: value -1 is out of range, expected > 0"));
    CHECK(run("--quiet sketch " + job.string() + " --set agents.count=-5 -o " + out.string(), &message) == 2);
    CHECK_THAT(message, Contains("--set agents.count=-5: value -5 is out of range, expected in [1, 1e+08]"));
    CHECK(run("--quiet sketch " + job.string() + " --set smoothing_windw=3 -o " + out.string(), &message) == 2);
    CHECK_THAT(message, Contains("--set smoothing_windw=3: unknown key 'smoothing_windw'") &&
                            Contains("smoothing_window") && Contains("obstacles"));
    CHECK_THAT(message, !Contains("region"));
    CHECK(run("--quiet sketch " + job.string() + " --set region.min=[0,0] -o " + out.string(), &message) == 2);
    CHECK_THAT(message, Contains("--set region.min=[0,0] (region): sketch does not use a region"));
  }
  CHECK(only_inputs_left(dir));
}

TEST_CASE("sketch is a step of throng run: a crowd from strokes, plotted, written") {
  const auto dir = test::scratch_dir("cli_sketch_run");
  write_file(dir / "strokes.yaml", small_job());
  write_file(dir / "pipeline.yaml",
             "steps:\n"
             "  - step: sketch\n"
             "    job: " +
                 (dir / "strokes.yaml").string() +
                 "\n"
                 "    duration: 4\n"
                 "    output: " +
                 (dir / "crowd.h5").string() +
                 "\n"
                 "  - step: plot\n"
                 "    output: " +
                 (dir / "crowd.svg").string() + "\n");
  REQUIRE(run("--quiet run " + (dir / "pipeline.yaml").string()) == 0);
  CHECK(std::filesystem::exists(dir / "crowd.svg"));
  const CrowdFile f = read_crowd_file(dir / "crowd.h5");
  CHECK(f.motion.agent_count() == 8);
  CHECK(f.motion.times.back() == Approx(4.0));
  const h5::File file = h5::File::open(dir / "crowd.h5");
  CHECK(open_throng_parameters(file).has("sketch"));
}
