// Crowd files whose columns are reused slots (H5MD's variable particle set, as a windowed `throng tile` writes
// them): read into one column per agent exactly, the same crowd as the classic layout gives, another program's
// slotted file read by first appearance, and every refusal naming what is wrong.
#include "crowd_fixtures.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/io/crowd_file.h>
#include <throng/io/hdf5.h>

#include <catch2/catch.hpp>
#include "check_throws.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace throng;
using Catch::Matchers::Contains;

namespace {

const double nan_value = std::numeric_limits<double>::quiet_NaN();

// Which agent each slot holds at each frame (−1: empty), frames by slots.
using SlotLayout = std::vector<std::vector<std::int64_t>>;

// 5 frames, 2 slots, 3 agents: agent 0 holds slot 0 for frames 0–1, slot 0 is empty at frame 2 and agent 2 takes
// it for frames 3–4; agent 1 holds slot 1 for frames 0–3.
const SlotLayout reused_layout{{0, 1}, {0, 1}, {-1, 1}, {2, 1}, {2, -1}};
const std::vector<double> frame_times{0.0, 0.5, 1.25, 2.0, 3.5};

// Each agent's motion, a function of its id and the frame, so that tests know every value.
Eigen::Vector3d place(std::int64_t agent, std::size_t t) { return {static_cast<double>(agent) + 0.1 * t, 2.0 * agent - 0.05 * t, 0.0}; }
Eigen::Vector3d speed(std::int64_t agent, std::size_t t) { return {0.2 + agent, -0.1 * t, 0.0}; }
Eigen::Quaterniond facing(std::int64_t agent, std::size_t t) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * t + agent, Eigen::Vector3d::UnitZ()));
}
std::int32_t doing(std::int64_t agent, std::size_t t) { return static_cast<std::int32_t>((t + agent) % 3); }

// A slotted crowd file laid out as the streaming writer lays it out, written by hand; tests change a field
// (a defect) before write().
struct SlottedFile {
  std::vector<double> times;
  std::uint64_t slots = 0;
  std::vector<std::int64_t> id;             // [T][S], −1 where empty
  std::vector<double> position;             // [T][S][3], NaN where empty
  std::vector<double> velocity;             // [T][S][3] or empty (no element)
  std::vector<double> orientation;          // [T][S][4] or empty
  std::vector<std::int32_t> action;         // [T][S] or empty; names walk, stand, run
  std::vector<std::int32_t> slot_species;   // [S] or empty
  bool throng_parameters = true;            // /parameters/throng with agents (else: another program's file)
  std::vector<std::int64_t> agent_id;
  std::vector<double> agent_radius;
  std::vector<std::int32_t> agent_species;  // empty: not written
  bool formation_edges = false;

  std::uint64_t frames() const { return times.size(); }

  void write(const std::filesystem::path& path) const {
    const std::uint64_t T = frames(), S = slots;
    h5::File f = h5::File::create(path);
    {
      const h5::Group root = f.root();
      root.create_group("h5md").set_attribute("version", std::vector<std::int32_t>{1, 1});
      const h5::Group traj = root.create_group("particles").create_group("trajectory");
      const h5::Group pos = traj.create_group("position");
      pos.write("value", position, {T, S, 3}, {true, 2});
      pos.write("time", times, {T});
      std::vector<std::int64_t> step(T);
      for (std::uint64_t t = 0; t < T; ++t) step[t] = static_cast<std::int64_t>(t);
      pos.write("step", step, {T});
      auto element = [&](const std::string& name) {
        h5::Group g = traj.create_group(name);
        g.link("step", "/particles/trajectory/position/step");
        g.link("time", "/particles/trajectory/position/time");
        return g;
      };
      element("id").write("value", id, {T, S}, {true, 2});
      if (!velocity.empty()) element("velocity").write("value", velocity, {T, S, 3}, {true, 2});
      if (!orientation.empty()) {
        const h5::Group o = element("orientation");
        o.set_attribute("components", std::vector<std::string>{"x", "y", "z", "w"});
        o.write("value", orientation, {T, S, 4}, {true, 2});
      }
      if (!action.empty()) {
        const h5::Group a = element("action");
        a.set_attribute("names", std::vector<std::string>{"walk", "stand", "run"});
        a.set_attribute("props", std::vector<std::string>{"", "", ""});
        a.write("value", action, {T, S}, {true, 2});
      }
      if (!slot_species.empty()) traj.write("species", slot_species, {S});
      if (formation_edges) root.create_group("connectivity").write("formation_edges", std::vector<std::int32_t>{0, 1}, {1, 2});
      if (throng_parameters) {
        const h5::Group params = root.create_group("parameters").create_group("throng");
        params.set_attribute("format_version", std::int64_t{1});
        const h5::Group agents = params.create_group("agents");
        agents.write("id", agent_id, {agent_id.size()});
        agents.write("radius", agent_radius, {agent_radius.size()});
        if (!agent_species.empty()) agents.write("species", agent_species, {agent_species.size()});
      }
    }
    f.close();
  }
};

