// The Result of an editor's last deform (edit.h), built one way for the one-shot edits (edit_group_motion,
// edit_locally) and the session's answers (session.cpp): the samples resampled to the input's frames, the
// report, the clip's range and sampled frames, and for a local edit the step across its region's edge.
#pragma once

#include <throng/edit/edit.h>
#include <throng/edit/local_edit.h>

#include <Eigen/Core>

namespace throng::edit {

/// samples: #vertices by 2, what editor.deform() returned.
inline Result edit_result(const Editor& editor, const Eigen::Matrix<double, Eigen::Dynamic, 2>& samples) {
  const Clip& clip = editor.graph().clip;
  return {editor.resample(samples), editor.report(), clip.first_frame, clip.last_frame, clip.frames, std::nullopt};
}

inline Result edit_result(const LocalEditor& editor, const Eigen::Matrix<double, Eigen::Dynamic, 2>& samples) {
  const Clip& clip = editor.graph().clip;
  return {editor.resample(samples), editor.report(), clip.first_frame, clip.last_frame, clip.frames, editor.boundary_step()};
}

}  // namespace throng::edit
