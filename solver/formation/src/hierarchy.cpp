#include "hierarchy.h"

#include "dense.h"
#include "fiedler.h"

#include <throng/core/errors.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace throng::formation {
namespace {

std::string group_label(const Group& g, const std::string& path) {
  return g.name.empty() ? "group " + path : "group '" + g.name + "'";
}

void flatten(const Group& group, int parent, int depth, const std::string& path, int individual_count, Tree& tree,
             std::vector<std::string>& owner) {
  const int index = static_cast<int>(tree.nodes.size());
  tree.nodes.push_back(TreeNode{});
  tree.depth_count = std::max(tree.depth_count, depth + 1);
  {
    TreeNode& node = tree.nodes.back();
    node.name = group_label(group, path);
    node.parent = parent;
    node.depth = depth;
    node.members = group.members;
  }
  const std::string label = tree.nodes[static_cast<std::size_t>(index)].name;
  if (group.members.empty() && group.subgroups.empty())
    throw ConfigError("hierarchy: " + label + " is empty; every group needs members or subgroups");
  for (const int i : group.members) {
    if (i < 0 || i >= individual_count)
      throw ConfigError("hierarchy: " + label + " names individual " + std::to_string(i) + ", but there are " +
                        std::to_string(individual_count) + " (0.." + std::to_string(individual_count - 1) + ")");
    std::string& where = owner[static_cast<std::size_t>(i)];
    if (!where.empty())
      throw ConfigError("hierarchy: individual " + std::to_string(i) + " is in both " + where + " and " + label +
                        "; each individual belongs to exactly one group");
    where = label;
  }
  for (std::size_t s = 0; s < group.subgroups.size(); ++s) {
    const int child = static_cast<int>(tree.nodes.size());
    tree.nodes[static_cast<std::size_t>(index)].children.push_back(child);
    flatten(group.subgroups[s], index, depth + 1, path + "." + std::to_string(s), individual_count, tree, owner);
  }
  TreeNode& node = tree.nodes[static_cast<std::size_t>(index)];
  node.individuals = node.members;
  for (const int child : node.children) {
    const auto& below = tree.nodes[static_cast<std::size_t>(child)].individuals;
    node.individuals.insert(node.individuals.end(), below.begin(), below.end());
  }
}

// Splits `subset` into `parts` groups of proportional sizes by recursive Fiedler bisection; the two halves
// are split in parallel (independent: the same result whatever the thread count), `out` in a fixed order.
void split(const Adjacency& graph, std::vector<int> subset, int parts, std::vector<std::vector<int>>& out) {
  if (parts <= 1 || subset.size() <= 1) {
    out.push_back(std::move(subset));
    return;
  }
  const Eigen::VectorXd f = fiedler_vector(graph, subset);
  std::vector<std::size_t> order(subset.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return f(static_cast<Eigen::Index>(a)) < f(static_cast<Eigen::Index>(b));
  });
  const int left_parts = parts / 2;
  const auto cut = static_cast<std::size_t>(std::llround(static_cast<double>(subset.size()) * left_parts / parts));
  std::vector<int> left, right;
  for (std::size_t i = 0; i < order.size(); ++i) (i < cut ? left : right).push_back(subset[order[i]]);
  std::sort(left.begin(), left.end());
  std::sort(right.begin(), right.end());
  std::vector<int>* halves[2] = {&left, &right};
  const int half_parts[2] = {left_parts, parts - left_parts};
  std::vector<std::vector<int>> pieces[2];
  const double work = 1e4 * static_cast<double>(subset.size());  // sparse Lanczos: products of ~1e4 flops per item
  dense::for_each(2, work, [&](std::size_t h) { split(graph, std::move(*halves[h]), half_parts[h], pieces[h]); });
  for (auto& piece : pieces)
    for (auto& group : piece) out.push_back(std::move(group));
}

Group build(const Adjacency& graph, std::vector<int> individuals, int group_size, const std::string& name) {
  Group g;
  g.name = name;
  const int count = static_cast<int>(individuals.size());
  if (count <= group_size) {
    g.members = std::move(individuals);
    return g;
  }
  const int parts = std::min(group_size, (count + group_size - 1) / group_size);
  std::vector<std::vector<int>> pieces;
  split(graph, std::move(individuals), std::max(parts, 2), pieces);
  for (std::size_t i = 0; i < pieces.size(); ++i)
    g.subgroups.push_back(build(graph, std::move(pieces[i]), group_size, name + "." + std::to_string(i)));
  return g;
}

}  // namespace

Tree flatten_tree(const Group& root, int individual_count) {
  Tree tree;
  std::vector<std::string> owner(static_cast<std::size_t>(individual_count));
  flatten(root, -1, 0, "root", individual_count, tree, owner);
  for (int i = 0; i < individual_count; ++i)
    if (owner[static_cast<std::size_t>(i)].empty())
      throw ConfigError("hierarchy: individual " + std::to_string(i) + " is in no group; every individual belongs "
                        "to exactly one group");
  return tree;
}

Group cluster_hierarchy(const Adjacency& graph, int group_size) {
  std::vector<int> everyone(static_cast<std::size_t>(graph.count));
  std::iota(everyone.begin(), everyone.end(), 0);
  return build(graph, std::move(everyone), std::max(group_size, 2), "auto");
}

EditMapper::EditMapper(const Tree& tree, int individual_count) : path_(static_cast<std::size_t>(individual_count)) {
  // Walk down from the root: depth-first, recording (node, item) for each individual.
  std::vector<std::pair<int, int>> trail;
  auto visit = [&](auto&& self, int index) -> void {
    const TreeNode& node = tree.nodes[static_cast<std::size_t>(index)];
    for (std::size_t m = 0; m < node.members.size(); ++m) {
      auto& p = path_[static_cast<std::size_t>(node.members[m])];
      p = trail;
      p.emplace_back(index, static_cast<int>(m));
    }
    for (std::size_t c = 0; c < node.children.size(); ++c) {
      trail.emplace_back(index, static_cast<int>(node.members.size() + c));
      self(self, node.children[c]);
      trail.pop_back();
    }
  };
  visit(visit, 0);
}

EditTarget EditMapper::locate(int a, int b) const {
  const auto& pa = path_[static_cast<std::size_t>(a)];
  const auto& pb = path_[static_cast<std::size_t>(b)];
  for (std::size_t level = 0; level < std::min(pa.size(), pb.size()); ++level) {
    if (pa[level].second != pb[level].second) return EditTarget{pa[level].first, pa[level].second, pb[level].second};
  }
  return EditTarget{pa.back().first, pa.back().second, pb.back().second};  // unreachable for a ≠ b
}

}  // namespace throng::formation
