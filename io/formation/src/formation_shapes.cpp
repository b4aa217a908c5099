// The `shapes:` key of a formation keyframe: each entry's parameters read with their lines, the points made by
// the generators in throng/formation/shapes.h.
#include <throng/core/errors.h>
#include <throng/formation/shapes.h>
#include <throng/io/formation_shapes.h>

#include <cmath>

namespace throng {
namespace {

using formation::Line;

int read_count(const ConfigNode& shape, const char* key = "count") {
  const ConfigNode n = shape.at(key);
  const std::int64_t v = n.as_int();
  if (v < 1 || v > 10'000'000) n.fail(std::string(key) + " must be in [1, 10000000], got " + std::to_string(v));
  return static_cast<int>(v);
}

double read_length(const ConfigNode& shape, const char* key, bool positive = true) {
  const ConfigNode n = shape.at(key);
  const double v = n.as_double();
  if (!std::isfinite(v) || (positive ? !(v > 0) : v < 0))
    n.fail(std::string(key) + " must be a finite number " + (positive ? "> 0" : "≥ 0") + " (metres)");
  return v;
}

Line read_line(const ConfigNode& node) {
  Line line;
  for (const ConfigNode& p : node.elements()) {
    const std::vector<double> v = p.as_doubles({2});
    line.emplace_back(v[0], v[1]);
  }
  if (line.size() < 2) node.fail("a line needs at least 2 points, found " + std::to_string(line.size()));
  return line;
}

// A generator's result, its errors placed at `where`.
template <class Make>
Eigen::MatrixXd made_at(const ConfigNode& where, Make&& make) {
  try {
    return make();
  } catch (const ConfigError& e) {
    where.fail(e.what());
  }
}

// The placement keys of a generated shape: rotation (degrees), center, axes.
Eigen::MatrixXd place(Eigen::MatrixXd shape, const ConfigNode& spec) {
  double degrees = 0;
  if (auto r = spec.find("rotation")) degrees = r->as_double();
  std::vector<double> center{0.0, 0.0};
  if (auto c = spec.find("center")) center = c->as_doubles({2, 3});
  std::optional<std::array<Eigen::Vector3d, 2>> axes;
  const auto axes_node = spec.find("axes");
  if (axes_node) {
    const std::vector<ConfigNode> list = axes_node->elements();
    if (list.size() != 2) axes_node->fail("axes: give two directions, [[ux, uy, uz], [vx, vy, vz]]");
    const std::vector<double> a = list[0].as_doubles({3}), b = list[1].as_doubles({3});
    axes = std::array<Eigen::Vector3d, 2>{Eigen::Vector3d(a[0], a[1], a[2]), Eigen::Vector3d(b[0], b[1], b[2])};
  }
  return made_at(axes_node ? *axes_node : spec, [&] { return formation::place(std::move(shape), degrees, center, axes); });
}

Eigen::MatrixXd grid(const ConfigNode& s) {
  const int rows = read_count(s, "rows"), columns = read_count(s, "columns");
  const ConfigNode sp = s.at("spacing");
  const std::vector<double> d = sp.is_sequence() ? sp.as_doubles({2}) : std::vector<double>(2, sp.as_double());
  if (!(d[0] > 0) || !(d[1] > 0) || !std::isfinite(d[0]) || !std::isfinite(d[1])) sp.fail("spacing must be > 0 (metres)");
  return formation::grid(rows, columns, d[0], d[1]);
}

Eigen::MatrixXd polyline(const ConfigNode& s) {
  const ConfigNode points = s.at("points");
  Line line = read_line(points);
  const int n = read_count(s);
  bool closed = false;
  if (auto c = s.find("closed")) closed = c->as_bool();
  return made_at(points, [&] { return formation::polyline(std::move(line), n, closed); });
}

Eigen::MatrixXd star(const ConfigNode& s) {
  const int n = read_count(s);
  const double outer = read_length(s, "outer_radius"), inner = read_length(s, "inner_radius");
  int tips = 5;
  if (auto t = s.find("tips")) {
    const std::int64_t v = t->as_int();
    if (v < 3 || v > 1000) t->fail("tips must be in [3, 1000]");
    tips = static_cast<int>(v);
  }
  return formation::star(n, outer, inner, tips);
}

Eigen::MatrixXd strokes(const ConfigNode& s) {
  const ConfigNode lines_node = s.at("lines");
  std::vector<Line> lines;
  for (const ConfigNode& l : lines_node.elements()) lines.push_back(read_line(l));
  if (lines.empty()) lines_node.fail("give at least one line");
  const int n = read_count(s);
  return made_at(lines_node, [&] { return formation::sample_strokes(lines, n); });
}

Eigen::MatrixXd text(const ConfigNode& s) {
  const ConfigNode t = s.at("text");
  const double height = read_length(s, "height");
  const int n = read_count(s);
  return made_at(t, [&] { return formation::sample_strokes(formation::text_strokes(t.as_string(), height), n); });
}

Eigen::MatrixXd nested(const ConfigNode& s) {
  std::vector<Eigen::MatrixXd> parts;
  for (const ConfigNode& part : s.elements()) parts.push_back(generate_shape(part));
  if (parts.empty()) s.fail("nested: give at least one shape");
  return made_at(s, [&] { return formation::nested(parts); });
}

Eigen::MatrixXd points(const ConfigNode& s) {
  const std::vector<ConfigNode> rows = s.elements();
  if (rows.empty()) s.fail("points: give at least one point");
  const std::size_t d = rows.front().as_doubles({2, 3}).size();
  Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(d));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::vector<double> v = rows[i].as_doubles({d});
    for (std::size_t a = 0; a < d; ++a) out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(a)) = v[a];
  }
  return out;
}

}  // namespace

Eigen::MatrixXd generate_shape(const ConfigNode& shape) {
  if (!shape.is_map() || shape.yaml().size() != 1)
    shape.fail("a shape is a mapping with one generator key: points, circle, grid, polyline, star, strokes, text or nested");
  const std::string kind = shape.keys().front();
  const ConfigNode spec = shape.at(kind);
  if (kind == "nested") return nested(spec);
  if (kind == "points") return points(spec);
  if (!spec.is_map()) spec.fail(kind + ": expected a mapping of parameters");
  Eigen::MatrixXd raw;
  if (kind == "circle") raw = formation::circle(read_count(spec), read_length(spec, "radius"));
  else if (kind == "grid") raw = grid(spec);
  else if (kind == "polyline") raw = polyline(spec);
  else if (kind == "star") raw = star(spec);
  else if (kind == "strokes") raw = strokes(spec);
  else if (kind == "text") raw = text(spec);
  else shape.fail("unknown shape '" + kind + "'; expected points, circle, grid, polyline, star, strokes, text or nested");
  return place(std::move(raw), spec);
}

Eigen::MatrixXd generate_shapes(const ConfigNode& shapes) {
  std::vector<Eigen::MatrixXd> parts;
  for (const ConfigNode& s : shapes.elements()) parts.push_back(generate_shape(s));
  if (parts.empty()) shapes.fail("give at least one shape");
  return formation::stacked(parts);
}

}  // namespace throng
