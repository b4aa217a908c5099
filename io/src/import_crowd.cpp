#include "import_readers.h"
#include "track_rows.h"

#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/hdf5.h>
#include <throng/io/import_crowd.h>
#include <throng/io/input_file.h>
#include <throng/io/real_dataset.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <unordered_map>

namespace throng {
namespace {

constexpr const char* known_formats =
    "throng imports: an ETH/UCY obsmat.txt (8 numbers a row: frame id x z y vx vz vy) or the folder holding it; "
    "the trajectory-prediction benchmarks' files (4 numbers a row: frame id x y); Jülich/PeTrack text files "
    "(5 numbers a row: id frame x y z, in cm, # comment header); a CSV table with a header row (columns time or "
    "frame, id, x, y [, z], or named with --columns); JuPedSim/PedPy HDF5 (/trajectory with fps); throng crowd files";

constexpr char hdf5_signature[] = "\x89HDF\r\n\x1a\n";

// The first bytes of a file (at most `count`), after check_input_file.
std::string head_of(const std::filesystem::path& path, std::size_t count) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot be read");
  std::string out(count, '\0');
  in.read(out.data(), static_cast<std::streamsize>(count));
  out.resize(static_cast<std::size_t>(in.gcount()));
  return out;
}

// Text after a UTF-8 byte order mark (spreadsheets write one before a CSV's header).
std::string_view without_byte_order_mark(std::string_view text) {
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  return text;
}

[[noreturn]] void unknown(const std::filesystem::path& path, const std::string& found) {
  throw InputError(path.string() + ": cannot tell its format (" + found + "). " + known_formats);
}

ImportFormat detect_hdf5(const std::filesystem::path& path, const ReadLimits& limits) {
  const h5::File file = h5::File::open(path, limits);
  const h5::Group root = file.root();
  if (root.has("trajectory") && !root.has_group("trajectory")) return ImportFormat::pedpy;
  if (root.has_group("h5md") || root.has_group("particles")) return ImportFormat::crowd;
  unknown(path, "an HDF5 file with neither /trajectory (JuPedSim/PedPy) nor /h5md (a crowd file)");
}

// A text file: the first line that is not blank or a `#` comment decides; a PeTrack header names its columns.
ImportFormat detect_text(const std::filesystem::path& path, std::string_view head, bool whole) {
  std::string header;
  std::string_view first;
  bool found = false;
  detail::for_each_line(head, [&](std::string_view line, std::size_t) {
    if (found) return;
    const auto fields = detail::whitespace_fields(line);
    if (fields.empty()) return;
    if (fields.front().front() == '#') header.append(line).append("\n");
    else {
      first = line;
      found = true;
    }
  });
  if (!found) unknown(path, whole ? "no data rows" : "no data row in its first 64 KB");
  if (std::any_of(first.begin(), first.end(), [](char c) { return c == '\0' || (static_cast<unsigned char>(c) < 32 && c != '\t'); })) {
    unknown(path, "binary content");
  }
  if (first.find(',') != std::string_view::npos || first.find(';') != std::string_view::npos) return ImportFormat::csv;
  const auto fields = detail::whitespace_fields(first);
  // Numbers as from_chars reads them (a "nan" cell is a number here, and refused with its line by the reader).
  const bool numbers = std::all_of(fields.begin(), fields.end(), [&](std::string_view f) {
    double v = 0;
    const auto [end, error] = std::from_chars(f.data(), f.data() + f.size(), v);
    return error != std::errc::invalid_argument && end == f.data() + f.size();
  });
  if (!numbers) {
    if (first.find('\t') != std::string_view::npos) return ImportFormat::csv;  // a tab-separated table with a header row
    unknown(path, "its first row '" + std::string(first.substr(0, 60)) + "' is neither numbers nor a header row separated by commas, semicolons or tabs");
  }
  std::string lower_header = header;
  for (char& c : lower_header) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::size_t id_at = lower_header.find("id"), frame_at = std::min(lower_header.find("fr"), lower_header.find("frame"));
  const bool petrack_header = id_at != std::string::npos && frame_at != std::string::npos && id_at < frame_at;
  switch (fields.size()) {
    case 8: return ImportFormat::obsmat;
    case 5: return ImportFormat::petrack;
    case 4: return petrack_header ? ImportFormat::petrack : ImportFormat::frame_id_x_y;
    default: unknown(path, "rows of " + std::to_string(fields.size()) + " numbers");
  }
}

std::vector<std::vector<std::int64_t>> read_groups_file(const std::filesystem::path& path, const ReadLimits& limits) {
  MemoryBudget budget(limits);
  const std::string text = read_text_file(path, budget, "a groups file (one walking group of agent ids per line)");
  budget.charge(checked_product(text.size(), sizeof(std::int64_t)).value_or(UINT64_MAX), path.string(), "its ids");
  std::vector<std::vector<std::int64_t>> groups;
  detail::for_each_line(text, [&](std::string_view line, std::size_t number) {
    std::vector<std::int64_t> group;
    const std::string where = path.string() + ":" + std::to_string(number);
    for (std::string_view token : detail::whitespace_fields(line)) {
      group.push_back(detail::whole_id(detail::strict_number(token, where, "agent id"), token, where, "agent id"));
    }
    if (!group.empty()) groups.push_back(std::move(group));
  });
  return groups;
}

void check_options(const ImportOptions& o) {
  auto finite_at_least_zero = [](double v, const char* what) {
    if (!std::isfinite(v) || v < 0) {
      std::ostringstream m;
      m << what << " = " << v << ": expected a finite number ≥ 0";
      throw ConfigError(m.str());
    }
  };
  finite_at_least_zero(o.fps, "fps");
  finite_at_least_zero(o.radius, "radius");
  finite_at_least_zero(o.wall_thickness, "wall thickness");
  (void)detail::metres_per_unit(o.units, 1.0);
}

}  // namespace

