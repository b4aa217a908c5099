#include "position_group.h"

#include "dense.h"

#include <cassert>

namespace throng::formation {

PositionGroup::PositionGroup(const GroupKeyframes& keyframes, const Options& options)
    : polar_(options.interpolation == Interpolation::polar),
      items_(static_cast<int>(keyframes.positions.front().rows())),
      dimension_(static_cast<int>(keyframes.positions.front().cols())),
      tension_(options.tension),
      sharp_(keyframes.sharp) {
  assert(options.interpolation != Interpolation::spectral);
  const std::size_t k_count = keyframes.positions.size();
  graphs_.resize(k_count);
  dense::for_each(k_count, 2000.0 * items_, [&](std::size_t k) { graphs_[k] = keyframe_graph(keyframes, k); });
  relative_.resize(k_count);
  for (std::size_t k = 0; k < k_count; ++k) relative_[k] = keyframes.positions[k].rowwise() - keyframes.anchors[k].transpose();
  if (!polar_) return;
  // The PCA adjustment (§3.3) on the keyframes about their own barycentres, as the spectral method does; the
  // polar coordinates are about the anchor (the group's barycentre over all its individuals).
  std::vector<Eigen::MatrixXd> centred(k_count);
  for (std::size_t k = 0; k < k_count; ++k)
    centred[k] = keyframes.positions[k].rowwise() - keyframes.positions[k].colwise().mean();
  std::vector<Eigen::MatrixXd> rotations = keyframe_orientations(centred, options.orientation, options.isotropy_tolerance);
  std::vector<Eigen::MatrixXd> common(k_count);
  for (std::size_t k = 0; k < k_count; ++k) common[k] = relative_[k] * rotations[k];
  track_ = CoefficientTrack(common, 0);
  orientation_ = OrientationTrack(std::move(rotations));
  relative_.clear();
}

Eigen::MatrixXd PositionGroup::evaluate(const Timeline& timeline, const Eigen::MatrixXd& anchor_path) const {
  const std::size_t frames = timeline.frame_count();
  const int d = dimension_;
  const int k_count = static_cast<int>(graphs_.size());
  assert(anchor_path.rows() == d && static_cast<std::size_t>(anchor_path.cols()) == frames);
  Eigen::MatrixXd out(static_cast<Eigen::Index>(items_) * d, static_cast<Eigen::Index>(frames));
  // Per interval: its controls and, for polar, the track's interval data (3-D rotations).
  std::vector<ControlKeys> keys(static_cast<std::size_t>(k_count - 1));
  std::vector<CoefficientTrack::Interval> intervals(keys.size());
  for (int s = 0; s + 1 < k_count; ++s) {
    keys[static_cast<std::size_t>(s)] = control_keys(s, k_count, sharp_);
    if (polar_) intervals[static_cast<std::size_t>(s)] = track_.interval(keys[static_cast<std::size_t>(s)]);
  }
  dense::for_each(frames, (polar_ ? 60.0 : 10.0) * items_ * d, [&](std::size_t f) {
    const auto segment = static_cast<std::size_t>(timeline.segment[f]);
    const SplineWeights w = catmull_rom_weights(timeline.local[f], tension_);
    const auto& k = keys[segment].keys;
    Eigen::MatrixXd x(items_, d);
    if (polar_) {
      track_.evaluate(intervals[segment], w, x);
      x = (x * orientation_.evaluate(keys[segment], w).transpose()).eval();
    } else {
      x.setZero();
      for (int i = 0; i < 4; ++i) x += w.c[static_cast<std::size_t>(i)] * relative_[static_cast<std::size_t>(k[static_cast<std::size_t>(i)])];
    }
    const auto column = static_cast<Eigen::Index>(f);
    for (int j = 0; j < items_; ++j)
      for (int axis = 0; axis < d; ++axis) out(static_cast<Eigen::Index>(j) * d + axis, column) = x(j, axis) + anchor_path(axis, column);
  });
  return out;
}

}  // namespace throng::formation
