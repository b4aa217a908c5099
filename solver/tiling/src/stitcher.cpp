#include "stitcher.h"

#include "within_limits.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace throng::tiling {
namespace {

// An entry (side 0) or exit (side 1) of a fragment.
struct EndRef {
  FragmentRef fragment;
  int side = 0;
  friend bool operator==(const EndRef&, const EndRef&) = default;
};

// The paths an instance has in the attempt: its new ones when it is re-deformed, else the state's.
const std::vector<Path>& paths_of(const TilingState& state, const Attempt& attempt, std::uint32_t id) {
  if (id == state.next_id()) return attempt.change.paths;
  for (const auto& [mid, paths] : attempt.change.modified) {
    if (mid == id) return paths;
  }
  return state.at(id).paths;
}

// Builds the coupling rows of a joint solve (deformation.h) in terms of members and their fragments.
class RowBuilder {
 public:
  RowBuilder(JointProblem& problem, const std::vector<const PatchType*>& types, const Periods& periods)
      : problem_(problem), types_(types), periods_(periods) {}

  // Eq. 1–3 between the exit of (a, fa) and the entry of (b, fb): exit = entry + image ⊙ period.
  void join(std::uint32_t a, std::size_t fa, std::uint32_t b, std::size_t fb, const std::array<int, 3>& image) {
    const std::size_t n = last(a, fa);
    for (int c = 0; c < 2; ++c) {
      Row r;
      r.add(a, sx(a, fa, n) + c, 1.0);
      r.add(b, sx(b, fb, 0) + c, -1.0);
      r.value = image[static_cast<std::size_t>(c)] * periods_.p[static_cast<std::size_t>(c)];
      problem_.space_rows.push_back(r);
      Row tangent;
      tangent.add(a, sx(a, fa, n) + c, 1.0);
      tangent.add(a, sx(a, fa, n - 1) + c, -1.0);
      tangent.add(b, sx(b, fb, 1) + c, -1.0);
      tangent.add(b, sx(b, fb, 0) + c, 1.0);
      problem_.space_rows.push_back(tangent);
    }
    Row t;
    t.add(a, st(a, fa, n), 1.0);
    t.add(b, st(b, fb, 0), -1.0);
    t.value = image[2] * periods_.p[2];
    problem_.time_rows.push_back(t);
  }

  // The end (side 0 entry, 1 exit) of (m, f) held at a position, tangent and time.
  void pin(std::uint32_t m, std::size_t f, int side, const Eigen::Vector2d& position, const Eigen::Vector2d& tangent,
           double time) {
    const std::size_t end = side == 1 ? last(m, f) : 0;
    const std::size_t inner = side == 1 ? end - 1 : 1;
    for (int c = 0; c < 2; ++c) {
      Row r;
      r.add(m, sx(m, f, end) + c, 1.0);
      r.value = position[c];
      problem_.space_rows.push_back(r);
      // exit: p_N − p_{N−1} = tangent; entry: p_1 − p_0 = tangent.
      Row tr;
      tr.add(m, sx(m, f, side == 1 ? end : inner) + c, 1.0);
      tr.add(m, sx(m, f, side == 1 ? inner : end) + c, -1.0);
      tr.value = tangent[c];
      problem_.space_rows.push_back(tr);
    }
    Row t;
    t.add(m, st(m, f, end), 1.0);
    t.value = time;
    problem_.time_rows.push_back(t);
  }

 private:
  [[nodiscard]] std::size_t last(std::uint32_t m, std::size_t f) const { return types_[m]->fragments[f].sample_count() - 1; }
  [[nodiscard]] Eigen::Index sx(std::uint32_t m, std::size_t f, std::size_t s) const {
    return 2 * problem_.members[m].system->sample(f, s);
  }
  [[nodiscard]] Eigen::Index st(std::uint32_t m, std::size_t f, std::size_t s) const {
    return problem_.members[m].system->sample(f, s);
  }
  JointProblem& problem_;
  const std::vector<const PatchType*>& types_;
  const Periods& periods_;
};

Eigen::Vector2d exit_tangent(const Path& p) { return p.positions.back() - p.positions[p.positions.size() - 2]; }
Eigen::Vector2d entry_tangent(const Path& p) { return p.positions[1] - p.positions[0]; }

}  // namespace

