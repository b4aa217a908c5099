// Slotted crowd files into one column per agent (crowd_file_slots.h; the rules are in crowd_file.h).
#include "crowd_file_slots.h"

#include "crowd_file_pose.h"

#include <throng/core/errors.h>
#include <throng/io/checked_numbers.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <unordered_map>
#include <utility>

namespace throng::detail {
namespace {

// The radius of an agent whose file does not list it (another program's), as the classic reader gives it.
constexpr double unlisted_radius = 0.25;

// The agents of a slotted file, in column order, and each id's column.
struct SlotAgents {
  std::vector<std::int64_t> ids;
  std::vector<double> radii;
  std::vector<std::int32_t> species;
  std::unordered_map<std::int64_t, std::uint64_t> column;
};

// What the agent columns of `frames` frames cost, charged on top of the slot arrays (both are held while the
// entries move): per frame and agent the arrays the file has (position 24 bytes, velocity 24, orientation 32,
// action 4); per agent its id, radius and species (20), its entry in the id → column index (about 48) and its
// latest frame and slot (16, for the one-slot-per-frame check).
struct ColumnCost {
  std::uint64_t frames = 0;
  std::uint64_t per_entry = 24;
  static constexpr std::uint64_t per_agent = 84;

  ColumnCost(const h5::Group& trajectory, std::uint64_t frame_count) : frames(frame_count) {
    if (trajectory.has("velocity/value")) per_entry += 24;
    if (trajectory.has("orientation/value")) per_entry += 32;
    if (trajectory.has("action/value")) per_entry += 4;
  }

