#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/checked_numbers.h>
#include <throng/io/csv.h>
#include <throng/io/input_file.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <string_view>
#include <type_traits>

namespace throng {
namespace {

void append_number(std::string& out, double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, r.ptr);
}

std::string format_number(double v) {
  std::string s;
  append_number(s, v);
  return s;
}

struct Row {
  double time;
  std::int64_t id;
  double x, y, z;
};

std::string_view trimmed(std::string_view cell) {
  while (!cell.empty() && (cell.front() == ' ' || cell.front() == '\t')) cell.remove_prefix(1);
  while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\t')) cell.remove_suffix(1);
  return cell;
}

// The whole cell as a number (surrounding spaces allowed, nothing else): "1.5xyz" is refused, not read as 1.5.
template <class T>
T parse_cell(std::string_view cell, const char* column, const std::string& where) {
  const std::string_view text = trimmed(cell);
  T value{};
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error == std::errc::invalid_argument || end != text.data() + text.size()) {
    throw InputError(where + ": " + column + " '" + std::string(cell.substr(0, 40)) + "' is not a number");
  }
  if (error == std::errc::result_out_of_range) {
    throw InputError(where + ": " + column + " '" + std::string(cell.substr(0, 40)) + "' is out of range");
  }
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) throw InputError(where + ": " + column + " '" + std::string(cell.substr(0, 40)) + "' is not finite");
  }
  return value;
}

Row parse_row(std::string_view line, const std::string& where) {
  std::string_view cells[5];
  std::size_t count = 0;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    if (count == 5) throw InputError(where + ": expected 5 comma-separated values, found more");
    cells[count++] = line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (count != 5) throw InputError(where + ": expected 5 comma-separated values, found " + std::to_string(count));
  return Row{parse_cell<double>(cells[0], "time", where), parse_cell<std::int64_t>(cells[1], "id", where),
             parse_cell<double>(cells[2], "x", where), parse_cell<double>(cells[3], "y", where),
             parse_cell<double>(cells[4], "z", where)};
}

}  // namespace

void write_csv(const std::filesystem::path& path, const CrowdMotion& motion) {
  motion.validate("CSV output");
  AtomicOutput output(path);
  std::string text = "time,id,x,y,z\n";
  for (std::size_t t = 0; t < motion.frame_count(); ++t) {
    for (std::size_t n = 0; n < motion.agent_count(); ++n) {
      if (!motion.present(t, n)) continue;
      const auto p = motion.position(t, n);
      append_number(text, motion.times[t]);
      text += ',';
      text += std::to_string(motion.ids[n]);
      for (int k = 0; k < 3; ++k) {
        text += ',';
        append_number(text, p[k]);
      }
      text += '\n';
    }
    if (text.size() > (1u << 20)) {
      output.write(text);
      text.clear();
    }
  }
  output.write(text);
  output.commit();
}

CrowdMotion read_csv(const std::filesystem::path& path, double agent_radius, const ReadLimits& limits) {
  MemoryBudget budget(limits);
  const std::string text = read_text_file(path, budget, "a CSV file");
  const std::string name = path.string();
  const auto rows_at_most = static_cast<std::uint64_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  budget.charge(checked_product(rows_at_most, sizeof(Row) + 2 * sizeof(double)).value_or(UINT64_MAX), name,
                std::to_string(rows_at_most) + " rows");

  std::vector<Row> rows;
  rows.reserve(static_cast<std::size_t>(rows_at_most));
  std::size_t number = 0;
  bool header = false;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string_view line(text.data() + start, end - start);
    start = end + 1;
    ++number;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (!header) {
      if (line != "time,id,x,y,z") {
        throw InputError(name + ":1: header is '" + std::string(line.substr(0, 80)) + "', expected time,id,x,y,z");
      }
      header = true;
      continue;
    }
    if (line.empty()) continue;
    rows.push_back(parse_row(line, name + ":" + std::to_string(number)));
  }
  if (!header) throw InputError(name + ": empty file, expected the header time,id,x,y,z");
  if (rows.empty()) throw InputError(name + ": no rows");

  std::vector<double> times;
  std::vector<std::int64_t> ids;
  times.reserve(rows.size());
  ids.reserve(rows.size());
  for (const Row& r : rows) {
    times.push_back(r.time);
    ids.push_back(r.id);
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  // The table becomes a dense frames × agents array: a table of a few rows per time and id can ask for far more
  // than its size (every row a new time and a new id: rows² entries).
  const std::uint64_t T = times.size(), N = ids.size();
  const auto entries = checked_product(T, N);
  budget.charge(entries ? checked_product(*entries, 3 * sizeof(double)).value_or(UINT64_MAX) : UINT64_MAX, name,
                std::to_string(T) + " distinct times × " + std::to_string(N) + " distinct ids × 24 bytes");
  CrowdMotion m = CrowdMotion::with_shape(times.size(), ids.size(), agent_radius);
  m.times = times;
  m.ids = ids;
  for (const Row& r : rows) {
    const auto t = static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), r.time) - times.begin());
    const auto n = static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), r.id) - ids.begin());
    if (m.present(t, n)) throw InputError(name + ": id " + std::to_string(r.id) + " has two rows at time " + format_number(r.time));
    m.position(t, n) = Eigen::Vector3d(r.x, r.y, r.z);
  }
  m.validate(name);
  return m;
}

}  // namespace throng
