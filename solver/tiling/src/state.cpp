#include "state.h"

#include <algorithm>
#include <cassert>

namespace throng::tiling {

TilingState::TilingState(const Problem& problem)
    : problem_(problem),
      segments_(problem.index_region, problem.options.index, index_margin_m(problem.options, problem.max_extent_m),
                index_margin_s(problem.options, problem.max_half_duration_s)),
      ends_(problem.index_region, problem.options.match),
      presence_(problem.environment, problem.options.density, problem.presence_span) {}

void TilingState::presence_of(std::uint32_t id, double sign, Presence::Delta& delta) const {
  if (!presence_.enabled()) return;
  const LiveInstance& inst = instances_[id];
  const PatchType& type = problem_.library.types[inst.type];
  for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
    if (!type.fragments[f].is_character()) continue;
    presence_.path(inst.paths[f], sign, delta);
    for (int side = 0; side < 2; ++side) {
      const EndStatus status = inst.ends[f][static_cast<std::size_t>(side)].status;
      if (status != EndStatus::dangling && status != EndStatus::free) continue;
      const EndPoint e = problem_.end_point(inst.type, inst.paths, f, side == 1);
      presence_.projection(e.position, e.heading, e.time, side == 1, status == EndStatus::dangling, sign, delta);
    }
  }
}

void TilingState::track_presence(std::uint32_t id, double sign) {
  if (!presence_.enabled()) return;
  scratch_.clear();
  presence_of(id, sign, scratch_);
  presence_.apply(scratch_);
}

std::uint32_t TilingState::next_id() const noexcept {
  return free_ids_.empty() ? static_cast<std::uint32_t>(instances_.size()) : free_ids_.back();
}

double TilingState::energy(double dangling, double connected) const noexcept {
  return (dangling + problem_.options.annealing.alpha) / std::max(connected + dangling, 1.0);
}

EndStatus TilingState::classify(const EndPoint& end, bool is_exit) const {
  return end_needs_no_partner(problem_.environment, end.position, end.time, is_exit) ? EndStatus::free : EndStatus::dangling;
}

void TilingState::index_ends(std::uint32_t id, bool insert) {
  const LiveInstance& inst = instances_[id];
  for (std::uint32_t f = 0; f < inst.ends.size(); ++f) {
    for (int side = 0; side < 2; ++side) {
      if (inst.ends[f][static_cast<std::size_t>(side)].status != EndStatus::dangling) continue;
      const EndPoint e = problem_.end_point(inst.type, inst.paths, f, side == 1);
      if (insert) {
        ends_.insert({id, f}, side == 1, e);
        ++dangling_;
      } else {
        ends_.remove({id, f}, side == 1, e);
        --dangling_;
      }
    }
  }
}

void TilingState::set_unconnected(std::uint32_t id, std::uint32_t fragment, int side) {
  LiveInstance& inst = instances_[id];
  EndLink& e = inst.ends[fragment][static_cast<std::size_t>(side)];
  const EndPoint p = problem_.end_point(inst.type, inst.paths, fragment, side == 1);
  e = EndLink{classify(p, side == 1), {}, {0, 0, 0}};
  if (e.status == EndStatus::dangling) {
    ends_.insert({id, fragment}, side == 1, p);
    ++dangling_;
  }
}

std::uint32_t TilingState::apply(const Change& change) {
  const std::uint32_t id = next_id();
  if (id == instances_.size()) {
    instances_.emplace_back();
  } else {
    free_ids_.pop_back();
  }
  const PatchType& type = problem_.library.types[change.type];
  // The instances the change touches leave the presence as they were and come back as they become.
  std::vector<std::uint32_t> touched;
  if (presence_.enabled()) {
    for (const NewLink& link : change.links) touched.push_back(link.existing.instance);
    for (const auto& m : change.modified) touched.push_back(m.first);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    for (std::uint32_t t : touched) track_presence(t, -1.0);
  }

  // 1. The existing ends the new instance is stitched to stop dangling.
  for (const NewLink& link : change.links) {
    LiveInstance& x = instances_[link.existing.instance];
    const int side = link.new_is_exit ? 0 : 1;
    EndLink& e = x.ends[link.existing.fragment][static_cast<std::size_t>(side)];
    assert(e.status == EndStatus::dangling);
    ends_.remove(link.existing, side == 1, problem_.end_point(x.type, x.paths, link.existing.fragment, side == 1));
    --dangling_;
    e = EndLink{EndStatus::connected, {id, link.new_fragment}, link.image};
  }
  // 2. Re-deformed neighbours: new paths in the index, their unconnected ends re-classified.
  for (const auto& [mid, paths] : change.modified) {
    LiveInstance& x = instances_[mid];
    const PatchType& xt = problem_.library.types[x.type];
    index_ends(mid, false);
    segments_.remove(mid, x.paths, xt);
    x.paths = paths;
    segments_.insert(mid, xt, x.paths);
    for (std::uint32_t f = 0; f < x.ends.size(); ++f) {
      for (int side = 0; side < 2; ++side) {
        EndLink& e = x.ends[f][static_cast<std::size_t>(side)];
        if (e.status == EndStatus::dangling || e.status == EndStatus::free) {
          e.status = classify(problem_.end_point(x.type, x.paths, f, side == 1), side == 1);
        }
      }
    }
    index_ends(mid, true);
  }
  // 3. The new instance.
  LiveInstance& inst = instances_[id];
  inst = LiveInstance{true, change.type, change.transform, change.keyframed, false, change.paths, {}};
  inst.ends.resize(type.fragments.size());
  for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
    if (!type.fragments[f].is_character()) continue;
    ++character_fragments_;
    for (int side = 0; side < 2; ++side) {
      inst.ends[f][static_cast<std::size_t>(side)].status =
          classify(problem_.end_point(change.type, inst.paths, f, side == 1), side == 1);
    }
  }
  for (const NewLink& link : change.links) {
    inst.ends[link.new_fragment][link.new_is_exit ? 1 : 0] = EndLink{EndStatus::connected, link.existing, link.image};
  }
  segments_.insert(id, type, inst.paths);
  index_ends(id, true);
  connections_ += change.links.size();
  ++live_;
  for (std::uint32_t t : touched) track_presence(t, 1.0);
  track_presence(id, 1.0);
  return id;
}

