// Patch construction from recorded trajectories (construct.h).
#include <throng/tiling/construct.h>

#include <throng/core/errors.h>

#include "boundaries.h"
#include "episodes.h"
#include "geometry.h"
#include "real_track.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace throng::tiling {
namespace {

using Run = std::vector<std::pair<double, Eigen::Vector2d>>;  // recorded (time, position) of one agent, no gap

// The run resampled at the global grid's samples inside it (linear in between); no track when too short.
void resample_run(std::size_t agent, const Run& run, double dt, std::vector<Track>& tracks) {
  if (run.size() < 2 || run.back().first - run.front().first < 2 * dt) return;
  Track tr;
  tr.agent = agent;
  tr.start = std::lround(std::ceil(run.front().first / dt - 1e-9));
  std::size_t k = 0;
  for (double t = static_cast<double>(tr.start) * dt; t <= run.back().first + 1e-9; t = static_cast<double>(tr.end()) * dt) {
    while (k + 2 < run.size() && run[k + 1].first < t) ++k;
    const double u = std::clamp((t - run[k].first) / (run[k + 1].first - run[k].first), 0.0, 1.0);
    tr.p.push_back(run[k].second + u * (run[k + 1].second - run[k].second));
  }
  if (tr.p.size() >= 3) tracks.push_back(std::move(tr));
}

// Velocity, heading, turn rate, standing, clean and Eq. 4 of a track's positions (construct.h steps 1, 2, 5).
void fill_state(Track& tr, const RealPatchOptions& o) {
  const double dt = 1.0 / o.sample_rate_hz;
  const std::size_t n = tr.size();
  tr.v.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    const std::size_t lo = s == 0 ? 0 : s - 1, hi = s + 1 == n ? s : s + 1;
    tr.v[s] = (tr.p[hi] - tr.p[lo]) / (static_cast<double>(hi - lo) * dt);
  }
  tr.heading.assign(n, std::nan(""));
  tr.standing.resize(n);
  // Heading: of the velocity where moving; held (forwards, then backwards from the first) where standing.
  double last = std::nan("");
  for (std::size_t s = 0; s < n; ++s) {
    tr.standing[s] = tr.v[s].norm() < o.standing_speed_mps;
    if (!tr.standing[s]) last = std::atan2(tr.v[s].y(), tr.v[s].x());
    tr.heading[s] = last;
  }
  const auto first = std::find_if(tr.heading.begin(), tr.heading.end(), [](double h) { return !std::isnan(h); });
  const double first_heading = first == tr.heading.end() ? 0.0 : *first;
  for (double& h : tr.heading) {
    if (!std::isnan(h)) break;
    h = first_heading;
  }
  tr.turn_rate.assign(n, 0.0);
  tr.clean.assign(n, false);
  for (std::size_t s = 1; s + 1 < n; ++s) {
    tr.turn_rate[s] = wrap_angle(tr.heading[s + 1] - tr.heading[s - 1]) / (2 * dt);
    const double accel = (tr.v[s + 1] - tr.v[s - 1]).norm() / (2 * dt);
    tr.clean[s] = tr.standing[s] ? tr.v[s].norm() < o.standing_speed_mps / 3 : accel < o.clean_acceleration_mps2;
  }
  tr.variation = motion_variation(tr.v, static_cast<std::size_t>(std::lround(o.reaction_window_s * o.sample_rate_hz)));
}

