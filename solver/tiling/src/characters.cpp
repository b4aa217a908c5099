#include <throng/tiling/characters.h>

#include <throng/core/errors.h>

#include "laid_pose.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

namespace throng::tiling {
namespace {

using Copy = std::array<int, 3>;

// A fragment in a copy of the tile.
struct Node {
  FragmentRef fragment;
  Copy copy;
  friend auto operator<=>(const Node&, const Node&) = default;
};

// Successor of each character fragment (by its exit's connection) and whether it has a predecessor.
struct Links {
  std::map<FragmentRef, std::pair<FragmentRef, Copy>> next;  // to, image
  std::map<FragmentRef, bool> has_previous;
  std::map<FragmentRef, Copy> previous_image;  // the image of the connection into each entry
};

Links links_of(const Tiling& tiling) {
  Links l;
  for (const Connection& c : tiling.connections) {
    l.next[c.from] = {c.to, c.image};
    l.has_previous[c.to] = true;
    l.previous_image[c.to] = c.image;
  }
  return l;
}

}  // namespace

PatchActions patch_actions(const PatchLibrary& library) {
  PatchActions a;
  a.table = standard_actions();
  for (const PatchType& type : library.types) {
    std::vector<std::int32_t>& of = a.of_fragment.emplace_back(type.fragments.size(), -1);
    for (std::size_t f = 0; f < type.fragments.size(); ++f) {
      if (!type.fragments[f].is_character()) continue;
      const ActionKind kind{type.name, type.fragments[f].prop};
      const auto it = std::find(a.table.begin(), a.table.end(), kind);
      of[f] = static_cast<std::int32_t>(it - a.table.begin());
      if (it == a.table.end()) a.table.push_back(kind);
    }
  }
  return a;
}

std::size_t count_characters(const PatchLibrary& library, const Tiling& tiling) {
  const Links links = links_of(tiling);
  std::size_t heads = 0;
  std::vector<FragmentRef> all;
  for (std::uint32_t i = 0; i < tiling.instances.size(); ++i) {
    const PatchType& type = library.types[tiling.instances[i].type];
    for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
      if (!type.fragments[f].is_character()) continue;
      all.push_back({i, f});
      if (!links.has_previous.contains({i, f})) ++heads;
    }
  }
  // Closed loops: fragments every one of which has a predecessor, found by walking from each unvisited one.
  std::map<FragmentRef, bool> seen;
  std::size_t loops = 0;
  for (const FragmentRef& start : all) {
    if (seen[start] || !links.has_previous.contains(start)) continue;
    FragmentRef at = start;
    bool closed = false;
    for (std::size_t steps = 0; steps <= all.size(); ++steps) {
      if (seen[at]) {
        closed = at == start;
        break;
      }
      seen[at] = true;
      const auto it = links.next.find(at);
      if (it == links.next.end()) break;
      at = it->second.first;
    }
    loops += closed ? 1 : 0;
  }
  return heads + loops;
}

double max_turn_per_frame(const LayoutOptions& options) {
  if (!(options.frame_rate_hz > 0) || !std::isfinite(options.frame_rate_hz)) {
    throw ConfigError("output frame rate " + std::to_string(options.frame_rate_hz) + " Hz, expected > 0");
  }
  if (!(options.max_facing_rate_rad_s >= 0) || !std::isfinite(options.max_facing_rate_rad_s)) {
    throw ConfigError("output max facing rate " + std::to_string(options.max_facing_rate_rad_s) + " rad/s, expected ≥ 0");
  }
  return options.max_facing_rate_rad_s > 0 ? options.max_facing_rate_rad_s / options.frame_rate_hz
                                           : std::numeric_limits<double>::infinity();
}

