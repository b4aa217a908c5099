// The PCA adjustment of §3.3 and the interpolation of the keyframes' orientations.
#pragma once

#include "spline.h"

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// Rotations O_k (d×d) bringing each keyframe into a common frame: body_k = Y_k O_k, with Y_k the keyframe's
/// positions about its barycentre (#items by d, rows). O_0 = I; O_k aligns Y_k with body_{k−1}:
///   pca:        the rotation matching principal axes (largest variance to largest), among the 2 (2-D) or 4
///               (3-D) sign choices the one closest to body_{k−1} (correspondence settles the axes' signs);
///               when either shape is nearly isotropic (two principal variances within `isotropy_tolerance` of
///               their sum) its axes mean nothing and the procrustes rotation is used instead;
///   procrustes: the rotation minimising |Y_k O − body_{k−1}|² (Kabsch);
///   none:       identity.
[[nodiscard]] std::vector<Eigen::MatrixXd> keyframe_orientations(const std::vector<Eigen::MatrixXd>& centred,
                                                                 OrientationAlignment alignment,
                                                                 double isotropy_tolerance);

/// The rotation minimising |a O − b|² over proper rotations O (a, b: #items by d).
[[nodiscard]] Eigen::MatrixXd best_rotation(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

/// Candidate rotations aligning the principal axes of `a` with those of `b` (all sign choices with det +1);
/// empty when either is nearly isotropic.
[[nodiscard]] std::vector<Eigen::MatrixXd> principal_axis_rotations(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                                                    double isotropy_tolerance);

/// The orientation between keyframes: 2-D, the rotation by the spline of the keyframes' angles (unwrapped so
/// consecutive keyframes differ by less than π); 3-D, Eq. 5 on rotations in cumulative form,
/// O(t) = (O_{n+2}O_{n+1}ᵀ)^{c2} (O_{n+1}O_nᵀ)^{c1+c2} (O_n O_{n−1}ᵀ)^{−c−1} O_n. Keyframes are reproduced exactly.
class OrientationTrack {
 public:
  OrientationTrack() = default;
  explicit OrientationTrack(std::vector<Eigen::MatrixXd> rotations);
  [[nodiscard]] Eigen::MatrixXd evaluate(const ControlKeys& keys, const SplineWeights& w) const;
  [[nodiscard]] const Eigen::MatrixXd& key(int k) const { return rotations_[static_cast<std::size_t>(k)]; }

 private:
  std::vector<Eigen::MatrixXd> rotations_;
  std::vector<double> angles_;  // 2-D, unwrapped
};

}  // namespace throng::formation