// Throws ConfigError naming the key of the first impossible option.
void validate(const RealPatchOptions& o) {
  const auto require = [](bool ok, const char* key, const char* what) {
    if (!ok) throw ConfigError(std::string("real patches: ") + key + " must be " + what);
  };
  const auto positive = [&](double v, const char* key) { require(v > 0 && std::isfinite(v), key, "> 0"); };
  const auto non_negative = [&](double v, const char* key) { require(v >= 0 && std::isfinite(v), key, "≥ 0"); };
  positive(o.sample_rate_hz, "sample_rate");
  positive(o.max_gap_s, "max_gap");
  positive(o.radius_m, "radius");
  positive(o.standing_speed_mps, "standing_speed");
  positive(o.clean_acceleration_mps2, "clean_acceleration");
  non_negative(o.reaction_window_s, "reaction_window");
  non_negative(o.contact_m, "contact");
  positive(o.near_m, "near");
  non_negative(o.reaction_min_m2ps2, "reaction_min");
  non_negative(o.sync_range_m, "sync_range");
  non_negative(o.synchronicity_min, "synchronicity_min");
  non_negative(o.min_contact_s, "min_contact");
  non_negative(o.merge_gap_s, "merge_gap");
  non_negative(o.merge_distance_m, "merge_distance");
  require(o.max_episode_characters >= 2, "max_episode_characters", "≥ 2");
  non_negative(o.margin_s, "margin");
  non_negative(o.boundary_lead_s, "boundary_lead");
  positive(o.pose_speed_scale_mps, "pose_speed_scale");
  positive(o.pose_turn_scale_radps, "pose_turn_scale");
  require(o.pose_threshold >= 0.05, "pose_threshold", "≥ 0.05 (the clustering grid grows as its inverse square)");
  require(o.pose_groups >= 1 && o.pose_groups <= 16, "pose_groups", "in [1, 16] (every subset is scored)");
  non_negative(o.diversity_weight, "diversity_weight");
  positive(o.single_duration_s, "single_duration");
  positive(o.preference_per_character, "preference_per_character");
}

// Pose classes of the chosen groups (construct.h step 6): the class index of each group, −1 when not chosen.
std::vector<int> name_classes(PatchLibrary& lib, const PoseGroups& groups, GroupMask chosen, const RealPatchOptions& o,
                              RealPatchReport& found) {
  std::vector<int> class_of(groups.samples.size(), -1);
  for (std::size_t g = 0; g < groups.samples.size(); ++g) {
    if (((chosen >> g) & 1U) == 0) continue;
    const std::string name = !o.builtin_classes                             ? o.prefix + "pose_" + std::to_string(g)
                             : groups.centre_speed[g] < o.standing_speed_mps ? "standing"
                                                                              : "walking";
    class_of[g] = static_cast<int>(lib.pose_class(name));
    found.chosen_classes.push_back(name);
  }
  return class_of;
}

// The pose class of a boundary sample (a clean sample of a chosen group), −1 for any other sample.
int class_at(const Track& tr, std::size_t s, const std::vector<int>& class_of) {
  return tr.group[s] < 0 ? -1 : class_of[static_cast<std::size_t>(tr.group[s])];
}

// The boundary sample of `tr` nearest to `s` within [lo, hi]; tr.size() (none) when there is none.
std::size_t nearest_boundary(const Track& tr, std::size_t s, std::size_t lo, std::size_t hi, const std::vector<int>& class_of) {
  for (std::size_t d = 0; d <= hi - lo; ++d) {
    if (s >= lo + d && s - d <= hi && class_at(tr, s - d, class_of) >= 0) return s - d;
    if (s + d <= hi && s + d >= lo && class_at(tr, s + d, class_of) >= 0) return s + d;
  }
  return tr.size();
}

// Samples a..b of `tr` as a fragment whose ends are boundary samples.
Fragment fragment_of(const Track& tr, std::size_t a, std::size_t b, const std::vector<int>& class_of, const RealPatchOptions& o) {
  const double dt = 1.0 / o.sample_rate_hz;
  Fragment f;
  f.radius_m = o.radius_m;
  for (std::size_t s = a; s <= b; ++s) {
    f.positions.push_back(tr.p[s]);
    f.headings.push_back(wrap_angle(tr.heading[s]));
    f.times.push_back(static_cast<double>(tr.start + static_cast<long>(s)) * dt);
  }
  f.entry_class = static_cast<std::size_t>(class_at(tr, a, class_of));
  f.exit_class = static_cast<std::size_t>(class_at(tr, b, class_of));
  // Moving ends face along the path (as the built-in patches): the end's heading is its tangent's.
  const auto along = [&](std::size_t i, std::size_t j, double& h) {
    const Eigen::Vector2d d = f.positions[j] - f.positions[i];
    if (d.norm() > 1e-6) h = std::atan2(d.y(), d.x());
  };
  if (!tr.standing[a]) along(0, 1, f.headings.front());
  if (!tr.standing[b]) along(f.positions.size() - 2, f.positions.size() - 1, f.headings.back());
  return f;
}

