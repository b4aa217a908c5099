#include "track_rows.h"

#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace throng::detail {

std::vector<std::string_view> whitespace_fields(std::string_view line) {
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

double strict_number(std::string_view field, const std::string& where, const std::string& what) {
  double v = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), v);
  const std::string shown(field.substr(0, 40));
  if (field.empty() || error == std::errc::invalid_argument || end != field.data() + field.size()) {
    throw InputError(where + ": " + what + " '" + shown + "' is not a number");
  }
  if (error == std::errc::result_out_of_range) throw InputError(where + ": " + what + " '" + shown + "' is out of range");
  if (!std::isfinite(v)) throw InputError(where + ": " + what + " '" + shown + "' is not finite");
  return v;
}

std::int64_t whole_id(double v, std::string_view field, const std::string& where, const std::string& what) {
  const auto whole = whole_number_in(v, 0, static_cast<std::int64_t>(largest_exact_integer));
  if (!whole) throw InputError(where + ": " + what + " '" + std::string(field.substr(0, 40)) + "' is not a whole number from 0 to 2^53");
  return *whole;
}

void charge_rows(std::string_view text, std::uint64_t bytes_per_row, MemoryBudget& budget, const std::string& what) {
  const auto lines = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  budget.charge(checked_product(lines, bytes_per_row).value_or(UINT64_MAX), what, std::to_string(lines) + " rows");
}

CrowdMotion motion_from_rows(const std::vector<TrackRow>& rows, double seconds_per_key, double radius, MemoryBudget& budget,
                             const std::string& source) {
  if (rows.empty()) throw InputError(source + ": no trajectory rows");
  std::vector<double> keys;
  std::vector<std::int64_t> ids;
  budget.charge(checked_product(rows.size(), 2 * sizeof(double)).value_or(UINT64_MAX), source, "sorting its rows");
  keys.reserve(rows.size());
  ids.reserve(rows.size());
  for (const TrackRow& r : rows) {
    keys.push_back(r.key);
    ids.push_back(r.id);
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  // A dense frames × agents array (positions, 24 bytes per entry): sparse rows (every row a new frame and a new
  // agent) ask for far more than the file's size.
  const std::uint64_t T = keys.size(), N = ids.size();
  const auto entries = checked_product(T, N);
  budget.charge(entries ? checked_product(*entries, 3 * sizeof(double)).value_or(UINT64_MAX) : UINT64_MAX, source,
                std::to_string(T) + " frames × " + std::to_string(N) + " agents × 24 bytes");
  CrowdMotion m = CrowdMotion::with_shape(keys.size(), ids.size(), radius);
  m.ids = ids;
  for (std::size_t t = 0; t < keys.size(); ++t) m.times[t] = keys[t] * seconds_per_key;
  for (const TrackRow& r : rows) {
    const auto t = static_cast<std::size_t>(std::lower_bound(keys.begin(), keys.end(), r.key) - keys.begin());
    const auto n = static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), r.id) - ids.begin());
    if (m.present(t, n)) {
      char key[32];
      const auto end = std::to_chars(key, key + sizeof key, r.key).ptr;
      throw InputError(source + ": agent " + std::to_string(r.id) + " has two rows at " +
                       (seconds_per_key == 1.0 ? "time " : "frame ") + std::string(key, end));
    }
    m.position(t, n) = Eigen::Vector3d(r.x, r.y, r.z);
  }
  return m;
}

std::vector<double> per_agent(const std::vector<TrackRow>& rows, const std::vector<double>& values,
                              const std::vector<std::int64_t>& ids, const std::string& source, const std::string& what) {
  std::vector<double> out(ids.size(), std::nan(""));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto n = static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), rows[i].id) - ids.begin());
    if (std::isnan(out[n])) out[n] = values[i];
    else if (out[n] != values[i]) {
      throw InputError(source + ": agent " + std::to_string(rows[i].id) + " changes its " + what + " (" + std::to_string(out[n]) +
                       ", then " + std::to_string(values[i]) + "); a " + what + " belongs to the whole agent");
    }
  }
  return out;
}

}  // namespace throng::detail
