// throng export --format F and the pipeline's export step, run as a user would: each format's file is what the
// format says (light checks: tests/io/test_export_*.cpp open them in ParaView, Blender, a strict USD reader and
// h5py), the options reach the exporter, and every bad request exits with its code, a message and no file.
#include "cli.h"
#include "test_export_fixtures.h"
#include "test_paths.h"

#include <throng/io/crowd_file.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

using test::run;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// Runs a Python script with Debian's python3 (h5py) and returns what it prints; fails the test when it fails.
std::string python(const std::filesystem::path& dir, const std::string& script) {
  const auto path = test::write_file(dir / "check.py", script);
  const std::string out = test::run_tool(test::system_python() + " " + path.string());
  std::filesystem::remove(path);
  return out;
}

/// The fixture crowd (6 agents, 25 frames, 140 present agent-frames, three obstacles) written to dir/crowd.h5.
std::filesystem::path fixture(const std::filesystem::path& dir, bool obstacles = true) {
  CrowdFile f = test::export_crowd();
  if (!obstacles) f.scene.obstacles.clear();
  write_crowd_file(dir / "crowd.h5", f);
  return dir / "crowd.h5";
}

constexpr std::size_t fixture_rows = 140;
const char* csv_header = "frame,time,id,x,y,z,qx,qy,qz,qw,heading_deg,action,prop,radius,species";

/// The JSON chunk of a .glb, after checking its 12-byte header (magic "glTF", version 2, the file's length).
nlohmann::json glb_json(const std::filesystem::path& p) {
  const std::string bytes = slurp(p);
  REQUIRE(bytes.size() > 20);
  std::uint32_t header[5];
  std::memcpy(header, bytes.data(), sizeof header);
  CHECK(bytes.substr(0, 4) == "glTF");
  CHECK(header[1] == 2);
  CHECK(header[2] == bytes.size());
  CHECK(bytes.substr(16, 4) == "JSON");
  return nlohmann::json::parse(bytes.substr(20, header[3]));
}

}  // namespace

TEST_CASE("export writes each format through the program, reporting its files and the crowd's size") {
  const auto dir = test::scratch_dir("cli_export_formats");
  const auto crowd = fixture(dir).string();
  std::string out;

  SECTION("gltf: a .glb with a node per agent and one animation") {
    REQUIRE(run("--json export " + crowd + " --format gltf -o " + (dir / "c.glb").string(), &out) == 0);
    const auto report = nlohmann::json::parse(out);
    CHECK(report["format"] == "gltf");
    CHECK(report["agents"] == 6);
    CHECK(report["frames"] == 25);
    const auto gltf = glb_json(dir / "c.glb");
    std::size_t agents = 0;
    for (const auto& node : gltf["nodes"]) agents += node["name"].get<std::string>().rfind("agent_", 0) == 0 ? 1 : 0;
    CHECK(agents == 6);
    CHECK(gltf["nodes"].size() >= 6);
    CHECK(gltf["animations"].size() == 1);
    CHECK(gltf["nodes"][0]["extras"]["id"] == 10);
  }
  SECTION("xdmf: an .xmf that parses as XML, a grid per frame, pointing into the crowd file") {
    REQUIRE(run("--json export " + crowd + " --format xdmf -o " + (dir / "c.xmf").string(), &out) == 0);
    CHECK(nlohmann::json::parse(out)["frames"] == 25);
    const std::string found = python(dir, "import xml.etree.ElementTree as E\n"
                                          "r = E.parse('" + (dir / "c.xmf").string() + "').getroot()\n"
                                          "grids = [g for g in r.iter('Grid') if g.get('GridType') == 'Uniform']\n"
                                          "refs = {d.text.split(':')[0] for d in r.iter('DataItem') if d.get('Format') == 'HDF'}\n"
                                          "print(len(grids), sorted(refs))\n");
    CHECK_THAT(found, Contains("25 ['crowd.h5']"));
  }
  SECTION("usd: a .usda layer with a PointInstancer, Z up, in metres") {
    REQUIRE(run("export " + crowd + " --format usd -o " + (dir / "c.usda").string(), &out) == 0);
    const std::string text = slurp(dir / "c.usda");
    CHECK(text.rfind("#usda 1.0", 0) == 0);
    CHECK_THAT(text, Contains("def PointInstancer") && Contains("upAxis = \"Z\"") && Contains("metersPerUnit = 1"));
  }
  SECTION("pedpy: /trajectory holds a row per present agent-frame, fps and the walkable area") {
    REQUIRE(run("--json export " + crowd + " --format pedpy -o " + (dir / "c.h5").string(), &out) == 0);
    CHECK(nlohmann::json::parse(out)["rows"] == fixture_rows);
    const std::string found = python(dir, "import h5py\n"
                                          "f = h5py.File('" + (dir / "c.h5").string() + "', 'r')\n"
                                          "t = f['trajectory']\n"
                                          "print(len(t), float(t.attrs['fps']), list(t.dtype.names), 'wkt_geometry' in f.attrs)\n");
    CHECK_THAT(found, Contains("140 25.0 ['frame', 'id', 'x', 'y', 'z', 'ox', 'oy'] True"));
  }
  SECTION("csv: the table's header and a row per present agent-frame, obstacles beside") {
    REQUIRE(run("--json export " + crowd + " --format csv -o " + (dir / "c.csv").string(), &out) == 0);
    const auto report = nlohmann::json::parse(out);
    CHECK(report["rows"] == fixture_rows);
    CHECK(report["files"] == nlohmann::json::array({(dir / "c.csv").string(), (dir / "c_obstacles.csv").string()}));
    const auto rows = lines_of(dir / "c.csv");
    REQUIRE(rows.size() == fixture_rows + 1);
    CHECK(rows.front() == csv_header);
    CHECK(lines_of(dir / "c_obstacles.csv").front() == "obstacle,name,kind,size,point,x,y,moving");
  }
}

