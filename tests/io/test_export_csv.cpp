// The CSV tables read back with an RFC 4180 reader: every present agent and frame once, the numbers exactly as
// stored, the facing, the action and prop names (quoted where they hold commas and quotes), radius and species;
// the obstacles file with each obstacle's points.
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/io/export/csv_table.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

using namespace throng;

namespace {

// Rows of an RFC 4180 file (quoted fields may hold commas, doubled quotes and line breaks).
std::vector<std::vector<std::string>> read_csv_rows(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::vector<std::vector<std::string>> rows(1);
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
      else if (c == '"') quoted = false;
      else field += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().push_back(field), field.clear();
    } else if (c == '\n') {
      rows.back().push_back(field), field.clear();
      rows.emplace_back();
    } else {
      field += c;
    }
  }
  REQUIRE(rows.back().empty());  // the file ends with a line break
  rows.pop_back();
  return rows;
}

double number(const std::string& s) {
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  REQUIRE(r.ptr == s.data() + s.size());
  return v;
}

}  // namespace

TEST_CASE("the csv export holds one row per present agent and frame with every value as stored") {
  const auto dir = test::scratch_dir("export_csv");
  for (const bool posed : {true, false}) {
    INFO((posed ? "stored facing and actions" : "derived facing and actions"));
    const CrowdFile crowd = posed ? test::posed_export_crowd() : test::export_crowd();
    const CrowdMotion& m = crowd.motion;
    export_csv(crowd, dir / "crowd.csv");
    const auto rows = read_csv_rows(dir / "crowd.csv");
    REQUIRE(rows.front() == std::vector<std::string>{"frame", "time", "id", "x", "y", "z", "qx", "qy", "qz", "qw",
                                                     "heading_deg", "action", "prop", "radius", "species"});
    const auto& table = posed ? m.action_table : standard_actions();
    PathFacing derived(m);
    std::size_t r = 1;
    for (std::size_t t = 0; t < m.frame_count(); ++t) {
      for (std::size_t n = 0; n < m.agent_count(); ++n) {
        if (!m.present(t, n)) continue;
        INFO("frame " << t << " agent " << m.ids[n]);
        REQUIRE(r < rows.size());
        const auto& row = rows[r++];
        REQUIRE(row.size() == 15);
        CHECK(number(row[0]) == static_cast<double>(t));
        CHECK(number(row[1]) == m.times[t]);
        CHECK(number(row[2]) == static_cast<double>(m.ids[n]));
        for (int k = 0; k < 3; ++k) CHECK(number(row[3 + static_cast<std::size_t>(k)]) == m.position(t, n)[k]);
        const Eigen::Quaterniond q = posed ? Eigen::Quaterniond(m.orientation(t, n)) : derived.at(t, n);
        for (int k = 0; k < 4; ++k) CHECK(number(row[6 + static_cast<std::size_t>(k)]) == q.coeffs()[k]);
        const Eigen::Vector3d forward = q * Eigen::Vector3d::UnitX();
        CHECK(std::abs(number(row[10]) - std::atan2(forward.y(), forward.x()) * 180 / EIGEN_PI) < 1e-12);
        const ActionKind& action = table[static_cast<std::size_t>(posed ? m.action(t, n) : path_action(m, t, n))];
        CHECK(row[11] == action.name);
        CHECK(row[12] == action.prop);
        CHECK(number(row[13]) == m.radii[n]);
        CHECK(number(row[14]) == m.species[n]);
      }
    }
    CHECK(r == rows.size());
  }
}

