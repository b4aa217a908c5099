#include "segment_index.h"

#include <algorithm>

namespace throng::tiling {

SegmentIndex::SegmentIndex(const Region& region, const IndexOptions& options, double margin_m, double margin_s)
    : grid_(region, options.cell_m, options.cell_s, margin_m, margin_s) {
  const Eigen::Vector3d p = periods(region);
  periods_.p = {p.x(), p.y(), p.z()};
  cells_.resize(grid_.cells());
}

void SegmentIndex::insert(std::uint32_t instance, const PatchType& type, const std::vector<Path>& paths) {
  for (std::size_t f = 0; f < paths.size(); ++f) {
    const Path& path = paths[f];
    const double r = type.fragments[f].radius_m;
    max_radius_ = std::max(max_radius_, r);
    for (std::size_t s = 0; s + 1 < path.times.size(); ++s) {
      const Entry e{{path.positions[s], path.positions[s + 1], path.times[s], path.times[s + 1], r}, instance,
                    static_cast<std::uint32_t>(f)};
      for_each_cell_of(e.disc, r, [&](std::size_t cell) { cells_[cell].push_back(e); });
      ++entries_;
    }
  }
}

void SegmentIndex::remove(std::uint32_t instance, const std::vector<Path>& paths, const PatchType& type) {
  for (std::size_t f = 0; f < paths.size(); ++f) {
    const Path& path = paths[f];
    const double r = type.fragments[f].radius_m;
    for (std::size_t s = 0; s + 1 < path.times.size(); ++s) {
      const MovingDisc d{path.positions[s], path.positions[s + 1], path.times[s], path.times[s + 1], r};
      for_each_cell_of(d, r, [&](std::size_t cell) {
        std::vector<Entry>& c = cells_[cell];
        // Unordered removal: the order within a cell never changes a result (a query asks "any collision?").
        for (std::size_t i = 0; i < c.size();) {
          if (c[i].instance == instance) {
            c[i] = c.back();
            c.pop_back();
          } else {
            ++i;
          }
        }
      });
      --entries_;
    }
  }
}

}  // namespace throng::tiling