  // UINT64_MAX when the estimate does not fit in 64 bits (refused as any estimate above the limit is).
  [[nodiscard]] std::uint64_t bytes(std::uint64_t agents) const {
    const auto entries = checked_product({frames, agents, per_entry});
    const auto total = entries ? checked_sum(*entries, checked_product(agents, per_agent).value_or(UINT64_MAX)) : std::nullopt;
    return total.value_or(UINT64_MAX);
  }
  // "600 frames × 3 agents × 60 bytes, ...": `at_least` while the agents are still being counted.
  [[nodiscard]] std::string detail(std::uint64_t agents, bool at_least) const {
    return std::to_string(frames) + " frames × " + (at_least ? "at least " : "") + std::to_string(agents) + " agents × " +
           std::to_string(per_entry) + " bytes, the agent columns built from the slots";
  }
};

// The agents /parameters/throng/agents lists (`agents`): id[A], radius[A], species[A] (optional, else 0), in that
// order. Their columns are charged from id's shape before anything is read: a file listing 10^9 agents is refused
// by its estimate. InputError for a length that differs from id's and for an id listed twice.
SlotAgents listed_agents(const h5::Group& agents, const h5::Group& trajectory, const ColumnCost& cost) {
  const std::vector<std::uint64_t> shape = agents.shape("id");
  if (shape.size() != 1) throw InputError(agents.where("id") + ": has rank " + std::to_string(shape.size()) + ", expected 1");
  const std::uint64_t A = shape[0];
  trajectory.budget().charge(cost.bytes(A), trajectory.where("id/value"), cost.detail(A, false));
  auto length_check = [&](const std::string& name, std::size_t size) {
    if (size != A) {
      throw InputError(agents.where(name) + ": has " + std::to_string(size) + " entries for " + std::to_string(A) +
                       " agents (agents/id)");
    }
  };
  SlotAgents out;
  out.ids = agents.read_int64("id", 1).values;
  out.radii = agents.read_doubles("radius", 1).values;
  length_check("radius", out.radii.size());
  if (agents.has("species")) {
    out.species = agents.read_int32("species", 1).values;
    length_check("species", out.species.size());
  } else {
    out.species.assign(A, 0);
  }
  out.column.reserve(A);
  for (std::uint64_t a = 0; a < A; ++a) {
    const auto [at, added] = out.column.emplace(out.ids[a], a);
    if (!added) {
      throw InputError(agents.where("id") + ": id " + std::to_string(out.ids[a]) + " is listed twice (entries " +
                       std::to_string(at->second) + " and " + std::to_string(a) + ")");
    }
  }
  return out;
}

// Another program's file: the distinct ids ≥ 0 of id/value in order of first appearance (frame by frame, slot by
// slot), radius 0.25 m, species the slot's (/particles/trajectory/species[S], else 0) where the agent first
// appears. Each new agent's column is checked against the budget before the agent is counted, so a file naming
// ever more ids is refused before its index outgrows the limit.
SlotAgents agents_by_appearance(const h5::Group& trajectory, const std::vector<std::int64_t>& per_frame_id,
                                std::uint64_t S, const ColumnCost& cost) {
  std::vector<std::int32_t> slot_species(S, 0);
  if (trajectory.has("species")) {
    slot_species = trajectory.read_int32("species", 1).values;
    if (slot_species.size() != S) {
      throw InputError(trajectory.where("species") + ": has " + std::to_string(slot_species.size()) + " entries for " +
                       std::to_string(S) + " slots");
    }
  }
  SlotAgents out;
  for (std::uint64_t i = 0; i < per_frame_id.size(); i += S) {
    for (std::uint64_t s = 0; s < S; ++s) {
      const std::int64_t id = per_frame_id[i + s];
      if (id < 0 || out.column.contains(id)) continue;
      const std::uint64_t A = out.ids.size() + 1;
      trajectory.budget().require(cost.bytes(A), trajectory.where("id/value"), cost.detail(A, true));
      out.column.emplace(id, out.ids.size());
      out.ids.push_back(id);
      out.species.push_back(slot_species[s]);
    }
  }
  out.radii.assign(out.ids.size(), unlisted_radius);
  trajectory.budget().charge(cost.bytes(out.ids.size()), trajectory.where("id/value"), cost.detail(out.ids.size(), false));
  return out;
}

// id/value turned, in place, into the agent column of each slot at each frame (−1 where empty). InputError naming
// id/value for an id `agents` does not list (with its frame and slot, worded as the classic reader's "column n
// holds id X at frame t": a classic file whose column changes id is slotted by the rule and ends here) and for an
// agent in two slots at one frame.
void ids_to_columns(const h5::Group& trajectory, const SlotAgents& agents, std::vector<std::int64_t>& per_frame_id,
                    std::uint64_t S) {
  const std::uint64_t T = S ? per_frame_id.size() / S : 0;
  // Per agent: 1 + the frame of its latest slot (0: none yet), and that slot.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> latest(agents.ids.size(), {0, 0});
  for (std::uint64_t t = 0; t < T; ++t) {
    for (std::uint64_t s = 0; s < S; ++s) {
      std::int64_t& entry = per_frame_id[t * S + s];
      if (entry < 0) {
        entry = -1;
        continue;
      }
      const auto at = agents.column.find(entry);
      if (at == agents.column.end()) {
        throw InputError(trajectory.where("id/value") + ": column " + std::to_string(s) + " holds id " +
                         std::to_string(entry) + " at frame " + std::to_string(t) +
                         ", an id /parameters/throng/agents/id does not list (this file's columns are slots reused "
                         "by several agents, and every agent in them must be listed)");
      }
      const std::uint64_t a = at->second;
      if (latest[a].first == t + 1) {
        throw InputError(trajectory.where("id/value") + ": agent " + std::to_string(entry) + " is in slots " +
                         std::to_string(latest[a].second) + " and " + std::to_string(s) + " at frame " +
                         std::to_string(t) + " (an agent holds one slot at a time)");
      }
      latest[a] = {t + 1, s};
      entry = static_cast<std::int64_t>(a);
    }
  }
}

// Empty slots' positions become NaN; a present slot's position must be finite (InputError naming the frame and
// the slot otherwise).
void mark_slot_presence(const h5::Group& trajectory, const std::vector<std::int64_t>& columns, std::uint64_t S,
                        const ColumnName& name, std::vector<double>& positions) {
  for (std::uint64_t i = 0; i < columns.size(); ++i) {
    double* p = positions.data() + 3 * i;
    if (columns[i] < 0) {
      p[0] = p[1] = p[2] = absent;
    } else if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) {
      const bool nan = std::isnan(p[0]) || std::isnan(p[1]) || std::isnan(p[2]);
      throw InputError(trajectory.where("position/value") + ": " + (nan ? "NaN" : "infinite") + " position for present " +
                       name(i / S, i % S) + " at frame " + std::to_string(i / S));
    }
  }
}

template <class T>
void copy_entry(const std::vector<T>& from, std::uint64_t i, std::vector<T>& to, std::uint64_t j, std::uint64_t width) {
  if (from.empty()) return;
  std::copy_n(from.begin() + static_cast<std::ptrdiff_t>(i * width), width, to.begin() + static_cast<std::ptrdiff_t>(j * width));
}

// Every present slot's entries moved to its agent's column; the columns start absent (NaN, action −1). The arrays
// the slots do not have stay empty.
CrowdMotion to_agent_columns(CrowdMotion& slots, const std::vector<std::int64_t>& columns, SlotAgents& agents) {
  const std::uint64_t T = slots.frame_count(), S = slots.agent_count(), A = agents.ids.size();
  CrowdMotion m;
  m.times = std::move(slots.times);
  m.ids = std::move(agents.ids);
  m.radii = std::move(agents.radii);
  m.species = std::move(agents.species);
  m.positions.assign(T * A * 3, absent);
  if (!slots.velocities.empty()) m.velocities.assign(T * A * 3, absent);
  if (!slots.orientations.empty()) m.orientations.assign(T * A * 4, absent);
  if (!slots.actions.empty()) m.actions.assign(T * A, -1);
  m.action_table = std::move(slots.action_table);
  for (std::uint64_t t = 0; t < T; ++t) {
    for (std::uint64_t s = 0; s < S; ++s) {
      const std::int64_t c = columns[t * S + s];
      if (c < 0) continue;
      const std::uint64_t from = t * S + s, to = t * A + static_cast<std::uint64_t>(c);
      copy_entry(slots.positions, from, m.positions, to, 3);
      copy_entry(slots.velocities, from, m.velocities, to, 3);
      copy_entry(slots.orientations, from, m.orientations, to, 4);
      copy_entry(slots.actions, from, m.actions, to, 1);
    }
  }
  return m;
}

}  // namespace