namespace detail {
bool species_from_file(const std::string& species_from) {
  if (species_from.empty() || species_from == "none") return false;
  std::error_code ec;
  return species_from == "groups.txt" || std::filesystem::is_regular_file(species_from, ec);
}
}  // namespace detail

const char* format_name(ImportFormat format) {
  switch (format) {
    case ImportFormat::obsmat: return "obsmat";
    case ImportFormat::frame_id_x_y: return "frame-id-x-y";
    case ImportFormat::petrack: return "petrack";
    case ImportFormat::csv: return "csv";
    case ImportFormat::pedpy: return "pedpy";
    case ImportFormat::crowd: return "crowd";
  }
  return "unknown";
}

ImportFormat detect_import_format(const std::filesystem::path& path, const ReadLimits& limits) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string() + ": no such file or folder");
  if (std::filesystem::is_directory(path, ec)) {
    if (std::filesystem::exists(path / "obsmat.txt", ec)) return ImportFormat::obsmat;
    unknown(path, "a folder without obsmat.txt");
  }
  const std::uint64_t size = check_input_file(path, "a trajectory file or a dataset folder");
  constexpr std::size_t sniff = 1 << 16;
  const std::string head = head_of(path, sniff);
  if (head.rfind(std::string(hdf5_signature, 8), 0) == 0) return detect_hdf5(path, limits);
  // Text: the last line of the sniffed part may be cut; only whole lines decide.
  std::string_view text(head);
  if (size > head.size()) text = text.substr(0, text.rfind('\n') == std::string_view::npos ? 0 : text.rfind('\n'));
  return detect_text(path, without_byte_order_mark(text), size <= head.size());
}

ImportedCrowd import_crowd(const std::filesystem::path& path, const ImportOptions& options, const ReadLimits& limits) {
  check_options(options);
  const ImportFormat format = detect_import_format(path, limits);
  const std::string source = path.string();
  const bool groups_file = detail::species_from_file(options.species_from);
  if (!options.columns.empty() && format != ImportFormat::csv) {
    throw ConfigError("--columns applies to CSV tables; " + source + " is " + format_name(format));
  }
  if (!options.species_from.empty() && options.species_from != "none" && !groups_file && format != ImportFormat::csv) {
    throw IoError("--species-from " + options.species_from + ": no such groups file (" + source + " is " + format_name(format) +
                  ", which has no columns to take species from)");
  }
  ImportedCrowd out{CrowdFile{}, format, {}};
  switch (format) {
    case ImportFormat::obsmat: {
      RealDatasetOptions o;
      o.video_fps = options.fps;
      o.agent_radius = options.radius;
      o.wall_thickness = options.wall_thickness;
      o.groups = options.species_from.empty();
      o.map = options.obstacles.empty();
      if (!options.units.empty() && options.units != "m") throw ConfigError("--units " + options.units + ": obsmat.txt is in metres");
      out.crowd = import_real_dataset(path, o, limits);
      break;
    }
    case ImportFormat::crowd: {
      if (options.fps > 0) throw ConfigError(source + ": a crowd file has times in seconds; --fps does not apply");
      out.crowd = read_crowd_file(path, limits);
      break;
    }
    case ImportFormat::pedpy: out = detail::read_pedpy(path, options, limits); break;
    case ImportFormat::frame_id_x_y:
    case ImportFormat::petrack:
    case ImportFormat::csv: {
      MemoryBudget budget(limits);
      const std::string text = read_text_file(path, budget, "a trajectory text file");
      const std::string_view body = without_byte_order_mark(text);
      out = format == ImportFormat::csv ? detail::read_table(source, body, options, budget)
            : format == ImportFormat::petrack ? detail::read_petrack(source, body, options, budget)
                                             : detail::read_frame_id_x_y(source, body, options, budget);
      out.crowd.provenance.inputs.push_back(source);
      break;
    }
  }

  CrowdMotion& m = out.crowd.motion;
  if (groups_file) {
    std::filesystem::path file = options.species_from;
    if (options.species_from == "groups.txt") {
      // The groups.txt beside the data (in the folder given, or beside the file given).
      std::error_code ec;
      const std::filesystem::path folder = std::filesystem::is_directory(path, ec) ? path : path.parent_path();
      file = (folder.empty() ? std::filesystem::path(".") : folder) / "groups.txt";
    }
    const auto groups = read_groups_file(file, limits);
    std::unordered_map<std::int64_t, std::size_t> column;
    for (std::size_t n = 0; n < m.ids.size(); ++n) column[m.ids[n]] = n;
    std::fill(m.species.begin(), m.species.end(), 0);
    for (std::size_t g = 0; g < groups.size(); ++g) {
      for (std::int64_t id : groups[g]) {
        const auto it = column.find(id);
        if (it != column.end() && m.species[it->second] == 0) m.species[it->second] = static_cast<std::int32_t>(g + 1);
      }
    }
  } else if (options.species_from == "none") {
    std::fill(m.species.begin(), m.species.end(), 0);
  }
  if (!options.obstacles.empty()) {
    std::error_code ec;
    check_input_file(options.obstacles, "an obstacle file (map.xml or a crowd file)");
    const std::string head = head_of(options.obstacles, 8);
    out.crowd.scene = head.rfind(std::string(hdf5_signature, 8), 0) == 0 ? read_crowd_file(options.obstacles, limits).scene
                                                                         : read_obstacle_map(options.obstacles, options.wall_thickness, limits);
  }
  if (!options.credit.empty()) out.crowd.provenance.credits.push_back(options.credit);
  m.validate(source);
  return out;
}

}  // namespace throng