Characters lay_out(const PatchLibrary& library, const Tiling& tiling, const Region& region, const LayoutOptions& options) {
  const double max_turn = max_turn_per_frame(options);  // checks the frame rate and the facing rate
  const Eigen::Vector3d L = periods(region);
  Copy lo{0, 0, 0}, hi{0, 0, 0};
  for (int a = 0; a < 3; ++a) {
    const int n = options.repeat[static_cast<std::size_t>(a)];
    if (n < 1 || (n > 1 && !region.periodic[static_cast<std::size_t>(a)])) {
      throw ConfigError("output repeat " + std::to_string(n) + " on axis " + "xyt"[a] +
                        ", expected ≥ 1, and 1 unless the region is periodic on that axis");
    }
    if (region.periodic[static_cast<std::size_t>(a)]) {
      lo[static_cast<std::size_t>(a)] = -1;  // neighbours of the laid copies reach into them
      hi[static_cast<std::size_t>(a)] = n;
    }
  }
  const auto in_range = [&](const Copy& c) {
    for (std::size_t a = 0; a < 3; ++a) {
      if (c[a] < lo[a] || c[a] > hi[a]) return false;
    }
    return true;
  };
  const double t_begin = region.t0;
  const double t_end = region.t0 + options.repeat[2] * (region.t1 - region.t0);
  const auto frames_total = static_cast<std::size_t>(std::floor((t_end - t_begin) * options.frame_rate_hz + 1e-9)) +
                            (region.periodic[2] ? 0 : 1);
  const auto frame_time = [&](std::size_t f) { return t_begin + static_cast<double>(f) / options.frame_rate_hz; };
  const auto inside = [&](const Eigen::Vector2d& p) {
    for (int a = 0; a < 2; ++a) {
      if (!region.periodic[static_cast<std::size_t>(a)]) continue;
      const double m = region.min[a], M = region.min[a] + options.repeat[static_cast<std::size_t>(a)] * L[a];
      if (p[a] < m || p[a] >= M) return false;
    }
    return true;
  };

  const Links links = links_of(tiling);
  const PatchActions actions = patch_actions(library);
  struct Piece {
    std::size_t first_frame;
    Node head;
    std::size_t index;
    std::vector<Eigen::Vector2d> positions;  // one per frame from first_frame
    std::vector<double> headings;            // one per frame from first_frame
    std::vector<std::int32_t> actions;       // one per frame from first_frame
    double radius;
    std::vector<AgentPiece> fragments;
  };
  std::vector<Piece> pieces;

  // Every chain: from each fragment copy with no predecessor in range, along the connections.
  for (std::uint32_t i = 0; i < tiling.instances.size(); ++i) {
    const PatchType& type = library.types[tiling.instances[i].type];
    for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
      if (!type.fragments[f].is_character()) continue;
      for (int cx = lo[0]; cx <= hi[0]; ++cx) {
        for (int cy = lo[1]; cy <= hi[1]; ++cy) {
          for (int ct = lo[2]; ct <= hi[2]; ++ct) {
            const Node head{{i, f}, {cx, cy, ct}};
            // A predecessor exists in range: this copy is not a chain head.
            const auto previous = links.previous_image.find(head.fragment);
            if (previous != links.previous_image.end() &&
                in_range({cx - previous->second[0], cy - previous->second[1], ct - previous->second[2]})) {
              continue;
            }
            // Walk the chain, gathering samples (shifted into their copies).
            std::vector<Eigen::Vector2d> pos;
            std::vector<double> times;
            std::vector<double> heads;
            std::vector<std::int32_t> acts;  // per sample: the action of the segment that ends there
            std::vector<std::pair<Node, std::pair<double, double>>> spans;
            double radius = 0;
            Node at = head;
            for (std::size_t guard = 0; guard < 100000; ++guard) {
              const Instance& inst = tiling.instances[at.fragment.instance];
              const Path& p = inst.paths[at.fragment.fragment];
              radius = std::max(radius, library.types[inst.type].fragments[at.fragment.fragment].radius_m);
              const Eigen::Vector2d shift(at.copy[0] * L.x(), at.copy[1] * L.y());
              const double tshift = at.copy[2] * L.z();
              for (std::size_t s = 0; s < p.times.size(); ++s) {
                const double t = p.times[s] + tshift;
                if (!times.empty() && t <= times.back()) continue;  // the shared sample at a join
                pos.push_back(p.positions[s] + shift);
                times.push_back(t);
                heads.push_back(p.headings[s]);
                acts.push_back(actions.of_fragment[inst.type][at.fragment.fragment]);
              }
              spans.push_back({at, {p.times.front() + tshift, p.times.back() + tshift}});
              const auto it = links.next.find(at.fragment);
              if (it == links.next.end()) break;
              const Copy next{at.copy[0] + it->second.second[0], at.copy[1] + it->second.second[1],
                              at.copy[2] + it->second.second[2]};
              if (!in_range(next)) break;
              at = Node{it->second.first, next};
            }
            // Sample at the frames; split where the chain is absent.
            std::size_t k = 0;
            Piece current{0, head, 0, {}, {}, {}, radius, {}};
            std::size_t count = 0;
            const auto close = [&](std::size_t last_frame) {
              if (current.positions.empty()) return;
              const double a = frame_time(current.first_frame), b = frame_time(last_frame);
              for (const auto& [node, span] : spans) {
                if (span.second >= a && span.first <= b) current.fragments.push_back({node.fragment, node.copy});
              }
              current.index = count++;
              pieces.push_back(std::move(current));
              current = Piece{0, head, 0, {}, {}, {}, radius, {}};
            };
            for (std::size_t fr = 0; fr < frames_total; ++fr) {
              const double t = frame_time(fr);
              bool present = false;
              Eigen::Vector2d q;
              double h = 0;
              std::int32_t action = -1;
              if (t >= times.front() && t <= times.back()) {
                while (k + 1 < times.size() && times[k + 1] < t) ++k;
                const bool segment = k + 1 < times.size();
                const double u = segment ? (t - times[k]) / (times[k + 1] - times[k]) : 0.0;
                q = segment ? Eigen::Vector2d(pos[k] + std::clamp(u, 0.0, 1.0) * (pos[k + 1] - pos[k])) : pos[k];
                h = segment ? heading_between(heads[k], heads[k + 1], std::clamp(u, 0.0, 1.0)) : heads[k];
                action = acts[segment ? k + 1 : k];
                present = inside(q);
              }
              if (present) {
                if (current.positions.empty()) {
                  current.first_frame = fr;
                } else {
                  h = facing_toward(current.headings.back(), h, max_turn);
                }
                current.positions.push_back(q);
                current.headings.push_back(h);
                current.actions.push_back(action);
              } else if (!current.positions.empty()) {
                close(fr - 1);
              }
            }
            if (!current.positions.empty()) close(current.first_frame + current.positions.size() - 1);
          }
        }
      }
    }
  }
  std::sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) {
    return std::tie(a.first_frame, a.head, a.index) < std::tie(b.first_frame, b.head, b.index);
  });

  Characters out;
  CrowdMotion& m = out.motion;
  m = CrowdMotion::with_shape(frames_total, pieces.size());
  for (std::size_t f = 0; f < frames_total; ++f) m.times[f] = frame_time(f);
  m.orientations.assign(frames_total * pieces.size() * 4, absent);
  m.actions.assign(frames_total * pieces.size(), -1);
  m.action_table = actions.table;
  for (std::size_t n = 0; n < pieces.size(); ++n) {
    const Piece& p = pieces[n];
    m.radii[n] = p.radius;
    for (std::size_t j = 0; j < p.positions.size(); ++j) {
      m.position(p.first_frame + j, n) = Eigen::Vector3d(p.positions[j].x(), p.positions[j].y(), 0);
      m.orientation(p.first_frame + j, n) = yaw_orientation(p.headings[j]);
      m.action(p.first_frame + j, n) = p.actions[j];
    }
    out.pieces.push_back(p.fragments);
  }
  return out;
}

}  // namespace throng::tiling
