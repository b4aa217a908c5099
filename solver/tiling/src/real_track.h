// One agent's resampled recorded span, shared by the steps of patch construction (construct.h).
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/tiling/construct.h>

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace throng::tiling {

/// An agent's uninterrupted span resampled on the global grid t = k / sample_rate (see construct.h, step 1).
struct Track {
  std::size_t agent = 0;
  long start = 0;                       ///< global sample index of sample 0
  std::vector<Eigen::Vector2d> p;       ///< positions
  std::vector<Eigen::Vector2d> v;       ///< velocities (central differences)
  std::vector<double> heading;          ///< of the velocity, held while standing
  std::vector<double> turn_rate;        ///< signed, rad/s (0 while standing)
  std::vector<bool> standing;
  std::vector<bool> clean;              ///< a boundary may fall here (before the pose groups are chosen)
  std::vector<double> variation;        ///< Eq. 4
  std::vector<int> group;               ///< rank of a clean sample's pose group among the largest, else −1

  [[nodiscard]] std::size_t size() const noexcept { return p.size(); }
  [[nodiscard]] long end() const noexcept { return start + static_cast<long>(p.size()); }  ///< one past the last
  [[nodiscard]] bool covers(long g) const noexcept { return g >= start && g < end(); }
  [[nodiscard]] std::size_t local(long g) const noexcept { return static_cast<std::size_t>(g - start); }
};

/// The tracks of `motion` with every field filled.
[[nodiscard]] std::vector<Track> resample(const CrowdMotion& motion, const RealPatchOptions& o);

}  // namespace throng::tiling
