// Windowed tiling: perfect across every seam (the independent checker on the whole delivered tiling), the
// frames streamed window by window equal to what lay_out makes of the whole tiling, the density held in every
// window, the same bits for any thread count and after a resume, a state that does not grow with the horizon,
// and the restrictions refused up front.
#include <catch2/catch.hpp>

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/tiling/characters.h>
#include <throng/tiling/check.h>
#include <throng/tiling/windowed.h>

#include "tiling_scenes.h"

#include <cmath>
#include <cstring>
#include <sstream>

using namespace throng;
using namespace throng::tiling;
using namespace throng::tiling::test;

namespace {

PatchLibrary plaza_library() {
  return builtin_library({"walk", "walk_slow", "walk_fast", "turn_left", "turn_right", "turn_left_90", "turn_right_90",
                          "stop", "start", "wait", "turn_in_place", "meet", "pass", "handshake", "bump"});
}

Options plaza_options(std::uint64_t seed) {
  Options o;
  o.seed = seed;
  o.chains = 2;
  o.annealing.max_failures = 1000;
  o.search.max_steps = 50000;
  o.density.per_m2 = 0.06;
  return o;
}

// Everything a run delivers, assembled: the whole tiling, the frames, the reports.
struct Run {
  Tiling tiling;
  std::vector<FrameWindow> frames;
  std::vector<WindowReport> reports;
  std::vector<std::vector<std::byte>> states;  // after each window
  std::size_t lost = 0;
  std::size_t first = 0;  // the delivered id of tiling.instances[0] (a resumed run starts later)
};

void collect(Run& run, const WindowOutput& out, const WindowedTiler& tiler) {
  if (run.reports.empty()) run.first = out.first_instance;
  REQUIRE(out.first_instance == run.first + run.tiling.instances.size());
  run.tiling.instances.insert(run.tiling.instances.end(), out.instances.begin(), out.instances.end());
  run.tiling.connections.insert(run.tiling.connections.end(), out.connections.begin(), out.connections.end());
  for (const FrameWindow& f : out.frames) run.frames.push_back(f);
  run.reports.push_back(out.report);
  run.states.push_back(tiler.state());
  run.lost = out.lost_dangling;
}

Run run_all(WindowedTiler& tiler) {
  Run run;
  NoProgress quiet;
  tile_windows(tiler, [&](const WindowOutput& out, const WindowedTiler& t) { collect(run, out, t); }, quiet);
  return run;
}

// Every number a run delivers, for bitwise comparison.
std::vector<double> flatten(const Run& run, std::size_t from_window = 0) {
  std::vector<double> v;
  for (const Instance& i : run.tiling.instances) {
    v.insert(v.end(), {static_cast<double>(i.type), i.transform.translation.x(), i.transform.translation.y(),
                       i.transform.angle, i.transform.time_shift});
    for (const Path& p : i.paths) {
      for (const auto& q : p.positions) v.insert(v.end(), {q.x(), q.y()});
      v.insert(v.end(), p.times.begin(), p.times.end());
    }
  }
  for (const Connection& c : run.tiling.connections) {
    v.insert(v.end(), {static_cast<double>(c.from.instance), static_cast<double>(c.from.fragment),
                       static_cast<double>(c.to.instance), static_cast<double>(c.to.fragment)});
  }
  for (const FrameWindow& f : run.frames) {
    if (f.index < from_window) continue;
    v.insert(v.end(), f.frames.times.begin(), f.frames.times.end());
    v.insert(v.end(), f.frames.positions.begin(), f.frames.positions.end());
    for (std::int64_t id : f.frames.ids) v.push_back(static_cast<double>(id));
  }
  return v;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

CheckOptions check_options(const Options& o) {
  CheckOptions c;
  c.limits = o.limits;
  c.match = o.match;
  return c;
}

std::string failures(const CheckReport& r) {
  std::string s;
  for (const Failure& f : r.failures) s += std::string(to_string(f.kind)) + ": " + f.message + "\n";
  return s;
}

// The streamed frames against lay_out of the whole tiling: the same frame times, the same agents present at
// every frame under the same ids, the same positions, facings and actions (bit for bit), the same action table.
void check_frames(const PatchLibrary& lib, const Run& run, const Region& region, double rate) {
  const Characters laid = lay_out(lib, run.tiling, region, LayoutOptions{rate, {1, 1, 1}});
  const CrowdMotion& whole = laid.motion;
  for (const FrameWindow& fw : run.frames) {
    REQUIRE_NOTHROW(fw.frames.validate("window " + std::to_string(fw.index)));
    REQUIRE(fw.frames.action_table == whole.action_table);
  }
  std::size_t frame = 0, mismatches = 0, present = 0;
  std::int64_t highest = -1;
  for (const FrameWindow& fw : run.frames) {
    REQUIRE(fw.first_frame == frame);
    const CrowdMotion& m = fw.frames;
    for (std::size_t f = 0; f < m.frame_count(); ++f) {
      REQUIRE(m.times[f] == whole.times[frame + f]);
      REQUIRE(m.times[f] >= fw.t0);
      if (fw.index + 1 < run.frames.size()) REQUIRE(m.times[f] < fw.t1);
      std::size_t here = 0;
      for (std::size_t a = 0; a < m.agent_count(); ++a) {
        const auto id = static_cast<std::size_t>(m.ids[a]);
        highest = std::max(highest, m.ids[a]);
        REQUIRE(id < whole.agent_count());
        if (!m.present(f, a)) {
          mismatches += whole.present(frame + f, id);
          continue;
        }
        ++here;
        mismatches += !whole.present(frame + f, id) || m.position(f, a) != whole.position(frame + f, id) ||
                      m.orientation(f, a).coeffs() != whole.orientation(frame + f, id).coeffs() ||
                      m.action(f, a) != whole.action(frame + f, id);
      }
      // No agent of the whole crowd is missing from the window.
      std::size_t expected = 0;
      for (std::size_t n = 0; n < whole.agent_count(); ++n) expected += whole.present(frame + f, n);
      mismatches += here != expected;
      present += here;
    }
    frame += m.frame_count();
  }
  CHECK(frame == whole.frame_count());
  CHECK(static_cast<std::size_t>(highest + 1) == whole.agent_count());
  CHECK(present > 0);
  CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("a windowed run is perfect across every seam and streams the frames lay_out makes of the whole") {
  const PatchLibrary lib = plaza_library();
  SECTION("an open plaza") {
    const Environment env = box(24, 24, 150);
    const Options o = plaza_options(3);
    WindowedTiler tiler(lib, env, o, WindowOptions{30, 10});
    CHECK(tiler.windows() == 5);
    const Run run = run_all(tiler);
    const CheckReport c = check_tiling(lib, run.tiling, env, check_options(o));
    INFO(failures(c));
    CHECK(c.perfect());
    CHECK(run.lost == 0);
    // The tiling crosses the seams: connections between instances on either side of t = 30, 60, 90, 120 s.
    std::size_t across = 0;
    for (const Connection& k : run.tiling.connections) {
      const double a = run.tiling.instances[k.from.instance].paths[k.from.fragment].times.front();
      const double b = run.tiling.instances[k.to.instance].paths[k.to.fragment].times.back();
      for (double seam : {30.0, 60.0, 90.0, 120.0}) across += a < seam && b > seam;
    }
    CHECK(across > 20);
    check_frames(lib, run, *env.scene.region, 10);
    // The density in every delivered window.
    REQUIRE(run.frames.size() == 5);
    for (const FrameWindow& f : run.frames) {
      REQUIRE(f.density.areas.size() == 1);
      INFO("window " << f.index << ": target " << f.density.areas[0].target << ", mean " << f.density.areas[0].mean);
      CHECK(f.density.areas[0].target == Approx(0.06 * 576));
      CHECK(std::abs(f.density.areas[0].error()) <= o.density.tolerance);
    }
  }
  SECTION("a plaza periodic in x (characters walk on across the side)") {
    const Environment env = box(20, 20, 120, {true, false, false});
    const Options o = plaza_options(4);
    WindowedTiler tiler(lib, env, o, WindowOptions{30, 5});
    const Run run = run_all(tiler);
    const CheckReport c = check_tiling(lib, run.tiling, env, check_options(o));
    INFO(failures(c));
    CHECK(c.perfect());
    std::size_t seams = 0;
    for (const Connection& k : run.tiling.connections) seams += k.image[0] != 0;
    CHECK(seams > 0);
    check_frames(lib, run, *env.scene.region, 5);
  }
}

TEST_CASE("a windowed run gives the same bits for 1 and 2 threads and when resumed after any window") {
  const PatchLibrary lib = plaza_library();
  const Environment env = box(20, 20, 100);
  const Options o = plaza_options(5);
  const WindowOptions w{25, 5};
  Run one, two;
  {
    ThreadLimit limit(1);
    WindowedTiler tiler(lib, env, o, w);
    one = run_all(tiler);
  }
  {
    ThreadLimit limit(2);
    WindowedTiler tiler(lib, env, o, w);
    two = run_all(tiler);
  }
  CHECK(same_bits(flatten(one), flatten(two)));
  REQUIRE(one.states.size() == 4);
  for (std::size_t k = 0; k + 1 < one.states.size(); ++k) {
    INFO("resumed after window " << k);
    WindowedTiler resumed(lib, env, o, w, one.states[k]);
    CHECK(resumed.next_window() == k + 1);
    Run rest = run_all(resumed);
    // The resumed run delivers the rest: put the earlier deliveries in front and compare everything.
    Run joined;
    NoProgress quiet;
    WindowedTiler again(lib, env, o, w);
    for (std::size_t j = 0; j <= k; ++j) collect(joined, again.next(quiet), again);
    REQUIRE(joined.states.back().size() == one.states[k].size());
    CHECK(std::memcmp(joined.states.back().data(), one.states[k].data(), one.states[k].size()) == 0);
    joined.tiling.instances.insert(joined.tiling.instances.end(), rest.tiling.instances.begin(), rest.tiling.instances.end());
    joined.tiling.connections.insert(joined.tiling.connections.end(), rest.tiling.connections.begin(),
                                     rest.tiling.connections.end());
    joined.frames.insert(joined.frames.end(), rest.frames.begin(), rest.frames.end());
    CHECK(same_bits(flatten(joined), flatten(one)));
  }
  // Another seed: other bits.
  WindowedTiler other(lib, env, plaza_options(6), w);
  CHECK_FALSE(same_bits(flatten(run_all(other)), flatten(one)));
}

TEST_CASE("a windowed run's state holds a window, not the past") {
  // Over 8 windows the state after each one stays the size of the first ones (a state that kept the past
  // would grow by a window's instances every time).
  const PatchLibrary lib = plaza_library();
  const Environment env = box(20, 20, 200);
  WindowedTiler tiler(lib, env, plaza_options(7), WindowOptions{25, 5});
  const Run run = run_all(tiler);
  REQUIRE(run.states.size() == 8);
  std::size_t first = run.states[1].size(), largest = 0;
  for (std::size_t k = 1; k + 1 < run.states.size(); ++k) largest = std::max(largest, run.states[k].size());
  INFO("state after window 1: " << first << " bytes, largest " << largest);
  CHECK(largest < 2 * first);
  for (const WindowReport& r : run.reports) {
    INFO("window " << r.index << " carried out " << r.carried_out << ", after window 1 " << run.reports[1].carried_out);
    CHECK(r.carried_out < 2 * run.reports[1].carried_out);
  }
  CHECK(run.reports.back().carried_out == 0);
}

TEST_CASE("a windowed run refuses what it cannot do, at once, and a state that is not its own") {
  const PatchLibrary lib = plaza_library();
  const auto message = [&](const Environment& env, const Options& o, const WindowOptions& w) {
    try {
      WindowedTiler tiler(lib, env, o, w);
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const Options o = plaza_options(1);
  CHECK(message(box(10, 10, 60, {true, true, true}), o, WindowOptions{20, 10}).find("periodic in time") != std::string::npos);
  Options capped = o;
  capped.characters = 30;
  CHECK(message(box(10, 10, 60), capped, WindowOptions{20, 10}).find("characters") != std::string::npos);
  CHECK(message(box(10, 10, 60), o, WindowOptions{5, 10}).find("twice the longest patch") != std::string::npos);
  CHECK(message(box(10, 10, 60), o, WindowOptions{20, 0}).find("frame rate") != std::string::npos);
  CHECK(message(box(10, 10, 60), o, WindowOptions{std::nan(""), 10}).find("window") != std::string::npos);

  // A state: truncated, from another seed, or not a state at all.
  const Environment env = box(16, 16, 60);
  const WindowOptions w{20, 5};
  WindowedTiler tiler(lib, env, o, w);
  NoProgress quiet;
  (void)tiler.next(quiet);
  std::vector<std::byte> state = tiler.state();
  CHECK_NOTHROW(WindowedTiler(lib, env, o, w, state));
  std::vector<std::byte> cut(state.begin(), state.begin() + static_cast<std::ptrdiff_t>(state.size() / 2));
  CHECK_THROWS_AS(WindowedTiler(lib, env, o, w, cut), InputError);
  CHECK_THROWS_AS(WindowedTiler(lib, env, plaza_options(2), w, state), InputError);
  CHECK_THROWS_AS(WindowedTiler(lib, env, o, w, std::vector<std::byte>(64, std::byte{7})), InputError);
  WindowedTiler done(lib, env, o, w, state);
  while (!done.done()) (void)done.next(quiet);
  CHECK_THROWS_AS(done.next(quiet), std::logic_error);
}
