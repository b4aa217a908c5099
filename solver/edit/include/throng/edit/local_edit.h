// Local edits: solve only the part of the space-time graph an edit reaches, leave the rest untouched (the
// paper's Discussion: "take only small part of the crowd animation into consideration, while leaving the
// remaining parts intact"; docs/METHODS.md §1.4).
//
// Method. The motion graph is split once into LocalOptions::parts parts by METIS (throng/graph/partition.h,
// over formation and motion edges), or with parts = LocalOptions::by_size into parts of about
// vertices_per_part vertices, each a block of consecutive samples × a group of agents close in them
// (partition_time_blocks), so that a region's size, and a drag's cost, do not grow with the crowd. For each
// deform():
//  1. Reached vertices: handles whose target differs from their current position (a pin that keeps a vertex
//     where it is reaches nothing) and every vertex a general constraint names. Reached parts: their parts.
//  2. Region R: the reached parts and every part within LocalOptions::halo hops of them in the part adjacency.
//  3. The energy of the Editor (step 1, then step 2 with its triangle fits) is minimised over the positions of R
//     with every other vertex held at its current position. Only features that touch R carry R's unknowns, so
//     the subproblem holds exactly those features; the vertices outside R they also touch (the region's
//     boundary, feature-wise: spatiotemporal features reach one sample across) are pinned at their current
//     positions, and the handles inside R are pinned at their targets.
//  4. The result: R's solved positions, and every other vertex's current position copied bit for bit.
// So with a region that covers the whole graph the subproblem is the Editor's problem (same features, same
// unknown order) and the result equals the global solve up to round-off.
//
// Current positions. They start as the clip's input positions; commit() makes the last result current (an
// interactive session commits when the user lets go, so the next edit builds on it). Handles always target
// the request's positions (pins without a position: the input position), as in the Editor.
//
// Cache. A region's assembled subproblem and both factorisations are kept, keyed by the region's parts and its
// pinned handles; new constraint rows or a new grouping of the same handles into pins and drags update the
// cached region in place (a new Schur complement, a new pin basis; no refactorisation, as in the Editor).
// Pins reach the solvers as coordinates in the handles' basis (request.h: cos θ, sin θ and a translation per
// drag, a position per pin) and the boundary's current positions through the right-hand sides, so a drag of the
// same handles costs step 1 a dense product (no back-substitution) and step 2 one pair of triangular sweeps
// (Report::factorizations and regions_built do not grow). Committing changes only the boundary's values: the
// next drag of a region whose boundary moved costs step 1 one back-substitution. Up to
// LocalOptions::max_cached_regions regions are kept, the least recently used dropped first. A deform's other
// costs are the region's own size and the request's resolution: a request that differs from the last one only
// in its drags' offsets, rotations and pivots resolves only the changed drags' handles (redrag, request.h), so a
// drag whose request holds every agent's first and last frame no longer rebuilds those 2 × agents handles' rows,
// basis and targets (it still passes over them twice, to find the moved ones and those inside the region).
//
// Decisions where the issue is open: the halo is measured in parts (not vertices) because parts are the unit
// that is factorised and cached; a region is at least one part even when the moved handles sit on a part's
// edge. An edit that moves nothing and has no constraint solves nothing and returns the current positions.
#pragma once

#include <throng/edit/edit.h>
#include <throng/graph/partition.h>

#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

namespace throng::edit {

/// The stateful local editor (same request language and options as Editor; options.local.parts ≥ 1).
///   positions  #samples*#agents by 2, row = graph().clip.vertex(sample, agent)
class LocalEditor {
 public:
  /// Builds the clip (the request's frames become samples), graph, features and the partition. Throws
  /// ConfigError as Editor does, and for local options out of range (parts < 1 or above the vertex count,
  /// halo < −1, max_cached_regions < 1).
  LocalEditor(const CrowdMotion& crowd, const Options& options, const Request& request);
  ~LocalEditor();
  LocalEditor(const LocalEditor&) = delete;
  LocalEditor& operator=(const LocalEditor&) = delete;

  /// Deforms the region `request` reaches (see above) and returns every sample position: the region's solved,
  /// the rest current. Frames it names must be samples of this editor's clip. Throws NumericalError for
  /// contradictory handles or constraints, or a region whose pins leave it free to move (singular; a wider
  /// halo or more pins help).
  [[nodiscard]] const Eigen::Matrix<double, Eigen::Dynamic, 2>& deform(const Request& request);

  /// Makes the last deform()'s result the current positions.
  void commit();

  /// Current positions (see above).
  [[nodiscard]] const Eigen::Matrix<double, Eigen::Dynamic, 2>& current() const noexcept;

  /// The vertices the last deform() solved, increasing (empty when it moved nothing).
  [[nodiscard]] const std::vector<int>& region() const noexcept;
  /// The parts the last deform() solved, increasing.
  [[nodiscard]] const std::vector<int>& region_parts() const noexcept;

  /// The last deform()'s steps across the region's edge in time, against the input (see BoundaryStep).
  /// Per-frame steps are sample-to-sample distances over the frames between the samples. O(#vertices).
  [[nodiscard]] BoundaryStep boundary_step() const;

  /// The edited clip at the source frame rate for these sample positions (as Editor::resample).
  [[nodiscard]] CrowdMotion resample(const Eigen::Ref<const Eigen::Matrix<double, Eigen::Dynamic, 2>>& samples) const;

  [[nodiscard]] const MotionGraph& graph() const noexcept;
  [[nodiscard]] const FeatureSet& features() const noexcept;
  [[nodiscard]] const Partition& partition() const noexcept;
  [[nodiscard]] const Report& report() const noexcept;
  [[nodiscard]] const Options& options() const noexcept;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// One-off local edit of the input positions (what edit_group_motion runs when options.local.parts > 0), with
/// the step across the region's edge in Result::boundary.
[[nodiscard]] Result edit_locally(const CrowdMotion& crowd, const Options& options, const Request& request,
                                  Progress* progress = nullptr);

}  // namespace throng::edit
