#include <throng/core/errors.h>
#include <throng/formation/shapes.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace throng::formation {
namespace {

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

}  // namespace

Eigen::MatrixXd circle(int count, double radius) {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < count; ++i) {
    const double a = 2 * std::numbers::pi * i / count;
    p.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  return rows_of(p);
}

Eigen::MatrixXd grid(int rows, int columns, double dx, double dy) {
  std::vector<Eigen::Vector2d> p;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) p.emplace_back((c - 0.5 * (columns - 1)) * dx, (0.5 * (rows - 1) - r) * dy);
  return rows_of(p);
}

Eigen::MatrixXd polyline(Line line, int count, bool closed) {
  if (closed) line.push_back(line.front());
  const double length = line_length(line);
  if (!(length > 0)) throw ConfigError("the polyline has zero length");
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < count; ++i) {
    const double s = closed ? length * i / count : (count == 1 ? 0.5 * length : length * i / (count - 1));
    p.push_back(point_at(line, s));
  }
  return rows_of(p);
}

Eigen::MatrixXd star(int count, double outer_radius, double inner_radius, int tips) {
  Line outline;
  for (int i = 0; i <= 2 * tips; ++i) {
    const double a = std::numbers::pi / 2 + std::numbers::pi * i / tips;
    const double r = i % 2 == 0 ? outer_radius : inner_radius;
    outline.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  const double length = line_length(outline);
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < count; ++i) p.push_back(point_at(outline, length * i / count));
  return rows_of(p);
}

Eigen::MatrixXd sample_strokes(const std::vector<Line>& lines, int count) {
  double total = 0;
  for (const Line& l : lines) total += line_length(l);
  if (!(total > 0)) throw ConfigError("the lines have zero length");
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

Eigen::MatrixXd place(Eigen::MatrixXd shape, double rotation_degrees, std::vector<double> center,
                      const std::optional<std::array<Eigen::Vector3d, 2>>& axes) {
  if (rotation_degrees != 0) {
    const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(rotation_degrees * std::numbers::pi / 180.0).toRotationMatrix();
    shape = shape * rotation.transpose();
  }
  if (center.size() == 2 && !axes) {
    shape.col(0).array() += center[0];
    shape.col(1).array() += center[1];
    return shape;
  }
  Eigen::Vector3d u(1, 0, 0), v(0, 1, 0);
  if (axes) {
    u = (*axes)[0];
    v = (*axes)[1];
    if (u.norm() == 0 || v.norm() == 0 || u.cross(v).norm() < 1e-9 * u.norm() * v.norm())
      throw ConfigError("axes: the two directions must be non-zero and not parallel");
  }
  center.resize(3, 0.0);
  Eigen::MatrixXd out(shape.rows(), 3);
  for (Eigen::Index i = 0; i < shape.rows(); ++i)
    out.row(i) = (Eigen::Vector3d(center[0], center[1], center[2]) + shape(i, 0) * u + shape(i, 1) * v).transpose();
  return out;
}

Eigen::MatrixXd nested(const std::vector<Eigen::MatrixXd>& parts) {
  Eigen::Index d = 2, total = 1;
  for (const Eigen::MatrixXd& part : parts) {
    d = std::max(d, part.cols());
    total *= part.rows();
    if (total > 10'000'000) throw ConfigError("nested shapes make more than 10,000,000 points");
  }
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

Eigen::MatrixXd stacked(const std::vector<Eigen::MatrixXd>& parts) {
  Eigen::Index rows = 0, d = 2;
  for (const Eigen::MatrixXd& part : parts) {
    rows += part.rows();
    d = std::max(d, part.cols());
  }
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(rows, d);
  Eigen::Index row = 0;
  for (const Eigen::MatrixXd& part : parts) {
    out.block(row, 0, part.rows(), part.cols()) = part;
    row += part.rows();
  }
  return out;
}

}  // namespace throng::formation
