#include "chart.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace scale {
namespace {

namespace fs = std::filesystem;

// Writes `text` to `path` through a temporary file in the same folder (no half-written table on a crash).
void write_atomically(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

// Case names are "<study>/<series...>/<x key>:<x>" (size/local_drag/halo:1/agents:5000,
// strong/global_drag/petsc/threads:2): the study picks the picture, the middle the line, the last key the x axis.
std::string study_of(const std::string& name) {
  const auto slash = name.find('/');
  return slash == std::string::npos ? "other" : name.substr(0, slash);
}

std::string series_of(const std::string& name) {
  const auto first = name.find('/');
  const auto last = name.rfind('/');
  if (first == std::string::npos || last == first) return name;
  return name.substr(first + 1, last - first - 1);
}

std::string x_key_of(const std::string& name) {
  const auto last = name.rfind('/');
  const auto colon = name.rfind(':');
  if (last == std::string::npos || colon == std::string::npos || colon < last) return "";
  return name.substr(last + 1, colon - last - 1);
}

struct Point {
  double x, y;
};
using Series = std::map<std::string, std::vector<Point>>;

const char* palette[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"};

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}

// One log–log panel at (left, top) of size w × h.
void panel(std::ostringstream& svg, double left, double top, double w, double h, const std::string& title,
           const std::string& x_label, const std::string& y_label, const Series& series,
           const std::vector<std::pair<std::string, double>>& lines) {
  double x0 = 1e300, x1 = 0, y0 = 1e300, y1 = 0;
  for (const auto& [name, points] : series) {
    for (const Point& p : points) {
      if (p.x <= 0 || p.y <= 0) continue;
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    }
  }
  for (const auto& [name, y] : lines) y0 = std::min(y0, y), y1 = std::max(y1, y);
  if (x1 <= 0) x0 = 1, x1 = 10;
  if (y1 <= 0) y0 = 1, y1 = 10;
  const double lx0 = std::floor(std::log10(x0) * 2) / 2, lx1 = std::ceil(std::log10(x1) * 2) / 2 + (x0 == x1 ? 0.5 : 0);
  const double ly0 = std::floor(std::log10(y0)), ly1 = std::ceil(std::log10(y1)) + (y0 == y1 ? 1 : 0);
  auto X = [&](double x) { return left + w * (std::log10(x) - lx0) / std::max(lx1 - lx0, 1e-9); };
  auto Y = [&](double y) { return top + h - h * (std::log10(y) - ly0) / std::max(ly1 - ly0, 1e-9); };
  svg << "<text x='" << left + w / 2 << "' y='" << top - 12 << "' text-anchor='middle' font-size='15'>" << title << "</text>\n";
  svg << "<rect x='" << left << "' y='" << top << "' width='" << w << "' height='" << h << "' fill='none' stroke='#444'/>\n";
  for (double e = ly0; e <= ly1 + 1e-9; e += 1) {
    const double y = Y(std::pow(10, e));
    svg << "<line x1='" << left << "' x2='" << left + w << "' y1='" << y << "' y2='" << y << "' stroke='#ddd'/>";
    svg << "<text x='" << left - 6 << "' y='" << y + 4 << "' text-anchor='end' font-size='11'>" << number(std::pow(10, e)) << "</text>\n";
  }
  for (double e = std::ceil(lx0); e <= lx1 + 1e-9; e += 1) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * std::pow(10, e);
      if (std::log10(v) < lx0 - 1e-9 || std::log10(v) > lx1 + 1e-9) continue;
      const double x = X(v);
      svg << "<line x1='" << x << "' x2='" << x << "' y1='" << top << "' y2='" << top + h << "' stroke='#ddd'/>";
      svg << "<text x='" << x << "' y='" << top + h + 16 << "' text-anchor='middle' font-size='11'>" << number(v) << "</text>\n";
    }
  }
  svg << "<text x='" << left + w / 2 << "' y='" << top + h + 36 << "' text-anchor='middle' font-size='12'>" << x_label << "</text>\n";
  svg << "<text transform='translate(" << left - 48 << "," << top + h / 2 << ") rotate(-90)' text-anchor='middle' font-size='12'>"
      << y_label << "</text>\n";
  for (const auto& [name, y] : lines) {
    svg << "<line x1='" << left << "' x2='" << left + w << "' y1='" << Y(y) << "' y2='" << Y(y)
        << "' stroke='#888' stroke-dasharray='6,4'/><text x='" << left + w - 4 << "' y='" << Y(y) - 4
        << "' text-anchor='end' font-size='11' fill='#555'>" << name << "</text>\n";
  }
  int k = 0;
  for (const auto& [name, points] : series) {
    const char* colour = palette[k % 8];
    std::vector<Point> sorted = points;
    std::sort(sorted.begin(), sorted.end(), [](const Point& a, const Point& b) { return a.x < b.x; });
    std::ostringstream path;
    for (const Point& p : sorted) {
      if (p.x <= 0 || p.y <= 0) continue;
      path << (path.tellp() == 0 ? "" : " ") << X(p.x) << "," << Y(p.y);
      svg << "<circle cx='" << X(p.x) << "' cy='" << Y(p.y) << "' r='3.5' fill='" << colour << "'/>";
    }
    svg << "<polyline points='" << path.str() << "' fill='none' stroke='" << colour << "' stroke-width='2'/>\n";
    svg << "<rect x='" << left + 10 << "' y='" << top + 10 + 18 * k << "' width='12' height='12' fill='" << colour << "'/>"
        << "<text x='" << left + 28 << "' y='" << top + 20 + 18 * k << "' font-size='12'>" << name << "</text>\n";
    ++k;
  }
}

