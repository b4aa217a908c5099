// Hierarchical control (§4.4): groups interpolated at each level relative to their barycentres.
#include <throng/formation/formation.h>

#include "fixtures.h"

#include <catch2/catch.hpp>

#include <set>

using namespace throng::formation;

namespace {

constexpr int groups = 4, per_group = 5;

// 4 clusters of 5; the clusters' layout and their inner shapes change from keyframe to keyframe.
Problem clustered(std::uint64_t seed) {
  Problem p;
  for (int k = 0; k < 3; ++k) {
    const Eigen::MatrixXd centres = throng::test::scattered(groups, 8.0, seed + 10 * static_cast<std::uint64_t>(k), 5.0) * 1.5;
    Keyframe key;
    key.time_s = 2.0 * k;
    key.positions.resize(groups * per_group, 2);
    for (int g = 0; g < groups; ++g) {
      Eigen::MatrixXd local = throng::test::scattered(per_group, 1.2, seed + 100 * static_cast<std::uint64_t>(k) + static_cast<std::uint64_t>(g), 0.4);
      local = local.rowwise() - local.colwise().mean();  // the cluster's barycentre is its centre
      for (int i = 0; i < per_group; ++i) key.positions.row(g * per_group + i) = centres.row(g) + local.row(i);
    }
    p.keyframes.push_back(key);
  }
  Group root;
  root.name = "crowd";
  for (int g = 0; g < groups; ++g) {
    Group sub;
    sub.name = "g" + std::to_string(g);
    for (int i = 0; i < per_group; ++i) sub.members.push_back(g * per_group + i);
    root.subgroups.push_back(sub);
  }
  p.hierarchy = root;
  return p;
}

Eigen::MatrixXd barycentres(const Eigen::MatrixXd& positions) {
  Eigen::MatrixXd b(groups, positions.cols());
  for (int g = 0; g < groups; ++g) b.row(g) = positions.middleRows(g * per_group, per_group).colwise().mean();
  return b;
}

}  // namespace

TEST_CASE("each subgroup's barycentre follows the spectral path of the barycentres' formation") {
  const Problem p = clustered(1);
  const Result r = animate_formation(p, Options{});
  // The top level alone: the flat method on the groups' barycentres.
  Problem top;
  for (const Keyframe& k : p.keyframes) top.keyframes.push_back(Keyframe{k.time_s, barycentres(k.positions), {}});
  const Result flat = animate_formation(top, Options{});
  REQUIRE(flat.motion.frame_count() == r.motion.frame_count());
  double worst = 0.0;
  for (std::size_t f = 0; f < r.motion.frame_count(); ++f)
    worst = std::max(worst, (barycentres(r.motion.frame(f)) - flat.motion.frame(f)).cwiseAbs().maxCoeff());
  CHECK(worst <= 1e-12 * 20);
  // Keyframes are hit, and species name each individual's group.
  for (std::size_t k = 0; k < 3; ++k)
    CHECK((r.motion.frame(k * 60).leftCols(2) - p.keyframes[k].positions).cwiseAbs().maxCoeff() <= 1e-12 * 20);
  for (int i = 0; i < groups * per_group; ++i) CHECK(r.motion.species[static_cast<std::size_t>(i)] == 1 + i / per_group);
}

TEST_CASE("one hierarchy level equals the flat method") {
  Problem p = clustered(2);
  p.hierarchy.reset();
  const Result flat = animate_formation(p, Options{});
  // Root holding everyone directly: the same computation.
  Group everyone;
  for (int i = 0; i < groups * per_group; ++i) everyone.members.push_back(i);
  p.hierarchy = everyone;
  const Result direct = animate_formation(p, Options{});
  CHECK(direct.motion.positions == flat.motion.positions);
  // Root → one subgroup → everyone: the root level interpolates a single point (the barycentre), the group
  // level the whole formation about it.
  Group wrapped;
  wrapped.subgroups.push_back(everyone);
  p.hierarchy = wrapped;
  const Result nested = animate_formation(p, Options{});
  double worst = 0.0;
  for (std::size_t i = 0; i < flat.motion.positions.size(); ++i)
    worst = std::max(worst, std::abs(nested.motion.positions[i] - flat.motion.positions[i]));
  CHECK(worst <= 1e-12 * 20);
}

TEST_CASE("an edit inside one subgroup changes only that subgroup's paths") {
  Problem p = clustered(3);
  const Result before = animate_formation(p, Options{});
  EdgeScale tighten;
  tighten.members = {5, 6, 7};  // part of group 1 (scaling every edge of a group would not change its eigenvectors)
  tighten.factor = 10.0;
  p.edits.scale.push_back(tighten);
  const Result after = animate_formation(p, Options{});
  double inside = 0.0, outside = 0.0;
  for (std::size_t f = 0; f < before.motion.frame_count(); ++f) {
    const Eigen::MatrixXd d = (after.motion.frame(f) - before.motion.frame(f)).cwiseAbs();
    inside = std::max(inside, d.middleRows(5, 5).maxCoeff());
    outside = std::max(outside, std::max(d.topRows(5).maxCoeff(), d.bottomRows(10).maxCoeff()));
  }
  CHECK(inside > 1e-3);
  CHECK(outside == 0.0);
}

