#include "text.h"

#include <throng/core/errors.h>
#include <throng/stitch/split.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <unordered_map>

namespace throng::stitch {

namespace {

// Frames first..last of the given agents (in that order), with everything each agent carries.
CrowdMotion copy_part(const CrowdMotion& crowd, std::size_t first, std::size_t last, const std::vector<std::size_t>& agents) {
  const std::size_t frames = last - first + 1;
  CrowdMotion out = CrowdMotion::with_shape(frames, agents.size());
  out.times.assign(crowd.times.begin() + static_cast<std::ptrdiff_t>(first), crowd.times.begin() + static_cast<std::ptrdiff_t>(last) + 1);
  const bool velocities = !crowd.velocities.empty();
  if (velocities) out.velocities.assign(out.positions.size(), absent);
  const bool facing = !crowd.orientations.empty(), acting = !crowd.actions.empty();
  if (facing) out.orientations.assign(frames * agents.size() * 4, absent);
  if (acting) out.actions.assign(frames * agents.size(), -1);
  out.action_table = crowd.action_table;
  for (std::size_t k = 0; k < agents.size(); ++k) {
    const std::size_t a = agents[k];
    out.ids[k] = crowd.ids[a];
    out.radii[k] = crowd.radii[a];
    out.species[k] = crowd.species[a];
    for (std::size_t f = 0; f < frames; ++f) {
      const auto from = static_cast<std::ptrdiff_t>(crowd.index(first + f, a));
      const auto to = static_cast<std::ptrdiff_t>(out.index(f, k));
      std::copy_n(crowd.positions.begin() + from, 3, out.positions.begin() + to);
      if (velocities) std::copy_n(crowd.velocities.begin() + from, 3, out.velocities.begin() + to);
      if (facing) out.orientation(f, k) = crowd.orientation(first + f, a);
      if (acting) out.action(f, k) = crowd.action(first + f, a);
    }
  }
  return out;
}

}  // namespace

CrowdMotion take_agents(const CrowdMotion& crowd, const std::vector<std::size_t>& agents) {
  if (crowd.frame_count() == 0) throw InputError("the crowd has no frames");
  return copy_part(crowd, 0, crowd.frame_count() - 1, agents);
}

CrowdMotion slice_frames(const CrowdMotion& crowd, std::size_t first, std::size_t last, bool present_throughout) {
  const std::size_t frames = crowd.frame_count();
  if (frames == 0) throw InputError("the crowd has no frames");
  if (last >= frames) {
    throw ConfigError("frame " + std::to_string(last) + " is past the crowd's last frame " + std::to_string(frames - 1));
  }
  if (first >= last) {
    throw ConfigError("frames [" + std::to_string(first) + ", " + std::to_string(last) +
                      "]: a part needs at least two frames (first < last)");
  }
  std::vector<std::size_t> agents;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
    std::size_t present = 0;
    for (std::size_t f = first; f <= last; ++f) present += crowd.present(f, a) ? 1 : 0;
    if (present_throughout ? present == last - first + 1 : present > 0) agents.push_back(a);
  }
  if (agents.empty()) {
    throw InputError("no agent is present " + std::string(present_throughout ? "over all of" : "anywhere in") + " frames [" +
                     std::to_string(first) + ", " + std::to_string(last) + "] (" + detail::seconds(crowd.times[first]) +
                     " to " + detail::seconds(crowd.times[last]) + ")");
  }
  return copy_part(crowd, first, last, agents);
}

TimeSplit split_at_frame(const CrowdMotion& crowd, std::size_t frame, bool present_throughout) {
  const std::size_t frames = crowd.frame_count();
  if (frames < 3 || frame == 0 || frame + 1 >= frames) {
    throw ConfigError("split at frame " + std::to_string(frame) + ": expected a frame in [1, " +
                      (frames >= 2 ? std::to_string(frames - 2) : std::string("-")) + "] so that both parts hold two frames or more (the crowd has " +
                      std::to_string(frames) + " frames)");
  }
  return {slice_frames(crowd, 0, frame, present_throughout), slice_frames(crowd, frame, frames - 1, present_throughout)};
}

std::size_t frame_nearest(const CrowdMotion& crowd, double time) {
  const auto& t = crowd.times;
  if (t.empty()) throw InputError("the crowd has no frames");
  if (!std::isfinite(time)) throw ConfigError("time " + detail::number(time) + ": expected a finite time in seconds");
  const double half_first = t.size() > 1 ? 0.5 * (t[1] - t[0]) : 0.0;
  const double half_last = t.size() > 1 ? 0.5 * (t.back() - t[t.size() - 2]) : 0.0;
  if (time < t.front() - half_first || time > t.back() + half_last) {
    throw ConfigError("time " + detail::seconds(time) + " is outside the crowd's times [" + detail::seconds(t.front()) + ", " +
                      detail::seconds(t.back()) + "]");
  }
  const auto it = std::lower_bound(t.begin(), t.end(), time);
  if (it == t.begin()) return 0;
  if (it == t.end()) return t.size() - 1;
  const auto after = static_cast<std::size_t>(it - t.begin());
  return (time - t[after - 1] <= t[after] - time) ? after - 1 : after;
}

std::vector<std::size_t> select_agents(const CrowdMotion& crowd, const AgentSelection& selection, bool complement) {
  if (selection.ids.empty() && selection.species.empty()) {
    throw ConfigError("empty agent selection: give at least one agent id or species");
  }
  std::unordered_map<std::int64_t, std::size_t> index_of;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) index_of.emplace(crowd.ids[a], a);
  std::vector<char> chosen(crowd.agent_count(), 0);
  for (std::int64_t id : selection.ids) {
    const auto it = index_of.find(id);
    if (it == index_of.end()) {
      throw ConfigError("agents: no agent with id " + std::to_string(id) + " in the crowd (its ids: " +
                        detail::id_list(crowd.ids) + ")");
    }
    chosen[it->second] = 1;
  }
  const std::set<std::int32_t> present_species(crowd.species.begin(), crowd.species.end());
  for (std::int32_t s : selection.species) {
    if (!present_species.count(s)) {
      std::vector<std::int64_t> have(present_species.begin(), present_species.end());
      throw ConfigError("species: no agent has species " + std::to_string(s) + " (the crowd's species: " +
                        detail::id_list(have) + ")");
    }
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      if (crowd.species[a] == s) chosen[a] = 1;
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
    if ((chosen[a] != 0) != complement) out.push_back(a);
  }
  if (out.empty()) {
    throw InputError("the selection takes every agent of the crowd (" + std::to_string(crowd.agent_count()) +
                     "), so the rest is empty");
  }
  return out;
}

}  // namespace throng::stitch
