// Patch construction from recorded trajectories (construct.h): Eq. 4 and Eq. 5, episode detection and merging,
// the choice of boundary pose groups, and the shipped recorded crowds.
#include <catch2/catch.hpp>

#include <throng/io/import_crowd.h>
#include <throng/tiling/construct.h>

#include "test_paths.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

using namespace throng;
using namespace throng::tiling;

namespace {

using Walk = std::function<Eigen::Vector2d(double)>;

// A crowd recorded at 10 Hz over [0, duration]: agent k at paths[k](t).
CrowdMotion crowd_of(const std::vector<Walk>& paths, double duration) {
  const auto frames = static_cast<std::size_t>(std::lround(duration * 10)) + 1;
  CrowdMotion m = CrowdMotion::with_shape(frames, paths.size());
  for (std::size_t f = 0; f < frames; ++f) {
    m.times[f] = 0.1 * static_cast<double>(f);
    for (std::size_t k = 0; k < paths.size(); ++k) {
      const Eigen::Vector2d p = paths[k](m.times[f]);
      m.position(f, k) = Eigen::Vector3d(p.x(), p.y(), 0);
    }
  }
  return m;
}

// Walks at 1.2 m/s toward `centre` from direction `angle`, reaches centre + 0.6 m toward `angle` at t = 5 s,
// then turns a quarter left and walks on: a sharp reaction next to whoever else arrives there.
Walk meeting_walker(Eigen::Vector2d centre, double angle) {
  const Eigen::Vector2d out(std::cos(angle), std::sin(angle)), left(-out.y(), out.x());
  return [=](double t) -> Eigen::Vector2d {
    const Eigen::Vector2d arrival = centre + 0.6 * out;
    return t < 5 ? Eigen::Vector2d(arrival + 1.2 * (5 - t) * out) : Eigen::Vector2d(arrival + 1.2 * (t - 5) * left);
  };
}

std::size_t episode_patches(const PatchLibrary& lib) {
  return static_cast<std::size_t>(
      std::count_if(lib.types.begin(), lib.types.end(), [](const PatchType& t) { return t.character_count() >= 2; }));
}

}  // namespace

TEST_CASE("motion variation is Eq. 4 with the window clamped at the ends") {
  const std::vector<Eigen::Vector2d> v{{0, 0}, {1, 0}, {1, 1}};
  // w = 1: sample 0 sees {0, 1}: ‖v0 − v1‖² = 1; sample 1 sees all three: 1 + 2 + 1; sample 2 sees {1, 2}: 1.
  const std::vector<double> one = motion_variation(v, 1);
  REQUIRE(one.size() == 3);
  CHECK(one[0] == Approx(1));
  CHECK(one[1] == Approx(4));
  CHECK(one[2] == Approx(1));
  for (double x : motion_variation(v, 2)) CHECK(x == Approx(4));
  for (double x : motion_variation(v, 0)) CHECK(x == 0);
}

TEST_CASE("synchronicity is Eq. 5 with the heading as gaze") {
  // A at the origin faces B (g(A, B) = 0); B at (2, 0) faces +y, a quarter turn away from A (g(B, A) = π/2).
  const double s = synchronicity(2, 3, {0, 0}, 0, {2, 0}, std::numbers::pi / 2);
  CHECK(s == Approx(6 * std::exp(-std::numbers::pi / 2)));
  CHECK(synchronicity(3, 2, {2, 0}, std::numbers::pi / 2, {0, 0}, 0) == Approx(s));
  // Back to back: both angles π.
  CHECK(synchronicity(1, 1, {0, 0}, std::numbers::pi, {1, 0}, 0) == Approx(std::exp(-2 * std::numbers::pi)));
}

TEST_CASE("three walkers meeting at one spot make one group patch and a far walker stays out") {
  std::vector<Walk> paths;
  for (int k = 0; k < 3; ++k) paths.push_back(meeting_walker({0, 0}, std::numbers::pi / 2 + 2 * std::numbers::pi / 3 * k));
  paths.push_back([](double t) { return Eigen::Vector2d(-8 + 1.5 * t, -8); });  // straight, 7 m away at best
  RealPatchReport report;
  const PatchLibrary lib = patches_from_trajectories(crowd_of(paths, 10), {}, &report);
  CHECK(report.episodes == 1);
  CHECK(report.groups_of_3 == 1);
  CHECK(report.pairs == 0);
  REQUIRE(episode_patches(lib) == 1);
  const PatchType& group = lib.types[lib.find("real_group_0")];
  CHECK(group.label == "group");
  CHECK(group.fragments.size() == 3);
  CHECK(group.constraints.size() == 3);  // every pair had an event
  CHECK(report.chosen_classes == std::vector<std::string>{"walking"});
}

