// Tables with a header row (CSV with `,` or `;`, or tab-separated): columns found by name or mapped by
// ImportOptions::columns, positions scaled by ImportOptions::units.
#include "import_readers.h"
#include "track_rows.h"

#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <limits>
#include <map>
#include <optional>

namespace throng::detail {
namespace {

enum Role { time, frame, id, x, y, z, species, radius, role_count };
constexpr std::array<const char*, role_count> role_names{"time", "frame", "id", "x", "y", "z", "species", "radius"};

// Column names each role is found under (lower case, after any unit suffix "x [m]", "x/m", "x (m)" is cut off).
const std::map<std::string, Role>& known_names() {
  static const std::map<std::string, Role> names{
      {"time", time},     {"t", time},           {"seconds", time},      {"time_s", time},      {"timestamp", time},
      {"frame", frame},   {"fr", frame},         {"frame_id", frame},    {"frame_number", frame}, {"frame_no", frame},
      {"id", id},         {"pid", id},           {"ped_id", id},         {"person", id},        {"person_id", id},
      {"agent", id},      {"agent_id", id},      {"track", id},          {"track_id", id},      {"pedestrian", id},
      {"pedestrian_id", id},
      {"x", x},           {"pos_x", x},          {"x_m", x},             {"px", x},
      {"y", y},           {"pos_y", y},          {"y_m", y},             {"py", y},
      {"z", z},           {"pos_z", z},          {"z_m", z},             {"pz", z},
      {"species", species}, {"group", species},  {"group_id", species},  {"type", species},     {"class", species},
      {"radius", radius}, {"r", radius}};
  return names;
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '"')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '"')) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

std::string bare_name(std::string_view cell) {
  std::string name = lower(trimmed(cell));
  const std::size_t cut = name.find_first_of("[(/");
  if (cut != std::string::npos && cut > 0) name = std::string(trimmed(name.substr(0, cut)));
  return name;
}

std::vector<std::string_view> split(std::string_view line, char separator) {
  std::vector<std::string_view> cells;
  for (std::size_t start = 0;;) {
    const std::size_t at = line.find(separator, start);
    cells.push_back(line.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) break;
    start = at + 1;
  }
  return cells;
}

bool all_numbers(const std::vector<std::string_view>& cells) {
  return std::all_of(cells.begin(), cells.end(), [](std::string_view c) {
    c = trimmed(c);
    double v = 0;
    const auto [end, error] = std::from_chars(c.data(), c.data() + c.size(), v);
    return !c.empty() && error == std::errc{} && end == c.data() + c.size();
  });
}

// Column index per role (npos: absent). `header` is empty for a header-less table.
using ColumnMap = std::array<std::size_t, role_count>;
constexpr std::size_t none = std::numeric_limits<std::size_t>::max();