TEST_CASE("a three-level hierarchy with members at every level hits its keyframes") {
  Problem p = clustered(4);
  Group root;
  root.members = {0};                          // an individual directly at the top
  Group left, right, inner;
  left.members = {1, 2, 3, 4, 5, 6, 7};
  inner.members = {8, 9, 10, 11};
  left.subgroups.push_back(inner);             // third level
  right.members = {12, 13, 14, 15, 16, 17, 18, 19};
  root.subgroups = {left, right};
  p.hierarchy = root;
  const Result r = animate_formation(p, Options{});
  for (std::size_t k = 0; k < 3; ++k)
    CHECK((r.motion.frame(k * 60).leftCols(2) - p.keyframes[k].positions).cwiseAbs().maxCoeff() <= 1e-12 * 20);
  CHECK(r.motion.species[0] == 0);
  CHECK(r.motion.species[8] == r.motion.species[11]);
  CHECK(r.motion.species[8] != r.motion.species[1]);
}

TEST_CASE("without a tree, spectral clustering groups well-separated clusters together") {
  Problem p = clustered(5);
  p.hierarchy.reset();
  Options o;
  o.auto_group_size = per_group;
  const Result r = animate_formation(p, o);
  // Every automatic leaf group lies inside one cluster (the graph summed over keyframes is cut between clusters).
  std::set<int> leaf_species(r.motion.species.begin(), r.motion.species.end());
  for (int s : leaf_species) {
    std::set<int> clusters;
    for (int i = 0; i < groups * per_group; ++i)
      if (r.motion.species[static_cast<std::size_t>(i)] == s) clusters.insert(i / per_group);
    CHECK(clusters.size() == 1);
  }
  CHECK(!r.hierarchy.subgroups.empty());
  for (std::size_t k = 0; k < 3; ++k)
    CHECK((r.motion.frame(k * 60).leftCols(2) - p.keyframes[k].positions).cwiseAbs().maxCoeff() <= 1e-12 * 20);
}

TEST_CASE("without a tree the hierarchy is automatic only beyond auto_group_size, by default 2,000") {
  // The issue: a tree "from YAML, or built automatically by spectral clustering when not given". Flat up to the
  // size (so every flat benchmark up to 2,000 stays one group), clustered beyond it, never with 0.
  CHECK(Options{}.auto_group_size == 2000);
  Problem p = clustered(5);
  p.hierarchy.reset();
  const int n = groups * per_group;
  Options o;
  o.auto_group_size = n;  // exactly the size: flat
  CHECK(animate_formation(p, o).hierarchy.subgroups.empty());
  o.auto_group_size = n - 1;  // one more than the size: clustered
  CHECK_FALSE(animate_formation(p, o).hierarchy.subgroups.empty());
  o.auto_group_size = 0;  // always flat
  CHECK(animate_formation(p, o).hierarchy.subgroups.empty());
  CHECK(animate_formation(p, Options{}).hierarchy.subgroups.empty());  // 20 individuals: flat by default
}

namespace {
// Largest item count (members + subgroups) of any group of the tree.
int largest_group(const Group& g) {
  int largest = static_cast<int>(g.members.size() + g.subgroups.size());
  for (const Group& s : g.subgroups) largest = std::max(largest, largest_group(s));
  return largest;
}
}  // namespace

TEST_CASE("an automatic hierarchy's groups have at most min(auto_group_size, auto_cluster_size) items, by default 250") {
  CHECK(Options{}.auto_cluster_size == 250);
  Problem p = clustered(5);
  p.hierarchy.reset();
  const int n = groups * per_group;
  Options o;
  o.auto_group_size = n - 1;  // clustered ...
  o.auto_cluster_size = 3;    // ... into groups of at most 3 items: three levels for 20 individuals
  const Result small = animate_formation(p, o);
  CHECK(largest_group(small.hierarchy) <= 3);
  CHECK(largest_group(small.hierarchy) >= 2);
  o.auto_cluster_size = 1000;  // the other bound: at most auto_group_size
  CHECK(largest_group(animate_formation(p, o).hierarchy) <= n - 1);
  for (std::size_t k = 0; k < 3; ++k)
    CHECK((small.motion.frame(k * 60).leftCols(2) - p.keyframes[k].positions).cwiseAbs().maxCoeff() <= 1e-12 * 20);
}