// The slot arrays of `layout` (frames × slots) filled from each agent's motion; pose elements when `pose`.
SlottedFile from_layout(const SlotLayout& layout, bool pose) {
  SlottedFile f;
  f.slots = layout.front().size();
  f.times.assign(frame_times.begin(), frame_times.begin() + static_cast<std::ptrdiff_t>(layout.size()));
  for (std::size_t t = 0; t < layout.size(); ++t) {
    for (const std::int64_t a : layout[t]) {
      f.id.push_back(a);
      const bool here = a >= 0;
      const Eigen::Vector3d p = place(a, t), v = speed(a, t);
      const Eigen::Vector4d q = facing(a, t).coeffs();
      for (int k = 0; k < 3; ++k) {
        f.position.push_back(here ? p[k] : nan_value);
        f.velocity.push_back(here ? v[k] : nan_value);
      }
      for (int k = 0; k < 4; ++k) f.orientation.push_back(here ? q[k] : nan_value);
      f.action.push_back(here ? doing(a, t) : -1);
    }
  }
  if (!pose) {
    f.velocity.clear();
    f.orientation.clear();
    f.action.clear();
  }
  return f;
}

// The test crowd: reused_layout with velocity, orientation and action, agents 0, 1, 2 listed with their radii and
// species.
SlottedFile reused_slots() {
  SlottedFile f = from_layout(reused_layout, true);
  f.slot_species = {0, 0};
  f.agent_id = {0, 1, 2};
  f.agent_radius = {0.3, 0.25, 0.4};
  f.agent_species = {1, 2, 3};
  return f;
}

// The same crowd in memory, one column per agent (what the classic writer is given).
CrowdFile reused_crowd() {
  CrowdFile f;
  CrowdMotion& m = f.motion;
  const std::size_t T = reused_layout.size(), A = 3;
  m = CrowdMotion::with_shape(T, A);
  m.times = frame_times;
  m.ids = {0, 1, 2};
  m.radii = {0.3, 0.25, 0.4};
  m.species = {1, 2, 3};
  m.velocities.assign(T * A * 3, absent);
  m.orientations.assign(T * A * 4, absent);
  m.actions.assign(T * A, -1);
  m.action_table = standard_actions();
  for (std::size_t t = 0; t < T; ++t) {
    for (const std::int64_t a : reused_layout[t]) {
      if (a < 0) continue;
      const auto n = static_cast<std::size_t>(a);
      m.position(t, n) = place(a, t);
      Eigen::Map<Eigen::Vector3d>(m.velocities.data() + m.index(t, n)) = speed(a, t);
      m.orientation(t, n) = facing(a, t);
      m.action(t, n) = doing(a, t);
    }
  }
  return f;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

std::filesystem::path written(const std::string& name, const SlottedFile& f) {
  const auto dir = test::scratch_dir("io_slots_" + name);
  f.write(dir / "crowd.h5");
  return dir / "crowd.h5";
}

}  // namespace