void TilingState::remove(std::uint32_t id) {
  LiveInstance& inst = instances_[id];
  assert(inst.alive && !inst.fixed);
  const PatchType& type = problem_.library.types[inst.type];
  track_presence(id, -1.0);
  index_ends(id, false);
  for (std::uint32_t f = 0; f < inst.ends.size(); ++f) {
    if (!type.fragments[f].is_character()) continue;
    --character_fragments_;
    for (int side = 0; side < 2; ++side) {
      const EndLink e = inst.ends[f][static_cast<std::size_t>(side)];
      if (e.status != EndStatus::connected) continue;
      --connections_;
      if (e.partner.instance == gone) continue;
      track_presence(e.partner.instance, -1.0);
      set_unconnected(e.partner.instance, e.partner.fragment, 1 - side);
      track_presence(e.partner.instance, 1.0);
    }
  }
  segments_.remove(id, inst.paths, type);
  inst = LiveInstance{};
  free_ids_.push_back(id);
  --live_;
}

void TilingState::restore(std::vector<LiveInstance> instances) {
  assert(live_ == 0 && instances_.empty());
  instances_ = std::move(instances);
  free_ids_.clear();
  dangling_ = connections_ = character_fragments_ = live_ = 0;
  for (std::uint32_t id = 0; id < instances_.size(); ++id) {
    LiveInstance& inst = instances_[id];
    if (!inst.alive) {
      free_ids_.push_back(id);
      continue;
    }
    const PatchType& type = problem_.library.types[inst.type];
    for (std::uint32_t f = 0; f < type.fragments.size(); ++f) {
      if (!type.fragments[f].is_character()) continue;
      ++character_fragments_;
      for (int side = 0; side < 2; ++side) {
        EndLink& e = inst.ends[f][static_cast<std::size_t>(side)];
        if (e.status == EndStatus::connected) {
          // Each connection once: at its exit, or at an entry whose exit is gone.
          if (side == 1 || e.partner.instance == gone) ++connections_;
          continue;
        }
        e = EndLink{classify(problem_.end_point(inst.type, inst.paths, f, side == 1), side == 1), {}, {0, 0, 0}};
      }
    }
    segments_.insert(id, type, inst.paths);
    index_ends(id, true);
    ++live_;
    track_presence(id, 1.0);
  }
  // Free ids are reused last-freed first (next_id): the lowest id first.
  std::reverse(free_ids_.begin(), free_ids_.end());
}

Tiling TilingState::snapshot() const {
  Tiling t;
  std::vector<std::uint32_t> renumber(instances_.size(), 0);
  for (std::uint32_t id = 0; id < instances_.size(); ++id) {
    const LiveInstance& inst = instances_[id];
    if (!inst.alive) continue;
    renumber[id] = static_cast<std::uint32_t>(t.instances.size());
    t.instances.push_back(Instance{inst.type, inst.transform, inst.keyframed, inst.paths});
  }
  for (std::uint32_t id = 0; id < instances_.size(); ++id) {
    const LiveInstance& inst = instances_[id];
    if (!inst.alive) continue;
    for (std::uint32_t f = 0; f < inst.ends.size(); ++f) {
      const EndLink& e = inst.ends[f][1];
      if (e.status != EndStatus::connected || e.partner.instance == gone) continue;
      t.connections.push_back(Connection{{renumber[id], f}, {renumber[e.partner.instance], e.partner.fragment}, e.image});
    }
  }
  return t;
}

}  // namespace throng::tiling
