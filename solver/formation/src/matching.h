// Individual matching between keyframes when rows are not in correspondence (beyond the paper: its stated
// future work), by minimum-cost assignment.
#pragma once

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <vector>

namespace throng::formation {

/// For each keyframe k, the row of keyframe k taken by individual i (keyframe 0: the identity). Keyframe k is
/// matched to keyframe k−1 (already matched): both are taken about their barycentres, keyframe k is turned by
/// each candidate rotation (the principal-axis rotations unless `alignment` is none or the shapes are nearly
/// isotropic; always the identity too), and the assignment of least summed squared distance over all candidates
/// wins (the first candidate on ties). Deterministic.
[[nodiscard]] std::vector<std::vector<int>> match_keyframes(const std::vector<Eigen::MatrixXd>& positions,
                                                            OrientationAlignment alignment, double isotropy_tolerance);

}  // namespace throng::formation
