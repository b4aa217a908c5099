// Shared by the importers (io/src, not installed): reading text tables of numbers strictly, and turning rows of
// (frame or time, id, x, y, z) into a CrowdMotion with its arrays charged to the read's MemoryBudget first.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/io/read_limits.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace throng::detail {

/// One sample of one agent. `key` is a frame number or a time in seconds (see motion_from_rows).
struct TrackRow {
  double key;
  std::int64_t id;
  double x, y, z;
};

/// Whitespace-separated fields of a line (spaces, tabs, a trailing CR).
[[nodiscard]] std::vector<std::string_view> whitespace_fields(std::string_view line);

/// The whole field as a finite number ("1.5xyz", "nan", "" are refused): InputError "<where>: <what> '<field>' is
/// not a number" (or "is not finite", "is out of range").
[[nodiscard]] double strict_number(std::string_view field, const std::string& where, const std::string& what = "value");

/// `v` as an agent id / frame number: a whole number from 0 to 2^53, else InputError naming `where` and `what`.
[[nodiscard]] std::int64_t whole_id(double v, std::string_view field, const std::string& where, const std::string& what);

/// Calls f(line, number) for every line of `text` (1-based numbers), CR of CRLF line ends removed.
template <class F>
void for_each_line(std::string_view text, F&& f) {
  std::size_t number = 0;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    f(line, ++number);
    start = end + 1;
  }
}

/// Charges what `text`'s lines can become as rows (`bytes_per_row` each) to `budget` (InputError beyond it).
void charge_rows(std::string_view text, std::uint64_t bytes_per_row, MemoryBudget& budget, const std::string& what);

/// Frames are the distinct keys in order, time = key × seconds_per_key; agents the distinct ids (sorted); an agent
/// is present exactly where it has a row. The frames × agents array is charged to `budget` before it is
/// allocated. InputError naming `source` for no rows or an id with two rows at one key.
[[nodiscard]] CrowdMotion motion_from_rows(const std::vector<TrackRow>& rows, double seconds_per_key, double radius,
                                           MemoryBudget& budget, const std::string& source);

/// Per-agent values (species, radius) given per row: each agent's rows must agree. `values[i]` belongs to rows[i];
/// the result is indexed like motion.ids. InputError naming `source` and `what` when an agent's rows disagree.
[[nodiscard]] std::vector<double> per_agent(const std::vector<TrackRow>& rows, const std::vector<double>& values,
                                            const std::vector<std::int64_t>& ids, const std::string& source,
                                            const std::string& what);

}  // namespace throng::detail