TEST_CASE("export: the format told by the output's extension, and the default output beside the crowd") {
  const auto dir = test::scratch_dir("cli_export_defaults");
  const auto crowd = fixture(dir).string();
  std::string out;
  REQUIRE(run("--json export " + crowd + " -o " + (dir / "told.glb").string(), &out) == 0);
  CHECK(nlohmann::json::parse(out)["format"] == "gltf");
  glb_json(dir / "told.glb");
  REQUIRE(run("--json export " + crowd + " --format usd", &out) == 0);
  CHECK(nlohmann::json::parse(out)["output"] == (dir / "crowd.usda").string());
  CHECK(slurp(dir / "crowd.usda").rfind("#usda 1.0", 0) == 0);
  REQUIRE(run("export " + crowd + " --format pedpy", &out) == 0);  // never onto the crowd itself
  CHECK(std::filesystem::exists(dir / "crowd.pedpy.h5"));
  CHECK(read_crowd_file(crowd).motion.agent_count() == 6);
  REQUIRE(run("export " + crowd + " --format xdmf", &out) == 0);
  CHECK(std::filesystem::exists(dir / "crowd.xmf"));
}

TEST_CASE("export: the pose thresholds and the walkable area reach the exporter") {
  const auto dir = test::scratch_dir("cli_export_options");
  const auto crowd = fixture(dir).string();
  // The fixture's agents walk at 1.3 m/s (agent 30 stands from 0.4 s on): walk by default, run from 0.5 m/s (agent 30 slows through 0.65 m/s).
  auto actions = [&](const std::string& flags) {
    REQUIRE(run("export " + crowd + " --format csv -o " + (dir / "a.csv").string() + " " + flags) == 0);
    std::map<std::string, std::size_t> count;
    const auto rows = lines_of(dir / "a.csv");
    for (std::size_t i = 1; i < rows.size(); ++i) {
      std::vector<std::string> cells;
      std::stringstream s(rows[i]);
      for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
      REQUIRE(cells.size() >= 12);
      ++count[cells[11]];
    }
    return count;
  };
  const auto plain = actions("");
  CHECK(plain.count("run") == 0);
  CHECK(plain.at("walk") > 100);
  const auto fast = actions("--running-speed 0.5");
  CHECK(fast.count("walk") == 0);
  CHECK(fast.at("run") == plain.at("walk"));
  const auto slow = actions("--standing-speed 1.5 --running-speed 3");
  CHECK(slow.count("walk") == 0);
  CHECK(slow.at("stand") == fixture_rows);

  REQUIRE(run("export " + crowd + " --format pedpy --walkable-area none -o " + (dir / "n.h5").string()) == 0);
  CHECK_THAT(python(dir, "import h5py\nprint('wkt_geometry' in h5py.File('" + (dir / "n.h5").string() + "', 'r').attrs)\n"),
             Contains("False"));
}

