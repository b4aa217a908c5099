// Hierarchical control (§4.4): the tree of groups, its validation, automatic construction by spectral
// clustering, and the mapping of individual-level graph edits onto the groups.
#pragma once

#include "adjacency.h"

#include <throng/formation/formation.h>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace throng::formation {

/// A flattened tree: nodes[0] is the root, parents come before their children.
/// Items of a node: its members (individuals) first, in order, then its children (subgroups), in order.
struct TreeNode {
  std::string name;
  int parent = -1;
  int depth = 0;
  std::vector<int> members;      ///< individuals
  std::vector<int> children;     ///< node indices
  std::vector<int> individuals;  ///< every individual below this node
  [[nodiscard]] int item_count() const noexcept { return static_cast<int>(members.size() + children.size()); }
};
struct Tree {
  std::vector<TreeNode> nodes;
  int depth_count = 1;
};

/// Flattens and checks `root` for n individuals: every individual in exactly one group, no empty group.
/// Throws ConfigError naming the group and the individual otherwise.
[[nodiscard]] Tree flatten_tree(const Group& root, int individual_count);

/// A tree built by spectral clustering of `graph` (over the individuals; the sum of the keyframes' graphs):
/// a group with more than `group_size` items is split into min(group_size, ⌈count/group_size⌉) parts by
/// recursive Fiedler-vector bisection (sizes in proportion), until every group has at most `group_size` items.
[[nodiscard]] Group cluster_hierarchy(const Adjacency& graph, int group_size);

/// Where an edit between individuals a and b lands: the deepest node containing both, and their items there.
struct EditTarget {
  int node = 0;
  int item_a = 0;
  int item_b = 0;
};
class EditMapper {
 public:
  explicit EditMapper(const Tree& tree, int individual_count);
  [[nodiscard]] EditTarget locate(int a, int b) const;

 private:
  std::vector<std::vector<std::pair<int, int>>> path_;  // per individual: (node, item) from the root down
};

}  // namespace throng::formation
