#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/csv.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

namespace throng {
namespace {

void append_number(std::string& out, double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, r.ptr);
}

}  // namespace

void write_csv(const std::filesystem::path& path, const CrowdMotion& motion) {
  motion.validate("CSV output");
  AtomicOutput output(path);
  {
    std::ofstream out(output.temporary(), std::ios::binary);
    if (!out) throw IoError(path.string() + ": cannot be created");
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
        out << text;
        text.clear();
      }
    }
    out << text;
    out.close();
    if (!out) throw IoError(path.string() + ": write failed (is the disk full?)");
  }
  output.commit();
}

CrowdMotion read_csv(const std::filesystem::path& path, double agent_radius) {
  std::ifstream in(path);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw IoError(path.string() + ": no such file");
  if (!in) throw IoError(path.string() + ": cannot be opened for reading");
  std::string line;
  if (!std::getline(in, line)) throw InputError(path.string() + ": empty file, expected the header time,id,x,y,z");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != "time,id,x,y,z") throw InputError(path.string() + ":1: header is '" + line + "', expected time,id,x,y,z");

  struct Row {
    double time;
    std::int64_t id;
    double x, y, z;
  };
  std::vector<Row> rows;
  std::size_t number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::istringstream fields(line);
    std::string cell[5];
    for (int i = 0; i < 5; ++i) {
      if (!std::getline(fields, cell[i], ',')) throw InputError(path.string() + ":" + std::to_string(number) + ": expected 5 comma-separated values");
    }
    Row r{};
    try {
      std::size_t used = 0;
      r.time = std::stod(cell[0]);
      r.id = std::stoll(cell[1], &used);
      if (used != cell[1].size()) throw std::invalid_argument(cell[1]);
      r.x = std::stod(cell[2]);
      r.y = std::stod(cell[3]);
      r.z = std::stod(cell[4]);
    } catch (const std::exception&) {
      throw InputError(path.string() + ":" + std::to_string(number) + ": a value is not a number");
    }
    if (!std::isfinite(r.time) || !std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(r.z)) {
      throw InputError(path.string() + ":" + std::to_string(number) + ": a value is not finite");
    }
    rows.push_back(r);
  }
  if (rows.empty()) throw InputError(path.string() + ": no rows");

  std::vector<double> times;
  std::vector<std::int64_t> ids;
  for (const Row& r : rows) {
    times.push_back(r.time);
    ids.push_back(r.id);
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  CrowdMotion m = CrowdMotion::with_shape(times.size(), ids.size(), agent_radius);
  m.times = times;
  m.ids = ids;
  for (const Row& r : rows) {
    const auto t = static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), r.time) - times.begin());
    const auto n = static_cast<std::size_t>(std::lower_bound(ids.begin(), ids.end(), r.id) - ids.begin());
    if (m.present(t, n)) throw InputError(path.string() + ": id " + std::to_string(r.id) + " has two rows at time " + std::to_string(r.time));
    m.position(t, n) = Eigen::Vector3d(r.x, r.y, r.z);
  }
  m.validate(path.string());
  return m;
}

}  // namespace throng