TEST_CASE("export: bad requests exit with their code and a message, leaving no file") {
  const auto dir = test::scratch_dir("cli_export_errors");
  const auto crowd = fixture(dir).string();
  const auto bare = test::scratch_dir("cli_export_errors_bare");
  const auto no_obstacles = fixture(bare, false).string();
  const auto size = std::filesystem::file_size(crowd);
  std::string out;

  CHECK(run("export " + crowd + " --format fbx -o " + (dir / "x.fbx").string(), &out) == 2);
  CHECK_THAT(out, Contains("--format fbx") && Contains("xdmf, gltf, usd, pedpy, csv"));
  CHECK(run("export " + crowd + " --format gltf -o " + (dir / "missing" / "x.glb").string(), &out) == 4);
  CHECK_THAT(out, Contains("x.glb: cannot write, folder") && Contains("does not exist"));
  CHECK(run("export " + no_obstacles + " --format pedpy --walkable-area required -o " + (bare / "x.h5").string(), &out) == 2);
  CHECK_THAT(out, Contains("a walkable area was asked for, but the crowd has no obstacles"));
  for (const char* format : {"xdmf", "gltf", "usd", "pedpy", "csv"}) {
    INFO(format);
    CHECK(run("export " + crowd + " --format " + format + " -o " + crowd, &out) == 2);
    CHECK_THAT(out, Contains("is the input file"));
  }
  CHECK(run("export " + crowd + " --format gltf --walkable-area none -o " + (dir / "x.glb").string(), &out) == 2);
  CHECK_THAT(out, Contains("walkable_area applies to the pedpy format only"));
  CHECK(run("export " + crowd, &out) == 2);
  CHECK_THAT(out, Contains("give --format"));
  CHECK(run("export " + crowd + " -o " + (dir / "x.fbx").string(), &out) == 2);
  CHECK_THAT(out, Contains("no export format"));
  CHECK(run("export " + crowd + " --format csv --running-speed 0.2 -o " + (dir / "x.csv").string(), &out) == 2);
  CHECK_THAT(out, Contains("running_speed 0.2 m/s must be above standing_speed 0.3 m/s"));
  CHECK(run("export " + (dir / "absent.h5").string() + " --format usd -o " + (dir / "x.usda").string(), &out) == 4);

  CHECK(test::files_in(dir) == std::vector<std::string>{"crowd.h5"});
  CHECK(test::files_in(bare) == std::vector<std::string>{"crowd.h5"});
  CHECK(std::filesystem::file_size(crowd) == size);
}

TEST_CASE("a throng run job exports its crowd as steps, by format key or by the output's extension") {
  const auto dir = test::scratch_dir("cli_export_run");
  const auto data = test::real_data_dir();
  fixture(dir);
  // zara01 (imported) to glTF and CSV; the fixture crowd (evenly spaced frames, as PedPy needs: the recordings
  // have gaps) to pedpy by its file name.
  test::write_file(dir / "job.yaml", "steps:\n"
                                     "  - step: import\n"
                                     "    dataset: " + (data / "zara01").string() + "\n"
                                     "  - step: export\n"
                                     "    output: " + (dir / "zara.glb").string() + "\n"
                                     "  - step: export\n"
                                     "    format: csv\n"
                                     "    running_speed: 1.5\n"
                                     "    output: " + (dir / "zara.csv").string() + "\n"
                                     "  - step: export\n"
                                     "    input: crowd.h5\n"
                                     "    format: pedpy\n"
                                     "    walkable_area: required\n"
                                     "    output: " + (dir / "fixture_pedpy.h5").string() + "\n");
  std::string out;
  REQUIRE(run("--quiet run " + (dir / "job.yaml").string(), &out) == 0);
  const auto gltf = glb_json(dir / "zara.glb");
  std::size_t agents = 0;
  for (const auto& node : gltf["nodes"]) agents += node["name"].get<std::string>().rfind("agent_", 0) == 0 ? 1 : 0;
  CHECK(agents == 148);  // zara01's pedestrians
  const std::string found = python(dir, "import h5py\n"
                                        "f = h5py.File('" + (dir / "fixture_pedpy.h5").string() + "', 'r')\n"
                                        "print(len(f['trajectory']), f.attrs['wkt_geometry'][:7])\n");
  CHECK_THAT(found, Contains("140") && Contains("POLYGON"));
  CHECK(lines_of(dir / "zara.csv").front() == csv_header);
  CHECK(std::filesystem::exists(dir / "zara_obstacles.csv"));

  // xdmf points into a crowd file: a crowd held in memory is refused, and nothing is written.
  test::write_file(dir / "xdmf.yaml", "steps:\n  - step: import\n    dataset: " + (data / "zara01").string() +
                                          "\n  - step: export\n    output: " + (dir / "zara.xmf").string() + "\n");
  CHECK(run("run " + (dir / "xdmf.yaml").string(), &out) == 2);
  CHECK_THAT(out, Contains("step 2/2 export") && Contains("xdmf points into a crowd file on disk"));
  CHECK_FALSE(std::filesystem::exists(dir / "zara.xmf"));

  // An export step never writes onto the crowd file it reads (exit 2, the file untouched).
  const auto size = std::filesystem::file_size(dir / "crowd.h5");
  test::write_file(dir / "same.yaml", "steps:\n  - step: export\n    input: crowd.h5\n    format: pedpy\n"
                                      "    output: " + (dir / "crowd.h5").string() + "\n");
  CHECK(run("run " + (dir / "same.yaml").string(), &out) == 2);
  CHECK_THAT(out, Contains("step 1/1 export") && Contains("is the input file"));
  CHECK(std::filesystem::file_size(dir / "crowd.h5") == size);
  CHECK(read_crowd_file(dir / "crowd.h5").motion.agent_count() == 6);
}
