// What every exporter shares: the options of the facing and action it writes for a crowd that carries none.
#pragma once

#include <throng/core/crowd_motion.h>

namespace throng {

/// Options every export format takes. A crowd file with orientations and actions is exported as stored; one
/// without them (older files, methods that fill neither yet) gets the documented default derived from each
/// agent's path (PathFacing: face along the velocity, a standing agent keeps its last facing; path_action:
/// stand, walk or run by speed), with these thresholds.
struct ExportOptions {
  PathPoseRule pose;
};

}  // namespace throng
