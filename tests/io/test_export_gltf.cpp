// The .glb imported by Blender (Debian's blender, headless): one object per agent with its id and species,
// the animation's length, and at sampled frames each agent's position, heading and (when absent) hidden.
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/export/gltf.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

using namespace throng;

namespace {

// Imports the .glb at 25 fps (the crowd's rate, so crowd frame k is a whole Blender frame) and prints per agent
// object its custom properties, and at each requested frame its location, scale and the heading of its proxy's
// tip (the one bottom vertex farthest from the agent's axis).
const char* blender_script = R"(
import sys, math, bpy
args = sys.argv[sys.argv.index('--') + 1:]
path, frames = args[0], [int(f) for f in args[1:]]
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.context.scene.render.fps = 25
bpy.context.scene.render.fps_base = 1
# Debian 12's Blender 3.4 importer fails in its default shading guess ('NORMALS': np.bool, gone from NumPy 1.24);
# the proxy has no normals, so flat shading is what that guess gives anyway.
bpy.ops.import_scene.gltf(filepath=path, import_shading='FLAT')
agents = sorted([o for o in bpy.context.scene.objects if o.name.startswith('agent_')], key=lambda o: o['id'])
print('objects', len(bpy.context.scene.objects), 'agents', len(agents))
ends = [o.animation_data.action.frame_range[1] for o in agents if o.animation_data and o.animation_data.action]
starts = [o.animation_data.action.frame_range[0] for o in agents if o.animation_data and o.animation_data.action]
print('range', min(starts), max(ends))
for o in agents:
    print('agent', o['id'], o['species'], repr(o['radius']))
for f in frames:
    bpy.context.scene.frame_set(f)
    for o in agents:
        m = o.matrix_world
        loc = m.translation
        verts = [m @ v.co for v in o.data.vertices]
        bottom = min(v.z for v in verts)
        base = [v for v in verts if abs(v.z - bottom) < 1e-4]
        tip = max(base, key=lambda v: (v.x - loc.x) ** 2 + (v.y - loc.y) ** 2)
        heading = math.atan2(tip.y - loc.y, tip.x - loc.x)
        print('pose', f, o['id'], repr(loc.x), repr(loc.y), repr(loc.z), repr(o.matrix_world.to_scale().x), repr(heading))
)";

struct Pose {
  Eigen::Vector3d position;
  double scale, heading;
};

struct Imported {
  std::size_t objects = 0, agents = 0;
  double first_frame = 0, last_frame = 0;
  std::map<std::int64_t, std::pair<int, double>> species_radius;
  std::map<std::pair<int, std::int64_t>, Pose> poses;  // (blender frame, id)
};

Imported import_in_blender(const std::filesystem::path& dir, const std::filesystem::path& glb, const std::vector<int>& frames) {
  std::ofstream(dir / "blender_check.py") << blender_script;
  std::string command = "blender -b --factory-startup --python " + (dir / "blender_check.py").string() + " -- " + glb.string();
  for (const int f : frames) command += " " + std::to_string(f);
  const std::string out = test::run_tool(command + " 2>&1");
  Imported seen;
  std::istringstream lines(out);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::string key, word;
    in >> key;
    if (key == "objects") in >> seen.objects >> word >> seen.agents;
    if (key == "range") in >> seen.first_frame >> seen.last_frame;
    if (key == "agent") {
      std::int64_t id;
      int species;
      double radius;
      in >> id >> species >> radius;
      seen.species_radius[id] = {species, radius};
    }
    if (key == "pose") {
      int frame;
      std::int64_t id;
      Pose p;
      in >> frame >> id >> p.position.x() >> p.position.y() >> p.position.z() >> p.scale >> p.heading;
      seen.poses[{frame, id}] = p;
    }
  }
  INFO(out);
  REQUIRE(seen.agents > 0);
  return seen;
}

// Angle between two headings, in (−π, π].
double turn(double a, double b) { return std::remainder(a - b, 2 * EIGEN_PI); }

}  // namespace

TEST_CASE("Blender imports the glb: one object per agent, the animation's length, positions and headings") {
  const auto dir = test::scratch_dir("export_gltf");
  for (const bool posed : {true, false}) {
    INFO((posed ? "stored facing" : "facing derived from the paths"));
    const CrowdFile crowd = posed ? test::posed_export_crowd() : test::export_crowd();
    const CrowdMotion& m = crowd.motion;
    export_gltf(crowd, dir / "crowd.glb");
    // Crowd frame k is at (t_k − t_0) = k / 25 s: Blender frame k at 25 fps.
    const std::vector<int> frames{2, 12, 24};
    const Imported seen = import_in_blender(dir, dir / "crowd.glb", frames);
    CHECK(seen.objects == m.agent_count());
    CHECK(seen.agents == m.agent_count());
    CHECK(seen.first_frame == 0);
    CHECK(seen.last_frame == static_cast<double>(m.frame_count() - 1));
    PathFacing derived(m);
    for (std::size_t n = 0; n < m.agent_count(); ++n) {
      INFO("agent " << m.ids[n]);
      CHECK(seen.species_radius.at(m.ids[n]).first == m.species[n]);
      CHECK(seen.species_radius.at(m.ids[n]).second == m.radii[n]);
      for (const int f : frames) {
        INFO("frame " << f);
        const auto t = static_cast<std::size_t>(f);
        const Pose& p = seen.poses.at({f, m.ids[n]});
        if (!m.present(t, n)) {
          CHECK(p.scale == 0);  // hidden
          continue;
        }
        // Single precision in the file: positions to a few 1e-7 m of these 10 m coordinates.
        CHECK((p.position - m.position(t, n)).norm() < 1e-5);
        CHECK(std::abs(p.scale - m.radii[n]) < 1e-6);
        const Eigen::Quaterniond q = posed ? Eigen::Quaterniond(m.orientation(t, n)) : derived.at(t, n);
        const Eigen::Vector3d forward = q * Eigen::Vector3d::UnitX();
        CHECK(std::abs(turn(p.heading, std::atan2(forward.y(), forward.x()))) < 1e-5);
      }
    }
    // Agent 30 stands from frame 10 on: its heading at frame 24 is the one it had when it stopped.
    if (!posed) CHECK(std::abs(turn(seen.poses.at({24, 30}).heading, seen.poses.at({2, 30}).heading)) < 1e-5);
  }
}

TEST_CASE("a crowd with no frames or no agents is refused, leaving no file") {
  const auto dir = test::scratch_dir("export_gltf_empty");
  CrowdFile empty;
  CHECK_THROWS_AS(export_gltf(empty, dir / "crowd.glb"), InputError);
  CHECK(test::files_in(dir).empty());
}
