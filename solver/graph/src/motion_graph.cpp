#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/graph/delaunay.h>
#include <throng/graph/motion_graph.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

namespace throng {
namespace {

using Edge = std::array<int, 2>;
using Triangle = std::array<int, 3>;

// An edit resolved to graph agents and the samples it covers.
struct ResolvedEdit {
  int a = 0;
  int b = 0;
  std::size_t first_sample = 0;
  std::size_t last_sample = 0;  // inclusive
  bool add = true;
};

// A split resolved to graph agents (side[j] = 1 for the split's agents) and the samples it covers.
struct ResolvedSplit {
  std::vector<char> side;
  std::size_t first_sample = 0;
  std::size_t last_sample = 0;  // inclusive
};

std::string frames_text(std::size_t first, std::size_t last) {
  return "[" + std::to_string(first) + ", " +
         (last == std::numeric_limits<std::size_t>::max() ? std::string("end") : std::to_string(last)) + "]";
}

// The samples [first, last] of the clip whose source frames lie in [first_frame, last_frame]; a ConfigError naming
// `where` when there is none (or the range is reversed).
std::pair<std::size_t, std::size_t> samples_of_range(const Clip& clip, std::size_t first_frame, std::size_t last_frame,
                                                     const std::string& where) {
  if (first_frame > last_frame) {
    throw ConfigError(where + ": first_frame " + std::to_string(first_frame) + " is after last_frame " + std::to_string(last_frame));
  }
  const auto first = std::lower_bound(clip.frames.begin(), clip.frames.end(), first_frame);
  const auto past = std::upper_bound(clip.frames.begin(), clip.frames.end(), last_frame);
  if (first >= past) {
    throw ConfigError(where + ": frames " + frames_text(first_frame, last_frame) + " hold no sample of the clip [" +
                      std::to_string(clip.first_frame) + ", " + std::to_string(clip.last_frame) + "]");
  }
  return {static_cast<std::size_t>(first - clip.frames.begin()), static_cast<std::size_t>(past - clip.frames.begin()) - 1};
}

std::vector<ResolvedSplit> resolve_splits(const Clip& clip, const FormationOptions& options) {
  std::vector<ResolvedSplit> out;
  for (std::size_t k = 0; k < options.splits.size(); ++k) {
    const FormationSplit& split = options.splits[k];
    const std::string where = "formation.splits[" + std::to_string(k) + "]";
    if (split.agents.empty()) throw ConfigError(where + ".agents: no agent given: a split needs the agents of one side");
    ResolvedSplit r;
    r.side.assign(clip.agent_count(), 0);
    for (std::size_t i = 0; i < split.agents.size(); ++i) {
      const std::int64_t id = split.agents[i];
      const long j = clip.agent_of_id(id);
      const std::string entry = where + ".agents[" + std::to_string(i) + "]";
      if (j < 0) {
        throw ConfigError(entry + ": agent " + std::to_string(id) +
                          " is not in the clip (absent from the crowd, not selected, or absent somewhere in the clip)");
      }
      if (r.side[static_cast<std::size_t>(j)]) throw ConfigError(entry + ": agent " + std::to_string(id) + " is named twice");
      r.side[static_cast<std::size_t>(j)] = 1;
    }
    if (split.agents.size() == clip.agent_count()) {
      throw ConfigError(where + ".agents: all " + std::to_string(clip.agent_count()) +
                        " agents of the clip are on one side: nothing is left to split them from");
    }
    std::tie(r.first_sample, r.last_sample) = samples_of_range(clip, split.first_frame, split.last_frame, where);
    out.push_back(std::move(r));
  }
  return out;
}

Edge ordered(int a, int b) { return a < b ? Edge{a, b} : Edge{b, a}; }

// Rotates a triple so the smallest index comes first and makes it counter-clockwise in `points`.
Triangle canonical_ccw(Triangle t, const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& points) {
  const Eigen::Vector2d p = points.row(t[0]), q = points.row(t[1]), r = points.row(t[2]);
  const double area2 = (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
  if (area2 < 0) std::swap(t[1], t[2]);
  while (t[0] > t[1] || t[0] > t[2]) t = {t[1], t[2], t[0]};
  return t;
}

std::vector<ResolvedEdit> resolve_edits(const Clip& clip, const FormationOptions& options) {
  std::vector<ResolvedEdit> out;
  for (std::size_t k = 0; k < options.edits.size(); ++k) {
    const EdgeEdit& e = options.edits[k];
    const std::string where = "formation.edits[" + std::to_string(k) + "]";
    const long a = clip.agent_of_id(e.agent_a);
    const long b = clip.agent_of_id(e.agent_b);
    for (auto [id, index] : {std::pair{e.agent_a, a}, std::pair{e.agent_b, b}}) {
      if (index < 0) {
        throw ConfigError(where + ": agent " + std::to_string(id) +
                          " is not in the clip (absent from the crowd, not selected, or absent somewhere in the clip)");
      }
    }
    if (a == b) throw ConfigError(where + ": an edge needs two different agents, got " + std::to_string(e.agent_a) + " twice");
    const auto [first, last] = samples_of_range(clip, e.first_frame, e.last_frame, where);
    out.push_back({static_cast<int>(a), static_cast<int>(b), first, last, e.add});
  }
  return out;
}

// Formation edges and triangles of one sample.
void build_sample(const Clip& clip, std::size_t sample, double max_length, const std::vector<ResolvedEdit>& edits,
                  const std::vector<ResolvedSplit>& splits, std::vector<Edge>& edges, std::vector<Triangle>& triangles) {
  const auto n = static_cast<Eigen::Index>(clip.agent_count());
  const auto points = clip.positions.middleRows(clip.vertex(sample, 0), n);
  const Triangulation dt = delaunay_2d(points);

  auto too_long = [&](const Edge& e) {
    return max_length > 0 && (points.row(e[0]) - points.row(e[1])).norm() > max_length;
  };
  edges.clear();
  for (const auto& e : dt.edges) {
    if (!too_long(e)) edges.push_back(e);
  }
  std::vector<Edge> added;
  for (const ResolvedEdit& edit : edits) {
    if (sample < edit.first_sample || sample > edit.last_sample) continue;
    const Edge e = ordered(edit.a, edit.b);
    const auto at = std::lower_bound(edges.begin(), edges.end(), e);
    const bool present = at != edges.end() && *at == e;
    if (edit.add && !present) {
      edges.insert(at, e);
      added.push_back(e);
    } else if (!edit.add && present) {
      edges.erase(at);
      added.erase(std::remove(added.begin(), added.end(), e), added.end());
    }
  }
  for (const ResolvedSplit& split : splits) {
    if (sample < split.first_sample || sample > split.last_sample) continue;
    auto crosses = [&](const Edge& e) {
      return split.side[static_cast<std::size_t>(e[0])] != split.side[static_cast<std::size_t>(e[1])];
    };
    edges.erase(std::remove_if(edges.begin(), edges.end(), crosses), edges.end());
    added.erase(std::remove_if(added.begin(), added.end(), crosses), added.end());
  }
  auto has = [&](int a, int b) { return std::binary_search(edges.begin(), edges.end(), ordered(a, b)); };

  triangles.clear();
  for (const auto& t : dt.triangles) {
    if (has(t[0], t[1]) && has(t[1], t[2]) && has(t[2], t[0])) triangles.push_back(t);
  }
  // Triangles closed by a user-added edge (a, b) with a common neighbour c; collinear ones carry no formation.
  for (const Edge& e : added) {
    for (const Edge& other : edges) {
      int c = -1;
      if (other[0] == e[0] && other[1] != e[1]) c = other[1];
      if (other[1] == e[0] && other[0] != e[1]) c = other[0];
      if (c < 0 || !has(c, e[1])) continue;
      const Eigen::Vector2d p = points.row(e[0]), q = points.row(e[1]), r = points.row(c);
      if ((q - p).x() * (r - p).y() - (q - p).y() * (r - p).x() == 0.0) continue;
      triangles.push_back(canonical_ccw({e[0], e[1], c}, points));
    }
  }
  std::sort(triangles.begin(), triangles.end());
  triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
}

}  // namespace

std::size_t MotionGraph::formation_edge_count() const noexcept {
  std::size_t count = 0;
  for (const auto& e : edges) count += e.size();
  return count;
}

MotionGraph build_motion_graph(Clip clip, const FormationOptions& options) {
  if (!(options.max_edge_length >= 0)) {
    throw ConfigError("formation.max_edge_length " + std::to_string(options.max_edge_length) +
                      ": expected a length ≥ 0 in metres (0 keeps every edge)");
  }
  const std::vector<ResolvedEdit> edits = resolve_edits(clip, options);
  const std::vector<ResolvedSplit> splits = resolve_splits(clip, options);
  MotionGraph graph;
  graph.clip = std::move(clip);
  const std::size_t samples = graph.clip.sample_count();
  graph.edges.resize(samples);
  graph.triangles.resize(samples);
  parallel_for(samples, 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      build_sample(graph.clip, i, options.max_edge_length, edits, splits, graph.edges[i], graph.triangles[i]);
    }
  });
  return graph;
}

}  // namespace throng