TEST_CASE("a slotted file with 2 slots and 3 agents reads into 3 agent columns exactly") {
  const CrowdFile read = read_crowd_file(written("read", reused_slots()));
  const CrowdMotion& m = read.motion;
  REQUIRE(m.frame_count() == 5);
  REQUIRE(m.agent_count() == 3);
  CHECK(m.times == frame_times);
  CHECK(m.ids == std::vector<std::int64_t>{0, 1, 2});
  CHECK(m.radii == std::vector<double>{0.3, 0.25, 0.4});
  CHECK(m.species == std::vector<std::int32_t>{1, 2, 3});
  CHECK(m.action_table == standard_actions());
  REQUIRE(m.velocities.size() == 5 * 3 * 3);
  REQUIRE(m.orientations.size() == 5 * 3 * 4);
  REQUIRE(m.actions.size() == 5 * 3);
  // Agent 0: frames 0–1 (slot 0); agent 1: frames 0–3 (slot 1); agent 2: frames 3–4 (slot 0, after agent 0).
  const bool presence[5][3] = {{true, true, false}, {true, true, false}, {false, true, false}, {false, true, true}, {false, false, true}};
  for (std::size_t t = 0; t < 5; ++t) {
    for (std::size_t n = 0; n < 3; ++n) {
      INFO("frame " << t << " agent " << n);
      REQUIRE(m.present(t, n) == presence[t][n]);
      const auto a = static_cast<std::int64_t>(n);
      if (presence[t][n]) {
        CHECK(m.position(t, n) == place(a, t));
        CHECK(Eigen::Map<const Eigen::Vector3d>(m.velocities.data() + m.index(t, n)) == speed(a, t));
        CHECK(m.orientation(t, n).coeffs() == facing(a, t).coeffs());
        CHECK(m.action(t, n) == doing(a, t));
      } else {
        CHECK(std::isnan(m.position(t, n).x()));
        CHECK(std::isnan(m.velocities[m.index(t, n)]));
        CHECK(std::isnan(m.orientation(t, n).w()));
        CHECK(m.action(t, n) == -1);
      }
    }
  }
}

TEST_CASE("the same crowd written classic by write_crowd_file and slotted by hand reads the same") {
  const auto dir = test::scratch_dir("io_slots_same");
  write_crowd_file(dir / "classic.h5", reused_crowd());
  reused_slots().write(dir / "slotted.h5");
  const CrowdFile classic = read_crowd_file(dir / "classic.h5");
  const CrowdFile slotted = read_crowd_file(dir / "slotted.h5");
  CHECK(test::same_crowd(classic, slotted));  // times, positions, ids, radii, species, velocities, scene, provenance
  CHECK(same_bits(classic.motion.orientations, slotted.motion.orientations));
  CHECK(same_bits(classic.motion.actions, slotted.motion.actions));
  CHECK(classic.motion.action_table == slotted.motion.action_table);
  CHECK(test::same_crowd(classic, reused_crowd()));
}

TEST_CASE("agents listed in another order than they appear keep the listed order") {
  SlottedFile f = reused_slots();
  f.agent_id = {2, 0, 1};
  f.agent_radius = {0.4, 0.3, 0.25};
  f.agent_species.clear();  // species 0 without agents/species
  const CrowdMotion m = read_crowd_file(written("order", f)).motion;
  CHECK(m.ids == std::vector<std::int64_t>{2, 0, 1});
  CHECK(m.radii == std::vector<double>{0.4, 0.3, 0.25});
  CHECK(m.species == std::vector<std::int32_t>{0, 0, 0});
  CHECK(m.position(4, 0) == place(2, 4));  // agent 2, slot 0 at frame 4
  CHECK(m.position(0, 1) == place(0, 0));
  CHECK(m.position(3, 2) == place(1, 3));
  CHECK_FALSE(m.present(0, 0));
}