Attempt Stitcher::stitch(const Proposal& proposal) {
  Attempt attempt;
  Change& change = attempt.change;
  change.type = proposal.type;
  change.transform = proposal.transform;
  change.keyframed = proposal.keyframed;
  const PatchType& type = problem_.library.types[proposal.type];
  change.paths = place(type, proposal.transform);

  // Candidate stitches of every free end of the new instance, best first.
  struct Candidate {
    double score;
    std::uint32_t fragment;
    int side;
    EndMatch match;
  };
  std::vector<Candidate> candidates;
  for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
    if (!type.fragments[f].is_character()) continue;
    for (int side = 0; side < 2; ++side) {
      if (proposal.forced && proposal.forced->new_fragment == f && proposal.forced->new_is_exit == (side == 1)) continue;
      matches_.clear();
      state_.dangling_ends().matches(problem_.end_point(proposal.type, change.paths, f, side == 1), side == 0, matches_);
      for (const EndMatch& m : matches_) {
        if (proposal.forced && proposal.forced->existing == m.end && proposal.forced->new_is_exit == (side == 1)) continue;
        candidates.push_back({m.score, f, side, m});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.score, a.fragment, a.side, a.match.end) < std::tie(b.score, b.fragment, b.side, b.match.end);
  });
  std::vector<EndRef> used_new, used_existing;
  if (proposal.forced) {
    change.links.push_back(*proposal.forced);
    used_new.push_back({{0, proposal.forced->new_fragment}, proposal.forced->new_is_exit ? 1 : 0});
    used_existing.push_back({proposal.forced->existing, proposal.forced->new_is_exit ? 0 : 1});
  }
  for (const Candidate& c : candidates) {
    const EndRef mine{{0, c.fragment}, c.side}, theirs{c.match.end, 1 - c.side};
    if (std::find(used_new.begin(), used_new.end(), mine) != used_new.end()) continue;
    if (std::find(used_existing.begin(), used_existing.end(), theirs) != used_existing.end()) continue;
    used_new.push_back(mine);
    used_existing.push_back(theirs);
    // The match's image takes the existing end to the new one; a connection's takes the entry to the exit.
    std::array<int, 3> image = c.match.image;
    if (c.side == 0) image = {-image[0], -image[1], -image[2]};
    change.links.push_back({c.fragment, c.side == 1, c.match.end, image});
  }

  attempt.feasible = change.links.empty() || deform(proposal, attempt);
  if (!attempt.feasible) return attempt;

  // What the counts of Eq. 6 become.
  const auto links = static_cast<long>(change.links.size());
  long dangling = -links;
  for (const auto& [mid, paths] : change.modified) {
    const LiveInstance& x = state_.at(mid);
    for (std::uint32_t f = 0; f < x.ends.size(); ++f) {
      for (int side = 0; side < 2; ++side) {
        const EndStatus before = x.ends[f][static_cast<std::size_t>(side)].status;
        if (before != EndStatus::dangling && before != EndStatus::free) continue;
        if (std::find(used_existing.begin(), used_existing.end(), EndRef{{mid, f}, side}) != used_existing.end()) continue;
        const EndStatus after = state_.classify(problem_.end_point(x.type, paths, f, side == 1), side == 1);
        dangling += (after == EndStatus::dangling) - (before == EndStatus::dangling);
      }
    }
  }
  for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
    if (!type.fragments[f].is_character()) continue;
    for (int side = 0; side < 2; ++side) {
      if (std::find(used_new.begin(), used_new.end(), EndRef{{0, f}, side}) != used_new.end()) continue;
      dangling += state_.classify(problem_.end_point(proposal.type, change.paths, f, side == 1), side == 1) == EndStatus::dangling;
    }
  }
  attempt.delta_dangling = dangling;
  attempt.delta_connected = 2 * links;
  attempt.delta_characters = static_cast<long>(type.character_count()) - links;
  return attempt;
}

