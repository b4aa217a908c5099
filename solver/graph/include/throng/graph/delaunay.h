// Delaunay triangulation of 2-D points (CGAL), the source of formation edges and formation adjacency.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace throng {

/// A planar Delaunay triangulation over input point indices.
///   triangles  #triangles, each 3 point indices in counter-clockwise order
///   edges      #edges, each 2 point indices (i < j), sorted; includes edges of degenerate (collinear) input
///   duplicate_of  #points; −1 for a point that is a vertex, else the index of the earlier point at the same
///                 position (CGAL keeps one vertex per position: such a point has no triangle or edge)
struct Triangulation {
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 2>> edges;
  std::vector<int> duplicate_of;

  [[nodiscard]] bool has_duplicates() const noexcept;
};

/// Delaunay triangulation of `points` (#points by 2, any finite values), with exact predicates so the result is
/// robust and deterministic. Fewer than 2 distinct points give no edges; collinear points give a path of edges
/// and no triangles. Output order is canonical (sorted), independent of CGAL's internal order.
[[nodiscard]] Triangulation delaunay_2d(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& points);

}  // namespace throng
