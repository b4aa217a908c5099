// One group's keyframes, as every interpolation of a group reads them (spectral_group.h, position_group.h), and
// the interface formation.cpp drives a group through, whichever the method.
#pragma once

#include "adjacency.h"
#include "spline.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace throng::formation {

/// One group's keyframes.
///   positions   K matrices #items by d (d = 2 or 3): the items (individuals, or subgroup barycentres)
///   anchors     K vectors of d: the group's reference point (its barycentre over all its individuals)
///   edits       K lists of graph edits on item indices
///   sharp       K flags (Keyframe::sharp), or empty for none: the splines duplicate these keyframes
///   what        the group in messages ("formation", "group 'brass'"); item_names: "individual 7", ...
///   places      K: where each keyframe was given (Keyframe::where), in front of messages about its graph
struct GroupKeyframes {
  std::vector<Eigen::MatrixXd> positions;
  std::vector<Eigen::VectorXd> anchors;
  std::vector<std::vector<EdgeEdit>> edits;
  std::vector<bool> sharp;
  std::string what;
  std::vector<std::string> item_names;
  std::vector<std::string> places;

  [[nodiscard]] int keyframe_count() const noexcept { return static_cast<int>(positions.size()); }
  /// The control keyframes of interval `segment` (spline.h), with this group's sharp keyframes.
  [[nodiscard]] ControlKeys controls(int segment) const noexcept { return control_keys(segment, keyframe_count(), sharp); }
};

/// The graph of keyframe k (§3.1): Delaunay, then the keyframe's edits; throws InputError / ConfigError naming
/// the keyframe for coincident items, bad edits or a graph that is not connected (formation.h).
[[nodiscard]] Adjacency keyframe_graph(const GroupKeyframes& keyframes, std::size_t k);

/// A group's interpolation (the spectral method or a baseline), after its analysis.
class GroupInterpolation {
 public:
  virtual ~GroupInterpolation() = default;

  /// Item positions at every frame of `timeline`, given the anchor's path (d by #frames): returns #items·d by
  /// #frames, column f = frame f's items, item-major (item j's coordinates at rows j·d...).
  [[nodiscard]] virtual Eigen::MatrixXd evaluate(const Timeline& timeline, const Eigen::MatrixXd& anchor_path) const = 0;
  /// The graph of keyframe k after edits.
  [[nodiscard]] virtual const Adjacency& graph(int k) const = 0;
};

}  // namespace throng::formation