bool Stitcher::deform(const Proposal& proposal, Attempt& attempt) {
  Change& change = attempt.change;
  const PatchType& type = problem_.library.types[proposal.type];

  // Members: the new instance, then (the paper) the instances it is stitched to, unless pinned (keyframed or fixed).
  std::vector<std::uint32_t> ids{state_.next_id()};
  std::vector<const PatchType*> types{&type};
  JointProblem jp;
  jp.members.push_back({&problem_.systems[proposal.type], problem_.systems[proposal.type].space_anchor(change.paths),
                        problem_.systems[proposal.type].time_anchor(change.paths), proposal.transform.angle});
  const auto member_of = [&](std::uint32_t id) -> long {
    const auto it = std::find(ids.begin(), ids.end(), id);
    return it == ids.end() ? -1 : it - ids.begin();
  };
  if (problem_.options.deformation.deform_neighbours) {
    for (const NewLink& link : change.links) {
      const std::uint32_t x = link.existing.instance;
      const LiveInstance& inst = state_.at(x);
      if (inst.pinned() || member_of(x) >= 0) continue;
      ids.push_back(x);
      types.push_back(&problem_.library.types[inst.type]);
      const PatchSystem& sys = problem_.systems[inst.type];
      jp.members.push_back({&sys, sys.space_anchor(inst.paths), sys.time_anchor(inst.paths), inst.transform.angle});
    }
  }

  RowBuilder rows(jp, types, problem_.periods);
  const Eigen::Vector2d period_xy(problem_.periods.p[0], problem_.periods.p[1]);
  for (const NewLink& link : change.links) {
    const long m = member_of(link.existing.instance);
    const std::size_t g = link.existing.fragment;
    if (m >= 0) {
      if (link.new_is_exit) rows.join(0, link.new_fragment, static_cast<std::uint32_t>(m), g, link.image);
      else rows.join(static_cast<std::uint32_t>(m), g, 0, link.new_fragment, link.image);
      continue;
    }
    const Path& p = state_.at(link.existing.instance).paths[g];
    const Eigen::Vector2d shift(link.image[0] * period_xy.x(), link.image[1] * period_xy.y());
    const double tshift = link.image[2] * problem_.periods.p[2];
    if (link.new_is_exit) {  // the existing end is an entry: exit = entry + shift
      rows.pin(0, link.new_fragment, 1, p.positions.front() + shift, entry_tangent(p), p.times.front() + tshift);
    } else {  // the existing end is an exit: entry = exit − shift
      rows.pin(0, link.new_fragment, 0, p.positions.back() - shift, exit_tangent(p), p.times.back() - tshift);
    }
  }
  for (std::uint32_t m = 1; m < ids.size(); ++m) {
    const LiveInstance& x = state_.at(ids[m]);
    for (std::uint32_t f = 0; f < x.ends.size(); ++f) {
      for (int side = 0; side < 2; ++side) {
        const EndLink& e = x.ends[f][static_cast<std::size_t>(side)];
        if (e.status != EndStatus::connected) continue;
        const long other = member_of(e.partner.instance);
        if (other >= 0) {
          if (side == 1) rows.join(m, f, static_cast<std::uint32_t>(other), e.partner.fragment, e.image);
          continue;
        }
        const Path& p = x.paths[f];
        if (side == 1) rows.pin(m, f, 1, p.positions.back(), exit_tangent(p), p.times.back());
        else rows.pin(m, f, 0, p.positions.front(), entry_tangent(p), p.times.front());
      }
    }
  }

  const JointSolution solution = solve_joint(jp);
  if (!(solution.max_residual <= problem_.options.deformation.constraint_tolerance)) return false;
  change.paths = paths_from(type, problem_.systems[proposal.type], proposal.transform.angle, solution.space[0], solution.time[0]);
  for (std::uint32_t m = 1; m < ids.size(); ++m) {
    const LiveInstance& x = state_.at(ids[m]);
    change.modified.emplace_back(ids[m], paths_from(problem_.library.types[x.type], problem_.systems[x.type],
                                                    x.transform.angle, solution.space[m], solution.time[m]));
  }
  return true;
}

bool Stitcher::entries_reachable(const Attempt& attempt) const {
  if (!std::isfinite(problem_.freeze)) return true;
  const Change& change = attempt.change;
  const PatchType& type = problem_.library.types[change.type];
  for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
    if (!type.fragments[f].is_character()) continue;
    const bool linked = std::any_of(change.links.begin(), change.links.end(),
                                    [&](const NewLink& l) { return l.new_fragment == f && !l.new_is_exit; });
    if (linked) continue;
    const EndPoint e = problem_.end_point(change.type, change.paths, f, false);
    if (state_.classify(e, false) != EndStatus::dangling) continue;
    const Eigen::Vector2d back = -Eigen::Vector2d(std::cos(e.heading), std::sin(e.heading));
    // The last patch in (at most the longest) must start after the freeze time too.
    const double in = time_to_side(problem_.region, e.position, back, problem_.options.density.projection_speed_mps);
    if (in + 2 * problem_.max_half_duration_s > e.time - problem_.freeze) {
      return false;
    }
  }
  return true;
}

