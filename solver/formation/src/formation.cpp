// Entry point: checks, matching, the tree of groups, one group interpolation per group (SpectralGroup, or a
// PositionGroup for the baselines), evaluation from the root down, collision avoidance, the CrowdMotion.
#include <throng/formation/formation.h>

#include "collision.h"
#include "dense.h"
#include "facing.h"
#include "hierarchy.h"
#include "matching.h"
#include "position_group.h"
#include "spectral_group.h"
#include "spline.h"

#include <throng/core/errors.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <sstream>

namespace throng::formation {
namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw ConfigError(message);
}

// "job.yaml:12:5 (keyframes[1]): " in front of a message about something given there; nothing without a place.
std::string at(const std::string& where) { return where.empty() ? std::string() : where + ": "; }

void check_options(const Options& o) {
  require(std::isfinite(o.frame_rate_hz) && o.frame_rate_hz > 0,
          "formation.frame_rate: " + std::to_string(o.frame_rate_hz) + " must be a finite number > 0 (frames per second)");
  require(o.tension >= 0 && o.tension <= 1, "formation.tension: " + std::to_string(o.tension) + " must be in [0, 1]");
  require(o.isotropy_tolerance >= 0 && o.isotropy_tolerance < 1,
          "formation.isotropy_tolerance: " + std::to_string(o.isotropy_tolerance) + " must be in [0, 1)");
  require(o.auto_group_size == 0 || o.auto_group_size >= 2,
          "formation.auto_group_size: " + std::to_string(o.auto_group_size) + " must be 0 (flat) or at least 2");
  require(o.auto_cluster_size >= 2,
          "formation.auto_cluster_size: " + std::to_string(o.auto_cluster_size) + " must be at least 2 (items per group)");
  require(std::isfinite(o.radius_m) && o.radius_m >= 0, "formation.radius: " + std::to_string(o.radius_m) + " must be ≥ 0 (metres)");
  const FacingOptions& f = o.facing;
  require(std::isfinite(f.smoothing_s) && f.smoothing_s >= 0,
          "formation.facing.smoothing: " + std::to_string(f.smoothing_s) + " must be a finite number ≥ 0 (seconds)");
  require(std::isfinite(f.rule.standing_speed) && f.rule.standing_speed > 0,
          "formation.facing.standing_speed: " + std::to_string(f.rule.standing_speed) + " must be a finite number > 0 (m/s)");
  require(std::isfinite(f.rule.running_speed) && f.rule.running_speed > f.rule.standing_speed,
          "formation.facing.running_speed: " + std::to_string(f.rule.running_speed) +
              " must be a finite number above standing_speed " + std::to_string(f.rule.standing_speed) + " (m/s)");
  require(std::isfinite(f.gravity_mps2) && f.gravity_mps2 > 0,
          "formation.facing.gravity: " + std::to_string(f.gravity_mps2) + " must be a finite number > 0 (m/s²)");
  require(std::isfinite(o.max_speed_mps) && o.max_speed_mps >= 0,
          "formation.max_speed: " + std::to_string(o.max_speed_mps) + " must be a finite number ≥ 0 (m/s; 0: the keyframes' own)");
  timewarp::validate(o.guard, "formation.guard");
  require(std::isfinite(f.max_turn_rate_rad_s) && f.max_turn_rate_rad_s > 0,
          "formation.facing.max_turn_rate: " + std::to_string(f.max_turn_rate_rad_s) + " must be a finite number > 0 (rad/s)");
  const CollisionOptions& c = o.collision;
  if (!c.enabled) return;
  auto positive = [&](double v, const char* key, const char* unit) {
    require(std::isfinite(v) && v > 0, std::string("formation.collision.") + key + ": " + std::to_string(v) +
                                           " must be a finite number > 0 (" + unit + ")");
  };
  positive(c.min_distance_m, "min_distance", "metres");
  positive(c.relaxation_time_s, "relaxation_time", "seconds");
  positive(c.tracking_time_s, "tracking_time", "seconds");
  positive(c.repulsion_range_m, "repulsion_range", "metres");
  positive(c.time_step_s, "time_step", "seconds");
  positive(c.smoothing_time_s, "smoothing_time", "seconds");
  require(std::isfinite(c.repulsion_strength_m_per_s2) && c.repulsion_strength_m_per_s2 >= 0,
          "formation.collision.repulsion_strength: must be a finite number ≥ 0 (m/s²)");
  require(c.smoothing_passes >= 1, "formation.collision.smoothing_passes: " + std::to_string(c.smoothing_passes) + " must be ≥ 1");
  require(c.projection_sweeps >= 1, "formation.collision.projection_sweeps: " + std::to_string(c.projection_sweeps) + " must be ≥ 1");
}

