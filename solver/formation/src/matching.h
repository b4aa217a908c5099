// Individual matching between keyframes when rows are not in correspondence (beyond the paper: its stated
// future work), by minimum-cost assignment.
#pragma once

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// For each keyframe k, the row of keyframe k taken by individual i (keyframe 0: the identity). Keyframe k is
/// matched to keyframe k−1 (already matched): both are taken about their barycentres; from each starting
/// rotation (the identity, and the principal-axis rotations unless the shapes are nearly isotropic) the
/// assignment of least summed squared distance is found, the least-squares rotation of that assignment is
/// fitted and the assignment solved again while the cost falls (iterative closest point with exact assignments;
/// with `alignment` none, the identity only and no rotation). The least cost over all starts wins (the first
/// on ties). Deterministic.
[[nodiscard]] std::vector<std::vector<int>> match_keyframes(const std::vector<Eigen::MatrixXd>& positions,
                                                            OrientationAlignment alignment, double isotropy_tolerance);

}  // namespace throng::formation
