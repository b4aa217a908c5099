// The XDMF sidecar opened by ParaView (Debian's python3-paraview, pvpython): time steps, positions read back equal
// to the file's, absent agents, and the point data id, radius, species, orientation, facing and action.
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/io/export/xdmf.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using namespace throng;

namespace {

// pvpython: loads the sidecar with ParaView's XDMF Reader and prints what it sees at frame `frame`.
const char* paraview_script = R"(
import sys
from paraview.simple import XDMFReader
from paraview import servermanager
from vtk.numpy_interface import dataset_adapter as dsa
reader = XDMFReader(FileNames=[sys.argv[1]])
times = list(reader.TimestepValues)
print('steps', len(times))
print('times', ' '.join(repr(t) for t in times))
frame = int(sys.argv[2])
reader.UpdatePipeline(times[frame])
data = servermanager.Fetch(reader)
if data.IsA('vtkMultiBlockDataSet'):
    data = data.GetBlock(0)
w = dsa.WrapDataObject(data)
print('points', w.GetNumberOfPoints())
for p in w.Points:
    print('point', ' '.join(repr(float(v)) for v in p))
for name in sorted(w.PointData.keys()):
    for value in w.PointData[name]:
        flat = value.ravel() if hasattr(value, 'ravel') else [value]
        print('data', name, ' '.join(repr(float(v)) for v in flat))
)";

struct Seen {
  std::size_t steps = 0;
  std::vector<double> times;
  std::vector<std::vector<double>> points;
  std::map<std::string, std::vector<std::vector<double>>> data;
};

Seen open_in_paraview(const std::filesystem::path& dir, const std::filesystem::path& xmf, std::size_t frame) {
  std::ofstream(dir / "paraview_check.py") << paraview_script;
  const std::string out = test::run_tool("pvpython " + (dir / "paraview_check.py").string() + " " + xmf.string() + " " + std::to_string(frame) + " 2>&1");
  Seen seen;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::string key;
    in >> key;
    auto numbers = [&] {
      std::vector<double> v;
      std::string word;
      while (in >> word) v.push_back(word == "nan" ? std::nan("") : std::stod(word));
      return v;
    };
    if (key == "steps") in >> seen.steps;
    if (key == "times") seen.times = numbers();
    if (key == "point") seen.points.push_back(numbers());
    if (key == "data") {
      std::string name;
      in >> name;
      seen.data[name].push_back(numbers());
    }
  }
  INFO(out);
  REQUIRE(seen.steps > 0);
  return seen;
}

}  // namespace

TEST_CASE("ParaView opens the xdmf sidecar as a time series with the file's positions and point data") {
  const auto dir = test::scratch_dir("export_xdmf");
  const CrowdFile crowd = test::posed_export_crowd();
  write_crowd_file(dir / "crowd.h5", crowd);
  export_xdmf(dir / "crowd.h5", dir / "crowd.xmf");
  const CrowdMotion& m = crowd.motion;
  for (const std::size_t frame : {std::size_t{2}, std::size_t{17}}) {
    INFO("frame " << frame);
    const Seen seen = open_in_paraview(dir, dir / "crowd.xmf", frame);
    CHECK(seen.steps == m.frame_count());
    CHECK(seen.times == m.times);
    REQUIRE(seen.points.size() == m.agent_count());
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      INFO("agent " << m.ids[n]);
      const auto& p = seen.points[n];
      const auto& id = seen.data.at("id")[n];
      if (m.present(frame, n)) {
        CHECK(p == std::vector<double>{m.position(frame, n).x(), m.position(frame, n).y(), m.position(frame, n).z()});
        CHECK(id[0] == static_cast<double>(m.ids[n]));
        CHECK(seen.data.at("action")[n][0] == m.action(frame, n));
        const Eigen::Quaterniond q = m.orientation(frame, n);
        CHECK(seen.data.at("orientation")[n] == std::vector<double>{q.x(), q.y(), q.z(), q.w()});
        const Eigen::Vector3d facing = q * Eigen::Vector3d::UnitX();
        const auto& f = seen.data.at("facing")[n];
        CHECK(Eigen::Vector3d(f[0], f[1], f[2]).isApprox(facing, 1e-14));
      } else {
        CHECK(std::isnan(p[0]));
        CHECK(id[0] == -1);
        CHECK(seen.data.at("action")[n][0] == -1);
      }
      CHECK(seen.data.at("radius")[n][0] == m.radii[n]);
      CHECK(seen.data.at("species")[n][0] == m.species[n]);
    }
  }
}

TEST_CASE("a crowd file without stored facing or actions opens without those arrays") {
  const auto dir = test::scratch_dir("export_xdmf_plain");
  const CrowdFile crowd = test::export_crowd();
  std::filesystem::create_directories(dir / "data");
  write_crowd_file(dir / "data" / "crowd.h5", crowd);
  export_xdmf(dir / "data" / "crowd.h5", dir / "crowd.xmf");  // another folder: a relative reference
  const Seen seen = open_in_paraview(dir, dir / "crowd.xmf", 10);
  CHECK(seen.steps == crowd.motion.frame_count());
  CHECK(seen.data.count("facing") == 0);
  CHECK(seen.data.count("orientation") == 0);
  CHECK(seen.data.count("action") == 0);
  REQUIRE(seen.points.size() == crowd.motion.agent_count());
  CHECK(seen.points[1][0] == crowd.motion.position(10, 1).x());
}