void check_problem(const Problem& p) {
  if (p.keyframes.size() < 2)
    throw InputError("formation: " + std::to_string(p.keyframes.size()) + " keyframe(s); at least 2 are needed");
  const Eigen::Index n = p.keyframes[0].positions.rows();
  const Eigen::Index d = p.keyframes[0].positions.cols();
  if (n < 1) throw InputError("formation keyframe 0: no individuals");
  if (d != 2 && d != 3) throw InputError("formation keyframe 0: positions have " + std::to_string(d) + " columns; expected 2 (x, y) or 3 (x, y, z)");
  for (std::size_t k = 0; k < p.keyframes.size(); ++k) {
    const Keyframe& key = p.keyframes[k];
    const std::string what = at(key.where) + "formation keyframe " + std::to_string(k);
    if (key.positions.rows() != n)
      throw InputError(what + " has " + std::to_string(key.positions.rows()) + " individuals, keyframe 0 has " +
                       std::to_string(n) + "; every keyframe needs the same individuals");
    if (key.positions.cols() != d)
      throw InputError(what + " has " + std::to_string(key.positions.cols()) + " coordinates per individual, keyframe 0 has " + std::to_string(d));
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index a = 0; a < d; ++a)
        if (!std::isfinite(key.positions(i, a)))
          throw InputError(what + ": individual " + std::to_string(i) + " has a non-finite coordinate");
    if (!std::isfinite(key.time_s)) throw InputError(what + ": time is not finite");
    if (!key.facings.empty() && static_cast<Eigen::Index>(key.facings.size()) != n)
      throw InputError(what + " gives " + std::to_string(key.facings.size()) + " facings for " + std::to_string(n) +
                       " individuals; give one per individual or none");
    for (std::size_t i = 0; i < key.facings.size(); ++i) {
      const Eigen::Vector4d q = key.facings[i].coeffs();
      if (!q.allFinite() || std::abs(q.norm() - 1.0) > orientation_tolerance) {
        std::ostringstream s;
        s << what << ": individual " << i << " has facing (" << q[0] << ", " << q[1] << ", " << q[2] << ", " << q[3]
          << "), expected a finite unit quaternion (x, y, z, w)";
        throw InputError(s.str());
      }
    }
    if (k > 0 && !(key.time_s > p.keyframes[k - 1].time_s)) {
      std::ostringstream s;
      s << what << ": time " << key.time_s << " s is not after keyframe " << k - 1 << "'s " << p.keyframes[k - 1].time_s
        << " s; keyframe times must increase strictly";
      throw InputError(s.str());
    }
  }
  if (!p.ids.empty()) {
    if (static_cast<Eigen::Index>(p.ids.size()) != n)
      throw InputError("formation: " + std::to_string(p.ids.size()) + " ids for " + std::to_string(n) + " individuals");
    std::set<std::int64_t> seen;
    for (std::int64_t id : p.ids)
      if (!seen.insert(id).second) throw InputError("formation: id " + std::to_string(id) + " is given twice");
  }
}