TEST_CASE("another program's slotted file reads its agents in order of first appearance") {
  // No /parameters/throng. Agent 7 appears first (frame 0 slot 1) and 42 next (frame 1 slot 0); 99 takes slot 0
  // after 42 and moves to slot 1 at frame 4.
  SlottedFile f = from_layout({{-1, 7}, {42, 7}, {42, -1}, {99, -1}, {-1, 99}}, false);
  f.throng_parameters = false;
  f.slot_species = {5, 6};
  const CrowdFile read = read_crowd_file(written("foreign", f));
  const CrowdMotion& m = read.motion;
  CHECK(m.ids == std::vector<std::int64_t>{7, 42, 99});
  CHECK(m.radii == std::vector<double>{0.25, 0.25, 0.25});
  CHECK(m.species == std::vector<std::int32_t>{6, 5, 5});  // the slot's where each first appears
  CHECK(m.velocities.empty());
  CHECK(m.orientations.empty());
  CHECK(m.actions.empty());
  const std::vector<std::vector<std::size_t>> present_at{{0, 1}, {1, 2}, {3, 4}};
  for (std::size_t n = 0; n < 3; ++n) {
    for (std::size_t t = 0; t < 5; ++t) {
      INFO("frame " << t << " agent " << m.ids[n]);
      const bool here = t == present_at[n][0] || t == present_at[n][1];
      REQUIRE(m.present(t, n) == here);
      if (here) CHECK(m.position(t, n) == place(m.ids[n], t));
    }
  }
  CHECK(read.provenance.program_version.empty());
  CHECK(read.scene.obstacles.empty());
}

TEST_CASE("a listed agent that is never present is an agent with no present frame") {
  SlottedFile f = reused_slots();
  f.agent_id = {0, 1, 2, 3};
  f.agent_radius = {0.3, 0.25, 0.4, 0.5};
  f.agent_species = {1, 2, 3, 4};
  const CrowdMotion m = read_crowd_file(written("absent_agent", f)).motion;
  REQUIRE(m.agent_count() == 4);
  CHECK(m.presence_span(3) == std::pair<std::size_t, std::size_t>{0, 0});
  CHECK(m.position(3, 2) == place(2, 3));
}

TEST_CASE("a slotted file naming an id that agents/id does not list is an InputError naming it") {
  SlottedFile f = reused_slots();
  f.id[3 * 2 + 0] = 5;  // frame 3, slot 0: agent 5 instead of 2
  CHECK_THROWS_AS_WITH(read_crowd_file(written("unlisted", f)), InputError,
                       Contains("/particles/trajectory/id/value") && Contains("column 0 holds id 5 at frame 3") &&
                           Contains("/parameters/throng/agents/id does not list"));
}

TEST_CASE("an id listed twice in agents/id of a slotted file is an InputError") {
  SlottedFile f = reused_slots();
  f.agent_id = {0, 1, 1};
  CHECK_THROWS_AS_WITH(read_crowd_file(written("listed_twice", f)), InputError,
                       Contains("/parameters/throng/agents/id") && Contains("id 1 is listed twice (entries 1 and 2)"));
}

TEST_CASE("one agent in two slots at one frame is an InputError naming the agent and the frame") {
  SlottedFile f = reused_slots();
  f.id[2 * 2 + 0] = 1;  // frame 2: agent 1 in slot 0 (empty there) as well as in slot 1
  for (int k = 0; k < 3; ++k) f.position[(2 * 2 + 0) * 3 + k] = place(1, 2)[k];
  CHECK_THROWS_AS_WITH(read_crowd_file(written("two_slots", f)), InputError,
                       Contains("id/value") && Contains("agent 1 is in slots 0 and 1 at frame 2"));
}

TEST_CASE("a non-finite position in a present slot is an InputError naming the frame and the slot") {
  SlottedFile f = reused_slots();
  f.position[(3 * 2 + 0) * 3 + 1] = nan_value;  // agent 2 in slot 0 at frame 3
  CHECK_THROWS_AS_WITH(read_crowd_file(written("nan", f)), InputError,
                       Contains("/particles/trajectory/position/value") &&
                           Contains("NaN position for present agent 2 (slot 0) at frame 3"));
  f.position[(3 * 2 + 0) * 3 + 1] = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS_WITH(read_crowd_file(written("infinite", f)), InputError,
                       Contains("infinite position for present agent 2 (slot 0) at frame 3"));
}