// Episodes of more than max_episode_characters removed and counted.
void drop_too_large(std::vector<Episode>& episodes, const RealPatchOptions& o, RealPatchReport& found) {
  const auto too_large = [&](const Episode& ep) { return ep.tracks.size() > o.max_episode_characters; };
  found.dropped_too_large = static_cast<std::size_t>(std::count_if(episodes.begin(), episodes.end(), too_large));
  episodes.erase(std::remove_if(episodes.begin(), episodes.end(), too_large), episodes.end());
}

// One constraint per pair of the episode that had an event, at the pair's closest approach over its events.
std::vector<InterpersonalConstraint> closest_approaches(const Episode& ep, const std::vector<Track>& tracks,
                                                        const std::vector<Bounds>& bounds) {
  std::map<std::pair<std::size_t, std::size_t>, long> closest;  // (track a, track b) → global sample
  const auto distance = [&](std::size_t a, std::size_t b, long g) {
    return (tracks[a].p[tracks[a].local(g)] - tracks[b].p[tracks[b].local(g)]).norm();
  };
  for (const Event& e : ep.events) {
    const auto [it, added] = closest.try_emplace({e.a, e.b}, e.closest);
    if (!added && distance(e.a, e.b, e.closest) < distance(e.a, e.b, it->second)) it->second = e.closest;
  }
  const auto fragment = [&](std::size_t track) {
    return static_cast<std::size_t>(std::find(ep.tracks.begin(), ep.tracks.end(), track) - ep.tracks.begin());
  };
  std::vector<InterpersonalConstraint> out;
  for (const auto& [pair, g] : closest) {
    const std::size_t fa = fragment(pair.first), fb = fragment(pair.second);
    out.push_back({fa, tracks[pair.first].local(g) - bounds[fa].first, fb, tracks[pair.second].local(g) - bounds[fb].first});
  }
  return out;
}

// Counts an episode patch of `characters` in the report's size classes.
void count_by_size(RealPatchReport& found, std::size_t characters) {
  if (characters == 2) {
    ++found.pairs;
  } else if (characters == 3) {
    ++found.groups_of_3;
  } else {
    ++found.groups_of_4_plus;
  }
}

// The episode patches (construct.h step 7), in order of time.
void add_episode_patches(PatchLibrary& lib, const std::vector<Episode>& episodes, const std::vector<Track>& tracks, GroupMask chosen,
                         const std::vector<int>& class_of, const RealPatchOptions& o, RealPatchReport& found) {
  for (const Episode& ep : episodes) {
    std::vector<Bounds> bounds;
    for (std::size_t t : ep.tracks) {
      if (const std::optional<Bounds> b = bound(tracks[t], ep, chosen, o)) bounds.push_back(*b);
    }
    if (bounds.size() < ep.tracks.size()) {
      ++found.dropped_no_boundary;
      continue;
    }
    const std::size_t made = found.pairs + found.groups_of_3 + found.groups_of_4_plus;
    if (made >= o.max_episode_patches) {
      ++found.dropped_over_cap;
      continue;
    }
    const bool pair = ep.tracks.size() == 2;
    PatchType t;
    t.name = o.prefix + (pair ? "pair_" + std::to_string(found.pairs) : "group_" + std::to_string(made - found.pairs));
    t.label = pair ? "pair" : "group";
    for (std::size_t k = 0; k < ep.tracks.size(); ++k) {
      t.fragments.push_back(fragment_of(tracks[ep.tracks[k]], bounds[k].first, bounds[k].second, class_of, o));
    }
    t.constraints = closest_approaches(ep, tracks, bounds);
    t.preference = static_cast<double>(ep.tracks.size()) * o.preference_per_character;
    lib.types.push_back(std::move(t));
    count_by_size(found, ep.tracks.size());
  }
}