// The individual-level edits of keyframe k (problem-wide first), each checked and named.
struct IndividualEdit {
  EdgeEdit edit;
  int scale_group = -1;  // member-list scales: which list, to count each group pair once
};
std::vector<IndividualEdit> individual_edits(const Problem& p, std::size_t k, int n) {
  std::vector<IndividualEdit> out;
  int scale_group = 0;
  std::string place;  // the place of the edit list being expanded
  auto check = [&](int i, const std::string& where) {
    if (i < 0 || i >= n)
      throw ConfigError(at(place) + where + ": individual " + std::to_string(i) + " does not exist (" + std::to_string(n) +
                        " individuals, 0.." + std::to_string(n - 1) + ")");
  };
  auto pair_edit = [&](EdgeEdit::Kind kind, const Pair& pair, double factor, const std::string& where) {
    check(pair[0], where);
    check(pair[1], where);
    if (pair[0] == pair[1]) throw ConfigError(at(place) + where + ": an edge needs two different individuals, got " + std::to_string(pair[0]) + " twice");
    out.push_back(IndividualEdit{EdgeEdit{kind, pair[0], pair[1], factor, where, place}, -1});
  };
  auto add_all = [&](const AdjacencyEdits& edits, const std::string& prefix) {
    place = edits.where;
    for (std::size_t i = 0; i < edits.remove.size(); ++i)
      pair_edit(EdgeEdit::Kind::remove, edits.remove[i], 1.0, prefix + "remove[" + std::to_string(i) + "]");
    for (std::size_t i = 0; i < edits.add.size(); ++i)
      pair_edit(EdgeEdit::Kind::add, edits.add[i], 1.0, prefix + "add[" + std::to_string(i) + "]");
    for (std::size_t s = 0; s < edits.scale.size(); ++s) {
      const EdgeScale& scale = edits.scale[s];
      const std::string where = prefix + "scale[" + std::to_string(s) + "]";
      if (!(scale.factor > 0) || !std::isfinite(scale.factor))
        throw ConfigError(at(place) + where + ": factor " + std::to_string(scale.factor) + " must be finite and > 0");
      for (std::size_t i = 0; i < scale.pairs.size(); ++i)
        pair_edit(EdgeEdit::Kind::scale, scale.pairs[i], scale.factor, where + ".pairs[" + std::to_string(i) + "]");
      for (int m : scale.members) check(m, where + ".members");
      for (std::size_t a = 0; a < scale.members.size(); ++a)
        for (std::size_t b = a + 1; b < scale.members.size(); ++b)
          if (scale.members[a] != scale.members[b])
            out.push_back(IndividualEdit{EdgeEdit{EdgeEdit::Kind::scale_if_edge, scale.members[a], scale.members[b], scale.factor, where + ".members", place}, scale_group});
      ++scale_group;
    }
  };
  add_all(p.edits, "edits.");
  add_all(p.keyframes[k].edits, "keyframe " + std::to_string(k) + " edits.");
  return out;
}

std::string individual_name(const Problem& p, int i) {
  std::string name = "individual " + std::to_string(i);
  if (!p.ids.empty() && p.ids[static_cast<std::size_t>(i)] != i) name += " (id " + std::to_string(p.ids[static_cast<std::size_t>(i)]) + ")";
  return name;
}

// The graph over all individuals summed over keyframes (for automatic clustering).
Adjacency summed_graph(const Problem& p, const std::vector<std::vector<IndividualEdit>>& edits) {
  const int n = static_cast<int>(p.keyframes[0].positions.rows());
  std::vector<std::string> names(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) names[static_cast<std::size_t>(i)] = individual_name(p, i);
  // The keyframes' graphs in parallel, summed in keyframe order.
  std::vector<Adjacency> graphs(p.keyframes.size());
  dense::for_each(graphs.size(), 2000.0 * n, [&](std::size_t k) {
    const std::string what = "formation keyframe " + std::to_string(k);
    graphs[k] = delaunay_adjacency(p.keyframes[k].positions, at(p.keyframes[k].where) + what, names);
    std::vector<EdgeEdit> plain;
    for (const IndividualEdit& e : edits[k]) plain.push_back(e.edit);
    apply_edits(graphs[k], p.keyframes[k].positions, plain, what, names);
  });
  Adjacency sum;
  sum.count = n;
  for (const Adjacency& g : graphs)
    for (const auto& [edge, w] : g.weights) sum.weights[edge] += w;
  return sum;
}

void check_keyframe_spacing(const Problem& p, double min_distance) {
  const auto n = static_cast<std::size_t>(p.keyframes[0].positions.rows());
  for (std::size_t k = 0; k < p.keyframes.size(); ++k) {
    std::vector<double> flat(n * 3, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (Eigen::Index a = 0; a < p.keyframes[k].positions.cols(); ++a)
        flat[i * 3 + static_cast<std::size_t>(a)] = p.keyframes[k].positions(static_cast<Eigen::Index>(i), a);
    const CollisionReport r = closest_approach(flat, n, 1, min_distance);
    if (!r.satisfied) {
      std::ostringstream s;
      s << at(p.keyframes[k].where) << "formation keyframe " << k << ": individuals " << r.closest_pair[0] << " and " << r.closest_pair[1] << " are "
        << r.closest_m << " m apart, closer than collision.min_distance " << min_distance
        << " m; keyframes are kept exactly, so they must respect the minimum distance";
      throw InputError(s.str());
    }
  }
}

Group root_of_everyone(int n) {
  Group g;
  g.name = "formation";
  for (int i = 0; i < n; ++i) g.members.push_back(i);
  return g;
}

}  // namespace