ColumnMap map_columns(const std::vector<std::string>& header, std::size_t width, const ImportOptions& options, const std::string& source) {
  ColumnMap map;
  map.fill(none);
  if (options.columns.empty()) {
    if (header.empty()) {
      throw ConfigError(source + ": the table has no header row; say which column is which with --columns "
                                 "(e.g. frame=0,id=1,x=2,y=3)");
    }
    for (std::size_t c = 0; c < header.size(); ++c) {
      const auto it = known_names().find(header[c]);
      if (it != known_names().end() && map[it->second] == none) map[it->second] = c;
    }
  } else {
    for (std::string_view entry : split(options.columns, ',')) {
      entry = trimmed(entry);
      if (entry.empty()) continue;
      const std::size_t eq = entry.find('=');
      if (eq == std::string_view::npos) throw ConfigError("--columns '" + options.columns + "': expected role=column pairs, e.g. time=t,id=pid,x=X,y=Y");
      const std::string role = lower(trimmed(entry.substr(0, eq)));
      const std::string column(trimmed(entry.substr(eq + 1)));
      const auto r = std::find(role_names.begin(), role_names.end(), role);
      if (r == role_names.end()) {
        throw ConfigError("--columns: unknown role '" + role + "' (roles: time or frame, id, x, y, z, species, radius)");
      }
      std::size_t index = none;
      std::size_t parsed = 0;
      const auto [end, error] = std::from_chars(column.data(), column.data() + column.size(), parsed);
      if (!column.empty() && error == std::errc{} && end == column.data() + column.size()) {
        index = parsed;
      } else {
        const auto it = std::find(header.begin(), header.end(), lower(column));
        if (it != header.end()) index = static_cast<std::size_t>(it - header.begin());
        else if (header.empty()) throw ConfigError("--columns: " + role + "=" + column + ": the table has no header row, give column numbers from 0");
      }
      if (index == none || index >= width) {
        std::string names;
        for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
        throw ConfigError("--columns: " + role + "=" + column + " is not a column of " + source +
                          (header.empty() ? " (it has " + std::to_string(width) + " columns)" : " (columns: " + names + ")"));
      }
      map[static_cast<std::size_t>(r - role_names.begin())] = index;
    }
  }
  if (map[time] != none && map[frame] != none) {
    if (!options.columns.empty()) throw ConfigError("--columns: give time or frame, not both");
    map[frame] = none;  // found both by name: times are the stronger statement
  }
  std::string missing;
  if (map[time] == none && map[frame] == none) missing += " time (or frame)";
  for (Role r : {id, x, y}) {
    if (map[r] == none) missing += std::string(" ") + role_names[r];
  }
  if (!missing.empty()) {
    std::string names;
    for (const auto& h : header) names += (names.empty() ? "" : ", ") + h;
    throw InputError(source + ": cannot find the column(s)" + missing + " (its columns: " + names +
                     "); name them with --columns, e.g. time=t,id=pid,x=X,y=Y");
  }
  return map;
}

// The unit a header cell states after its name: "x [mm]", "x (cm)", "x/m"; empty when none.
std::string unit_in(std::string_view cell) {
  const std::string name = lower(trimmed(cell));
  const std::size_t cut = name.find_first_of("[(/");
  if (cut == std::string::npos) return {};
  std::string unit;
  for (char c : name.substr(cut + 1)) {
    if (c != ' ' && c != ']' && c != ')') unit += c;
  }
  return unit == "m" || unit == "cm" || unit == "mm" ? unit : std::string{};
}

}  // namespace

