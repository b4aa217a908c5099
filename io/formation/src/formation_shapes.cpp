#include <throng/io/formation_shapes.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>

namespace throng {
namespace {

using Line = std::vector<Eigen::Vector2d>;

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

double line_length(const Line& line) {
  double length = 0;
  for (std::size_t i = 1; i < line.size(); ++i) length += (line[i] - line[i - 1]).norm();
  return length;
}

// The point at arc length s along `line` (clamped to its ends).
Eigen::Vector2d point_at(const Line& line, double s) {
  for (std::size_t i = 1; i < line.size(); ++i) {
    const double l = (line[i] - line[i - 1]).norm();
    if (s <= l && l > 0) return line[i - 1] + (s / l) * (line[i] - line[i - 1]);
    s -= l;
  }
  return line.back();
}

Eigen::MatrixXd rows_of(const std::vector<Eigen::Vector2d>& points) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return m;
}

// Places a 2-D shape: rotation (degrees) about its origin, then center (+ axes in 3-D).
Eigen::MatrixXd place(Eigen::MatrixXd shape, const ConfigNode& spec) {
  if (auto r = spec.find("rotation")) {
    const double degrees = r->as_double();
    if (!std::isfinite(degrees)) r->fail("rotation must be a finite number of degrees");
    const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(degrees * std::numbers::pi / 180.0).toRotationMatrix();
    shape = shape * rotation.transpose();
  }
  std::vector<double> center{0.0, 0.0};
  if (auto c = spec.find("center")) center = c->as_doubles({2, 3});
  const auto axes_node = spec.find("axes");
  if (center.size() == 2 && !axes_node) {
    shape.col(0).array() += center[0];
    shape.col(1).array() += center[1];
    return shape;
  }
  Eigen::Vector3d u(1, 0, 0), v(0, 1, 0);
  if (axes_node) {
    const std::vector<ConfigNode> axes = axes_node->elements();
    if (axes.size() != 2) axes_node->fail("axes: give two directions, [[ux, uy, uz], [vx, vy, vz]]");
    const std::vector<double> a = axes[0].as_doubles({3}), b = axes[1].as_doubles({3});
    u = Eigen::Vector3d(a[0], a[1], a[2]);
    v = Eigen::Vector3d(b[0], b[1], b[2]);
    if (u.norm() == 0 || v.norm() == 0 || u.cross(v).norm() < 1e-9 * u.norm() * v.norm())
      axes_node->fail("axes: the two directions must be non-zero and not parallel");
  }
  center.resize(3, 0.0);
  Eigen::MatrixXd out(shape.rows(), 3);
  for (Eigen::Index i = 0; i < shape.rows(); ++i)
    out.row(i) = (Eigen::Vector3d(center[0], center[1], center[2]) + shape(i, 0) * u + shape(i, 1) * v).transpose();
  return out;
}

Eigen::MatrixXd circle(const ConfigNode& s) {
  const int n = read_count(s);
  const double r = read_length(s, "radius");
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n;
    p.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return rows_of(p);
}

Eigen::MatrixXd grid(const ConfigNode& s) {
  const int rows = read_count(s, "rows"), columns = read_count(s, "columns");
  const ConfigNode sp = s.at("spacing");
  const std::vector<double> d = sp.is_sequence() ? sp.as_doubles({2}) : std::vector<double>(2, sp.as_double());
  if (!(d[0] > 0) || !(d[1] > 0) || !std::isfinite(d[0]) || !std::isfinite(d[1])) sp.fail("spacing must be > 0 (metres)");
  std::vector<Eigen::Vector2d> p;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c)
      p.emplace_back((c - 0.5 * (columns - 1)) * d[0], (0.5 * (rows - 1) - r) * d[1]);
  return rows_of(p);
}