TEST_CASE("two distant meeting pairs make two pair patches") {
  const std::vector<Walk> paths{meeting_walker({0, 0}, 0), meeting_walker({0, 0}, std::numbers::pi),
                                meeting_walker({20, 0}, 0), meeting_walker({20, 0}, std::numbers::pi)};
  RealPatchReport report;
  const PatchLibrary lib = patches_from_trajectories(crowd_of(paths, 10), {}, &report);
  CHECK(report.episodes == 2);
  CHECK(report.pairs == 2);
  REQUIRE(episode_patches(lib) == 2);
  for (const char* name : {"real_pair_0", "real_pair_1"}) {
    const PatchType& pair = lib.types[lib.find(name)];
    CHECK(pair.label == "pair");
    CHECK(pair.constraints.size() == 1);
  }
}

TEST_CASE("straight walkers that never react make no episode") {
  const std::vector<Walk> paths{[](double t) { return Eigen::Vector2d(-8 + 1.5 * t, 0); },
                                [](double t) { return Eigen::Vector2d(0, -8 + 1.3 * t); },
                                [](double t) { return Eigen::Vector2d(8 - 1.1 * t, 3); }};
  RealPatchReport report;
  const PatchLibrary lib = patches_from_trajectories(crowd_of(paths, 12), {}, &report);
  CHECK(report.episodes == 0);
  CHECK(episode_patches(lib) == 0);
  CHECK(lib.types.size() >= 3);  // single pieces
}

TEST_CASE("the subset of pose groups trades fewer groups against compact patches") {
  // A walks at 1.0 m/s but 1.6 m/s for 1.5 s either side of passing B (t = 10 s), who walks at 1.0 m/s
  // throughout. Near the episode A's clean samples are in the fast group, B's in the slow one: both groups give
  // tight boundaries, the slow group alone pushes A's boundaries out of the fast stretch.
  const auto a_x = [](double t) {
    const double fast_from = 8.5, fast_to = 11.5;
    const double slow_before = std::min(t, fast_from), fast = std::clamp(t, fast_from, fast_to) - fast_from;
    const double slow_after = std::max(t, fast_to) - fast_to;
    return slow_before + 1.6 * fast + slow_after - (fast_from + 1.6 * 1.5);
  };
  const std::vector<Walk> paths{[=](double t) { return Eigen::Vector2d(a_x(t), 0.2); },
                                [](double t) { return Eigen::Vector2d(10 - t, -0.2); }};
  RealPatchOptions o;
  o.contact_m = 1.0;  // the passing is the only event
  o.min_contact_s = 0.4;
  o.reaction_min_m2ps2 = 1e9;
  o.synchronicity_min = 1e18;
  o.margin_s = 3;
  o.boundary_lead_s = 0;  // the paper's tight boundaries
  o.builtin_classes = false;
  const auto episode_samples = [&](double weight, RealPatchReport& report) {
    o.diversity_weight = weight;
    const PatchLibrary lib = patches_from_trajectories(crowd_of(paths, 20), o, &report);
    return lib.types[lib.find("real_pair_0")].sample_count();
  };
  RealPatchReport diverse, few;
  const std::size_t compact = episode_samples(0.001, diverse), wide = episode_samples(1.0, few);
  CHECK(diverse.chosen_classes.size() == 2);
  CHECK(few.chosen_classes == std::vector<std::string>{"real_pose_0"});  // the slow, largest group
  CHECK(compact < wide);
}

TEST_CASE("impossible real-patch options are config errors naming the key") {
  const CrowdMotion m = crowd_of({meeting_walker({0, 0}, 0)}, 10);
  RealPatchOptions o;
  o.pose_groups = 0;
  CHECK_THROWS_WITH(patches_from_trajectories(m, o), Catch::Contains("pose_groups"));
  o = {};
  o.max_episode_characters = 1;
  CHECK_THROWS_WITH(patches_from_trajectories(m, o), Catch::Contains("max_episode_characters"));
}

TEST_CASE("the recorded zara01 crowd gives group episodes of three and more") {
  const CrowdMotion m = import_crowd(test::real_data_dir() / "zara01").crowd.motion;
  RealPatchReport report;
  const PatchLibrary lib = patches_from_trajectories(m, {}, &report);
  CHECK(report.episodes > 20);
  CHECK(report.groups_of_3 + report.groups_of_4_plus >= 3);
  CHECK(report.pairs + report.groups_of_3 + report.groups_of_4_plus == episode_patches(lib));
  CHECK(episode_patches(lib) >= 10);
  for (const PatchType& t : lib.types) {
    if (t.character_count() >= 3) {
      CHECK(t.label == "group");
      // Every character had an event with somebody, so each is tied to another (merged events of different
      // people are not tied to each other: only the pairs that had an event are).
      std::vector<bool> tied(t.fragments.size(), false);
      for (const InterpersonalConstraint& c : t.constraints) tied[c.fragment_a] = tied[c.fragment_b] = true;
      CHECK(std::count(tied.begin(), tied.end(), true) == static_cast<long>(t.fragments.size()));
    }
  }
  // Entries and exits use the built-in locomotion classes only.
  for (const std::string& c : lib.pose_classes) CHECK((c == "standing" || c == "walking"));
}