void Stitcher::placement_presence(std::uint32_t type, const std::vector<Path>& paths, Presence::Delta& delta) const {
  const PatchType& t = problem_.library.types[type];
  for (std::size_t f = 0; f < t.fragments.size(); ++f) {
    if (t.fragments[f].is_character()) state_.presence().path(paths[f], 1.0, delta);
  }
}

void Stitcher::presence_delta(const Attempt& attempt, Presence::Delta& delta) const {
  const Presence& presence = state_.presence();
  if (!presence.enabled()) return;
  const Change& change = attempt.change;
  // Adds the presence of an instance of `type` with `paths` whose ends have `status(f, side)`.
  const auto add = [&](std::uint32_t type, const std::vector<Path>& paths, const auto& status) {
    const PatchType& t = problem_.library.types[type];
    for (std::uint32_t f = 0; f < t.fragments.size(); ++f) {
      if (!t.fragments[f].is_character()) continue;
      presence.path(paths[f], 1.0, delta);
      for (int side = 0; side < 2; ++side) {
        const EndStatus s = status(f, side);
        if (s != EndStatus::dangling && s != EndStatus::free) continue;
        const EndPoint e = problem_.end_point(type, paths, f, side == 1);
        presence.projection(e.position, e.heading, e.time, side == 1, s == EndStatus::dangling, 1.0, delta);
      }
    }
  };
  // The existing instances the change touches: linked to, or re-deformed.
  std::vector<std::uint32_t> touched;
  for (const NewLink& link : change.links) touched.push_back(link.existing.instance);
  for (const auto& m : change.modified) touched.push_back(m.first);
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  for (std::uint32_t id : touched) {
    state_.presence_of(id, -1.0, delta);
    const LiveInstance& x = state_.at(id);
    const std::vector<Path>& paths = paths_of(state_, attempt, id);
    const bool moved = &paths != &x.paths;
    add(x.type, paths, [&](std::uint32_t f, int side) {
      for (const NewLink& link : change.links) {
        if (link.existing == FragmentRef{id, f} && (link.new_is_exit ? 0 : 1) == side) return EndStatus::connected;
      }
      const EndStatus before = x.ends[f][static_cast<std::size_t>(side)].status;
      if (!moved || (before != EndStatus::dangling && before != EndStatus::free)) return before;
      return state_.classify(problem_.end_point(x.type, paths, f, side == 1), side == 1);
    });
  }
  add(change.type, change.paths, [&](std::uint32_t f, int side) {
    for (const NewLink& link : change.links) {
      if (link.new_fragment == f && link.new_is_exit == (side == 1)) return EndStatus::connected;
    }
    return state_.classify(problem_.end_point(change.type, change.paths, f, side == 1), side == 1);
  });
}

bool Stitcher::connected(FragmentRef a, FragmentRef b, const Attempt& attempt) const {
  const std::uint32_t fresh = state_.next_id();
  for (const NewLink& link : attempt.change.links) {
    const FragmentRef n{fresh, link.new_fragment};
    if ((a == n && b == link.existing) || (b == n && a == link.existing)) return true;
  }
  for (const FragmentRef& r : {a, b}) {
    if (r.instance == fresh) continue;
    const FragmentRef other = r == a ? b : a;
    for (const EndLink& e : state_.at(r.instance).ends[r.fragment]) {
      if (e.status == EndStatus::connected && e.partner == other) return true;
    }
  }
  return false;
}

