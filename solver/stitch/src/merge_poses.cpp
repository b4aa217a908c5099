#include "merge_poses.h"

#include <algorithm>

namespace throng::stitch::detail {

CrowdMotion with_poses(const CrowdMotion& crowd) {
  CrowdMotion out = crowd;
  const std::size_t frames = crowd.frame_count(), agents = crowd.agent_count();
  if (out.orientations.empty()) {
    out.orientations.assign(frames * agents * 4, absent);
    PathFacing facing(crowd);
    for (std::size_t a = 0; a < agents; ++a) {  // agent by agent, frames in order: PathFacing's O(1) stream
      for (std::size_t f = 0; f < frames; ++f) {
        if (crowd.present(f, a)) out.orientation(f, a) = facing.at(f, a);
      }
    }
  }
  if (out.actions.empty()) {
    out.actions.assign(frames * agents, -1);
    out.action_table = standard_actions();
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t a = 0; a < agents; ++a) {
        if (crowd.present(f, a)) out.action(f, a) = path_action(crowd, f, a);
      }
    }
  }
  return out;
}

std::vector<std::int32_t> join_action_tables(std::vector<ActionKind>& table, const std::vector<ActionKind>& other) {
  std::vector<std::int32_t> index(other.size());
  for (std::size_t k = 0; k < other.size(); ++k) {
    const auto it = std::find(table.begin(), table.end(), other[k]);
    index[k] = static_cast<std::int32_t>(it - table.begin());
    if (it == table.end()) table.push_back(other[k]);
  }
  return index;
}

}  // namespace throng::stitch::detail
