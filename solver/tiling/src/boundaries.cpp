// Boundary determination: pose groups and the subset choice (boundaries.h, construct.h step 5).
#include "boundaries.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <map>

namespace throng::tiling {
namespace {

// Occupied bins of the scaled state (speed, turn rate): each a quarter of the threshold wide.
struct Bins {
  std::vector<Eigen::Vector2d> centre;   // scaled state
  std::vector<std::size_t> count;
  std::vector<double> speed_sum;
  std::vector<std::vector<int>> of_sample;  // per track, per sample: bin index or −1 (not clean)
};

Bins bin_states(const std::vector<Track>& tracks, const RealPatchOptions& o) {
  Bins bins;
  const double width = o.pose_threshold / 4;
  std::map<std::pair<long, long>, int> index;
  for (const Track& t : tracks) {
    std::vector<int>& of = bins.of_sample.emplace_back(t.size(), -1);
    for (std::size_t s = 0; s < t.size(); ++s) {
      if (!t.clean[s]) continue;
      const double speed = t.v[s].norm();
      const Eigen::Vector2d x(speed / o.pose_speed_scale_mps, t.turn_rate[s] / o.pose_turn_scale_radps);
      const std::pair<long, long> key{std::lround(std::floor(x.x() / width)), std::lround(std::floor(x.y() / width))};
      auto [it, added] = index.try_emplace(key, static_cast<int>(bins.count.size()));
      if (added) {
        bins.centre.emplace_back((static_cast<double>(key.first) + 0.5) * width, (static_cast<double>(key.second) + 0.5) * width);
        bins.count.push_back(0);
        bins.speed_sum.push_back(0);
      }
      ++bins.count[static_cast<std::size_t>(it->second)];
      bins.speed_sum[static_cast<std::size_t>(it->second)] += speed;
      of[s] = it->second;
    }
  }
  return bins;
}

// Complete-linkage clustering of the bins: the cluster of each bin. The distance of two bins is bounded from
// above by their centres' distance plus a bin's diagonal, so a cluster's diameter over the samples stays below
// the threshold.
std::vector<std::size_t> complete_linkage(const Bins& bins, double threshold) {
  const std::size_t m = bins.centre.size();
  const double diagonal = threshold / 4 * std::sqrt(2.0);
  std::vector<std::vector<double>> d(m, std::vector<double>(m, 0.0));
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = 0; j < m; ++j) d[i][j] = i == j ? 0 : (bins.centre[i] - bins.centre[j]).norm() + diagonal;
  }
  std::vector<std::size_t> cluster(m);
  std::vector<bool> active(m, true);
  for (std::size_t i = 0; i < m; ++i) cluster[i] = i;
  for (;;) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t bi = 0, bj = 0;
    for (std::size_t i = 0; i < m; ++i) {
      if (!active[i]) continue;
      for (std::size_t j = i + 1; j < m; ++j) {
        if (active[j] && d[i][j] < best) {
          best = d[i][j];
          bi = i;
          bj = j;
        }
      }
    }
    if (!(best < threshold)) break;
    for (std::size_t k = 0; k < m; ++k) d[bi][k] = d[k][bi] = std::max(d[bi][k], d[bj][k]);
    active[bj] = false;
    for (std::size_t& c : cluster) {
      if (c == bj) c = bi;
    }
  }
  return cluster;
}

}  // namespace

PoseGroups cluster_poses(std::vector<Track>& tracks, const RealPatchOptions& o) {
  const Bins bins = bin_states(tracks, o);
  const std::vector<std::size_t> cluster = complete_linkage(bins, o.pose_threshold);
  // Clusters by size, largest first (ties: the earlier cluster).
  std::map<std::size_t, std::pair<std::size_t, double>> size_and_speed;  // cluster → (samples, speed sum)
  for (std::size_t b = 0; b < cluster.size(); ++b) {
    size_and_speed[cluster[b]].first += bins.count[b];
    size_and_speed[cluster[b]].second += bins.speed_sum[b];
  }
  std::vector<std::size_t> order;
  for (const auto& entry : size_and_speed) order.push_back(entry.first);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return size_and_speed[x].first > size_and_speed[y].first; });
  order.resize(std::min(order.size(), o.pose_groups));
  PoseGroups groups;
  std::map<std::size_t, int> rank;
  for (std::size_t c : order) {
    rank[c] = static_cast<int>(groups.samples.size());
    groups.samples.push_back(size_and_speed[c].first);
    groups.centre_speed.push_back(size_and_speed[c].second / static_cast<double>(size_and_speed[c].first));
  }
  for (std::size_t t = 0; t < tracks.size(); ++t) {
    tracks[t].group.assign(tracks[t].size(), -1);
    for (std::size_t s = 0; s < tracks[t].size(); ++s) {
      const int b = bins.of_sample[t][s];
      if (b < 0) continue;
      const auto it = rank.find(cluster[static_cast<std::size_t>(b)]);
      if (it != rank.end()) tracks[t].group[s] = it->second;
    }
  }
  return groups;
}

namespace {

bool in_chosen(const Track& t, long g, GroupMask chosen) {
  if (!t.covers(g)) return false;
  const int group = t.group[t.local(g)];
  return group >= 0 && ((chosen >> group) & 1U) != 0;
}

long margin_samples(const RealPatchOptions& o) { return std::lround(o.margin_s * o.sample_rate_hz); }

}  // namespace

std::optional<Bounds> bound(const Track& t, const Episode& episode, GroupMask chosen, const RealPatchOptions& o) {
  const long margin = margin_samples(o), lead = std::lround(o.boundary_lead_s * o.sample_rate_hz);
  std::optional<long> entry, exit;
  for (long g = episode.first - 1 - lead; g >= episode.first - 1 - lead - margin && !entry; --g) {
    if (in_chosen(t, g, chosen)) entry = g;
  }
  for (long g = episode.last + 1 + lead; g <= episode.last + 1 + lead + margin && !exit; ++g) {
    if (in_chosen(t, g, chosen)) exit = g;
  }
  if (!entry || !exit) return std::nullopt;
  return Bounds{t.local(*entry), t.local(*exit)};
}

GroupMask choose_groups(const std::vector<Episode>& episodes, const std::vector<Track>& tracks, std::size_t groups,
                        const RealPatchOptions& o) {
  double track_frames = 0;
  for (const Track& t : tracks) track_frames += static_cast<double>(t.size());
  // A dropped episode costs its agents' whole tracks: the boundary search run on to the tracks' ends.
  const auto frames = [&](GroupMask chosen) {
    double total = 0;
    for (const Episode& ep : episodes) {
      double kept = 0, whole = 0;
      bool dropped = false;
      for (std::size_t t : ep.tracks) {
        whole += static_cast<double>(tracks[t].size());
        const std::optional<Bounds> b = bound(tracks[t], ep, chosen, o);
        dropped = dropped || !b;
        if (b) kept += static_cast<double>(b->second - b->first + 1);
      }
      total += dropped ? whole : kept;
    }
    return total;
  };
  GroupMask best = 1;
  double best_cost = std::numeric_limits<double>::infinity();
  for (GroupMask chosen = 1; chosen < (GroupMask{1} << groups); ++chosen) {
    const double cost = o.diversity_weight * std::popcount(chosen) + frames(chosen) / track_frames;
    if (cost < best_cost) {
      best_cost = cost;
      best = chosen;
    }
  }
  return best;
}

}  // namespace throng::tiling