bool has_reused_slots(const std::vector<std::int64_t>& per_frame_id, std::uint64_t slots) {
  std::vector<std::int64_t> first(slots, -1);  // per slot: the first id ≥ 0 it holds
  for (std::uint64_t i = 0; i < per_frame_id.size(); i += slots) {
    for (std::uint64_t s = 0; s < slots; ++s) {
      const std::int64_t id = per_frame_id[i + s];
      if (id < 0) continue;
      if (first[s] < 0) first[s] = id;
      else if (first[s] != id) return true;
    }
  }
  return false;
}

CrowdMotion read_slotted_motion(const h5::Group& root, const h5::Group& trajectory, CrowdMotion slots,
                                std::vector<std::int64_t> per_frame_id, std::uint64_t slot_count) {
  const std::uint64_t T = slots.frame_count(), S = slot_count;
  const ColumnCost cost(trajectory, T);
  SlotAgents agents = root.has("parameters/throng/agents")
                          ? listed_agents(root.open_group("parameters/throng/agents"), trajectory, cost)
                          : agents_by_appearance(trajectory, per_frame_id, S, cost);
  std::vector<std::int64_t>& columns = per_frame_id;
  ids_to_columns(trajectory, agents, columns, S);

  slots.ids.assign(S, -1);  // a slot is no agent: the ids only give the motion its S columns
  const ColumnName name = [&](std::uint64_t t, std::uint64_t s) {
    return "agent " + std::to_string(agents.ids[static_cast<std::size_t>(columns[t * S + s])]) + " (slot " +
           std::to_string(s) + ")";
  };
  mark_slot_presence(trajectory, columns, S, name, slots.positions);
  if (trajectory.has("velocity/value")) {
    auto velocity = trajectory.read_doubles("velocity/value", 3);
    if (velocity.shape != std::vector<std::uint64_t>{T, S, 3}) {
      throw InputError(trajectory.where("velocity/value") + ": shape differs from position/value");
    }
    slots.velocities = std::move(velocity.values);
  }
  read_pose_elements(trajectory, slots, name);
  return to_agent_columns(slots, columns, agents);
}

}  // namespace throng::detail