bool Stitcher::hits_obstacle(const Fragment& fragment, const Path& path) const {
  const auto& obstacles = problem_.environment.scene.obstacles;
  if (obstacles.empty()) return false;
  const Region& region = problem_.region;
  const double r = fragment.radius_m;
  Eigen::AlignedBox2d box;
  for (const Eigen::Vector2d& p : path.positions) box.extend(p);
  const auto test_point = [&](const Eigen::Vector2d& p, double t) {
    if (region.periodic[2]) t = region.t0 + std::fmod(std::fmod(t - region.t0, problem_.periods.p[2]) + problem_.periods.p[2], problem_.periods.p[2]);
    for (int ix = -1; ix <= 1; ++ix) {
      if (ix != 0 && !region.periodic[0]) continue;
      for (int iy = -1; iy <= 1; ++iy) {
        if (iy != 0 && !region.periodic[1]) continue;
        const Eigen::Vector2d q = p + Eigen::Vector2d(ix * problem_.periods.p[0], iy * problem_.periods.p[1]);
        for (std::size_t k = 0; k < obstacles.size(); ++k) {
          if (problem_.obstacle_bounds[k].exteriorDistance(q) >= r) continue;
          if (distance_to(obstacles[k], q, t).signed_distance < r) return true;
        }
      }
    }
    return false;
  };
  // Quick rejection: no image of the path's box comes near any obstacle.
  bool near = false;
  for (const Eigen::AlignedBox2d& ob : problem_.obstacle_bounds) {
    for (int ix = -1; ix <= 1 && !near; ++ix) {
      for (int iy = -1; iy <= 1 && !near; ++iy) {
        if ((ix != 0 && !region.periodic[0]) || (iy != 0 && !region.periodic[1])) continue;
        const Eigen::Vector2d s(ix * problem_.periods.p[0], iy * problem_.periods.p[1]);
        Eigen::AlignedBox2d moved(box.min() + s, box.max() + s);
        moved.min().array() -= r;
        moved.max().array() += r;
        near = moved.intersects(ob);
      }
    }
  }
  if (!near) return false;
  const double step_m = problem_.options.obstacle_step_m, step_s = problem_.options.obstacle_step_s;
  if (test_point(path.positions[0], path.times[0])) return true;
  for (std::size_t s = 0; s + 1 < path.times.size(); ++s) {
    const Eigen::Vector2d a = path.positions[s], b = path.positions[s + 1];
    const double ta = path.times[s], tb = path.times[s + 1];
    const auto n = static_cast<int>(std::max({1.0, std::ceil((b - a).norm() / step_m), std::ceil((tb - ta) / step_s)}));
    for (int j = 1; j <= n; ++j) {
      const double u = static_cast<double>(j) / n;
      if (test_point(a + u * (b - a), ta + u * (tb - ta))) return true;
    }
  }
  return false;
}

