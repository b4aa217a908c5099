// The crowd a shipped collide config hands its collide step (configs/collide-*.yaml), made in memory the way
// `throng run` makes it: the config's sketch and merge steps run through the same job readers and library calls as
// the commands (sketch::simulate, stitch::run; seed 1, the program's default), and the collide step's keys read by
// collide::read_job. So the benchmarks time the user-facing scenes.
#pragma once

#include <throng/collide/collide.h>
#include <throng/core/crowd_motion.h>
#include <throng/core/obstacle.h>

#include <string>
#include <vector>

namespace throng::bench {

struct ConfigScene {
  CrowdMotion crowd;                ///< the collide step's input
  std::vector<Obstacle> obstacles;  ///< the input's obstacles, then the collide step's own
  collide::Options options;         ///< the collide step's options
};

/// Runs the steps of the config at `path` before its collide step (sketch and merge only; anything else is a
/// ConfigError) and reads the collide step.
[[nodiscard]] ConfigScene config_scene(const std::string& path);

}  // namespace throng::bench
