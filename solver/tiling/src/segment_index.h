// The space-time index of path segments: which capsules of the tiling might come close to a new one.
//
// The paper's bottleneck ("more than half of the computation time is spent for bounding box tests"). Every
// segment between consecutive samples of every fragment (character or prop) is a disc moving linearly from one
// sample to the next; it is stored in each grid cell its space-time box (grown by its radius) overlaps. A query
// visits the cells of its own box grown by its radius and the largest stored radius, and runs the exact
// closest-approach test (geometry.h) on the nearest periodic image of each entry. Inserting and removing an
// instance touches only its own cells: adding or removing patches never rebuilds the index.
#pragma once

#include <throng/tiling/options.h>
#include <throng/tiling/patch.h>
#include <throng/tiling/tiling.h>

#include "geometry.h"
#include "grid.h"

#include <cstdint>
#include <vector>

namespace throng::tiling {

class SegmentIndex {
 public:
  /// An index over `region` (periodic axes wrap; others extend by the margins and clamp).
  SegmentIndex(const Region& region, const IndexOptions& options, double margin_m, double margin_s);

  /// Adds every segment of `paths` (fragments of `type`) under `instance`.
  void insert(std::uint32_t instance, const PatchType& type, const std::vector<Path>& paths);
  /// Removes what insert() added for `instance` with the same paths.
  void remove(std::uint32_t instance, const std::vector<Path>& paths, const PatchType& type);

  /// True when the moving disc `q` comes closer than the sum of radii to a stored segment of a fragment for
  /// which skip(instance, fragment) is false.
  template <class Skip>
  [[nodiscard]] bool collides(const MovingDisc& q, Skip&& skip) const;

  [[nodiscard]] std::size_t entries() const noexcept { return entries_; }

 private:
  struct Entry {
    MovingDisc disc;
    std::uint32_t instance;
    std::uint32_t fragment;
  };
  template <class Visit>
  void for_each_cell_of(const MovingDisc& d, double grow, Visit&& visit) const {
    grid_.for_each_cell(std::min(d.a.x(), d.b.x()) - grow, std::max(d.a.x(), d.b.x()) + grow,
                        std::min(d.a.y(), d.b.y()) - grow, std::max(d.a.y(), d.b.y()) + grow, d.ta, d.tb,
                        std::forward<Visit>(visit));
  }

  Grid3 grid_;
  Periods periods_;
  std::vector<std::vector<Entry>> cells_;
  double max_radius_ = 0;
  std::size_t entries_ = 0;
};

template <class Skip>
bool SegmentIndex::collides(const MovingDisc& q, Skip&& skip) const {
  bool hit = false;
  for_each_cell_of(q, q.radius + max_radius_, [&](std::size_t cell) {
    if (hit) return;
    for (const Entry& e : cells_[cell]) {
      if (skip(e.instance, e.fragment)) continue;
      const MovingDisc d = nearest_image_of(e.disc, q, periods_);
      if (d.tb < q.ta || d.ta > q.tb) continue;
      const double reach = q.radius + d.radius;
      if (std::min(d.a.x(), d.b.x()) > std::max(q.a.x(), q.b.x()) + reach ||
          std::max(d.a.x(), d.b.x()) < std::min(q.a.x(), q.b.x()) - reach ||
          std::min(d.a.y(), d.b.y()) > std::max(q.a.y(), q.b.y()) + reach ||
          std::max(d.a.y(), d.b.y()) < std::min(q.a.y(), q.b.y()) - reach) {
        continue;
      }
      if (closest_approach(q, d) < reach) {
        hit = true;
        return;
      }
    }
  });
  return hit;
}

}  // namespace throng::tiling
