#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/input_file.h>
#include <throng/io/real_dataset.h>

#include <pugixml.hpp>

#include <map>
#include <regex>

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

// The recordings whose content throng knows, identified by what the rows hold (never by the folder's name: the
// collections ship the same file as `hotel/`, `seq_hotel/`, `ETH/seq_hotel/` ...): number of rows, distinct
// agents, first and last frame number. Measured on OpenTraj's obsmat.txt files (crowdbotp/OpenTraj@97ec1d5e1b57,
// the origin of data/real); a file edited in any way is not one of them any more and needs --fps and --credit.
struct Fingerprint {
  const char* name;
  std::uint64_t rows, agents;
  std::int64_t first_frame, last_frame;
  double video_fps;
  bool eth;  ///< ETH/BIWI (else UCY)
};
constexpr Fingerprint known_recordings[] = {
    {"ETH/BIWI eth", 8908, 360, 780, 12381, 15.0, true},
    {"ETH/BIWI hotel", 6544, 390, 1, 18061, 25.0, true},
    {"UCY zara01", 5024, 148, 1, 9011, 25.0, false},
    {"UCY zara02", 9537, 204, 7, 10517, 25.0, false},
    {"UCY students03", 21846, 428, 1, 5391, 25.0, false},
};

std::string credit_of(const Fingerprint& f) {
  const std::string opentraj = " Collected and converted to metres by the OpenTraj project (crowdbotp/OpenTraj).";
  if (f.eth) {
    return "ETH/BIWI Walking Pedestrians: S. Pellegrini, A. Ess, K. Schindler, L. Van Gool, \"You'll never walk alone: "
           "modeling social behavior for multi-target tracking\", ICCV 2009." + opentraj;
  }
  return "UCY Crowds by Example: A. Lerner, Y. Chrysanthou, D. Lischinski, \"Crowds by example\", Computer Graphics "
         "Forum 26(3), 2007." + opentraj;
}

const Fingerprint* identify(const std::vector<Row>& rows, std::size_t agents, std::int64_t first, std::int64_t last) {
  for (const Fingerprint& f : known_recordings) {
    if (f.rows == rows.size() && f.agents == agents && f.first_frame == first && f.last_frame == last) return &f;
  }
  return nullptr;
}

// ETH's info.txt states the annotation's time step ("... that is with a timestep of 0.4 seconds"): with the
// frame numbers' usual step (the most common gap between an agent's consecutive rows) it gives the video rate.
// 0 when there is no info.txt or it does not say.
double video_fps_from_info(const std::filesystem::path& info, const std::vector<Row>& rows, MemoryBudget& budget) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(info, ec)) return 0.0;
  const std::string text = read_text_file(info, budget, "info.txt (a text file)");
  static const std::regex step(R"(time\s?step\s+of\s+([0-9]+(\.[0-9]+)?)\s*s)", std::regex::icase);
  std::smatch match;
  if (!std::regex_search(text, match, step)) return 0.0;
  const double seconds = std::stod(match[1].str());
  std::unordered_map<std::int64_t, std::int64_t> last_frame;
  std::map<std::int64_t, std::size_t> gaps;
  for (const Row& r : rows) {
    const auto it = last_frame.find(r.id);
    if (it != last_frame.end() && r.frame > it->second) ++gaps[r.frame - it->second];
    last_frame[r.id] = r.frame;
  }
  if (gaps.empty() || !(seconds > 0)) return 0.0;
  const auto usual = std::max_element(gaps.begin(), gaps.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  return static_cast<double>(usual->first) / seconds;
}

}  // namespace

Scene read_obstacle_map(const std::filesystem::path& map_xml, double wall_thickness, const ReadLimits& limits) {
  MemoryBudget budget(limits);
  return read_map(map_xml, wall_thickness, budget);
}

