#include "frame_stream.h"

#include "bytes.h"
#include "laid_pose.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace throng::tiling {

FrameStream::FrameStream(const PatchLibrary& library, const Region& region, double frame_rate_hz, double max_turn)
    : library_(library), actions_(patch_actions(library)), region_(region), period_(periods(region)), rate_(frame_rate_hz),
      max_turn_(max_turn) {
  // As lay_out: frames from t0 every 1 / rate, the last at t1 (the time axis is not periodic here).
  frames_ = static_cast<std::size_t>(std::floor((region.t1 - region.t0) * rate_ + 1e-9)) + 1;
  for (std::size_t a = 0; a < 3; ++a) {
    if (region.periodic[a]) {
      lo_[a] = -1;  // repeat 1: the neighbouring copies reach into the laid one
      hi_[a] = 1;
    }
  }
}

double FrameStream::frame_time(std::size_t f) const noexcept { return region_.t0 + static_cast<double>(f) / rate_; }

bool FrameStream::in_range(const Copy& c) const noexcept {
  for (std::size_t a = 0; a < 3; ++a) {
    if (c[a] < lo_[a] || c[a] > hi_[a]) return false;
  }
  return true;
}

void FrameStream::take(Walk& walk, const Node& node) {
  const Instance& inst = held_.at(node.fragment.instance);
  const Path& p = inst.paths[node.fragment.fragment];
  walk.radius = std::max(walk.radius, library_.types[inst.type].fragments[node.fragment.fragment].radius_m);
  const Eigen::Vector2d shift(node.copy[0] * period_.x(), node.copy[1] * period_.y());
  for (std::size_t s = 0; s < p.times.size(); ++s) {
    const double t = p.times[s];
    if (!walk.samples.empty() && t <= walk.samples.back().time) continue;  // the shared sample at a join
    walk.samples.push_back({p.positions[s] + shift, t, p.headings[s],
                            actions_.of_fragment[inst.type][node.fragment.fragment]});
  }
  walk.spans.push_back({node, {p.times.front(), p.times.back()}});
  walk.last = node;
}

bool FrameStream::extend(Walk& walk, double time) {
  while (walk.samples.back().time < time) {
    if (walk.ended) return false;
    const auto it = next_.find(walk.last.fragment);
    if (it == next_.end()) {
      walk.ended = true;  // the successor would start before `time`: it would have been delivered
      return false;
    }
    const Copy& image = it->second.second;
    const Copy copy{walk.last.copy[0] + image[0], walk.last.copy[1] + image[1], walk.last.copy[2] + image[2]};
    if (!in_range(copy)) {
      walk.ended = true;
      return false;
    }
    take(walk, Node{it->second.first, copy});
  }
  return true;
}

void FrameStream::start_walks(std::uint32_t id, const std::map<FragmentRef, Copy>& previous) {
  const Instance& inst = held_.at(id);
  const PatchType& type = library_.types[inst.type];
  for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
    if (!type.fragments[f].is_character()) continue;
    for (int cx = lo_[0]; cx <= hi_[0]; ++cx) {
      for (int cy = lo_[1]; cy <= hi_[1]; ++cy) {
        const Copy copy{cx, cy, 0};
        // A copy whose predecessor is among the laid copies is walked from that one, not from here.
        const auto p = previous.find({id, f});
        if (p != previous.end() && in_range({cx - p->second[0], cy - p->second[1], -p->second[2]})) continue;
        Walk w;
        w.head = Node{{id, f}, copy};
        take(w, w.head);
        walks_.push_back(std::move(w));
      }
    }
  }
}

void FrameStream::deliver(std::size_t first, const std::vector<Instance>& instances,
                          const std::vector<Connection>& connections) {
  for (std::size_t i = 0; i < instances.size(); ++i) held_.emplace(static_cast<std::uint32_t>(first + i), instances[i]);
  std::map<FragmentRef, Copy> previous;  // entry → the image of the connection into it
  for (const Connection& c : connections) {
    next_[c.from] = {c.to, c.image};
    previous[c.to] = c.image;
  }
  for (std::size_t i = 0; i < instances.size(); ++i) start_walks(static_cast<std::uint32_t>(first + i), previous);
}

