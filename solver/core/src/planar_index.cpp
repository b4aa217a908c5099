#include <throng/core/planar_index.h>

#include <nanoflann.hpp>

namespace throng {

// nanoflann's dataset interface over the copied points.
struct PlanarIndex::Tree {
  struct Source {
    PlanarPoints points;
    [[nodiscard]] std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points.rows()); }
    [[nodiscard]] double kdtree_get_pt(std::size_t row, std::size_t dim) const {
      return points(static_cast<Eigen::Index>(row), static_cast<Eigen::Index>(dim));
    }
    template <class Box>
    bool kdtree_get_bbox(Box& /*unused*/) const { return false; }  // nanoflann computes it
  };
  using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, Source>, Source, 2, std::size_t>;

  Source source;
  Index index;
  explicit Tree(const Eigen::Ref<const PlanarPoints>& points)
      : source{PlanarPoints(points)}, index(2, source, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}
};

PlanarIndex::PlanarIndex(const Eigen::Ref<const PlanarPoints>& points) : tree_(std::make_unique<Tree>(points)) {}
PlanarIndex::~PlanarIndex() = default;

std::size_t PlanarIndex::size() const noexcept { return static_cast<std::size_t>(tree_->source.points.rows()); }

std::size_t PlanarIndex::nearest(const Eigen::Vector2d& query) const {
  std::size_t row = 0;
  double squared = 0;
  tree_->index.knnSearch(query.data(), 1, &row, &squared);
  return row;
}

void PlanarIndex::nearest(const Eigen::Vector2d& query, std::size_t k, std::vector<std::size_t>& rows) const {
  k = std::min(k, size());
  rows.resize(k);
  std::vector<double> squared(k);
  rows.resize(tree_->index.knnSearch(query.data(), k, rows.data(), squared.data()));
}

}  // namespace throng