bool Stitcher::valid(const Attempt& attempt) {
  const Change& change = attempt.change;
  const DeformationLimits& limits = problem_.options.limits;
  const std::uint32_t fresh = state_.next_id();

  // The instances whose paths the attempt sets: the new one, then the re-deformed neighbours.
  struct Tested {
    std::uint32_t id;
    const PatchType* type;
    const std::vector<Path>* paths;
  };
  std::vector<Tested> tested{{fresh, &problem_.library.types[change.type], &change.paths}};
  for (const auto& [mid, paths] : change.modified) tested.push_back({mid, &problem_.library.types[state_.at(mid).type], &paths});

  // A window may not change what lies before its freeze time (problem.h): the past is already final.
  if (std::isfinite(problem_.freeze)) {
    for (const Tested& t : tested) {
      for (const Path& p : *t.paths) {
        if (p.times.front() < problem_.freeze) return false;
      }
    }
  }

  // Deformation within limits (the new instance only deforms when stitched).
  for (const Tested& t : tested) {
    if (t.id == fresh && change.links.empty()) continue;
    for (std::size_t f = 0; f < t.type->fragments.size(); ++f) {
      if (!within_limits(t.type->fragments[f], (*t.paths)[f], limits, problem_.max_speed_m_s)) return false;
    }
  }

  // Headings matched at every connection of a deformed instance (Eq. 2 matches the tangents; a standing
  // character's heading does not follow from its path).
  const auto heading = [&](FragmentRef r, bool exit) {
    const Path& p = paths_of(state_, attempt, r.instance)[r.fragment];
    return exit ? p.headings.back() : p.headings.front();
  };
  const double max_angle = problem_.options.match.angle_rad;
  for (const NewLink& link : change.links) {
    const double a = heading({fresh, link.new_fragment}, link.new_is_exit), b = heading(link.existing, !link.new_is_exit);
    if (std::abs(wrap_angle(a - b)) > max_angle) return false;
  }
  for (const auto& [mid, paths] : change.modified) {
    const LiveInstance& x = state_.at(mid);
    for (std::uint32_t f = 0; f < x.ends.size(); ++f) {
      for (int side = 0; side < 2; ++side) {
        const EndLink& e = x.ends[f][static_cast<std::size_t>(side)];
        if (e.status != EndStatus::connected || e.partner.instance == gone) continue;
        if (std::abs(wrap_angle(heading({mid, f}, side == 1) - heading(e.partner, side == 0))) > max_angle) return false;
      }
    }
  }

  // Obstacles.
  for (const Tested& t : tested) {
    for (std::size_t f = 0; f < t.type->fragments.size(); ++f) {
      if (hits_obstacle(t.type->fragments[f], (*t.paths)[f])) return false;
    }
  }

  // Other instances, through the index (the re-deformed ones are tested below with their new paths).
  const auto is_tested = [&](std::uint32_t id) {
    return std::any_of(tested.begin(), tested.end(), [&](const Tested& t) { return t.id == id; });
  };
  for (const Tested& t : tested) {
    for (std::uint32_t f = 0; f < t.type->fragments.size(); ++f) {
      const Path& p = (*t.paths)[f];
      const double r = t.type->fragments[f].radius_m;
      const FragmentRef me{t.id, f};
      const auto skip = [&](std::uint32_t instance, std::uint32_t fragment) {
        return is_tested(instance) || connected(me, {instance, fragment}, attempt);
      };
      for (std::size_t s = 0; s + 1 < p.times.size(); ++s) {
        if (state_.segments().collides({p.positions[s], p.positions[s + 1], p.times[s], p.times[s + 1], r}, skip)) return false;
      }
    }
  }
  // Within each deformed instance: the pairs its patch keeps clear stay clear (props and characters alike).
  for (const Tested& t : tested) {
    if (t.id == fresh && change.links.empty()) continue;  // placed rigidly: as clear as the patch itself
    const std::uint32_t type = t.id == fresh ? change.type : state_.at(t.id).type;
    for (const auto& [fa, fb] : problem_.clear_pairs[type]) {
      const Path& a = (*t.paths)[fa];
      const Path& b = (*t.paths)[fb];
      const double ra = t.type->fragments[fa].radius_m, rb = t.type->fragments[fb].radius_m;
      for (std::size_t s = 0; s + 1 < a.times.size(); ++s) {
        const MovingDisc q{a.positions[s], a.positions[s + 1], a.times[s], a.times[s + 1], ra};
        for (std::size_t u = 0; u + 1 < b.times.size(); ++u) {
          if (b.times[u] > q.tb || b.times[u + 1] < q.ta) continue;
          if (closest_approach(q, {b.positions[u], b.positions[u + 1], b.times[u], b.times[u + 1], rb}) < ra + rb) return false;
        }
      }
    }
  }
  // The tested instances among themselves.
  for (std::size_t i = 0; i < tested.size(); ++i) {
    for (std::size_t j = i + 1; j < tested.size(); ++j) {
      for (std::uint32_t fi = 0; fi < tested[i].type->fragments.size(); ++fi) {
        for (std::uint32_t fj = 0; fj < tested[j].type->fragments.size(); ++fj) {
          if (connected({tested[i].id, fi}, {tested[j].id, fj}, attempt)) continue;
          const Path& a = (*tested[i].paths)[fi];
          const Path& b = (*tested[j].paths)[fj];
          const double ra = tested[i].type->fragments[fi].radius_m, rb = tested[j].type->fragments[fj].radius_m;
          for (std::size_t s = 0; s + 1 < a.times.size(); ++s) {
            const MovingDisc q{a.positions[s], a.positions[s + 1], a.times[s], a.times[s + 1], ra};
            for (std::size_t u = 0; u + 1 < b.times.size(); ++u) {
              const MovingDisc d = nearest_image_of({b.positions[u], b.positions[u + 1], b.times[u], b.times[u + 1], rb}, q,
                                                    problem_.periods);
              if (d.tb < q.ta || d.ta > q.tb) continue;
              if (closest_approach(q, d) < ra + rb) return false;
            }
          }
        }
      }
    }
  }
  return true;
}

}  // namespace throng::tiling
