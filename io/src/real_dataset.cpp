#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/input_file.h>
#include <throng/io/real_dataset.h>

#include <pugixml.hpp>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <sstream>
#include <string_view>
#include <unordered_map>

namespace throng {
namespace {

struct Row {
  std::int64_t frame;
  std::int64_t id;
  double x, y, vx, vy;
};

// Largest frame number and agent id the importer takes: whole numbers a double holds exactly (2^53).
constexpr auto largest_whole = static_cast<std::int64_t>(largest_exact_integer);

// The whitespace-separated fields of a line.
std::vector<std::string_view> fields_of(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

// The whole field as a number ("1.5xyz" is refused, not read as 1.5).
double parse_number(std::string_view field, const std::string& where) {
  double v = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (error != std::errc{} || end != field.data() + field.size()) {
    throw InputError(where + ": '" + std::string(field.substr(0, 40)) + "' is not a number");
  }
  if (!std::isfinite(v)) throw InputError(where + ": a value is not finite");
  return v;
}

// Lines of a text, each with its 1-based number.
template <class F>
void for_each_line(const std::string& text, F&& f) {
  std::size_t number = 0;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    f(std::string_view(text.data() + start, end - start), ++number);
    start = end + 1;
  }
}

std::vector<Row> read_obsmat(const std::filesystem::path& path, MemoryBudget& budget) {
  const std::string text = read_text_file(path, budget, "obsmat.txt (a text file)");
  const auto lines = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  budget.charge(checked_product(lines, sizeof(Row) + 2 * sizeof(std::int64_t)).value_or(UINT64_MAX), path.string(),
                std::to_string(lines) + " rows");
  std::vector<Row> rows;
  for_each_line(text, [&](std::string_view line, std::size_t number) {
    const std::string where = path.string() + ":" + std::to_string(number);
    const std::vector<std::string_view> fields = fields_of(line);
    if (fields.empty()) return;
    if (fields.size() != 8) {
      throw InputError(where + ": expected 8 numbers (frame id x z y vx vz vy), found " + std::to_string(fields.size()) + " fields");
    }
    double v[8];
    for (int i = 0; i < 8; ++i) v[i] = parse_number(fields[static_cast<std::size_t>(i)], where);
    const auto frame = whole_number_in(v[0], 0, largest_whole), id = whole_number_in(v[1], 0, largest_whole);
    if (!frame || !id) {
      throw InputError(where + ": frame and id must be whole numbers from 0 to 2^53 (found " + std::string(fields[0].substr(0, 40)) +
                       " and " + std::string(fields[1].substr(0, 40)) + ")");
    }
    rows.push_back({*frame, *id, v[2], v[4], v[5], v[7]});
  });
  if (rows.empty()) throw InputError(path.string() + ": no trajectory rows");
  return rows;
}

std::vector<std::vector<std::int64_t>> read_groups(const std::filesystem::path& path, MemoryBudget& budget) {
  const std::string text = read_text_file(path, budget, "groups.txt (a text file)");
  budget.charge(checked_product(text.size(), sizeof(std::int64_t)).value_or(UINT64_MAX), path.string(), "its ids");
  std::vector<std::vector<std::int64_t>> groups;
  for_each_line(text, [&](std::string_view line, std::size_t number) {
    std::vector<std::int64_t> group;
    for (std::string_view token : fields_of(line)) {
      std::int64_t id = 0;
      const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), id);
      if (error != std::errc{} || end != token.data() + token.size()) {
        throw InputError(path.string() + ":" + std::to_string(number) + ": '" + std::string(token.substr(0, 40)) + "' is not an agent id");
      }
      group.push_back(id);
    }
    if (!group.empty()) groups.push_back(std::move(group));
  });
  return groups;
}

double attribute(const pugi::xml_node& n, const char* name, const std::filesystem::path& path) {
  const pugi::xml_attribute a = n.attribute(name);
  if (!a) throw InputError(path.string() + ": <" + std::string(n.name()) + "> at offset " + std::to_string(n.offset_debug()) + " has no " + name);
  const double v = a.as_double(std::nan(""));
  if (!std::isfinite(v)) throw InputError(path.string() + ": <" + std::string(n.name()) + "> attribute " + name + " is not a number");
  return v;
}

Scene read_map(const std::filesystem::path& path, double wall_thickness, MemoryBudget& budget) {
  const std::string text = read_text_file(path, budget, "map.xml (an XML file)");
  budget.charge(checked_product(text.size(), 4).value_or(UINT64_MAX), path.string(), "its parsed XML, about 4 bytes per byte");
  pugi::xml_document doc;
  // Default parse: no DOCTYPE processing and no external entities (pugixml has neither).
  const pugi::xml_parse_result result = doc.load_buffer(text.data(), text.size());
  if (!result) {
    throw InputError(path.string() + ": not valid XML (" + std::string(result.description()) + " at offset " +
                     std::to_string(result.offset) + ")");
  }
  Scene scene;
  int walls = 0, pillars = 0;
  for (const auto& x : doc.select_nodes("//Line")) {
    const pugi::xml_node n = x.node();
    Wall w{{attribute(n, "x1", path), attribute(n, "y1", path)}, {attribute(n, "x2", path), attribute(n, "y2", path)}, wall_thickness};
    scene.obstacles.push_back({w, {}, "wall " + std::to_string(++walls)});
  }
  for (const auto& x : doc.select_nodes("//Circle")) {
    const pugi::xml_node n = x.node();
    Circle c{{attribute(n, "x", path), attribute(n, "y", path)}, attribute(n, "radius", path)};
    scene.obstacles.push_back({c, {}, "pillar " + std::to_string(++pillars)});
  }
  scene.validate(path.string());
  return scene;
}

}  // namespace