TEST_CASE("the obstacles file lists each obstacle's points where they stand") {
  const auto dir = test::scratch_dir("export_csv_obstacles");
  CrowdFile crowd = test::export_crowd();
  // A moving obstacle: written where it stands at the crowd's first frame (t = 2 s: halfway along its path).
  crowd.scene.obstacles.push_back({Circle{{0, 0}, 0.3}, {{1.0, {0, 0}, 0}, {3.0, {2, 4}, 0}}, "cart"});
  export_csv(crowd, dir / "crowd.csv");
  CHECK(csv_obstacles_path(dir / "crowd.csv") == dir / "crowd_obstacles.csv");
  const auto rows = read_csv_rows(dir / "crowd_obstacles.csv");
  const std::vector<std::vector<std::string>> expected{
      {"obstacle", "name", "kind", "size", "point", "x", "y", "moving"},
      {"0", "pillar", "circle", "0.5", "0", "4", "6", "0"},
      {"1", "kiosk, \"north\"", "polygon", "0", "0", "8", "3", "0"},
      {"1", "kiosk, \"north\"", "polygon", "0", "1", "10", "3", "0"},
      {"1", "kiosk, \"north\"", "polygon", "0", "2", "10", "4", "0"},
      {"2", "fence", "wall", "0.2", "0", "-3", "-5", "0"},
      {"2", "fence", "wall", "0.2", "1", "13", "-5", "0"},
      {"3", "cart", "circle", "0.3", "0", "1", "2", "1"}};
  CHECK(rows == expected);

  crowd.scene.obstacles.clear();
  export_csv(crowd, dir / "bare.csv");
  CHECK(read_csv_rows(dir / "bare_obstacles.csv").size() == 1);  // the header alone
}

TEST_CASE("the Blender recipe of the export docs imports the csv: an object per agent at its positions and facings") {
  const auto dir = test::scratch_dir("export_csv_blender");
  const CrowdFile crowd = test::posed_export_crowd();
  const CrowdMotion& m = crowd.motion;
  export_csv(crowd, dir / "crowd.csv");
  // The recipe exactly as docs/commands/export.md gives it (a list item's code block, indented by two spaces).
  std::ifstream doc(test::source_dir() / "docs" / "commands" / "export.md");
  std::string line, recipe;
  bool inside = false;
  while (std::getline(doc, line)) {
    if (line == "  ```python") inside = true;
    else if (inside && line == "  ```") break;
    else if (inside) recipe += (line.size() >= 2 ? line.substr(2) : line) + "\n";
  }
  REQUIRE(recipe.find("/path/crowd.csv") != std::string::npos);
  recipe.replace(recipe.find("/path/crowd.csv"), 15, (dir / "crowd.csv").string());
  std::ofstream(dir / "recipe.py") << "import bpy, math\nbpy.ops.wm.read_factory_settings(use_empty=True)\n"
                                      "bpy.context.scene.render.fps = 25\n"
                                   << recipe << R"(
scene = bpy.context.scene
agents = sorted([o for o in scene.objects if o.name.startswith('agent_')], key=lambda o: int(o.name[6:]))
print('agents', len(agents))
for frame in (55, 60, 70):
    scene.frame_set(frame)
    for o in agents:
        arrow = o.matrix_world.to_3x3() @ mathutils.Vector((0, 0, 1))
        print('pose', frame, o.name[6:], repr(o.matrix_world.translation.x), repr(o.matrix_world.translation.y), repr(math.atan2(arrow.y, arrow.x)))
)";
  const std::string out = test::run_tool("blender -b --factory-startup --python " + (dir / "recipe.py").string() + " 2>&1");
  INFO(out);
  CHECK_THAT(out, Catch::Matchers::Contains("agents 6"));
  std::istringstream lines(out);
  std::size_t checked = 0;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::string key;
    int frame;
    std::int64_t id;
    double x, y, heading;
    if (!(in >> key) || key != "pose" || !(in >> frame >> id >> x >> y >> heading)) continue;
    const std::size_t t = static_cast<std::size_t>(frame - 50);  // time 2 s + k / 25 s is frame 50 + k at 25 fps
    const std::size_t n = static_cast<std::size_t>(std::find(m.ids.begin(), m.ids.end(), id) - m.ids.begin());
    if (!m.present(t, n)) continue;  // an absent agent holds its nearest key
    INFO("frame " << t << " agent " << id);
    CHECK(std::abs(x - m.position(t, n).x()) < 1e-5);
    CHECK(std::abs(y - m.position(t, n).y()) < 1e-5);
    const Eigen::Vector3d forward = Eigen::Quaterniond(m.orientation(t, n)) * Eigen::Vector3d::UnitX();
    CHECK(std::abs(std::remainder(heading - std::atan2(forward.y(), forward.x()), 2 * EIGEN_PI)) < 1e-5);
    ++checked;
  }
  CHECK(checked == 3 * 6 - 1);  // agent 50 has left by frame 20
}
