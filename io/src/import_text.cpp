// Whitespace-separated trajectory text files: the benchmarks' `frame id x y` and Jülich/PeTrack `id frame x y z`.
#include "import_readers.h"
#include "track_rows.h"

#include <throng/core/errors.h>

#include <cmath>
#include <regex>
#include <sstream>

namespace throng::detail {
namespace {

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Rows of `count` numbers; `#` lines are comments (collected into `header`), blank lines skipped.
template <class F>
void for_each_row(std::string_view text, const std::string& source, std::size_t count, const char* layout, std::string* header, F&& row) {
  for_each_line(text, [&](std::string_view line, std::size_t number) {
    const std::vector<std::string_view> fields = whitespace_fields(line);
    if (fields.empty()) return;
    if (fields.front().front() == '#') {
      if (header) header->append(line).append("\n");
      return;
    }
    const std::string where = source + ":" + std::to_string(number);
    if (fields.size() != count) {
      throw InputError(where + ": expected " + std::to_string(count) + " numbers (" + layout + "), found " + std::to_string(fields.size()) + " fields");
    }
    row(fields, where);
  });
}

}  // namespace

double metres_per_unit(const std::string& units, double fallback) {
  if (units.empty()) return fallback;
  if (units == "m") return 1.0;
  if (units == "cm") return 0.01;
  if (units == "mm") return 0.001;
  throw ConfigError("units '" + units + "': expected m, cm or mm");
}

double resolve_fps(double stated, double given, const std::string& source, const std::string& stated_where) {
  if (stated > 0 && given > 0 && stated != given) {
    throw ConfigError(source + ": " + stated_where + " states " + number_text(stated) + " frames per second; --fps " + number_text(given) +
                      " contradicts it (leave --fps out)");
  }
  if (stated > 0) return stated;
  if (given > 0) return given;
  throw ConfigError(source + ": the file numbers its frames but does not say how many there are per second; give the rate with --fps");
}

ImportedCrowd read_frame_id_x_y(const std::string& source, std::string_view text, const ImportOptions& options, MemoryBudget& budget) {
  const double scale = metres_per_unit(options.units, 1.0);
  charge_rows(text, sizeof(TrackRow), budget, source);
  std::vector<TrackRow> rows;
  for_each_row(text, source, 4, "frame id x y", nullptr, [&](const std::vector<std::string_view>& f, const std::string& where) {
    const double frame = strict_number(f[0], where, "frame"), id = strict_number(f[1], where, "id");
    rows.push_back({static_cast<double>(whole_id(frame, f[0], where, "frame")), whole_id(id, f[1], where, "id"),
                    scale * strict_number(f[2], where, "x"), scale * strict_number(f[3], where, "y"), 0.0});
  });
  const double fps = resolve_fps(0.0, options.fps, source, "");
  ImportedCrowd out{CrowdFile{}, ImportFormat::frame_id_x_y, {}};
  out.crowd.motion = motion_from_rows(rows, 1.0 / fps, options.radius, budget, source);
  return out;
}

ImportedCrowd read_petrack(const std::string& source, std::string_view text, const ImportOptions& options, MemoryBudget& budget) {
  // The header first (comments may come anywhere; PeTrack writes them at the top).
  std::string header;
  std::size_t columns = 0;
  for_each_line(text, [&](std::string_view line, std::size_t) {
    const auto fields = whitespace_fields(line);
    if (fields.empty()) return;
    if (fields.front().front() == '#') header.append(line).append("\n");
    else if (columns == 0) columns = fields.size();
  });
  // "framerate: 16.00 fps", "frame rate 25", "fps: 25", "25fps".
  static const std::regex rate_words(R"((frame\s*rate|fps)\s*[:=]?\s*([0-9]+(\.[0-9]+)?))", std::regex::icase);
  static const std::regex rate_after(R"(([0-9]+(\.[0-9]+)?)\s*fps)", std::regex::icase);
  // "x/cm", "X [m]", "(in cm)", "in metres".
  static const std::regex unit(R"((/\s*|\[\s*|\bin\s+)(mm|cm|m|meters|metres|centimeters|centimetres|millimeters|millimetres)\b)", std::regex::icase);
  double stated_fps = 0.0;
  std::smatch match;
  if (std::regex_search(header, match, rate_words)) stated_fps = std::stod(match[2].str());
  else if (std::regex_search(header, match, rate_after)) stated_fps = std::stod(match[1].str());
  std::string stated_unit;
  if (std::regex_search(header, match, unit)) {
    std::string u = match[2].str();
    for (char& c : u) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    stated_unit = u.rfind("mm", 0) == 0 || u.rfind("milli", 0) == 0 ? "mm" : u.rfind("c", 0) == 0 ? "cm" : "m";
  }
  if (!stated_unit.empty() && !options.units.empty() && stated_unit != options.units) {
    throw ConfigError(source + ": its header gives positions in " + stated_unit + "; --units " + options.units + " contradicts it (leave --units out)");
  }
  const double scale = metres_per_unit(options.units.empty() ? stated_unit : options.units, 0.01);
  const bool has_z = columns != 4;
  charge_rows(text, sizeof(TrackRow), budget, source);
  std::vector<TrackRow> rows;
  for_each_row(text, source, has_z ? 5 : 4, has_z ? "id frame x y z" : "id frame x y", nullptr,
               [&](const std::vector<std::string_view>& f, const std::string& where) {
                 const double id = strict_number(f[0], where, "id"), frame = strict_number(f[1], where, "frame");
                 rows.push_back({static_cast<double>(whole_id(frame, f[1], where, "frame")), whole_id(id, f[0], where, "id"),
                                 scale * strict_number(f[2], where, "x"), scale * strict_number(f[3], where, "y"),
                                 0.0});
                 if (has_z) (void)strict_number(f[4], where, "z");  // checked, not kept: see the note below
               });
  const double fps = resolve_fps(stated_fps, options.fps, source, "its header");
  ImportedCrowd out{CrowdFile{}, ImportFormat::petrack, {}};
  out.crowd.motion = motion_from_rows(rows, 1.0 / fps, options.radius, budget, source);
  if (has_z) {
    // PeTrack's z is the height of the tracked point (the head, about 1.7 m), not the floor's: people walk on the
    // ground plane z = 0.
    out.notes.push_back("PeTrack's z (the tracked head's height) is not a ground position: positions are (x, y, 0)");
  }
  return out;
}

}  // namespace throng::detail