CrowdFile import_real_dataset(const std::filesystem::path& folder_or_obsmat, const RealDatasetOptions& options,
                              const ReadLimits& limits) {
  std::error_code ec;
  MemoryBudget budget(limits);
  if (!std::filesystem::exists(folder_or_obsmat, ec)) throw IoError(folder_or_obsmat.string() + ": no such file or folder");
  // Any spelling: "obsmat.txt" from inside the folder (its parent path is empty: the working folder), "data/hotel/",
  // ".", "./obsmat.txt". Nothing here depends on the folder's name.
  const bool is_folder = std::filesystem::is_directory(folder_or_obsmat, ec);
  std::filesystem::path folder = is_folder ? folder_or_obsmat : folder_or_obsmat.parent_path();
  if (folder.empty()) folder = ".";
  const std::filesystem::path obsmat = is_folder ? folder / "obsmat.txt" : folder_or_obsmat;
  if (!std::filesystem::exists(obsmat, ec)) throw IoError(obsmat.string() + ": no such file (expected a dataset folder holding obsmat.txt)");

  const double given_fps = options.video_fps;
  if (!(given_fps >= 0.0) || !std::isfinite(given_fps)) {
    std::ostringstream m;
    m << "video frame rate (--fps) = " << given_fps << ", expected a finite number > 0 (or 0: the rate the data states)";
    throw ConfigError(m.str());
  }
  if (!(options.agent_radius >= 0) || !(options.wall_thickness >= 0)) throw ConfigError("radius and wall thickness must be ≥ 0");

  // The rows first: a file that is not an obsmat table says so before anything asks for its frame rate.
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
  const std::size_t N = ids.size();

  // A dense frames × agents array for positions and velocities (48 bytes per entry): sparse rows (every row a
  // new frame and a new agent) ask for far more than the file's size.
  const auto entries = checked_product(T, N);
  budget.charge(entries ? checked_product(*entries, 6 * sizeof(double)).value_or(UINT64_MAX) : UINT64_MAX, obsmat.string(),
                std::to_string(T) + " frames × " + std::to_string(N) + " agents × 48 bytes");
  // Every file beside it read and checked before the frame rate is asked for.
  std::vector<std::vector<std::int64_t>> groups;
  const auto groups_path = folder / "groups.txt";
  if (options.groups && std::filesystem::exists(groups_path, ec)) groups = read_groups(groups_path, budget);
  Scene scene;
  const auto map_path = folder / "map.xml";
  if (options.map && std::filesystem::exists(map_path, ec)) scene = read_map(map_path, options.wall_thickness, budget);

  const Fingerprint* known = identify(rows, N, frames.front(), frames.back());
  double fps = given_fps;
  if (known && fps > 0 && fps != known->video_fps) {
    std::ostringstream m;
    m << obsmat.string() << " is the " << known->name << " recording, filmed at " << known->video_fps << " fps; --fps " << fps
      << " contradicts it (leave --fps out)";
    throw ConfigError(m.str());
  }
  if (fps == 0.0 && known) fps = known->video_fps;
  if (fps == 0.0) fps = video_fps_from_info(folder / "info.txt", rows, budget);
  if (!(fps > 0.0)) {
    throw ConfigError("cannot tell the video frame rate of " + obsmat.string() +
                      ": its rows are not one of the recordings throng knows (ETH/BIWI eth, hotel; UCY zara01, zara02, "
                      "students03) and no info.txt beside it states the annotation's time step; give the rate with --fps");
  }

  std::unordered_map<std::int64_t, std::size_t> column;
  for (std::size_t n = 0; n < ids.size(); ++n) column[ids[n]] = n;

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

  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::int64_t id : groups[g]) {
      const auto it = column.find(id);
      if (it != column.end() && m.species[it->second] == 0) m.species[it->second] = static_cast<std::int32_t>(g + 1);
    }
  }
  out.scene = std::move(scene);
  out.provenance.inputs.push_back(obsmat.string());
  if (known) out.provenance.credits.push_back(credit_of(*known));
  m.validate(obsmat.string());
  return out;
}

}  // namespace throng
