// The crowd an edit writes: the edited clip put back into the whole input crowd (the default of `throng edit`),
// or the clip alone, with the velocities and the seam at the clip's ends accounted for.
//
// The clip (edit.h: Result::crowd) holds only the agents present over the whole clip and only the clip's frames.
// Put back, every other agent and every frame outside the clip are the input's, bit for bit; the edited agents
// keep their ids. At a clip end that is not an end of the input the edited agents continue from unedited
// frames: if the edit moved them there (a drag reaching the clip's first or last frame), the output jumps by
// that much between the two frames (seam_jump() measures it; hold the clip's ends to join smoothly).
//
// Velocities. An input without velocities gives an output without. Otherwise velocities stay valid where the
// positions are the input's; for every edited agent over the clip's frames they are recomputed from the output
// positions (central differences in time, one-sided at the ends of the clip), so they describe the new motion.
//
// Facing and actions. An input without them gives an output without (the exports derive them from the path).
// Otherwise every edited agent keeps its facing at the same angle to its path as in the input over the clip's
// frames (turned by the change of its path tangent's yaw; standing frames by the nearest moving frame's turn),
// and a walk/stand/run action follows the new path speed where the edit moved it into another class; other
// actions pass through (throng/core/facing_carry.h). Agents and frames the edit did not touch keep the input's.
#pragma once

#include <throng/core/crowd_motion.h>

#include <cstddef>

namespace throng::edit {

/// The whole crowd with `clip` (frames first_frame .. first_frame + #clip frames − 1 of the agents with the
/// clip's ids) replacing the input there. Throws std::invalid_argument when the clip does not fit the crowd
/// (frames beyond its end, an id it lacks, times that differ).
[[nodiscard]] CrowdMotion embed_clip(const CrowdMotion& crowd, const CrowdMotion& clip, std::size_t first_frame);

/// The clip alone (input frames first_frame ..), with velocities when the input has them (recomputed, see above;
/// the clip's times) and facing and actions when the input has them (carried, see above). Throws
/// std::invalid_argument when the clip does not fit the crowd.
[[nodiscard]] CrowdMotion clip_with_velocities(const CrowdMotion& crowd, CrowdMotion clip, std::size_t first_frame);

/// The largest distance (metres) the edit moved an edited agent at a clip end that joins unedited input frames
/// (the clip's first frame when first_frame > 0, its last frame when it ends before the input does): how far the
/// embedded output jumps there. 0 when the clip spans the whole input or its ends were held.
[[nodiscard]] double seam_jump(const CrowdMotion& crowd, const CrowdMotion& clip, std::size_t first_frame);

}  // namespace throng::edit
