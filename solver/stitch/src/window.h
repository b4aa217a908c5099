// The samples of a stitched clip and the blending window around its joint (solver/stitch/stitch.h, "Window" and
// "Sampling"). Private to the stitch layer.
#pragma once

#include <cstddef>
#include <vector>

namespace throng::stitch::detail {

/// Whether a frame `distance` seconds from the joint lies inside a window of `window` seconds (f_a > 0). A
/// relative 1e-9 absorbs the rounding of frame times (0.1·30 − 0.1·24 is not exactly 0.6).
[[nodiscard]] bool inside_window(double distance, double window) noexcept;

struct SampledWindow {
  double first_s = 0, second_s = 0;              ///< window per side (seconds), each ≤ its clip's duration
  std::size_t first_frames = 0, second_frames = 0;  ///< frames from the joint to each window edge
  bool limited = false;                          ///< the automatic window was shortened to the vertex budget
  std::size_t whole_vertices = 0;                ///< agents × solved samples of the whole clips (automatic only)
  std::vector<std::size_t> samples;              ///< stitched frames, increasing
  std::size_t joint_sample = 0;                  ///< index of the joint in `samples`
  std::size_t first_solved = 0, last_solved = 0; ///< the solved samples: the pinned edges and the free ones between
};

/// Samples every `step` frames counted from the joint J on both sides, each clip's outer frame, and each window
/// edge (the frame nearest the joint at or beyond the window: pinned). `times` are the stitched clip's frame
/// times (strictly increasing, at least J + 2 of them). `requested_s` > 0: that many seconds per side, capped at
/// each clip; 0: the whole clips unless agents × solved samples would exceed `max_vertices` (> 0), in which case
/// the longest common window that fits (at least one sample step).
[[nodiscard]] SampledWindow sample_window(const std::vector<double>& times, std::size_t J, std::size_t step,
                                          double requested_s, std::size_t agents, std::size_t max_vertices);

}  // namespace throng::stitch::detail
