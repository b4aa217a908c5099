#include <throng/core/errors.h>
#include <throng/graph/clip.h>

#include <algorithm>
#include <string>
#include <unordered_map>

namespace throng {
namespace {

std::string frame_range(std::size_t first, std::size_t last) {
  return "[" + std::to_string(first) + ", " + std::to_string(last) + "]";
}

// The frames of the clip where `agent` is absent, as "a..b" runs (at most a few, for a message).
std::string absent_runs(const CrowdMotion& crowd, std::size_t agent, std::size_t first, std::size_t last) {
  std::string out;
  int runs = 0;
  for (std::size_t f = first; f <= last; ++f) {
    if (crowd.present(f, agent)) continue;
    std::size_t end = f;
    while (end + 1 <= last && !crowd.present(end + 1, agent)) ++end;
    if (runs++ < 3) out += (out.empty() ? "" : ", ") + (end == f ? std::to_string(f) : std::to_string(f) + ".." + std::to_string(end));
    f = end;
  }
  return runs > 3 ? out + ", ..." : out;
}

bool present_throughout(const CrowdMotion& crowd, std::size_t agent, std::size_t first, std::size_t last) {
  for (std::size_t f = first; f <= last; ++f) {
    if (!crowd.present(f, agent)) return false;
  }
  return true;
}

}  // namespace

long Clip::sample_of_frame(std::size_t frame) const noexcept {
  const auto it = std::lower_bound(frames.begin(), frames.end(), frame);
  return it != frames.end() && *it == frame ? static_cast<long>(it - frames.begin()) : -1;
}

long Clip::agent_of_id(std::int64_t id) const noexcept {
  const auto it = std::find(ids.begin(), ids.end(), id);
  return it != ids.end() ? static_cast<long>(it - ids.begin()) : -1;
}

Clip make_clip(const CrowdMotion& crowd, const ClipOptions& options, std::span<const std::size_t> required_frames) {
  const std::size_t frame_count = crowd.frame_count();
  if (frame_count < 2) throw InputError("the crowd has " + std::to_string(frame_count) + " frames; a clip needs at least 2");
  const std::size_t last_frame = frame_count - 1;
  if (options.first_frame > last_frame) {
    throw ConfigError("clip.first_frame " + std::to_string(options.first_frame) + " is past the crowd's last frame " +
                      std::to_string(last_frame));
  }
  const bool last_given = options.last_frame != std::numeric_limits<std::size_t>::max();
  if (last_given && options.last_frame > last_frame) {
    throw ConfigError("clip.last_frame " + std::to_string(options.last_frame) + " is past the crowd's last frame " +
                      std::to_string(last_frame));
  }
  Clip clip;
  clip.first_frame = options.first_frame;
  clip.last_frame = last_given ? options.last_frame : last_frame;
  if (clip.last_frame <= clip.first_frame) {
    throw ConfigError("clip frames " + frame_range(clip.first_frame, clip.last_frame) +
                      ": a clip needs at least two frames (first_frame < last_frame)");
  }
  if (options.sample_step == 0) throw ConfigError("clip.sample_step is 0: expected a positive number of frames");

  // Samples: every step-th frame from the first, the last, and the required frames.
  for (std::size_t f = clip.first_frame; f <= clip.last_frame; f += options.sample_step) clip.frames.push_back(f);
  clip.frames.push_back(clip.last_frame);
  for (std::size_t f : required_frames) {
    if (f < clip.first_frame || f > clip.last_frame) {
      throw ConfigError("frame " + std::to_string(f) + " is outside the clip " + frame_range(clip.first_frame, clip.last_frame));
    }
    clip.frames.push_back(f);
  }
  std::sort(clip.frames.begin(), clip.frames.end());
  clip.frames.erase(std::unique(clip.frames.begin(), clip.frames.end()), clip.frames.end());
  for (std::size_t f : clip.frames) clip.times.push_back(crowd.times[f]);

  // Agents.
  if (options.agents.empty()) {
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      if (present_throughout(crowd, a, clip.first_frame, clip.last_frame)) {
        clip.agents.push_back(a);
      } else {
        bool somewhere = false;
        for (std::size_t f = clip.first_frame; f <= clip.last_frame && !somewhere; ++f) somewhere = crowd.present(f, a);
        if (somewhere) clip.left_out.push_back(crowd.ids[a]);
      }
    }
  } else {
    std::unordered_map<std::int64_t, std::size_t> index_of;
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) index_of.emplace(crowd.ids[a], a);
    for (std::int64_t id : options.agents) {
      const auto it = index_of.find(id);
      if (it == index_of.end()) throw ConfigError("clip.agents: no agent with id " + std::to_string(id) + " in the crowd");
      if (std::find(clip.agents.begin(), clip.agents.end(), it->second) != clip.agents.end()) {
        throw ConfigError("clip.agents: agent " + std::to_string(id) + " is listed twice");
      }
      if (!present_throughout(crowd, it->second, clip.first_frame, clip.last_frame)) {
        throw ConfigError("clip.agents: agent " + std::to_string(id) + " is absent at frames " +
                          absent_runs(crowd, it->second, clip.first_frame, clip.last_frame) + " of the clip " +
                          frame_range(clip.first_frame, clip.last_frame) +
                          "; only agents present over the whole clip can be edited");
      }
      clip.agents.push_back(it->second);
    }
  }
  if (clip.agents.empty()) {
    throw ConfigError("no agent is present over the whole clip " + frame_range(clip.first_frame, clip.last_frame) +
                      ": choose a shorter clip");
  }
  for (std::size_t a : clip.agents) clip.ids.push_back(crowd.ids[a]);

  const std::size_t n = clip.agents.size();
  clip.positions.resize(static_cast<Eigen::Index>(clip.frames.size() * n), 2);
  for (std::size_t i = 0; i < clip.frames.size(); ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      const auto p = crowd.position(clip.frames[i], clip.agents[j]);
      clip.positions.row(clip.vertex(i, j)) << p.x(), p.y();
    }
  }
  return clip;
}

}  // namespace throng
