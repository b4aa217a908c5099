// Nearest-neighbour queries among fixed points in the plane (a k-d tree: nanoflann). Built once, queried many
// times; used where an all-pairs scan would grow as n² (the stitch's boundary fit, the planar assignment).
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <vector>

namespace throng {

/// Points in the plane, one per row (metres).
using PlanarPoints = Eigen::Matrix<double, Eigen::Dynamic, 2>;

class PlanarIndex {
 public:
  /// Indexes a copy of `points` (n × 2, finite). O(n log n).
  explicit PlanarIndex(const Eigen::Ref<const PlanarPoints>& points);
  ~PlanarIndex();
  PlanarIndex(const PlanarIndex&) = delete;
  PlanarIndex& operator=(const PlanarIndex&) = delete;

  [[nodiscard]] std::size_t size() const noexcept;

  /// The row of the point nearest `query` (among equally near ones, the one the tree meets first: the same
  /// for the same points). Requires size() > 0.
  [[nodiscard]] std::size_t nearest(const Eigen::Vector2d& query) const;

  /// The rows of the min(k, size()) points nearest `query`, nearest first, into `rows` (resized).
  void nearest(const Eigen::Vector2d& query, std::size_t k, std::vector<std::size_t>& rows) const;

 private:
  struct Tree;
  std::unique_ptr<Tree> tree_;
};

}  // namespace throng
