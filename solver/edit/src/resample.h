// The edited clip at the source frame rate: the edited samples joined by natural cubic splines, with the
// original's detail between samples carried along with each agent's local motion.
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

/// The edited clip. At a sample frame: the edited position exactly. Between samples, per agent, with S_e and S_o
/// the natural cubic splines through its edited and its original samples and p(t) its original position:
///   p'(t) = S_e(t) + R(θ(t)) (p(t) − S_o(t)),
/// where θ is the spline through the agent's turn at each sample (the rotation that best maps its motion edges
/// to the samples before and after onto their edited copies; the whole formation's turn at that sample when the
/// agent stands still), unwrapped along time. A rigid motion of every sample (same R, T) gives R p(t) + T at
/// every frame; unchanged samples give p(t) back; z is kept.
///   edited  #samples*#agents by 2 (rows as clip.vertex)
[[nodiscard]] CrowdMotion resample_clip(const CrowdMotion& slice, const Clip& clip,
                                        const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& edited);

}  // namespace throng::edit