void FrameStream::emit(std::size_t end, CrowdMotion& frames, std::vector<std::vector<AgentPiece>>& pieces) {
  end = std::min(end, frames_);
  const std::size_t begin = next_frame_;
  const auto inside = [&](const Eigen::Vector2d& q) {
    for (int a = 0; a < 2; ++a) {
      if (!region_.periodic[static_cast<std::size_t>(a)]) continue;
      if (q[a] < region_.min[a] || q[a] >= region_.min[a] + period_[a]) return false;
    }
    return true;
  };
  // Per agent of these frames: (frame, position), and the walk it belongs to.
  struct Pose {
    Eigen::Vector2d position;
    double heading;
    std::int32_t action;
  };
  std::map<std::int64_t, std::vector<std::pair<std::size_t, Pose>>> tracks;
  std::map<std::int64_t, std::size_t> walk_of;
  std::vector<std::pair<std::size_t, Pose>> present;  // (walk, pose) at this frame
  std::vector<std::size_t> opened;
  for (std::size_t f = begin; f < end; ++f) {
    const double t = frame_time(f);
    present.clear();
    opened.clear();
    for (std::size_t w = 0; w < walks_.size(); ++w) {
      Walk& walk = walks_[w];
      if (t >= walk.samples.front().time && extend(walk, t)) {
        // Samples from the one at or before t (lay_out's k) on; interpolated as lay_out does.
        std::size_t k = 0;
        while (k + 1 < walk.samples.size() && walk.samples[k + 1].time < t) ++k;
        walk.samples.erase(walk.samples.begin(), walk.samples.begin() + static_cast<std::ptrdiff_t>(k));
        const Sample& a = walk.samples[0];
        Eigen::Vector2d q = a.position;
        double heading = a.heading;
        std::int32_t action = a.action;
        if (walk.samples.size() > 1) {
          const Sample& b = walk.samples[1];
          const double u = (t - a.time) / (b.time - a.time);
          q = a.position + std::clamp(u, 0.0, 1.0) * (b.position - a.position);
          heading = heading_between(a.heading, b.heading, std::clamp(u, 0.0, 1.0));
          action = b.action;
        }
        if (inside(q)) {
          if (walk.agent >= 0) heading = facing_toward(walk.facing, heading, max_turn_);  // a present run goes on
          walk.facing = heading;
          present.emplace_back(w, Pose{q, heading, action});
          if (walk.agent < 0) opened.push_back(w);
          continue;
        }
      }
      walk.agent = -1;  // absent: a present run, if any, ends
    }
    // New agents of this frame, in lay_out's order: by the head copy of their chain, then their run.
    std::sort(opened.begin(), opened.end(), [&](std::size_t a, std::size_t b) {
      return std::tie(walks_[a].head, walks_[a].runs) < std::tie(walks_[b].head, walks_[b].runs);
    });
    for (std::size_t w : opened) {
      walks_[w].agent = next_agent_++;
      ++walks_[w].runs;
    }
    for (const auto& [w, q] : present) {
      tracks[walks_[w].agent].emplace_back(f, q);
      walk_of[walks_[w].agent] = w;
    }
  }

  // The frames: agents by id.
  frames = CrowdMotion::with_shape(end - begin, tracks.size());
  frames.orientations.assign((end - begin) * tracks.size() * 4, absent);
  frames.actions.assign((end - begin) * tracks.size(), -1);
  frames.action_table = actions_.table;
  pieces.assign(tracks.size(), {});
  for (std::size_t f = begin; f < end; ++f) frames.times[f - begin] = frame_time(f);
  std::size_t n = 0;
  for (const auto& [agent, track] : tracks) {
    const Walk& walk = walks_[walk_of.at(agent)];
    frames.ids[n] = agent;
    frames.radii[n] = walk.radius;
    for (const auto& [f, pose] : track) {
      frames.position(f - begin, n) = Eigen::Vector3d(pose.position.x(), pose.position.y(), 0);
      frames.orientation(f - begin, n) = yaw_orientation(pose.heading);
      frames.action(f - begin, n) = pose.action;
    }
    const double a = frame_time(track.front().first), b = frame_time(track.back().first);
    for (const auto& [node, span] : walk.spans) {
      if (span[1] >= a && span[0] <= b) pieces[n].push_back({node.fragment, node.copy});
    }
    ++n;
  }
  next_frame_ = end;

  // Forget what no later frame needs: walks that are over, fragment copies and instances that end before the
  // last frame made (a walk past them never takes them again).
  const double last = frame_time(end == 0 ? 0 : end - 1) - 1e-6;
  const double next = end < frames_ ? frame_time(end) : 1e300;
  walks_.erase(std::remove_if(walks_.begin(), walks_.end(),
                              [&](const Walk& w) { return w.ended && w.samples.back().time < next; }),
               walks_.end());
  for (Walk& w : walks_) {
    w.spans.erase(std::remove_if(w.spans.begin(), w.spans.end(), [&](const auto& s) { return s.second[1] < last; }),
                  w.spans.end());
  }
  for (auto it = held_.begin(); it != held_.end();) {
    double latest = -1e300;
    for (const Path& p : it->second.paths) latest = std::max(latest, p.times.back());
    if (latest < last) {
      for (std::uint32_t f = 0; f < it->second.paths.size(); ++f) next_.erase({it->first, f});
      it = held_.erase(it);
    } else {
      ++it;
    }
  }
}

