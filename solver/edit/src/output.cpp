#include <throng/edit/output.h>

#include <throng/core/facing_carry.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace throng::edit {
namespace {

// The crowd's agent index of each clip agent (by id); std::invalid_argument when the clip does not fit.
std::vector<std::size_t> crowd_agents(const CrowdMotion& crowd, const CrowdMotion& clip, std::size_t first_frame) {
  if (clip.frame_count() == 0 || first_frame + clip.frame_count() > crowd.frame_count()) {
    throw std::invalid_argument("embed_clip: frames " + std::to_string(first_frame) + " + " + std::to_string(clip.frame_count()) +
                                " go past the crowd's " + std::to_string(crowd.frame_count()));
  }
  for (std::size_t f = 0; f < clip.frame_count(); ++f) {
    if (clip.times[f] != crowd.times[first_frame + f]) throw std::invalid_argument("embed_clip: the clip's times are not the crowd's");
  }
  std::unordered_map<std::int64_t, std::size_t> index;
  for (std::size_t a = 0; a < crowd.agent_count(); ++a) index.emplace(crowd.ids[a], a);
  std::vector<std::size_t> out;
  for (std::int64_t id : clip.ids) {
    const auto it = index.find(id);
    if (it == index.end()) throw std::invalid_argument("embed_clip: agent " + std::to_string(id) + " is not in the crowd");
    out.push_back(it->second);
  }
  return out;
}

// Velocities of agent `a` of `motion` over frames [first, last] from its positions: central differences,
// one-sided at the ends (a one-frame range gets 0).
void differentiate(CrowdMotion& motion, std::size_t a, std::size_t first, std::size_t last) {
  for (std::size_t f = first; f <= last; ++f) {
    const std::size_t f0 = f > first ? f - 1 : f, f1 = f < last ? f + 1 : f;
    Eigen::Map<Eigen::Vector3d> v(motion.velocities.data() + motion.index(f, a));
    if (f0 == f1) {
      v.setZero();
    } else {
      v = (motion.position(f1, a) - motion.position(f0, a)) / (motion.times[f1] - motion.times[f0]);
    }
  }
}

}  // namespace

CrowdMotion embed_clip(const CrowdMotion& crowd, const CrowdMotion& clip, std::size_t first_frame) {
  const std::vector<std::size_t> agents = crowd_agents(crowd, clip, first_frame);
  CrowdMotion out = crowd;
  const std::size_t last_frame = first_frame + clip.frame_count() - 1;
  for (std::size_t f = 0; f < clip.frame_count(); ++f) {
    for (std::size_t j = 0; j < agents.size(); ++j) out.position(first_frame + f, agents[j]) = clip.position(f, j);
  }
  if (!out.velocities.empty()) {
    for (std::size_t a : agents) differentiate(out, a, first_frame, last_frame);
  }
  // Facing and actions (out holds the input's): carried along the edited paths over the clip's frames.
  for (std::size_t a : agents) carry_facing(crowd, out, CarriedSpan{a, a, first_frame, last_frame, 0, 0.0});
  return out;
}

CrowdMotion clip_with_velocities(const CrowdMotion& crowd, CrowdMotion clip, std::size_t first_frame) {
  const std::vector<std::size_t> agents = crowd_agents(crowd, clip, first_frame);
  clip.velocities.clear();
  if (!crowd.velocities.empty()) {
    clip.velocities.assign(clip.positions.size(), 0.0);
    for (std::size_t a = 0; a < clip.agent_count(); ++a) differentiate(clip, a, 0, clip.frame_count() - 1);
  }
  // Facing and actions: the input's at the clip's frames, carried along the edited paths.
  clip.orientations.clear();
  clip.actions.clear();
  clip.action_table.clear();
  if (!crowd.orientations.empty()) clip.orientations.assign(clip.frame_count() * clip.agent_count() * 4, absent);
  if (!crowd.actions.empty()) {
    clip.actions.assign(clip.frame_count() * clip.agent_count(), -1);
    clip.action_table = crowd.action_table;
  }
  for (std::size_t j = 0; j < agents.size(); ++j) {
    carry_facing(crowd, clip,
                 CarriedSpan{agents[j], j, 0, clip.frame_count() - 1, static_cast<std::ptrdiff_t>(first_frame), 0.0});
  }
  return clip;
}

double seam_jump(const CrowdMotion& crowd, const CrowdMotion& clip, std::size_t first_frame) {
  const std::vector<std::size_t> agents = crowd_agents(crowd, clip, first_frame);
  const std::size_t last = clip.frame_count() - 1;
  double jump = 0;
  for (std::size_t j = 0; j < agents.size(); ++j) {
    if (first_frame > 0) jump = std::max(jump, (clip.position(0, j) - crowd.position(first_frame, agents[j])).norm());
    if (first_frame + last + 1 < crowd.frame_count()) {
      jump = std::max(jump, (clip.position(last, j) - crowd.position(first_frame + last, agents[j])).norm());
    }
  }
  return jump;
}

}  // namespace throng::edit
