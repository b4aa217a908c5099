// The incremental tracker reports exactly what a full search reports (same contacts, order and bits) after every
// iteration of a real repair, through both of its paths (neighbour lists, rebuilt intervals), with and without
// the moved-agent hint, whatever the thread count.
#include "same_contacts.h"
#include "scenes.h"

#include <throng/collide/broad_phase.h>
#include <throng/collide/collide.h>
#include <throng/collide/contact_tracker.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

using namespace throng;
using namespace throng::collide;
using check::require_same_contacts;

namespace {

NoProgress quiet;

// The crowds after 0, 1, …, `iterations` iterations of a repair (each run stops where the longer one passed).
std::vector<CrowdMotion> repair_steps(const CrowdMotion& crowd, const std::vector<Obstacle>& obstacles, Options options,
                                      std::size_t iterations) {
  std::vector<CrowdMotion> steps{crowd};
  for (std::size_t k = 1; k <= iterations; ++k) {
    options.max_iterations = k;
    steps.push_back(resolve_collisions(crowd, obstacles, options, quiet).crowd);
  }
  return steps;
}

// Agents whose x or y changed between two crowds.
std::vector<char> changed_agents(const CrowdMotion& before, const CrowdMotion& after) {
  std::vector<char> out(before.agent_count(), 0);
  for (std::size_t f = 0; f < before.frame_count(); ++f) {
    for (std::size_t a = 0; a < before.agent_count(); ++a) {
      const auto p = before.position(f, a), q = after.position(f, a);
      if (before.present(f, a) && (p.x() != q.x() || p.y() != q.y())) out[a] = 1;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("the incremental tracker equals a full search after every iteration of a repair") {
  const auto obstacles = scenes::scattered_obstacles();
  for (std::uint64_t seed : {1u, 2u}) {
    const CrowdMotion crowd = scenes::random_crowd(70, 40, 15.0, 0.1, seed);
    Options options;
    options.margin = 0.1;
    const auto steps = repair_steps(crowd, obstacles, options, 25);
    // Skin 0: every growing box rebuilds its interval; 0.15 m: the product's; 2 m: almost no rebuild.
    for (double skin : {0.0, 0.15, 2.0}) {
      INFO("seed " << seed << ", skin " << skin);
      ContactTracker all(crowd, obstacles, options.margin, skin), hinted(crowd, obstacles, options.margin, skin);
      REQUIRE(all.contacts().size() > 20);
      require_same_contacts(all.contacts(), find_contacts(crowd, obstacles, options.margin, BroadPhase::all_pairs));
      for (std::size_t k = 1; k < steps.size(); ++k) {
        INFO("after iteration " << k);
        all.update(steps[k]);
        hinted.update(steps[k], changed_agents(steps[k - 1], steps[k]));
        const Contacts full = find_contacts(steps[k], obstacles, options.margin, BroadPhase::all_pairs);
        require_same_contacts(all.contacts(), full);
        require_same_contacts(hinted.contacts(), full);
        // Below the margin the smallest gaps are exact, as find_contacts promises.
        if (full.min_pair_gap < options.margin) CHECK(all.contacts().min_pair_gap == full.min_pair_gap);
        if (full.min_obstacle_gap < options.margin) CHECK(all.contacts().min_obstacle_gap == full.min_obstacle_gap);
      }
      // The repair moved things, and both paths ran (the 2 m skin: neighbour lists; 0: rebuilds).
      CHECK(all.stats().moved_segments > 0);
      if (skin == 0.0) CHECK(all.stats().rebuilt_intervals > 0);
      if (skin > 0.0) CHECK(all.stats().refreshed_intervals > 0);
    }
  }
}

TEST_CASE("the incremental tracker follows arbitrary moves: large jumps, nudges, agents leaving and coming back") {
  // Moves a repair does not make: whole agents jumping across the scene (every round in three: every interval
  // rebuilt) and single vertices nudged, by less than the skin's half (0.075 m) or more.
  const auto obstacles = scenes::scattered_obstacles();
  CrowdMotion crowd = scenes::random_crowd(90, 30, 15.0, 0.12, 7);
  ContactTracker tracker(crowd, obstacles, 0.2, 0.15);
  Rng rng(11);
  std::pair<std::size_t, std::size_t> gone{0, 0};  // (agent, frame) made absent
  Eigen::Vector3d gone_at = crowd.position(0, 0);
  for (int round = 0; round < 12; ++round) {
    INFO("round " << round);
    for (int move = 0; move < 15; ++move) {
      const std::size_t a = rng.below(crowd.agent_count());
      const bool jump = round % 3 == 0 && move % 5 == 0;
      const std::size_t f0 = jump ? 0 : rng.below(crowd.frame_count());
      const std::size_t f1 = jump ? crowd.frame_count() : f0 + 1;
      const Eigen::Vector3d shift(rng.uniform(-1, 1) * (jump ? 6.0 : 0.1), rng.uniform(-1, 1) * (jump ? 6.0 : 0.1), 0.0);
      for (std::size_t f = f0; f < f1; ++f) {
        if (crowd.present(f, a)) crowd.position(f, a) += shift;
      }
    }
    // Presence changes: an agent in contact leaves at a frame of its contact, and comes back there a round later.
    if (round % 4 == 1 && !tracker.contacts().pairs.empty()) {
      const PairContact& c = tracker.contacts().pairs[rng.below(tracker.contacts().pairs.size())];
      gone = {c.a, c.interval + 1 < crowd.frame_count() - 1 ? c.interval + 1 : c.interval};
      gone_at = crowd.position(gone.second, gone.first);
      crowd.position(gone.second, gone.first) = Eigen::Vector3d::Constant(std::nan(""));
    } else if (round % 4 == 2) {
      crowd.position(gone.second, gone.first) = gone_at;
    }
    tracker.update(crowd);
    require_same_contacts(tracker.contacts(), find_contacts(crowd, obstacles, 0.2, BroadPhase::all_pairs));
  }
  CHECK(tracker.stats().rebuilt_intervals > 0);
  CHECK(tracker.stats().refreshed_intervals > 0);
}

TEST_CASE("the incremental tracker does not depend on the thread count") {
  const auto obstacles = scenes::scattered_obstacles();
  const CrowdMotion crowd = scenes::random_crowd(150, 40, 15.0, 0.1, 5);
  Options options;
  const auto steps = repair_steps(crowd, obstacles, options, 6);
  auto track = [&](std::size_t threads) {
    ThreadLimit limit(threads);
    ContactTracker tracker(crowd, obstacles, options.margin, 0.15);
    for (std::size_t k = 1; k < steps.size(); ++k) tracker.update(steps[k]);
    return tracker.contacts();
  };
  const Contacts one = track(1), two = track(2);
  REQUIRE(one.size() > 0);
  require_same_contacts(one, two);
}
