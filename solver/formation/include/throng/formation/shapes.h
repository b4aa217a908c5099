// Shape generators for formation keyframes: large keyframe sets (a ring of 35 groups of 6 rings of 6, ten planes
// spelling a letter) are impractical to type point by point. Each returns the rows (#points by 2, or 3 after
// placing in space) of one shape, made about its own origin; the job's `shapes:` key (throng/io/formation_shapes.h)
// reads the parameters and calls them. Impossible parameters are ConfigErrors (the job reader adds the place).
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace throng::formation {

using Line = std::vector<Eigen::Vector2d>;

/// A ring of `count` points, point 0 at angle 0, counter-clockwise.
[[nodiscard]] Eigen::MatrixXd circle(int count, double radius);
/// rows × columns points `dx`, `dy` apart, row-major from the top-left, centred.
[[nodiscard]] Eigen::MatrixXd grid(int rows, int columns, double dx, double dy);
/// `count` points evenly by arc length: open, both ends included; closed, back to the first point, `count` points
/// around. ConfigError for a line of zero length.
[[nodiscard]] Eigen::MatrixXd polyline(Line line, int count, bool closed);
/// `count` points evenly around the closed outline of a star with `tips` tips, a tip at 90° (up).
[[nodiscard]] Eigen::MatrixXd star(int count, double outer_radius, double inner_radius, int tips);
/// `count` points evenly by arc length along several polylines taken end to end (spacing L/count, the first
/// point half a spacing from the start of the first line). ConfigError for lines of zero total length.
[[nodiscard]] Eigen::MatrixXd sample_strokes(const std::vector<Line>& lines, int count);
/// The strokes of `text` in the built-in font (src/font.cpp): capitals A–Z and spaces, each letter in a box 0.6
/// wide and 1 high, letters 0.85 apart, the whole text centred on (0, 0) and scaled to `height`. ConfigError for a
/// character the font does not have.
[[nodiscard]] std::vector<Line> text_strokes(const std::string& text, double height);

/// Places a 2-D shape: rotated by `rotation_degrees` about its origin, then moved to `center` ([x, y], or
/// [x, y, z] to place it in space); with `axes` (the directions of the shape's x and y in space) the rows are
/// 3-D: center + x·axes[0] + y·axes[1]. ConfigError for axes that are zero or parallel.
[[nodiscard]] Eigen::MatrixXd place(Eigen::MatrixXd shape, double rotation_degrees, std::vector<double> center,
                                    const std::optional<std::array<Eigen::Vector3d, 2>>& axes);
/// Every combination of the parts' rows, the first part's index varying slowest; rows add up (a mix of 2-D and 3-D
/// is 3-D). ConfigError beyond 10,000,000 points.
[[nodiscard]] Eigen::MatrixXd nested(const std::vector<Eigen::MatrixXd>& parts);
/// The parts' rows one after the other (individuals 0.. of the first part, then the second's ...).
[[nodiscard]] Eigen::MatrixXd stacked(const std::vector<Eigen::MatrixXd>& parts);

}  // namespace throng::formation