Eigen::MatrixXd polyline(const ConfigNode& s) {
  const ConfigNode points = s.at("points");
  Line line = read_line(points);
  const int n = read_count(s);
  bool closed = false;
  if (auto c = s.find("closed")) closed = c->as_bool();
  if (closed) line.push_back(line.front());
  const double length = line_length(line);
  if (!(length > 0)) points.fail("the polyline has zero length");
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) {
    const double s_i = closed ? length * i / n : (n == 1 ? 0.5 * length : length * i / (n - 1));
    p.push_back(point_at(line, s_i));
  }
  return rows_of(p);
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
  Line outline;
  for (int i = 0; i <= 2 * tips; ++i) {
    const double a = std::numbers::pi / 2 + std::numbers::pi * i / tips;
    const double r = i % 2 == 0 ? outer : inner;
    outline.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  const double length = line_length(outline);
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < n; ++i) p.push_back(point_at(outline, length * i / n));
  return rows_of(p);
}

Eigen::MatrixXd strokes(const ConfigNode& s) {
  const ConfigNode lines_node = s.at("lines");
  std::vector<Line> lines;
  for (const ConfigNode& l : lines_node.elements()) lines.push_back(read_line(l));
  if (lines.empty()) lines_node.fail("give at least one line");
  return sample_strokes(lines, read_count(s), lines_node);
}

Eigen::MatrixXd text(const ConfigNode& s) {
  const ConfigNode t = s.at("text");
  return sample_strokes(text_strokes(t.as_string(), read_length(s, "height"), t), read_count(s), t);
}

// All combinations of the rows of `parts`, the first part's index varying slowest; rows add up.
Eigen::MatrixXd nested(const ConfigNode& s) {
  std::vector<Eigen::MatrixXd> parts;
  Eigen::Index d = 2, total = 1;
  for (const ConfigNode& part : s.elements()) {
    parts.push_back(generate_shape(part));
    d = std::max(d, parts.back().cols());
    total *= parts.back().rows();
    if (total > 10'000'000) s.fail("nested shapes make more than 10,000,000 points");
  }
  if (parts.empty()) s.fail("nested: give at least one shape");
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(1, d);
  for (const Eigen::MatrixXd& part : parts) {
    Eigen::MatrixXd next = Eigen::MatrixXd::Zero(out.rows() * part.rows(), d);
    for (Eigen::Index a = 0; a < out.rows(); ++a)
      for (Eigen::Index b = 0; b < part.rows(); ++b) {
        next.row(a * part.rows() + b) = out.row(a);
        next.row(a * part.rows() + b).head(part.cols()) += part.row(b);
      }
    out = std::move(next);
  }
  return out;
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

Eigen::MatrixXd sample_strokes(const std::vector<std::vector<Eigen::Vector2d>>& lines, int count, const ConfigNode& where) {
  double total = 0;
  for (const Line& l : lines) total += line_length(l);
  if (!(total > 0)) where.fail("the lines have zero length");
  std::vector<Eigen::Vector2d> p;
  std::size_t line = 0;
  double before = 0;  // arc length of the lines before `line`
  for (int i = 0; i < count; ++i) {
    const double s = (i + 0.5) * total / count;
    while (line + 1 < lines.size() && s > before + line_length(lines[line])) before += line_length(lines[line++]);
    p.push_back(point_at(lines[line], s - before));
  }
  return rows_of(p);
}

Eigen::MatrixXd generate_shape(const ConfigNode& shape) {
  if (!shape.is_map() || shape.yaml().size() != 1)
    shape.fail("a shape is a mapping with one generator key: points, circle, grid, polyline, star, strokes, text or nested");
  const std::string kind = shape.keys().front();
  const ConfigNode spec = shape.at(kind);
  if (kind == "nested") return nested(spec);
  if (kind == "points") return points(spec);
  if (!spec.is_map()) spec.fail(kind + ": expected a mapping of parameters");
  Eigen::MatrixXd raw;
  if (kind == "circle") raw = circle(spec);
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
  Eigen::Index rows = 0, d = 2;
  for (const ConfigNode& s : shapes.elements()) {
    parts.push_back(generate_shape(s));
    rows += parts.back().rows();
    d = std::max(d, parts.back().cols());
  }
  if (parts.empty()) shapes.fail("give at least one shape");
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(rows, d);
  Eigen::Index row = 0;
  for (const Eigen::MatrixXd& part : parts) {
    out.block(row, 0, part.rows(), part.cols()) = part;
    row += part.rows();
  }
  return out;
}

}  // namespace throng
