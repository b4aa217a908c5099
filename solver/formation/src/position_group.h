// The paper's baselines on one group (Interpolation::linear, Interpolation::polar): the items' positions
// interpolated directly, without the spectral decomposition (§3.3, Figures 3, 5 and 9).
#pragma once

#include "coefficient_track.h"
#include "group_keyframes.h"
#include "orientation.h"

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// Item j at spline weights c of interval n (control keyframes k_0..k_3, Eq. 5's weights, sharp keyframes
/// duplicated), with a_k the anchor of keyframe k and a(t) the anchor's path from the parent group:
///   linear: x_j(t) = a(t) + Σ_i c_i (x_{j,k_i} − a_{k_i})  — flat, a(t) = Σ_i c_i a_{k_i}, so x_j(t) = Σ_i c_i x_{j,k_i};
///   polar:  x_j(t) = a(t) + y_j(t) O(t)ᵀ, with y_{j,k} = (x_{j,k} − a_k) O_k in the common frame of the PCA
///           adjustment (keyframe_orientations) and y_j(t) their polar interpolation (CoefficientTrack with no
///           linear row: length and unwrapped angle splined; 3-D: direction along the shortest rotations), O(t)
///           the orientation track. Every row is polar, so an item at the barycentre stays put rather than
///           flying through it; an item with no direction at some keyframe takes its neighbour keyframe's.
/// Keyframes are hit exactly (to rounding) by both.
class PositionGroup final : public GroupInterpolation {
 public:
  /// Builds and checks the keyframes' graphs (as the spectral method does; they are not used otherwise), then
  /// the tracks. `options.interpolation` must be linear or polar.
  PositionGroup(const GroupKeyframes& keyframes, const Options& options);

  [[nodiscard]] Eigen::MatrixXd evaluate(const Timeline& timeline, const Eigen::MatrixXd& anchor_path) const override;
  [[nodiscard]] const Adjacency& graph(int k) const override { return graphs_[static_cast<std::size_t>(k)]; }

 private:
  bool polar_ = false;
  int items_ = 0;
  int dimension_ = 2;
  double tension_ = 0.5;
  std::vector<bool> sharp_;
  std::vector<Adjacency> graphs_;
  std::vector<Eigen::MatrixXd> relative_;  // linear: x_k − a_k per keyframe (#items by d)
  CoefficientTrack track_;                 // polar: the items in the common frame
  OrientationTrack orientation_;           // polar
};

}  // namespace throng::formation