void FrameStream::save(std::vector<std::byte>& out) const {
  ByteWriter w(out);
  w.put<std::uint64_t>(next_frame_);
  w.put<std::int64_t>(next_agent_);
  w.put<std::uint64_t>(held_.size());
  for (const auto& [id, inst] : held_) {
    w.put(id);
    w.put<std::uint64_t>(inst.type);
    w.put(inst.transform.translation.x());
    w.put(inst.transform.translation.y());
    w.put(inst.transform.angle);
    w.put(inst.transform.time_shift);
    w.put<std::uint8_t>(inst.keyframed ? 1 : 0);
    w.put<std::uint64_t>(inst.paths.size());
    for (const Path& p : inst.paths) put_path(w, p);
  }
  w.put<std::uint64_t>(next_.size());
  for (const auto& [from, to] : next_) {
    w.put(from);
    w.put(to.first);
    w.put(to.second);
  }
  w.put<std::uint64_t>(walks_.size());
  for (const Walk& walk : walks_) {
    w.put(walk.head);
    w.put(walk.last);
    w.put<std::uint64_t>(walk.samples.size());
    for (const Sample& s : walk.samples) {
      w.put(s.position.x());
      w.put(s.position.y());
      w.put(s.time);
      w.put(s.heading);
      w.put(s.action);
    }
    w.put(walk.radius);
    w.put<std::uint64_t>(walk.runs);
    w.put(walk.agent);
    w.put(walk.facing);
    w.put<std::uint64_t>(walk.spans.size());
    for (const auto& [node, span] : walk.spans) {
      w.put(node);
      w.put(span);
    }
    w.put<std::uint8_t>(walk.ended ? 1 : 0);
  }
}

void FrameStream::load(const std::vector<std::byte>& in, std::size_t& at) {
  ByteReader r(in, at, "windowed tiling state (frames)");
  next_frame_ = r.get<std::uint64_t>();
  next_agent_ = r.get<std::int64_t>();
  if (next_frame_ > frames_ || next_agent_ < 0) r.fail();
  held_.clear();
  for (std::size_t n = r.count(1); n > 0; --n) {
    const auto id = r.get<std::uint32_t>();
    Instance inst;
    inst.type = r.get<std::uint64_t>();
    inst.transform.translation.x() = r.get<double>();
    inst.transform.translation.y() = r.get<double>();
    inst.transform.angle = r.get<double>();
    inst.transform.time_shift = r.get<double>();
    inst.keyframed = r.get<std::uint8_t>() != 0;
    inst.paths.resize(r.count(1));
    for (Path& p : inst.paths) p = get_path(r);
    if (inst.type >= library_.types.size() || inst.paths.size() != library_.types[inst.type].fragments.size()) r.fail();
    for (std::size_t f = 0; f < inst.paths.size(); ++f) {
      const Path& p = inst.paths[f];
      if (p.times.size() != library_.types[inst.type].fragments[f].sample_count() || p.headings.size() != p.times.size() ||
          p.positions.size() != p.times.size()) {
        r.fail();
      }
    }
    held_.emplace(id, std::move(inst));
  }
  next_.clear();
  for (std::size_t n = r.count(1); n > 0; --n) {
    const auto from = r.get<FragmentRef>();
    const auto to = r.get<FragmentRef>();
    next_[from] = {to, r.get<Copy>()};
  }
  walks_.assign(r.count(1), Walk{});
  for (Walk& walk : walks_) {
    walk.head = r.get<Node>();
    walk.last = r.get<Node>();
    walk.samples.resize(r.count(4 * sizeof(double) + sizeof(std::int32_t)));
    for (Sample& s : walk.samples) {
      s.position.x() = r.get<double>();
      s.position.y() = r.get<double>();
      s.time = r.get<double>();
      s.heading = r.get<double>();
      s.action = r.get<std::int32_t>();
      if (s.action < 0 || static_cast<std::size_t>(s.action) >= actions_.table.size()) r.fail();
    }
    walk.radius = r.get<double>();
    walk.runs = r.get<std::uint64_t>();
    walk.agent = r.get<std::int64_t>();
    walk.facing = r.get<double>();
    walk.spans.resize(r.count(sizeof(Node) + 2 * sizeof(double)));
    for (auto& [node, span] : walk.spans) {
      node = r.get<Node>();
      span = r.get<std::array<double, 2>>();
    }
    walk.ended = r.get<std::uint8_t>() != 0;
    if (walk.samples.empty()) r.fail();
  }
}

}  // namespace throng::tiling