Result animate_formation(const Problem& input, const Options& options, Progress& progress) {
  check_options(options);
  check_problem(input);
  const int n = static_cast<int>(input.keyframes[0].positions.rows());
  const int d = static_cast<int>(input.keyframes[0].positions.cols());
  const std::size_t k_count = input.keyframes.size();
  if (options.collision.enabled) check_keyframe_spacing(input, options.collision.min_distance_m);
  progress.update(0.0, "formation analysis");

  Result result;
  // Matching: reorder the rows of keyframes 1.. to follow keyframe 0's individuals.
  Problem problem = input;
  if (options.match_individuals) {
    std::vector<Eigen::MatrixXd> raw;
    for (const Keyframe& k : input.keyframes) raw.push_back(k.positions);
    result.correspondence = match_keyframes(raw, options.orientation, options.isotropy_tolerance);
    for (std::size_t k = 1; k < k_count; ++k)
      for (int i = 0; i < n; ++i) {
        const int row = result.correspondence[k][static_cast<std::size_t>(i)];
        problem.keyframes[k].positions.row(i) = input.keyframes[k].positions.row(row);
        if (!input.keyframes[k].facings.empty())
          problem.keyframes[k].facings[static_cast<std::size_t>(i)] = input.keyframes[k].facings[static_cast<std::size_t>(row)];
      }
  } else {
    result.correspondence.assign(k_count, std::vector<int>(static_cast<std::size_t>(n)));
    for (auto& c : result.correspondence)
      for (int i = 0; i < n; ++i) c[static_cast<std::size_t>(i)] = i;
  }

  std::vector<std::vector<IndividualEdit>> edits(k_count);
  for (std::size_t k = 0; k < k_count; ++k) edits[k] = individual_edits(problem, k, n);

  // The tree of groups.
  if (problem.hierarchy) {
    result.hierarchy = *problem.hierarchy;
  } else if (options.auto_group_size > 0 && n > options.auto_group_size) {
    result.hierarchy = cluster_hierarchy(summed_graph(problem, edits), std::min(options.auto_group_size, options.auto_cluster_size));
  } else {
    result.hierarchy = root_of_everyone(n);
  }
  const Tree tree = [&] {
    try {
      return flatten_tree(result.hierarchy, n);
    } catch (const ConfigError& e) {
      if (result.hierarchy.where.empty()) throw;
      throw ConfigError(at(result.hierarchy.where) + e.what());
    }
  }();
  const EditMapper mapper(tree, n);

  // Each group's keyframes: items, anchors, edits mapped onto its items.
  const std::size_t node_count = tree.nodes.size();
  std::vector<GroupKeyframes> groups(node_count);
  for (std::size_t g = 0; g < node_count; ++g) {
    const TreeNode& node = tree.nodes[g];
    GroupKeyframes& gk = groups[g];
    gk.what = node_count == 1 ? "formation" : "formation " + node.name;
    for (int m : node.members) gk.item_names.push_back(individual_name(problem, m));
    for (int c : node.children) gk.item_names.push_back("sub" + tree.nodes[static_cast<std::size_t>(c)].name);
    for (const Keyframe& k : problem.keyframes) gk.sharp.push_back(k.sharp);
    for (std::size_t k = 0; k < k_count; ++k) {
      const Eigen::MatrixXd& all = problem.keyframes[k].positions;
      Eigen::MatrixXd items(node.item_count(), d);
      Eigen::Index row = 0;
      for (int m : node.members) items.row(row++) = all.row(m);
      for (int c : node.children) {
        Eigen::RowVectorXd mean = Eigen::RowVectorXd::Zero(d);
        for (int i : tree.nodes[static_cast<std::size_t>(c)].individuals) mean += all.row(i);
        items.row(row++) = mean / static_cast<double>(tree.nodes[static_cast<std::size_t>(c)].individuals.size());
      }
      Eigen::VectorXd anchor = Eigen::VectorXd::Zero(d);
      for (int i : node.individuals) anchor += all.row(i).transpose();
      gk.anchors.push_back(anchor / static_cast<double>(node.individuals.size()));
      gk.positions.push_back(std::move(items));
      gk.edits.emplace_back();
      gk.places.push_back(problem.keyframes[k].where);
    }
  }
  for (std::size_t k = 0; k < k_count; ++k) {
    std::set<std::tuple<int, int, int, int>> scaled;  // (node, item a, item b, member list) counted once
    for (const IndividualEdit& e : edits[k]) {
      const EditTarget target = mapper.locate(e.edit.a, e.edit.b);
      if (e.scale_group >= 0) {
        const auto key = std::make_tuple(target.node, std::min(target.item_a, target.item_b),
                                         std::max(target.item_a, target.item_b), e.scale_group);
        if (!scaled.insert(key).second) continue;
      }
      EdgeEdit mapped = e.edit;
      mapped.a = target.item_a;
      mapped.b = target.item_b;
      groups[static_cast<std::size_t>(target.node)].edits[k].push_back(std::move(mapped));
    }
  }

  // Analysis of every group (independent: in parallel).
  const bool spectral_method = options.interpolation == Interpolation::spectral;
  std::vector<std::unique_ptr<GroupInterpolation>> interpolation(node_count);
  double analysis_work = 0.0;  // eigenproblems: about 30 m³ per keyframe; the baselines' graphs about 2000 m
  for (const TreeNode& node : tree.nodes) {
    const double m = node.item_count();
    analysis_work += (spectral_method ? 30.0 * m * m * m : 2000.0 * m) * static_cast<double>(k_count);
  }
  dense::for_each(node_count, analysis_work / static_cast<double>(node_count), [&](std::size_t g) {
    if (spectral_method) interpolation[g] = std::make_unique<SpectralGroup>(groups[g], options);
    else interpolation[g] = std::make_unique<PositionGroup>(groups[g], options);
  });
  progress.update(1.0, "formation analysis");

  // The individual-level edges of every keyframe's graphs (for pictures and the output file).
  result.keyframe_edges.assign(k_count, {});
  for (std::size_t k = 0; k < k_count; ++k) {
    for (std::size_t g = 0; g < node_count; ++g) {
      const TreeNode& node = tree.nodes[g];
      const int members = static_cast<int>(node.members.size());
      for (const auto& [edge, weight] : interpolation[g]->graph(static_cast<int>(k)).weights) {
        if (edge.first >= members || edge.second >= members) continue;
        const int a = node.members[static_cast<std::size_t>(edge.first)];
        const int b = node.members[static_cast<std::size_t>(edge.second)];
        result.keyframe_edges[k].push_back({std::min(a, b), std::max(a, b)});
      }
    }
    std::sort(result.keyframe_edges[k].begin(), result.keyframe_edges[k].end());
  }

  // Frames, from the root down: each group's items give its members' positions and its subgroups' anchors.
  std::vector<double> keyframe_times;
  for (const Keyframe& k : problem.keyframes) keyframe_times.push_back(k.time_s);
  const Timeline timeline = make_timeline(keyframe_times, options.frame_rate_hz);
  const std::size_t frames = timeline.frame_count();
  result.keyframe_frames = timeline.keyframe_frame;
  std::vector<Eigen::MatrixXd> anchor_paths(node_count);
  anchor_paths[0].resize(d, static_cast<Eigen::Index>(frames));
  for (std::size_t f = 0; f < frames; ++f) {
    const ControlKeys keys = groups[0].controls(timeline.segment[f]);
    const SplineWeights w = catmull_rom_weights(timeline.local[f], options.tension);
    Eigen::VectorXd a = Eigen::VectorXd::Zero(d);
    for (int i = 0; i < 4; ++i) a += w.c[static_cast<std::size_t>(i)] * groups[0].anchors[static_cast<std::size_t>(keys.keys[static_cast<std::size_t>(i)])];
    anchor_paths[0].col(static_cast<Eigen::Index>(f)) = a;
  }
  CrowdMotion& motion = result.motion;
  motion = CrowdMotion::with_shape(frames, static_cast<std::size_t>(n), options.radius_m);
  motion.times = timeline.times;
  for (int depth = 0; depth < tree.depth_count; ++depth) {
    std::vector<std::size_t> level;
    for (std::size_t g = 0; g < node_count; ++g)
      if (tree.nodes[g].depth == depth) level.push_back(g);
    double level_work = 0.0;  // products of about 8 m² d flops per frame, plus the coefficients
    for (std::size_t g : level) {
      const double m = tree.nodes[g].item_count();
      level_work += ((spectral_method ? 8.0 * m * m * d : 0.0) + 100.0 * m) * static_cast<double>(frames);
    }
    dense::for_each(level.size(), level_work / static_cast<double>(std::max<std::size_t>(level.size(), 1)), [&](std::size_t li) {
      const std::size_t g = level[li];
      const TreeNode& node = tree.nodes[g];
      const Eigen::MatrixXd items = interpolation[g]->evaluate(timeline, anchor_paths[g]);
      for (std::size_t m = 0; m < node.members.size(); ++m) {
        const auto individual = static_cast<std::size_t>(node.members[m]);
        for (std::size_t f = 0; f < frames; ++f) {
          double* p = motion.positions.data() + motion.index(f, individual);
          for (int a = 0; a < 3; ++a) p[a] = a < d ? items(static_cast<Eigen::Index>(m) * d + a, static_cast<Eigen::Index>(f)) : 0.0;
        }
      }
      for (std::size_t c = 0; c < node.children.size(); ++c)
        anchor_paths[static_cast<std::size_t>(node.children[c])] = items.middleRows(static_cast<Eigen::Index>(node.members.size() + c) * d, d);
    });
    progress.update(static_cast<double>(depth + 1) / tree.depth_count, "formation frames");
  }

  // Identity, groups.
  for (int i = 0; i < n; ++i) motion.ids[static_cast<std::size_t>(i)] = input.ids.empty() ? i : input.ids[static_cast<std::size_t>(i)];
  for (std::size_t g = 0; g < node_count; ++g)
    for (int m : tree.nodes[g].members) motion.species[static_cast<std::size_t>(m)] = static_cast<std::int32_t>(g);

  if (options.collision.enabled) {
    result.collision = avoid_collisions(motion.positions, static_cast<std::size_t>(n), motion.times,
                                        timeline.keyframe_frame, options.collision, progress);
  }

  // Facing and action, from the final paths (step 13).
  std::vector<std::vector<Eigen::Quaterniond>> facings(k_count);
  for (std::size_t k = 0; k < k_count; ++k)
    for (const Eigen::Quaterniond& q : problem.keyframes[k].facings) facings[k].push_back(q.normalized());
  fill_facings(motion, timeline, facings, d, options.facing);
  return result;
}

