// Comparing crowds agent by agent, by id: what a split crowd merged back by identity must give again.
#pragma once

#include <throng/core/crowd_motion.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

namespace throng::test {

/// Each agent's positions at every frame (x, y, z per frame; NaN where absent), by id.
inline std::map<std::int64_t, std::vector<double>> positions_by_id(const CrowdMotion& c) {
  std::map<std::int64_t, std::vector<double>> out;
  for (std::size_t a = 0; a < c.agent_count(); ++a) {
    auto& v = out[c.ids[a]];
    for (std::size_t f = 0; f < c.frame_count(); ++f) {
      for (int d = 0; d < 3; ++d) v.push_back(c.position(f, a)[d]);
    }
  }
  return out;
}

/// The same values bit for bit, NaN equal to NaN (an absent frame in both).
inline bool same_values(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (!(a[k] == b[k] || (std::isnan(a[k]) && std::isnan(b[k])))) return false;
  }
  return true;
}

}  // namespace throng::test
