// The space-time motion graph of the paper (§3): vertex (i, j) is agent j at sample i; formation edges join
// agents within a sample (a Delaunay triangulation, minus edges longer than a threshold, plus or minus the
// user's edits); motion edges join (i, j) and (i + 1, j) and are implicit.
#pragma once

#include <throng/graph/clip.h>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace throng {

/// A user's change to the formation edges: add or remove the edge between two agents over a frame range.
struct EdgeEdit {
  std::int64_t agent_a = 0;  ///< agent id
  std::int64_t agent_b = 0;  ///< agent id
  std::size_t first_frame = 0;                                     ///< source frame, inclusive
  std::size_t last_frame = std::numeric_limits<std::size_t>::max();  ///< source frame, inclusive (default: to the end)
  bool add = true;           ///< true adds the edge, false removes it
};

/// A branch split: every formation edge between `agents` and the other agents of the clip is removed at every
/// sample whose source frame is in [first_frame, last_frame], so the two sides can be moved apart (the paper's
/// battlefield, Figure 1/12: part of a group dragged one way, part another). Edges within either side stay.
/// What goes with the cut edges: the spatial features of the triangles they bounded and the spatiotemporal
/// features along them (Eq. 5, 7), i.e. everything that ties one side's formation to the other's inside the
/// range. What stays: every agent's temporal features (Eq. 6: each keeps the shape of its own trajectory), and
/// every feature before and after the range, so the sides still share one graph through the frames they walk
/// together.
struct FormationSplit {
  std::vector<std::int64_t> agents;                                  ///< agent ids of one side (not empty, not all)
  std::size_t first_frame = 0;                                       ///< source frame, inclusive
  std::size_t last_frame = std::numeric_limits<std::size_t>::max();  ///< source frame, inclusive (default: to the end)
};

/// How formation edges are made.
struct FormationOptions {
  /// Delaunay edges longer than this (metres) are dropped (the paper's "long edge between two distant
  /// characters"); 0 keeps every edge.
  double max_edge_length = 0.0;
  /// Applied in order after the threshold, at every sample whose source frame is in the edit's range.
  std::vector<EdgeEdit> edits;
  /// Applied after the edits, at every sample in their range: they remove every crossing edge, a user-added one
  /// too (a user who wants an edge across a split adds it outside the split's range).
  std::vector<FormationSplit> splits;
};

/// The graph over a clip.
///   edges[i]      formation edges at sample i: agent pairs (a < b), sorted
///   triangles[i]  triangles at sample i (agent triples, counter-clockwise in the original positions) whose
///                 three edges are all formation edges: the Delaunay triangles that survived the threshold and
///                 removals, and every triangle a user-added edge closes with two other formation edges
struct MotionGraph {
  Clip clip;
  std::vector<std::vector<std::array<int, 2>>> edges;
  std::vector<std::vector<std::array<int, 3>>> triangles;

  [[nodiscard]] std::size_t sample_count() const noexcept { return clip.sample_count(); }
  [[nodiscard]] std::size_t agent_count() const noexcept { return clip.agent_count(); }
  [[nodiscard]] std::size_t vertex_count() const noexcept { return sample_count() * agent_count(); }
  [[nodiscard]] std::size_t formation_edge_count() const noexcept;
};

/// Builds the formation edges of every sample (in parallel; the result does not depend on the thread count).
/// Throws ConfigError for an edit naming an agent not in the clip, the same agent twice, or a negative
/// threshold, and for a split (named formation.splits[k]) with no agent, an agent not in the clip or named twice,
/// every agent of the clip (nothing to split from), or a frame range that holds no sample.
[[nodiscard]] MotionGraph build_motion_graph(Clip clip, const FormationOptions& options);

}  // namespace throng
