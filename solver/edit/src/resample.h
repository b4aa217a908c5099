// The edited clip at the source frame rate: natural cubic spline interpolation of the displacement.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/graph/clip.h>

#include <Eigen/Core>

namespace throng::edit {

/// Natural cubic spline through (t_i, y_i) (rows of y, any number of columns), evaluated at `at` (increasing,
/// inside [t_0, t_last]); with two knots it is the straight line. Values at a knot are that knot's y exactly.
///   knots  #knots (increasing);  y  #knots by #columns;  at  #points;  result  #points by #columns
[[nodiscard]] Eigen::MatrixXd natural_cubic_spline(const std::vector<double>& knots, const Eigen::Ref<const Eigen::MatrixXd>& y,
                                                   const std::vector<double>& at);

/// The part of `crowd` a clip covers at the source rate: its frames (first..last) and agents, with their ids,
/// radii and species. Frame f of the slice is source frame clip.first_frame + f; agent j is the clip's agent j.
[[nodiscard]] CrowdMotion slice_clip(const CrowdMotion& crowd, const Clip& clip);

/// The edited clip: each position of `slice` plus the spline of (edited − original) through the samples,
/// evaluated at every frame time (z kept); at sample frames exactly the edited position.
///   edited  #samples*#agents by 2 (rows as clip.vertex)
[[nodiscard]] CrowdMotion resample_clip(const CrowdMotion& slice, const Clip& clip,
                                        const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& edited);

}  // namespace throng::edit