TEST_CASE("a present slot's bad orientation or action is an InputError naming the slot") {
  SlottedFile f = reused_slots();
  f.orientation[(3 * 2 + 0) * 4 + 3] = 0.5;  // agent 2 in slot 0 at frame 3: not a unit quaternion
  CHECK_THROWS_AS_WITH(read_crowd_file(written("orientation", f)), InputError,
                       Contains("orientation/value") && Contains("agent 2 (slot 0) at frame 3") && Contains("unit quaternion"));
  SlottedFile g = reused_slots();
  g.action[3 * 2 + 1] = 3;  // agent 1 in slot 1 at frame 3: outside walk, stand, run
  CHECK_THROWS_AS_WITH(read_crowd_file(written("action", g)), InputError,
                       Contains("action/value") && Contains("agent 1 (slot 1) at frame 3 has action 3"));
}

TEST_CASE("a slotted file whose agent columns exceed the memory limit is refused with the estimate") {
  // 2 slots but 1000 listed agents: the slot arrays are a few hundred bytes, the agent columns 5 frames × 1000
  // agents × (24 position + 24 velocity + 32 orientation + 4 action) + 1000 agents × 84 = 504 KB.
  SlottedFile f = reused_slots();
  f.agent_id.resize(1000);
  f.agent_radius.resize(1000, 0.3);
  f.agent_species.resize(1000, 0);
  for (std::size_t a = 0; a < 1000; ++a) f.agent_id[a] = static_cast<std::int64_t>(a);
  const auto path = written("limit", f);
  CHECK_THROWS_AS_WITH(read_crowd_file(path, ReadLimits{200'000}), InputError,
                       Contains("/particles/trajectory/id/value") && Contains("about 504 KB") &&
                           Contains("5 frames × 1000 agents × 84 bytes, the agent columns built from the slots") &&
                           Contains("memory limit of 200 KB"));
  CHECK(read_crowd_file(path, ReadLimits{10'000'000}).motion.agent_count() == 1000);
}

TEST_CASE("another program's slotted file naming ever more ids is refused while they are counted") {
  // One slot, 1000 frames, a new agent each frame: 1000 agent columns of 1000 frames (24 MB) from 32 KB of slots.
  SlottedFile f;
  f.slots = 1;
  f.throng_parameters = false;
  for (std::size_t t = 0; t < 1000; ++t) {
    f.times.push_back(0.04 * t);
    f.id.push_back(static_cast<std::int64_t>(t));
    f.position.insert(f.position.end(), {0.01 * t, 0.0, 0.0});
  }
  const auto path = written("counting", f);
  CHECK_THROWS_AS_WITH(read_crowd_file(path, ReadLimits{1'000'000}), InputError,
                       Contains("/particles/trajectory/id/value") && Contains("1000 frames × at least ") &&
                           Contains(" agents × 24 bytes") && Contains("refused before reading"));
  CHECK(read_crowd_file(path, ReadLimits{100'000'000}).motion.agent_count() == 1000);
}

TEST_CASE("formation edges in a slotted file are an InputError") {
  SlottedFile f = reused_slots();
  f.formation_edges = true;
  CHECK_THROWS_AS_WITH(read_crowd_file(written("edges", f)), InputError,
                       Contains("/connectivity/formation_edges") && Contains("reused slots"));
}

TEST_CASE("a column that holds one agent with gaps is classic and reads as before") {
  // Agent 1 leaves slot 1 at frame 2 and comes back: one id per column, so one agent per column.
  SlottedFile f = from_layout({{0, 1}, {0, 1}, {0, -1}, {0, 1}}, false);
  f.agent_id = {0, 1};
  f.agent_radius = {0.3, 0.3};
  f.formation_edges = true;  // meaningful in the classic layout
  const CrowdFile read = read_crowd_file(written("classic_gaps", f));
  CHECK(read.motion.ids == std::vector<std::int64_t>{0, 1});
  CHECK_FALSE(read.motion.present(2, 1));
  CHECK(read.motion.position(3, 1) == place(1, 3));
  CHECK(read.formation_edges == std::vector<std::array<std::int32_t, 2>>{{0, 1}});
}