ImportedCrowd read_table(const std::string& source, std::string_view text, const ImportOptions& options, MemoryBudget& budget) {
  // The first line that is not blank or a `#` comment: a header row, or the first row of a header-less table.
  std::string_view first;
  std::size_t first_number = 0;
  for_each_line(text, [&](std::string_view line, std::size_t number) {
    if (first_number == 0 && !trimmed(line).empty() && trimmed(line).front() != '#') {
      first = line;
      first_number = number;
    }
  });
  if (first_number == 0) throw InputError(source + ": no rows");
  const char separator = first.find(',') != std::string_view::npos ? ',' : first.find(';') != std::string_view::npos ? ';' : '\t';
  const std::vector<std::string_view> first_cells = split(first, separator);
  const bool has_header = !all_numbers(first_cells);
  std::vector<std::string> header;
  if (has_header) {
    for (std::string_view c : first_cells) header.push_back(bare_name(c));
  }
  const std::size_t width = first_cells.size();
  ColumnMap map = map_columns(header, width, options, source);
  // Units: --units, or what the header states after the x column's name (the same for every position column).
  std::string stated_unit = has_header ? unit_in(first_cells[map[x]]) : std::string{};
  for (Role r : {y, z}) {
    if (has_header && map[r] != none && unit_in(first_cells[map[r]]) != stated_unit) stated_unit.clear();
  }
  if (!stated_unit.empty() && !options.units.empty() && stated_unit != options.units) {
    throw ConfigError(source + ": its header gives positions in " + stated_unit + "; --units " + options.units + " contradicts it (leave --units out)");
  }
  const double scale = metres_per_unit(options.units.empty() ? stated_unit : options.units, 1.0);
  if (options.species_from == "none") map[species] = none;
  else if (!options.species_from.empty() && !species_from_file(options.species_from)) {
    const auto it = std::find(header.begin(), header.end(), lower(options.species_from));
    if (it == header.end()) throw ConfigError("--species-from " + options.species_from + ": not a column of " + source);
    map[species] = static_cast<std::size_t>(it - header.begin());
  }

  ImportedCrowd out{CrowdFile{}, ImportFormat::csv, {}};
  for (std::size_t c = 0; c < width; ++c) {
    if (std::find(map.begin(), map.end(), c) == map.end()) {
      out.notes.push_back("column " + std::to_string(c) + (has_header ? " '" + header[c] + "'" : std::string()) +
                          " is not imported (map it with --columns to species or radius if it is one of those)");
    }
  }

  const bool by_time = map[time] != none;
  const std::size_t key_column = by_time ? map[time] : map[frame];
  charge_rows(text, sizeof(TrackRow) + 2 * sizeof(double), budget, source);
  std::vector<TrackRow> rows;
  std::vector<double> species_values, radius_values;
  for_each_line(text, [&](std::string_view line, std::size_t number) {
    if (number < first_number || (has_header && number == first_number)) return;
    if (trimmed(line).empty() || trimmed(line).front() == '#') return;
    const std::string where = source + ":" + std::to_string(number);
    const std::vector<std::string_view> cells = split(line, separator);
    if (cells.size() != width) {
      throw InputError(where + ": expected " + std::to_string(width) + " values separated by '" + std::string(1, separator == '\t' ? ' ' : separator) +
                       "' as in the first row, found " + std::to_string(cells.size()));
    }
    auto cell = [&](Role r) { return trimmed(cells[map[r]]); };
    auto number_of = [&](Role r) { return strict_number(cell(r), where, role_names[r]); };
    const double key = by_time ? number_of(time) : static_cast<double>(whole_id(number_of(frame), cell(frame), where, "frame"));
    rows.push_back({key, whole_id(number_of(id), cell(id), where, "id"), scale * number_of(x), scale * number_of(y),
                    map[z] != none ? scale * number_of(z) : 0.0});
    if (map[species] != none) {
      const double s = number_of(species);
      if (!whole_number_in(s, 0, std::numeric_limits<std::int32_t>::max())) {
        throw InputError(where + ": species '" + std::string(cell(species).substr(0, 40)) + "' is not a whole number from 0 to 2^31 - 1");
      }
      species_values.push_back(s);
    }
    if (map[radius] != none) {
      const double r = scale * number_of(radius);
      if (!(r >= 0)) throw InputError(where + ": radius '" + std::string(cell(radius).substr(0, 40)) + "' is negative");
      radius_values.push_back(r);
    }
  });
  const double seconds_per_key = by_time ? 1.0 : 1.0 / resolve_fps(0.0, options.fps, source, "");
  if (by_time && options.fps > 0) {
    throw ConfigError(source + ": its column '" + (has_header ? header[key_column] : std::to_string(key_column)) +
                      "' gives times in seconds; --fps applies only to frame numbers (leave it out, or map the column as frame=)");
  }
  out.crowd.motion = motion_from_rows(rows, seconds_per_key, options.radius, budget, source);
  CrowdMotion& m = out.crowd.motion;
  if (map[species] != none) {
    const auto s = per_agent(rows, species_values, m.ids, source, "species");
    for (std::size_t n = 0; n < s.size(); ++n) m.species[n] = static_cast<std::int32_t>(s[n]);
  }
  if (map[radius] != none) m.radii = per_agent(rows, radius_values, m.ids, source, "radius");
  return out;
}

}  // namespace throng::detail
