// JuPedSim/PedPy HDF5 trajectories (the Pedestrian Dynamics Data Archive layout, as io/export/pedpy.h writes it):
// /trajectory compound rows {frame, id, x, y, z, ...} with attribute fps; the root attribute wkt_geometry, the
// walkable area as one WKT polygon with holes, becomes obstacles: each hole a convex polygon obstacle when it is
// convex (how the export draws circles and walls: convex polygons around them), otherwise walls along its edges;
// the outer ring walls along its edges (the area's boundary: people do not leave it).
#include "import_readers.h"
#include "track_rows.h"

#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/hdf5.h>

#include <boost/geometry/algorithms/correct.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>
#include <boost/geometry/io/wkt/read.hpp>

#include <algorithm>
#include <cmath>

namespace throng::detail {
namespace {

namespace bg = boost::geometry;
using Point = bg::model::d2::point_xy<double>;
using Polygon = bg::model::polygon<Point, false>;  // counter-clockwise outer rings, closed

// The ring's vertices counter-clockwise without the closing repeat, collinear vertices kept.
std::vector<Eigen::Vector2d> vertices_ccw(const std::vector<Point>& ring) {
  std::vector<Eigen::Vector2d> v;
  for (const Point& p : ring) v.emplace_back(p.x(), p.y());
  if (v.size() > 1 && v.front() == v.back()) v.pop_back();
  double area = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % v.size()];
    area += a.x() * b.y() - b.x() * a.y();
  }
  if (area < 0) std::reverse(v.begin(), v.end());
  return v;
}

bool convex(const std::vector<Eigen::Vector2d>& v) {
  if (v.size() < 3) return false;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d a = v[(i + 1) % v.size()] - v[i], b = v[(i + 2) % v.size()] - v[(i + 1) % v.size()];
    if (a.x() * b.y() - a.y() * b.x() < -1e-12 * (a.norm() * b.norm())) return false;
  }
  return true;
}

void add_walls(Scene& scene, const std::vector<Eigen::Vector2d>& v, double thickness, const std::string& name, int& walls) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % v.size()];
    if (a != b) scene.obstacles.push_back({Wall{a, b, thickness}, {}, name + " " + std::to_string(++walls)});
  }
}

Scene scene_from_wkt(const std::string& wkt, double wall_thickness, const std::string& where) {
  Polygon area;
  try {
    bg::read_wkt(wkt, area);
  } catch (const std::exception& e) {
    throw InputError(where + ": not a WKT POLYGON (" + std::string(e.what()).substr(0, 200) + ")");
  }
  bg::correct(area);
  Scene scene;
  int walls = 0, holes = 0;
  add_walls(scene, vertices_ccw(area.outer()), wall_thickness, "boundary wall", walls);
  for (const auto& inner : area.inners()) {
    const auto v = vertices_ccw(inner);
    if (convex(v)) scene.obstacles.push_back({ConvexPolygon{v}, {}, "obstacle " + std::to_string(++holes)});
    else add_walls(scene, v, wall_thickness, "obstacle " + std::to_string(++holes) + " wall", walls);
  }
  scene.validate(where);
  return scene;
}

}  // namespace

ImportedCrowd read_pedpy(const std::filesystem::path& path, const ImportOptions& options, const ReadLimits& limits) {
  const std::string source = path.string();
  const h5::File file = h5::File::open(path, limits);
  const h5::Group root = file.root();
  const std::optional<double> stated = root.double_attribute_on("trajectory", "fps");
  if (stated && !(*stated > 0 && std::isfinite(*stated))) throw InputError(root.where("trajectory") + " attribute fps: not a number > 0");
  const double scale = metres_per_unit(options.units, 1.0);
  const auto frames = root.read_compound_member("trajectory", "frame");
  const auto ids = root.read_compound_member("trajectory", "id");
  const auto xs = root.read_compound_member("trajectory", "x");
  const auto ys = root.read_compound_member("trajectory", "y");
  const std::vector<std::string> members = root.compound_members("trajectory");
  const bool has_z = std::find(members.begin(), members.end(), "z") != members.end();
  const auto zs = has_z ? root.read_compound_member("trajectory", "z") : h5::Array<double>{};
  const std::size_t count = frames.values.size();
  // The rows and the motion built from them are charged to the file's budget, beside the columns still held.
  MemoryBudget& budget = root.budget();
  budget.charge(checked_product(count, sizeof(TrackRow)).value_or(UINT64_MAX), source, std::to_string(count) + " rows");
  std::vector<TrackRow> rows;
  rows.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const std::string where = root.where("trajectory") + " row " + std::to_string(i);
    auto finite = [&](double v, const char* what) {
      if (!std::isfinite(v)) throw InputError(where + ": " + what + " is not finite");
      return scale * v;
    };
    rows.push_back({static_cast<double>(whole_id(frames.values[i], std::to_string(frames.values[i]), where, "frame")),
                    whole_id(ids.values[i], std::to_string(ids.values[i]), where, "id"), finite(xs.values[i], "x"),
                    finite(ys.values[i], "y"), has_z ? finite(zs.values[i], "z") : 0.0});
  }
  const double fps = resolve_fps(stated.value_or(0.0), options.fps, source, "its /trajectory attribute fps");
  ImportedCrowd out{CrowdFile{}, ImportFormat::pedpy, {}};
  out.crowd.motion = motion_from_rows(rows, 1.0 / fps, options.radius, budget, source);
  for (const std::string& m : members) {
    if (m != "frame" && m != "id" && m != "x" && m != "y" && m != "z") {
      out.notes.push_back("/trajectory member '" + m + "' is not imported" +
                          (m == "ox" || m == "oy" ? " (facing: throng derives it from the motion)" : ""));
    }
  }
  if (const auto wkt = root.string_attribute("wkt_geometry"); wkt && !wkt->empty()) {
    out.crowd.scene = scene_from_wkt(*wkt, options.wall_thickness, source + " attribute wkt_geometry");
  }
  return out;
}

}  // namespace throng::detail