Result animate_formation(const Problem& problem, const Options& options) {
  NoProgress none;
  return animate_formation(problem, options, none);
}

std::vector<Keyframe> keyframes_from_motion(const CrowdMotion& motion, const std::vector<std::size_t>& frames, int dimension) {
  if (dimension != 2 && dimension != 3) throw ConfigError("keyframes from a crowd: dimension " + std::to_string(dimension) + " must be 2 or 3");
  std::vector<Keyframe> out;
  for (std::size_t f : frames) {
    if (f >= motion.frame_count())
      throw InputError("keyframes from a crowd: frame " + std::to_string(f) + " does not exist (" +
                       std::to_string(motion.frame_count()) + " frames)");
    Keyframe k;
    k.time_s = motion.times[f];
    k.positions.resize(static_cast<Eigen::Index>(motion.agent_count()), dimension);
    for (std::size_t i = 0; i < motion.agent_count(); ++i) {
      if (!motion.present(f, i))
        throw InputError("keyframes from a crowd: agent " + std::to_string(motion.ids[i]) + " is absent at frame " +
                         std::to_string(f) + "; every agent must be present at every keyframe frame");
      for (int a = 0; a < dimension; ++a) k.positions(static_cast<Eigen::Index>(i), a) = motion.position(f, i)(a);
    }
    out.push_back(std::move(k));
  }
  return out;
}

}  // namespace throng::formation