// Single-character pieces between boundary samples, spread over the data (construct.h step 7).
void add_single_patches(PatchLibrary& lib, const std::vector<Track>& tracks, const std::vector<int>& class_of, const RealPatchOptions& o) {
  struct Piece {
    std::size_t track, a, b;
  };
  std::vector<Piece> pieces;
  const auto length = static_cast<std::size_t>(std::lround(o.single_duration_s * o.sample_rate_hz));
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Track& tr = tracks[i];
    std::size_t a = nearest_boundary(tr, 1, 1, tr.size() - 2, class_of);
    while (a < tr.size() && a + length + 1 < tr.size()) {
      const std::size_t b = nearest_boundary(tr, a + length, a + length / 2, std::min(tr.size() - 2, a + 2 * length), class_of);
      if (b >= tr.size()) break;
      pieces.push_back({i, a, b});
      a = b + 1 < tr.size() - 1 ? nearest_boundary(tr, b + 1, b + 1, tr.size() - 2, class_of) : tr.size();
    }
  }
  const std::size_t keep = std::min(pieces.size(), o.max_single_patches);
  for (std::size_t k = 0; k < keep; ++k) {
    const Piece& pc = pieces[k * pieces.size() / keep];
    PatchType t;
    t.name = o.prefix + "single_" + std::to_string(k);
    t.label = "single";
    t.fragments.push_back(fragment_of(tracks[pc.track], pc.a, pc.b, class_of, o));
    t.preference = o.preference_per_character;
    lib.types.push_back(std::move(t));
  }
}

}  // namespace

std::vector<Track> resample(const CrowdMotion& m, const RealPatchOptions& o) {
  std::vector<Track> tracks;
  const double dt = 1.0 / o.sample_rate_hz;
  for (std::size_t a = 0; a < m.agent_count(); ++a) {
    Run run;
    for (std::size_t f = 0; f < m.frame_count(); ++f) {
      const bool gap = !m.present(f, a) || (!run.empty() && m.times[f] - run.back().first > o.max_gap_s);
      if (gap) {
        resample_run(a, run, dt, tracks);
        run.clear();
      }
      if (!m.present(f, a)) continue;
      const auto q = m.position(f, a);
      run.emplace_back(m.times[f], Eigen::Vector2d(q.x(), q.y()));
    }
    resample_run(a, run, dt, tracks);
  }
  for (Track& tr : tracks) fill_state(tr, o);
  return tracks;
}

PatchLibrary patches_from_trajectories(const CrowdMotion& motion, const RealPatchOptions& o, RealPatchReport* report) {
  validate(o);
  std::vector<Track> tracks = resample(motion, o);
  RealPatchReport found;
  std::vector<Episode> episodes = merge_events(detect_events(tracks, o), tracks, o);
  found.episodes = episodes.size();
  drop_too_large(episodes, o, found);
  const PoseGroups groups = cluster_poses(tracks, o);
  const GroupMask chosen = groups.samples.empty() ? 0 : choose_groups(episodes, tracks, groups.samples.size(), o);

  PatchLibrary lib;
  const std::vector<int> class_of = name_classes(lib, groups, chosen, o, found);
  add_episode_patches(lib, episodes, tracks, chosen, class_of, o, found);
  add_single_patches(lib, tracks, class_of, o);
  if (lib.types.empty()) {
    std::ostringstream m;
    m << "real patches: the trajectories give no patch (" << tracks.size() << " resampled spans, " << found.episodes
      << " episodes, none with boundaries in the chosen pose groups, and no span long enough for " << o.single_duration_s
      << " s pieces)";
    throw InputError(m.str());
  }
  normalise_frames(lib);
  lib.validate("real patches");
  if (report != nullptr) *report = found;
  return lib;
}

void merge_into(PatchLibrary& into, const PatchLibrary& more) {
  std::map<std::size_t, std::size_t> classes;
  for (std::size_t c = 0; c < more.pose_classes.size(); ++c) classes[c] = into.pose_class(more.pose_classes[c]);
  for (PatchType t : more.types) {
    if (std::any_of(into.types.begin(), into.types.end(), [&](const PatchType& x) { return x.name == t.name; })) {
      throw ConfigError("patch library: the type name '" + t.name + "' is used twice");
    }
    for (Fragment& f : t.fragments) {
      f.entry_class = classes[f.entry_class];
      f.exit_class = classes[f.exit_class];
    }
    into.types.push_back(std::move(t));
  }
}

}  // namespace throng::tiling
