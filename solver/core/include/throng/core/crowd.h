// A crowd as the methods take and make it: its motion, the scene it moves in, and the formation edges it keeps.
// The crowd file (throng/io/crowd_file.h) is a Crowd with its provenance.
#pragma once

#include <throng/core/crowd_motion.h>
#include <throng/core/scene.h>

#include <array>
#include <cstdint>
#include <vector>

namespace throng {

struct Crowd {
  CrowdMotion motion;
  Scene scene;
  std::vector<std::array<std::int32_t, 2>> formation_edges;  ///< optional, agent index pairs
};

/// The crowds a method reads, in order (none for the methods that start a crowd).
using Crowds = std::vector<const Crowd*>;

}  // namespace throng