// Bandwidth context for every case (stream_sweeps, bandwidth_fraction), from the table's stream_triad row: this
// run's or an earlier one's.
void add_bandwidth_notes(std::vector<Row>& rows) {
  double gbps = 0;
  for (const auto& r : rows) {
    if (r.name == "stream_triad") {
      if (auto it = r.values.find("bandwidth_GBps"); it != r.values.end()) gbps = it->second;
    }
  }
  if (gbps <= 0) return;
  for (auto& r : rows) {
    if (r.seconds <= 0) continue;
    if (auto it = r.values.find("memory_max_MB"); it != r.values.end() && it->second > 0) {
      r.values["stream_sweeps"] = r.seconds * gbps / (it->second / 1000.0);
    }
    if (auto it = r.values.find("drag_bytes_GB"); it != r.values.end() && it->second > 0) {
      r.values["bandwidth_fraction"] = it->second / r.seconds / gbps;
    }
  }
}

}  // namespace

void write_results(const fs::path& dir, std::vector<Row> rows) {
  fs::create_directories(dir);
  // Earlier rows of other cases stay.
  if (std::ifstream old(dir / "scale.json"); old) {
    const nlohmann::json earlier = nlohmann::json::parse(old, nullptr, false);
    if (earlier.is_array()) {
      for (const auto& j : earlier) {
        Row r;
        r.name = j.value("case", "");
        r.ranks = j.value("ranks", 1);
        r.repetitions = j.value("repetitions", 1);
        r.seconds = j.value("seconds", 0.0);
        const bool measured = std::any_of(rows.begin(), rows.end(), [&](const Row& n) { return n.name == r.name && n.ranks == r.ranks; });
        if (measured || r.name.empty()) continue;
        for (const auto& [key, value] : j.items()) {
          if (value.is_number() && key != "ranks" && key != "repetitions" && key != "seconds") r.values[key] = value.get<double>();
        }
        rows.push_back(std::move(r));
      }
    }
  }
  add_bandwidth_notes(rows);
  std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return std::tie(a.name, a.ranks) < std::tie(b.name, b.ranks);
  });
  std::set<std::string> keys;
  for (const Row& r : rows) {
    for (const auto& [key, value] : r.values) {
      if (key != "ranks" && key != "repetitions" && key != "seconds") keys.insert(key);  // columns of their own
    }
  }
  // CSV: case, series, seconds, then every counter (empty where a case lacks it).
  std::ostringstream csv;
  csv << std::setprecision(6) << "case,series,ranks,repetitions,seconds";
  for (const auto& key : keys) csv << "," << key;
  csv << "\n";
  nlohmann::json json = nlohmann::json::array();
  for (const Row& r : rows) {
    csv << r.name << "," << series_of(r.name) << "," << r.ranks << "," << r.repetitions << "," << r.seconds;
    for (const auto& key : keys) {
      csv << ",";
      if (auto it = r.values.find(key); it != r.values.end()) csv << it->second;
    }
    csv << "\n";
    nlohmann::json j = {{"case", r.name}, {"series", series_of(r.name)}, {"ranks", r.ranks}, {"repetitions", r.repetitions},
                        {"seconds", r.seconds}};
    for (const auto& [key, value] : r.values) j[key] = value;
    json.push_back(std::move(j));
  }
  write_atomically(dir / "scale.csv", csv.str());
  write_atomically(dir / "scale.json", json.dump(2) + "\n");

  // One picture per study: time and memory (max over ranks where measured) against its x.
  std::map<std::string, std::pair<Series, Series>> studies;
  std::map<std::string, std::string> x_labels;
  for (const Row& r : rows) {
    const std::string study = study_of(r.name);
    const std::string key = x_key_of(r.name);
    // Strong and weak scaling: x is the worker count (ranks × threads); otherwise the case's own x.
    const bool workers = study == "strong" || study == "weak";
    const auto x_it = r.values.find(workers ? "workers" : key);
    if (key.empty() || x_it == r.values.end()) continue;
    x_labels[study] = workers ? (study == "weak" ? "workers (ranks × threads), size per worker fixed" : "workers (ranks × threads), fixed size")
                              : key == "agents" ? "agents (× frames given in the case)" : key == "frames" ? "frames (agents fixed)" : key;
    // Strong and weak: one line per thread count, its points the rank counts (x = ranks × threads).
    std::string s = series_of(r.name);
    if (workers) {
      const auto t = r.values.find("threads");
      const int threads = t == r.values.end() ? 1 : static_cast<int>(t->second);
      s += " (" + std::to_string(threads) + (threads == 1 ? " thread" : " threads") + " per rank)";
    } else if (r.ranks > 1) {
      s += " (" + std::to_string(r.ranks) + " ranks)";
    }
    auto& [time, memory] = studies[study];
    time[s + " per drag"].push_back({x_it->second, r.seconds});
    for (const char* extra : {"precompute_s", "region_build_s"}) {
      if (auto it = r.values.find(extra); it != r.values.end()) {
        time[s + (std::string(extra) == "precompute_s" ? " precompute" : " region build")].push_back({x_it->second, it->second});
      }
    }
    auto m = r.values.find("memory_max_MB");
    if (m == r.values.end()) m = r.values.find("memory_MB");
    if (m != r.values.end()) memory[s].push_back({x_it->second, std::max(m->second, 1.0)});
  }
  for (const auto& [study, panels] : studies) {
    std::ostringstream svg;
    svg << std::setprecision(5);
    svg << "<svg xmlns='http://www.w3.org/2000/svg' width='1200' height='520' font-family='sans-serif'>\n"
        << "<rect width='1200' height='520' fill='white'/>\n";
    const std::vector<std::pair<std::string, double>> target =
        study == "size" || study == "parts" ? std::vector<std::pair<std::string, double>>{{"0.1 s target", 0.1}} : std::vector<std::pair<std::string, double>>{};
    panel(svg, 80, 50, 480, 400, "Time (" + study + ", median)", x_labels[study], "seconds", panels.first, target);
    panel(svg, 700, 50, 460, 400, "Memory held (max over ranks)", x_labels[study], "MB", panels.second, {});
    svg << "</svg>\n";
    write_atomically(dir / ("scale-" + study + ".svg"), svg.str());
  }
}

}  // namespace scale
