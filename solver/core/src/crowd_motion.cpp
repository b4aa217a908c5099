#include <throng/core/crowd_motion.h>
#include <throng/core/errors.h>

#include <string>
#include <unordered_map>

namespace throng {

CrowdMotion CrowdMotion::with_shape(std::size_t frame_count, std::size_t agent_count, double radius) {
  CrowdMotion m;
  m.times.resize(frame_count);
  for (std::size_t t = 0; t < frame_count; ++t) m.times[t] = static_cast<double>(t);
  m.positions.assign(frame_count * agent_count * 3, absent);
  m.ids.resize(agent_count);
  for (std::size_t n = 0; n < agent_count; ++n) m.ids[n] = static_cast<std::int64_t>(n);
  m.radii.assign(agent_count, radius);
  m.species.assign(agent_count, 0);
  return m;
}

std::pair<std::size_t, std::size_t> CrowdMotion::presence_span(std::size_t agent) const noexcept {
  const std::size_t T = frame_count();
  std::size_t first = T;
  std::size_t last = 0;
  for (std::size_t t = 0; t < T; ++t) {
    if (present(t, agent)) {
      if (first == T) first = t;
      last = t + 1;
    }
  }
  if (first == T) return {0, 0};
  return {first, last};
}

void CrowdMotion::validate(const std::string& what) const {
  const std::size_t T = frame_count();
  const std::size_t N = agent_count();
  auto fail = [&](const std::string& message) { throw InputError(what + ": " + message); };
  if (positions.size() != T * N * 3) {
    fail("positions hold " + std::to_string(positions.size()) + " values, expected frames × agents × 3 = " +
         std::to_string(T) + " × " + std::to_string(N) + " × 3");
  }
  if (!velocities.empty() && velocities.size() != positions.size()) {
    fail("velocities hold " + std::to_string(velocities.size()) + " values, expected " +
         std::to_string(positions.size()) + " (same shape as positions)");
  }
  if (radii.size() != N) fail("radii hold " + std::to_string(radii.size()) + " values for " + std::to_string(N) + " agents");
  if (species.size() != N) fail("species hold " + std::to_string(species.size()) + " values for " + std::to_string(N) + " agents");
  for (std::size_t t = 0; t < T; ++t) {
    if (!std::isfinite(times[t])) fail("time of frame " + std::to_string(t) + " is not finite");
    if (t > 0 && !(times[t] > times[t - 1])) {
      fail("times not strictly increasing at frame " + std::to_string(t) + " (" + std::to_string(times[t - 1]) +
           " then " + std::to_string(times[t]) + ")");
    }
  }
  for (std::size_t t = 0; t < T; ++t) {
    for (std::size_t n = 0; n < N; ++n) {
      const std::size_t i = index(t, n);
      const bool x = std::isfinite(positions[i]);
      const bool y = std::isfinite(positions[i + 1]);
      const bool z = std::isfinite(positions[i + 2]);
      if (x != y || x != z) {
        fail("agent " + std::to_string(ids[n]) + " at frame " + std::to_string(t) +
             " has a NaN or infinite coordinate while present");
      }
    }
  }
  std::unordered_map<std::int64_t, std::size_t> seen;
  for (std::size_t n = 0; n < N; ++n) {
    if (ids[n] < 0) fail("agent " + std::to_string(n) + " has negative id " + std::to_string(ids[n]));
    auto [it, inserted] = seen.emplace(ids[n], n);
    if (!inserted) {
      fail("id " + std::to_string(ids[n]) + " is used by agents " + std::to_string(it->second) + " and " + std::to_string(n));
    }
    if (!(std::isfinite(radii[n]) && radii[n] >= 0)) {
      fail("agent " + std::to_string(ids[n]) + " has radius " + std::to_string(radii[n]) + ", expected a finite value ≥ 0");
    }
  }
}

}  // namespace throng
