// The graph of a keyframe formation (§3.1): Delaunay edges weighted 1/distance, the user's edits, the Laplacian.
#pragma once

#include <Eigen/Core>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace throng::formation {

/// One edit of a graph, on item indices (a ≠ b). `where` names it in messages ("edits.remove[2]"), after
/// `place` when there is one.
struct EdgeEdit {
  enum class Kind {
    remove,          ///< the edge must exist
    add,             ///< weight 1/distance; an existing edge is left as it is
    scale,           ///< the edge must exist; weight × factor
    scale_if_edge    ///< weight × factor when the edge exists (expanded from a member list)
  };
  Kind kind = Kind::add;
  int a = 0;
  int b = 0;
  double factor = 1.0;
  std::string where;
  std::string place;  ///< where the edit's list was given in a job ("job.yaml:7:8 (edits)"), or empty
};

/// Weighted undirected graph over `count` items: edges (i < j) → weight > 0.
struct Adjacency {
  int count = 0;
  std::map<std::pair<int, int>, double> weights;
};

/// Delaunay graph of `points` (#items by 2 or 3) with weights 1/distance: CGAL's 2-D triangulation (throng::graph)
/// or 3-D triangulation (lower-dimensional input gives the triangulation of its plane or line). In 2-D, points on
/// a common empty circle (regular formations) are all connected: the unique Delaunay graph rather than one
/// arbitrary triangulation of it, so a turned ring or grid keeps its graph.
/// Throws InputError naming `what` and the two items (through `item_name`) when two points coincide.
[[nodiscard]] Adjacency delaunay_adjacency(const Eigen::Ref<const Eigen::MatrixXd>& points, const std::string& what,
                                           const std::vector<std::string>& item_names);

/// Applies `edits` (removes first, then adds, then scales, each in list order). Throws ConfigError naming `what`,
/// the edit and the items when a remove or scale names a pair that is not an edge, or a factor is not > 0.
void apply_edits(Adjacency& graph, const Eigen::Ref<const Eigen::MatrixXd>& points, const std::vector<EdgeEdit>& edits,
                 const std::string& what, const std::vector<std::string>& item_names);

/// Throws InputError naming `what` and the items cut off from item 0 when the graph is not connected.
void require_connected(const Adjacency& graph, const std::string& what, const std::vector<std::string>& item_names);

/// The Laplacian (#items by #items): L_ii = Σ_j w_ij, L_ij = −w_ij.
[[nodiscard]] Eigen::MatrixXd laplacian(const Adjacency& graph);

}  // namespace throng::formation
