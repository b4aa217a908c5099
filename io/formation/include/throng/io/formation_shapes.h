// The `shapes:` key of formation keyframes: large keyframe sets (a ring of 35 groups of 6 rings of 6, ten planes
// spelling a letter) are impractical to type point by point, so a keyframe may list shapes instead of positions.
// This reads their parameters; the generators are throng/formation/shapes.h.
//
// A keyframe's `shapes:` is a list; each entry is a mapping with exactly one generator key; the rows of all
// entries are concatenated in order (entry 0's points are individuals 0.., then entry 1's ...):
//
//   - points: [[x, y], ...]                         # explicit rows ([x, y, z] for 3-D)
//   - circle: {count: 12, radius: 5}                # a ring, point 0 at angle 0, counter-clockwise
//   - grid: {rows: 3, columns: 4, spacing: 1.5}     # spacing: d or [dx, dy]; row-major from the top-left
//   - polyline: {points: [[x, y], ...], count: 9, closed: false}
//                                                   # evenly by arc length; open: both ends included;
//                                                   # closed: back to the first point, count points around
//   - star: {count: 20, outer_radius: 6, inner_radius: 2.5, tips: 5}
//                                                   # the closed outline of a star, a tip at 90° (up)
//   - strokes: {lines: [[[x, y], ...], ...], count: 35}
//                                                   # several polylines (a stick figure): count points evenly
//                                                   # by arc length along the lines taken end to end, the
//                                                   # first and last half a spacing in from the ends
//   - text: {text: "T", count: 10, height: 40}      # capital letters A–Z (and spaces) of a built-in stroke
//                                                   # font, `height` tall, centred; sampled as `strokes`
//   - nested: [shape, shape, ...]                   # every point of the first shape carries a copy of the
//                                                   # second shape, and so on: the rows are all
//                                                   # combinations, the first shape's index varying slowest
//                                                   # (35 groups × 6 subgroups × 6 individuals)
//
// Every generator but `nested` also takes the placement keys (inside its mapping):
//   center: [0, 0]          # or [x, y, z] (a 3-D point: the shape is placed in space, see axes)
//   rotation: 0             # degrees, counter-clockwise about the shape's own origin, before placing
//   axes: [[1, 0, 0], [0, 1, 0]]   # the directions of the shape's x and y in space (3-D); giving axes or a
//                                  # 3-number center makes the rows 3-D: center + x·axes[0] + y·axes[1]
// Shapes are made about their own origin (a circle's centre, a grid's middle, a text's middle, a polyline's
// and a stroke set's given coordinates). In `nested`, the shapes' rows add up; a mix of 2-D and 3-D shapes is
// 3-D (z = 0 for the 2-D ones).
//
// Errors are ConfigErrors naming the line: an unknown generator, a count below 1, a zero-length polyline, an
// unknown letter. Coinciding points (a grid with spacing 0) are found later, as duplicate positions.
#pragma once

#include <throng/io/config.h>

#include <Eigen/Core>


namespace throng {

/// The rows (#points by 2 or 3) of one shapes list (a keyframe's `shapes:` value).
[[nodiscard]] Eigen::MatrixXd generate_shapes(const ConfigNode& shapes);

/// The rows of one entry of a shapes list.
[[nodiscard]] Eigen::MatrixXd generate_shape(const ConfigNode& shape);

}  // namespace throng