double known_video_fps(const std::string& folder_name) {
  if (folder_name == "eth") return 15.0;
  for (const char* name : {"hotel", "zara01", "zara02", "zara03", "univ", "students"}) {
    if (folder_name.rfind(name, 0) == 0 || folder_name.find(std::string("_") + name) != std::string::npos) return 25.0;
  }
  return 0.0;
}

std::string dataset_credit(const std::string& folder_name) {
  const std::string opentraj = " Collected and converted to metres by the OpenTraj project (crowdbotp/OpenTraj).";
  if (folder_name == "eth" || folder_name == "hotel") {
    return "ETH/BIWI Walking Pedestrians: S. Pellegrini, A. Ess, K. Schindler, L. Van Gool, \"You'll never walk alone: "
           "modeling social behavior for multi-target tracking\", ICCV 2009." + opentraj;
  }
  if (known_video_fps(folder_name) == 0.0) return {};
  return "UCY Crowds by Example: A. Lerner, Y. Chrysanthou, D. Lischinski, \"Crowds by example\", Computer Graphics "
         "Forum 26(3), 2007." + opentraj;
}

CrowdFile import_real_dataset(const std::filesystem::path& folder_or_obsmat, const RealDatasetOptions& options,
                              const ReadLimits& limits) {
  std::error_code ec;
  MemoryBudget budget(limits);
  const bool is_folder = std::filesystem::is_directory(folder_or_obsmat, ec);
  const std::filesystem::path folder = is_folder ? folder_or_obsmat : folder_or_obsmat.parent_path();
  const std::filesystem::path obsmat = is_folder ? folder / "obsmat.txt" : folder_or_obsmat;
  if (!std::filesystem::exists(folder_or_obsmat, ec)) throw IoError(folder_or_obsmat.string() + ": no such file or folder");
  if (!std::filesystem::exists(obsmat, ec)) throw IoError(obsmat.string() + ": no such file (expected a dataset folder holding obsmat.txt)");
  const std::string name = std::filesystem::absolute(folder).lexically_normal().filename().string();

  double fps = options.video_fps;
  if (!(fps >= 0.0) || !std::isfinite(fps)) {
    std::ostringstream m;
    m << "video frame rate (--fps) = " << fps << ", expected a finite number > 0 (or 0: the known rate of the dataset)";
    throw ConfigError(m.str());
  }
  if (fps == 0.0) fps = known_video_fps(name);
  if (!(fps > 0.0)) {
    throw ConfigError("cannot tell the video frame rate of dataset folder '" + name + "': give it with --fps");
  }
  if (!(options.agent_radius >= 0) || !(options.wall_thickness >= 0)) throw ConfigError("radius and wall thickness must be ≥ 0");

  const std::vector<Row> rows = read_obsmat(obsmat, budget);

  // Frames: the annotated video frames, in order (see the header for why not a regular grid).
  std::vector<std::int64_t> frames;
  for (const Row& r : rows) frames.push_back(r.frame);
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  const std::size_t T = frames.size();

  std::vector<std::int64_t> ids;
  for (const Row& r : rows) ids.push_back(r.id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::unordered_map<std::int64_t, std::size_t> column;
  for (std::size_t n = 0; n < ids.size(); ++n) column[ids[n]] = n;
  const std::size_t N = ids.size();
  // A dense frames × agents array for positions and velocities (48 bytes per entry): sparse rows (every row a
  // new frame and a new agent) ask for far more than the file's size.
  const auto entries = checked_product(T, N);
  budget.charge(entries ? checked_product(*entries, 6 * sizeof(double)).value_or(UINT64_MAX) : UINT64_MAX, obsmat.string(),
                std::to_string(T) + " frames × " + std::to_string(N) + " agents × 48 bytes");

  CrowdFile out;
  CrowdMotion& m = out.motion;
  m = CrowdMotion::with_shape(T, N, options.agent_radius);
  m.ids = ids;
  m.velocities.assign(m.positions.size(), absent);
  for (std::size_t t = 0; t < T; ++t) m.times[t] = static_cast<double>(frames[t]) / fps;
  for (const Row& r : rows) {
    const auto t = static_cast<std::size_t>(std::lower_bound(frames.begin(), frames.end(), r.frame) - frames.begin());
    const std::size_t n = column.at(r.id);
    if (m.present(t, n)) {
      throw InputError(obsmat.string() + ": agent " + std::to_string(r.id) + " has two rows at frame " + std::to_string(r.frame));
    }
    m.position(t, n) = Eigen::Vector3d(r.x, r.y, 0.0);
    m.velocities[m.index(t, n)] = r.vx;
    m.velocities[m.index(t, n) + 1] = r.vy;
    m.velocities[m.index(t, n) + 2] = 0.0;
  }

  const auto groups_path = folder / "groups.txt";
  if (std::filesystem::exists(groups_path, ec)) {
    const auto groups = read_groups(groups_path, budget);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      for (std::int64_t id : groups[g]) {
        const auto it = column.find(id);
        if (it != column.end() && m.species[it->second] == 0) m.species[it->second] = static_cast<std::int32_t>(g + 1);
      }
    }
  }
  const auto map_path = folder / "map.xml";
  if (std::filesystem::exists(map_path, ec)) out.scene = read_map(map_path, options.wall_thickness, budget);

  out.provenance.inputs.push_back(obsmat.string());
  if (auto credit = dataset_credit(name); !credit.empty()) out.provenance.credits.push_back(credit);
  m.validate(obsmat.string());
  return out;
}

}  // namespace throng
