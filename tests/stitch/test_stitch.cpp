// Stitching (paper §5): split-and-stitch gives the original back, the matching recovers a permutation, the
// alignment a rigid motion, the blend closes the gap smoothly within its window, and errors are named.
#include "../graph/synthetic_crowd.h"

#include <throng/check/motion_check.h>
#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/core/random.h>
#include <throng/graph/features.h>
#include <throng/stitch/split.h>
#include <throng/stitch/stitch.h>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <cstdio>
#include <numeric>

using namespace throng;
using namespace throng::stitch;

namespace {

double max_gap(const CrowdMotion& a, const CrowdMotion& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  double gap = 0;
  for (std::size_t k = 0; k < a.positions.size(); ++k) gap = std::max(gap, std::abs(a.positions[k] - b.positions[k]));
  return gap;
}

// Agents in a loose formation whose centre walks with a speed and a heading that change over time, so that the
// temporal features vary from frame to frame (unlike a rigid formation on a circle).
CrowdMotion wandering_group(std::size_t frames, double dt = 0.1) {
  CrowdMotion c = test::marching_grid(3, 4, frames, 1.2, 1.2, dt, 0.0, 0.3, 9);
  Eigen::Vector2d centre(0, 0);
  double heading = 0;
  std::vector<Eigen::Vector2d> offsets;
  for (std::size_t a = 0; a < c.agent_count(); ++a) offsets.emplace_back(c.position(0, a).head<2>());
  for (std::size_t f = 0; f < frames; ++f) {
    const double t = static_cast<double>(f) * dt;
    for (std::size_t a = 0; a < c.agent_count(); ++a) {
      // Each agent sways a little on its own (phase by agent), on top of the group's motion.
      const Eigen::Vector2d sway(0.15 * std::sin(1.3 * t + static_cast<double>(a)), 0.1 * std::cos(0.9 * t + 2.0 * static_cast<double>(a)));
      const Eigen::Vector2d p = centre + Eigen::Rotation2Dd(heading) * (offsets[a] + sway);
      c.position(f, a) << p.x(), p.y(), 0.0;
    }
    const double speed = 1.2 + 0.4 * std::sin(0.7 * t);
    centre += speed * dt * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    heading += (0.3 * std::sin(0.5 * t)) * dt;
  }
  return c;
}

// The second half's agents in another order (perm[k] = the original agent now at index k), with new ids.
CrowdMotion permuted(const CrowdMotion& c, const std::vector<std::size_t>& perm, std::int64_t id_base) {
  CrowdMotion out = take_agents(c, perm);
  for (std::size_t k = 0; k < perm.size(); ++k) out.ids[k] = id_base + static_cast<std::int64_t>(perm[k]);
  return out;
}

std::vector<std::size_t> shuffled(std::size_t n, std::uint64_t seed) {
  std::vector<std::size_t> p(n);
  std::iota(p.begin(), p.end(), 0);
  Rng rng(seed);
  for (std::size_t i = n; i > 1; --i) std::swap(p[i - 1], p[rng.below(i)]);
  return p;
}

// Applies p ↦ R p + t to every position (z kept).
CrowdMotion moved(CrowdMotion c, const Eigen::Isometry2d& m) {
  for (std::size_t f = 0; f < c.frame_count(); ++f) {
    for (std::size_t a = 0; a < c.agent_count(); ++a) c.position(f, a).head<2>() = m * Eigen::Vector2d(c.position(f, a).head<2>());
  }
  return c;
}

}  // namespace

TEST_CASE("split a clip at frame k and stitch the halves: the original comes back") {
  SECTION("a rigid formation on an arc: every feature of the halves is the original's, so the original is exact") {
    // Temporal features of agents turning at a constant rate are the same at every frame, so the joint's
    // interpolated feature is exact too: the least-squares solution is the original, up to rounding in a system
    // of ~2,500 unknowns with positions of ~10 m (1e-9 m is far above rounding and far below any real change).
    const CrowdMotion original = test::marching_grid(4, 5, 61, 1.0, 1.3, 0.1, 0.25, 0.15);
    for (std::size_t step : {1u, 3u}) {
      INFO("sample_step " << step);
      const TimeSplit halves = split_at_frame(original, 25);
      REQUIRE(halves.first.frame_count() == 26);
      REQUIRE(halves.second.frame_count() == 36);
      Options o;
      o.sample_step = step;
      const Result r = stitch_clips(halves.first, halves.second, o);
      REQUIRE(r.crowd.frame_count() == original.frame_count());  // t + t′ − 1
      CHECK(r.crowd.times == original.times);
      CHECK(r.crowd.ids == original.ids);
      CHECK(max_gap(r.crowd, original) <= 1e-9);
      CHECK(r.report.matched_same_id == original.agent_count());
      CHECK(r.report.gap_max <= 1e-12);
    }
  }
  SECTION("a wandering group: only the joint's interpolated temporal feature differs, and the error stays within its size") {
    // Here temporal features change from frame to frame, and the joint's feature (the average of its neighbours',
    // as the paper prescribes) differs from the original's by δc: its target is off by e = |δc| |w − u| for each
    // agent, and that is the only inconsistency. The least-squares solution spreads it over the window (a
    // temporal chain alone would take a tent-shaped offset; the spatiotemporal features resist it), measured at
    // 1.4 e here; the test allows 3 e. Any real fault (features misplaced, a wrong blend, a wrong alignment) moves
    // vertices by centimetres to metres, while e is ~10 µm.
    const CrowdMotion original = wandering_group(81);
    const std::size_t k = 40;
    const TimeSplit halves = split_at_frame(original, k);
    const Result r = stitch_clips(halves.first, halves.second, Options{});
    double e_max = 0;
    FeatureOptions fo;
    for (std::size_t a = 0; a < original.agent_count(); ++a) {
      auto at = [&](std::size_t f) { return Eigen::Vector2d(original.position(f, a).head<2>()); };
      const Feature before = make_feature(0, 1, 2, at(k - 2), at(k - 1), at(k), fo);
      const Feature joint = make_feature(0, 1, 2, at(k - 1), at(k), at(k + 1), fo);
      const Feature after = make_feature(0, 1, 2, at(k), at(k + 1), at(k + 2), fo);
      e_max = std::max(e_max, std::abs(joint.c - 0.5 * (before.c + after.c)) * (at(k + 1) - at(k - 1)).norm());
    }
    double error = 0;
    std::size_t worst_frame = 0;
    for (std::size_t f = 0; f < original.frame_count(); ++f) {
      for (std::size_t a = 0; a < original.agent_count(); ++a) {
        const double e = (r.crowd.position(f, a) - original.position(f, a)).norm();
        if (e > error) error = e, worst_frame = f;
      }
    }
    std::printf("split-and-stitch of a wandering group: joint feature target error e = %.3g m, result error %.3g m "
                "(%.2f e) at frame %zu, joint at %zu\n", e_max, error, error / e_max, worst_frame, k);
    CHECK(e_max > 1e-6);  // the case is not trivial
    CHECK(error <= 3 * e_max);
    CHECK(worst_frame + 3 >= k);  // the error comes from the joint
    CHECK(worst_frame <= k + 3);
    CHECK(r.crowd.position(0, 0) == original.position(0, 0));  // the outer frames are pinned
    CHECK(r.crowd.position(80, 5) == original.position(80, 5));
  }
}

TEST_CASE("the matching recovers a known permutation") {
  SECTION("of points with noise well below their spacing") {
    Rng rng(21);
    const Eigen::Index n = 40;
    Points a(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) a.row(i) << static_cast<double>(i % 8) + rng.uniform(-0.2, 0.2), static_cast<double>(i / 8) + rng.uniform(-0.2, 0.2);
    const std::vector<std::size_t> perm = shuffled(static_cast<std::size_t>(n), 4);
    Points b(n, 2);  // b row k = a row perm[k] plus noise
    for (Eigen::Index k = 0; k < n; ++k) b.row(k) = a.row(static_cast<Eigen::Index>(perm[static_cast<std::size_t>(k)])) + Eigen::RowVector2d(rng.uniform(-0.05, 0.05), rng.uniform(-0.05, 0.05));
    for (Matching m : {Matching::world, Matching::centred}) {
      const Correspondence c = match_boundary(a, b, m);
      for (std::size_t k = 0; k < perm.size(); ++k) CHECK(c.second_of_first[perm[k]] == k);
    }
  }
  SECTION("of the second clip's agents, end to end") {
    const CrowdMotion original = test::marching_grid(4, 5, 51, 1.0, 1.3, 0.1, 0.25, 0.15);
    const TimeSplit halves = split_at_frame(original, 20);
    const std::vector<std::size_t> perm = shuffled(original.agent_count(), 8);
    const Result r = stitch_clips(halves.first, permuted(halves.second, perm, 500), Options{});
    for (std::size_t j = 0; j < original.agent_count(); ++j) CHECK(r.second_ids[j] == 500 + static_cast<std::int64_t>(j));
    CHECK(r.report.matched_same_id == 0);
    CHECK(max_gap(r.crowd, original) <= 1e-9);
  }
  SECTION("end to end: a copy turned by 90 or 180 degrees and placed far away is put back, with either matching") {
    // The walking group's heading gives the start; the fit then matches every agent to itself.
    const CrowdMotion original = wandering_group(61);
    const TimeSplit halves = split_at_frame(original, 30);
    for (double degrees : {90.0, 180.0}) {
      for (Matching m : {Matching::world, Matching::centred}) {
        INFO(degrees << " degrees, matching " << (m == Matching::world ? "world" : "centred"));
        Eigen::Isometry2d away = Eigen::Isometry2d::Identity();
        away.linear() = Eigen::Rotation2Dd(degrees * std::numbers::pi / 180).toRotationMatrix();
        away.translation() << 40.0, 0.0;
        Options o;
        o.matching = m;
        const Result r = stitch_clips(halves.first, moved(halves.second, away), o);
        CHECK(std::abs(std::remainder(r.report.rotation + degrees * std::numbers::pi / 180, 2 * std::numbers::pi)) <= 1e-9);
        CHECK(r.report.matched_same_id == original.agent_count());
        CHECK(r.report.gap_max <= 1e-9);
        // The wandering group's joint feature differs from the original by ~10 µm (see the split-and-stitch test).
        CHECK(max_gap(r.crowd, original) <= 1e-3);
      }
    }
  }
}

TEST_CASE("the alignment recovers a known rotation and translation") {
  Rng rng(2);
  Points from(12, 2);
  for (Eigen::Index i = 0; i < from.rows(); ++i) from.row(i) << rng.uniform(-3, 3), rng.uniform(-2, 2);
  Eigen::Isometry2d truth = Eigen::Isometry2d::Identity();
  truth.linear() = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  truth.translation() << 3.0, -2.0;
  Points to(12, 2);
  for (Eigen::Index i = 0; i < from.rows(); ++i) to.row(i) = (truth * Eigen::Vector2d(from.row(i).transpose())).transpose();
  const Eigen::Isometry2d rigid = align(from, to, Alignment::rigid);
  CHECK((rigid.matrix() - truth.matrix()).cwiseAbs().maxCoeff() <= 1e-12);
  const Eigen::Isometry2d shift = align(from, to, Alignment::translation);
  CHECK(shift.linear().isIdentity());
  CHECK((shift.translation() - (to.colwise().mean() - from.colwise().mean()).transpose()).norm() <= 1e-12);
  CHECK(align(from, to, Alignment::none).matrix().isIdentity());

  SECTION("end to end: the second clip moved and shuffled is put back") {
    const CrowdMotion original = test::marching_grid(4, 5, 51, 1.2, 1.3, 0.1, 0.25, 0.1);
    const TimeSplit halves = split_at_frame(original, 30);
    // 8° moves the formation's outer agents by less than half their spacing: the centred matching is unambiguous.
    Eigen::Isometry2d away = Eigen::Isometry2d::Identity();
    away.linear() = Eigen::Rotation2Dd(8.0 * std::numbers::pi / 180).toRotationMatrix();
    away.translation() << 40.0, 10.0;
    Options o;
    o.matching = Matching::centred;
    const Result r = stitch_clips(halves.first, moved(permuted(halves.second, shuffled(20, 3), 0), away), o);
    const Eigen::Isometry2d back = away.inverse();
    CHECK(r.report.rotation == Approx(-8.0 * std::numbers::pi / 180).epsilon(1e-10));
    CHECK((r.report.translation - back.translation()).norm() <= 1e-9);
    CHECK(max_gap(r.crowd, original) <= 1e-9);
  }
}

TEST_CASE("the boundary fit recovers a clip turned by any angle, where one matching then one alignment does not") {
  // An irregular formation (no symmetry), its copy turned by a large angle, shuffled and moved far away: the
  // single matching pairs agents by where they happen to be; the iterated fit finds the rotation and the
  // permutation exactly (the copy is exact, so the fit's summed distance is rounding only).
  Rng rng(17);
  const Eigen::Index n = 30;
  Points a(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) a.row(i) << rng.uniform(-6, 6), rng.uniform(-2, 2);
  const std::vector<std::size_t> perm = shuffled(static_cast<std::size_t>(n), 11);
  for (double degrees : {90.0, 180.0, -135.0, 60.0}) {
    INFO(degrees << " degrees");
    Eigen::Isometry2d away = Eigen::Isometry2d::Identity();
    away.linear() = Eigen::Rotation2Dd(degrees * std::numbers::pi / 180).toRotationMatrix();
    away.translation() << 40.0, -15.0;
    Points b(n, 2);  // b row k = a row perm[k], moved
    for (Eigen::Index k = 0; k < n; ++k) b.row(k) = (away * Eigen::Vector2d(a.row(static_cast<Eigen::Index>(perm[static_cast<std::size_t>(k)])).transpose())).transpose();
    // The heading says nothing here (zero steps): only the principal axes can give the start.
    for (Matching m : {Matching::world, Matching::centred}) {
      const BoundaryFit fit = fit_boundary(a, b, Headings{}, m, Alignment::rigid);
      for (std::size_t k = 0; k < perm.size(); ++k) CHECK(fit.correspondence.second_of_first[perm[k]] == k);
      CHECK((fit.alignment.matrix() - away.inverse().matrix()).cwiseAbs().maxCoeff() <= 1e-9);
      CHECK(fit.correspondence.total_distance <= 1e-9);
      CHECK(fit.starts >= 2);
    }
    // Matching then aligning once does not get there (the reason for the iteration).
    const Correspondence once = match_boundary(a, b, Matching::centred);
    Points matched(n, 2);
    for (Eigen::Index i = 0; i < n; ++i) matched.row(i) = b.row(static_cast<Eigen::Index>(once.second_of_first[static_cast<std::size_t>(i)]));
    const Eigen::Isometry2d single = align(matched, a, Alignment::rigid);
    double residual = 0;
    for (Eigen::Index i = 0; i < n; ++i) residual += (a.row(i).transpose() - single * Eigen::Vector2d(matched.row(i).transpose())).norm();
    CHECK(residual > 1.0);
  }
}

TEST_CASE("the boundary fit is the same whatever the thread count") {
  // Its runs (the paper's round, each refined start) go side by side: each must be its own.
  Rng rng(19);
  const Eigen::Index n = 400;
  Points a(n, 2), b(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) a.row(i) << rng.uniform(-20, 20), rng.uniform(-5, 5);
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(2.0).toRotationMatrix();
  for (Eigen::Index i = 0; i < n; ++i) b.row(i) = (turn * Eigen::Vector2d(a.row(i).transpose()) + Eigen::Vector2d(30, 4 + rng.uniform(0, 0.3))).transpose();
  BoundaryFit one, two;
  {
    ThreadLimit limit(1);
    one = fit_boundary(a, b, Headings{}, Matching::world, Alignment::rigid);
  }
  {
    ThreadLimit limit(2);
    two = fit_boundary(a, b, Headings{}, Matching::world, Alignment::rigid);
  }
  CHECK(one.starts >= 3);
  CHECK(one.correspondence.second_of_first == two.correspondence.second_of_first);
  CHECK(one.correspondence.total_distance == two.correspondence.total_distance);
  CHECK(one.alignment.matrix() == two.alignment.matrix());
  CHECK(one.rounds == two.rounds);
}

TEST_CASE("of fits as close as each other, the boundary fit keeps the group walking forward") {
  // A 4 × 5 block is the same set of points turned by 180°: G′ = the block walking −x fits G (walking +x) as well
  // as placed (every agent onto the one at its place) as turned around (every agent onto its mirror image).
  Points a(20, 2);
  for (Eigen::Index i = 0; i < 20; ++i) a.row(i) << static_cast<double>(i % 4) - 1.5, static_cast<double>(i / 4) - 2.0;
  const std::vector<std::size_t> perm = shuffled(20, 5);
  Points b(20, 2);
  for (Eigen::Index k = 0; k < 20; ++k) b.row(k) = -a.row(static_cast<Eigen::Index>(perm[static_cast<std::size_t>(k)]));
  Headings walking;
  walking.first << 0.1, 0.0;    // G walks +x
  walking.second << -0.1, 0.0;  // G′ walks −x as given
  for (Matching m : {Matching::world, Matching::centred}) {
    const BoundaryFit forward = fit_boundary(a, b, walking, m, Alignment::rigid);
    CHECK(std::abs(std::remainder(std::atan2(forward.alignment.linear()(1, 0), forward.alignment.linear()(0, 0)) - std::numbers::pi,
                                  2 * std::numbers::pi)) <= 1e-9);
    CHECK(forward.correspondence.total_distance <= 1e-9);
    for (std::size_t k = 0; k < 20; ++k) CHECK(forward.correspondence.second_of_first[perm[k]] == k);  // the mirror image
    // Standing groups say nothing: the tie keeps the placement (the paper's single matching).
    const BoundaryFit placed = fit_boundary(a, b, Headings{}, m, Alignment::rigid);
    CHECK(placed.alignment.linear().isIdentity(1e-9));
    CHECK(placed.correspondence.total_distance <= 1e-9);
    // A deliberate U-turn keeps its placement with alignment translation.
    CHECK(fit_boundary(a, b, walking, m, Alignment::translation).alignment.linear().isIdentity());
  }
}

TEST_CASE("stitching two different formations closes the gap smoothly inside the window and keeps the far ends") {
  // G: a 1 m grid; G′: a 1.6 m grid walking on: the formations differ, so the joint has a gap to close.
  const CrowdMotion g = test::marching_grid(3, 4, 31, 1.0, 1.3, 0.1, 0.0, 0.05, 1);
  CrowdMotion g2 = test::marching_grid(3, 4, 41, 1.6, 1.3, 0.1, 0.0, 0.05, 2);
  const double shift = g.position(30, 0).x() - g2.position(0, 0).x();
  for (std::size_t f = 0; f < g2.frame_count(); ++f) {
    g2.times[f] += 10;
    for (std::size_t a = 0; a < g2.agent_count(); ++a) g2.position(f, a).x() += shift;
  }
  auto max_step = [](const CrowdMotion& c, std::size_t first, std::size_t last) {
    double m = 0;
    for (std::size_t f = first; f < last; ++f) {
      for (std::size_t a = 0; a < c.agent_count(); ++a) m = std::max(m, (c.position(f + 1, a) - c.position(f, a)).norm());
    }
    return m;
  };
  const std::size_t step = GENERATE(1u, 4u);
  INFO("sample_step " << step);
  Options base;
  base.sample_step = step;
  base.guard.enabled = false;  // the blend itself (the guard's own test is below)
  const Result r = stitch_clips(g, g2, base);
  REQUIRE(r.crowd.frame_count() == 31 + 41 - 1);
  CHECK(r.crowd.times[30] == g.times[30]);
  CHECK(r.crowd.times.back() == Approx(g.times[30] + 4.0).epsilon(1e-12));
  CHECK(r.report.gap_max > 0.3);
  // The outer frames are pinned where the clips put them.
  for (std::size_t a = 0; a < 12; ++a) {
    CHECK((r.crowd.position(0, a) - g.position(0, a)).norm() <= 1e-9);
    const std::size_t b = static_cast<std::size_t>(std::find(g2.ids.begin(), g2.ids.end(), r.second_ids[a]) - g2.ids.begin());
    CHECK((r.crowd.position(70, a).head<2>() - r.alignment * Eigen::Vector2d(g2.position(40, b).head<2>())).norm() <= 1e-9);
  }
  // Smooth: no frame-to-frame step much beyond the walk's 0.13 m plus the gap spread over the window (f_a's
  // slope is at most 1.5/W), whereas gluing the clips would jump by the whole gap at the joint. With samples
  // every 4th frame this holds at the frames between samples too (they follow Ḡ, which has no jump).
  const double walk = std::max(max_step(g, 0, 30), max_step(g2, 0, 40));
  const double spread = 1.5 * r.report.gap_max / static_cast<double>(std::min(r.report.window_first, r.report.window_second));
  CHECK(max_step(r.crowd, 0, 70) <= walk + 2 * spread);
  CHECK(walk + 2 * spread < r.report.gap_max);
  // A shorter window changes only frames within it.
  Options o = base;
  o.blend_window = 0.6;  // seconds: 6 frames of 0.1 s
  const Result short_window = stitch_clips(g, g2, o);
  for (std::size_t f = 0; f < 71; ++f) {
    if (f > 30 - 6 && f < 30 + 6) continue;
    for (std::size_t a = 0; a < 12; ++a) {
      const Eigen::Vector2d input = f <= 30 ? Eigen::Vector2d(g.position(f, a).head<2>())
                                            : Eigen::Vector2d(short_window.alignment * Eigen::Vector2d(g2.position(f - 30, static_cast<std::size_t>(std::find(g2.ids.begin(), g2.ids.end(), short_window.second_ids[a]) - g2.ids.begin())).head<2>()));
      CHECK((short_window.crowd.position(f, a).head<2>() - input).norm() <= 1e-12);
    }
  }
  if (step == 1) CHECK(short_window.report.solved_samples == 2 * 6 - 1 + 2);
  if (step == 4) CHECK(short_window.report.solved_samples == 2 * 2 - 1 + 2);  // joint ± 4 free, the window's edges ± 6 pinned
}

TEST_CASE("the blending window is a duration: the whole clips by default, shortened only past the vertex budget") {
  // The same motion sampled at 10 and at 20 frames per second: a 0.6-s window spans 6 and 12 frames.
  for (double dt : {0.1, 0.05}) {
    const auto frames = static_cast<std::size_t>(std::lround(4.0 / dt)) + 1;
    const CrowdMotion g = test::marching_grid(3, 4, frames, 1.0, 1.3, dt, 0.0, 0.05, 1);
    const TimeSplit halves = split_at_frame(g, frames / 2);
    Options o;
    o.blend_window = 0.6;
    const Result r = stitch_clips(halves.first, halves.second, o);
    INFO("dt " << dt);
    CHECK(r.report.window_first == static_cast<std::size_t>(std::lround(0.6 / dt)));
    CHECK(r.report.window_second == r.report.window_first);
    CHECK(r.report.window_first_s == 0.6);
    CHECK_FALSE(r.report.window_limited);
  }
  const CrowdMotion g = test::marching_grid(3, 4, 31, 1.0, 1.3, 0.1, 0.0, 0.05, 1);
  const CrowdMotion g2 = test::marching_grid(3, 4, 41, 1.6, 1.3, 0.1, 0.0, 0.05, 2);
  SECTION("automatic, within the budget: each clip's whole duration (the paper's window)") {
    const Result r = stitch_clips(g, g2, Options{});
    CHECK(r.report.window_first == 30);
    CHECK(r.report.window_second == 40);
    CHECK(r.report.window_first_s == Approx(3.0).epsilon(1e-12));
    CHECK(r.report.window_second_s == Approx(4.0).epsilon(1e-12));
    CHECK(r.report.solved_samples == 71);
    CHECK(r.report.whole_clip_vertices == 12 * 71);
    CHECK_FALSE(r.report.window_limited);
  }
  SECTION("automatic, past the budget: the longest common window that fits") {
    Options o;
    o.guard.enabled = false;  // the window itself
    o.max_blend_vertices = 12 * 25;  // 25 samples of the 12 agents: the joint, 11 free on each side, 2 pinned edges
    const Result r = stitch_clips(g, g2, o);
    CHECK(r.report.window_limited);
    CHECK(r.report.whole_clip_vertices == 12 * 71);
    CHECK(r.report.solved_samples * 12 <= o.max_blend_vertices);
    CHECK(r.report.solved_samples == 25);
    CHECK(r.report.window_first == 12);
    CHECK(r.report.window_second == 12);
    // Frames beyond the window keep their input.
    for (std::size_t a = 0; a < 12; ++a) CHECK((r.crowd.position(30 - 12, a) - g.position(30 - 12, a)).norm() <= 1e-12);
    o.max_blend_vertices = 1;  // less than any window: one sample step per side remains
    const Result tiny = stitch_clips(g, g2, o);
    CHECK(tiny.report.solved_samples == 3);
    CHECK(tiny.report.window_first == 1);
  }
}

TEST_CASE("the guard keeps a sharp stitch within the speed and acceleration limits, and reports it") {
  // Two formations that differ (a 1 m and a 1.6 m grid) blended over 0.6 s: closing the gap that fast makes the
  // outer agents faster and bends their paths sharply. Judged by the independent checker against the clips'
  // own motion: speed ≤ 1.25 × the faster clip's fastest, acceleration ≤ 3 m/s² wherever the clips were below.
  const CrowdMotion g = test::marching_grid(3, 4, 31, 1.0, 1.3, 0.1, 0.0, 0.05, 1);
  CrowdMotion g2 = test::marching_grid(3, 4, 41, 1.6, 1.3, 0.1, 0.0, 0.05, 2);
  const double shift = g.position(30, 0).x() - g2.position(0, 0).x();
  for (std::size_t f = 0; f < g2.frame_count(); ++f) {
    g2.times[f] += 10;
    for (std::size_t a = 0; a < g2.agent_count(); ++a) g2.position(f, a).x() += shift;
  }
  const check::Settings settings;
  const double source_speed = std::max(check::measure(g, {}, settings).speed.max, check::measure(g2, {}, settings).speed.max);
  const double source_acceleration =
      std::max(check::measure(g, {}, settings).acceleration.max, check::measure(g2, {}, settings).acceleration.max);
  check::Limits limits;
  limits.max_speed = 1.25 * source_speed;
  limits.max_acceleration = limits.acceleration_p99 = std::max(3.0, source_acceleration);
  Options o;
  o.blend_window = 0.6;
  o.guard.enabled = false;
  const Result raw = stitch_clips(g, g2, o);
  const check::Verdict before = check::check(check::measure(raw.crowd, {}, settings), limits);
  REQUIRE_FALSE(before.passed());  // the problem is there without the guard
  o.guard.enabled = true;
  const Result guarded = stitch_clips(g, g2, o);
  const check::Statistics after = check::measure(guarded.crowd, {}, settings);
  INFO("speed " << after.speed.max << " (limit " << limits.max_speed << "), acceleration " << after.acceleration.max);
  for (const check::Violation& v : check::check(after, limits).violations) INFO(check::describe(v));
  CHECK(check::check(after, limits).passed());
  const timewarp::GuardReport& r = guarded.report.guard;
  CHECK((r.warped || r.windows > 0));
  CHECK(r.kinks_after == 0);
  CHECK(r.speed_limit == Approx(limits.max_speed));
  CHECK(r.max_speed_after <= r.speed_limit * (1 + 1e-6));
  if (r.warped) CHECK(guarded.crowd.times.back() > raw.crowd.times.back());  // slowed down: a longer clip
  // The guard leaves the clips' far ends: the first frame is untouched.
  for (std::size_t a = 0; a < 12; ++a) CHECK((guarded.crowd.position(0, a) - g.position(0, a)).norm() <= 1e-9);
}

TEST_CASE("formation edits by agent id of the first clip act at the solved samples in their frames") {
  const CrowdMotion g = test::marching_grid(3, 4, 31, 1.0, 1.3, 0.1, 0.0, 0.05, 1);
  CrowdMotion g2 = test::marching_grid(3, 4, 41, 1.6, 1.3, 0.1, 0.0, 0.05, 2);
  for (std::size_t f = 0; f < g2.frame_count(); ++f) g2.times[f] += 10;
  Options o;
  o.blend_window = 1.0;
  const Result plain = stitch_clips(g, g2, o);
  // Removing the edge between two neighbours changes Ḡ's triangles, so the solve, inside the window only.
  o.formation.edits.push_back({g.ids[0], g.ids[1], 0, std::numeric_limits<std::size_t>::max(), false});
  const Result removed = stitch_clips(g, g2, o);
  CHECK(removed.report.formation_edits == 1);
  CHECK(removed.report.spatial_features < plain.report.spatial_features);
  CHECK(max_gap(removed.crowd, plain.crowd) > 1e-6);
  // An edit whose frames hold no solved sample changes nothing.
  o.formation.edits.back().first_frame = 0;
  o.formation.edits.back().last_frame = 15;
  const Result outside = stitch_clips(g, g2, o);
  CHECK(outside.report.formation_edits == 0);
  CHECK(outside.crowd.positions == plain.crowd.positions);
  // An id the first clip does not have: ConfigError naming the edit.
  o.formation.edits.back().agent_b = 99999;
  CHECK_THROWS_AS(stitch_clips(g, g2, o), ConfigError);
  CHECK_THROWS_WITH(stitch_clips(g, g2, o), Catch::Contains("formation.edits[0]") && Catch::Contains("99999"));
}

TEST_CASE("a stitched clip has the same bits with one thread and with two") {
  const CrowdMotion a = wandering_group(40);
  const CrowdMotion b = wandering_group(50);
  Options o;
  o.matching = Matching::centred;
  o.sample_step = 2;
  Result one, two;
  {
    ThreadLimit limit(1);
    one = stitch_clips(a, b, o);
  }
  {
    ThreadLimit limit(2);
    two = stitch_clips(a, b, o);
  }
  CHECK(one.crowd.positions == two.crowd.positions);
  CHECK(one.second_ids == two.second_ids);
}

TEST_CASE("a single agent stitches like its trajectory") {
  const CrowdMotion one = take_agents(test::marching_grid(1, 3, 41, 1.0, 1.3, 0.1, 0.3, 0.0), {1});
  const TimeSplit halves = split_at_frame(one, 15);
  const Result r = stitch_clips(halves.first, halves.second, Options{});
  CHECK(max_gap(r.crowd, one) <= 1e-9);
}

TEST_CASE("mismatched agent counts, too-short clips and bad options are errors naming the problem") {
  const CrowdMotion a = test::marching_grid(3, 4, 20);
  const CrowdMotion b = test::marching_grid(3, 5, 20);
  CHECK_THROWS_AS(stitch_clips(a, b, Options{}), InputError);
  CHECK_THROWS_WITH(stitch_clips(a, b, Options{}), Catch::Contains("12 agents") && Catch::Contains("the second 15"));
  // An agent absent at one frame is left out: the counts then differ, and the message lists it.
  CrowdMotion gappy = a;
  gappy.position(5, 2) << absent, absent, absent;
  CHECK_THROWS_WITH(stitch_clips(gappy, a, Options{}), Catch::Contains("left out: first 102"));
  CHECK_THROWS_WITH(stitch_clips(slice_frames(a, 0, 1), take_agents(a, {0}), Options{}), Catch::Contains("12 agents"));
  CrowdMotion single = a;
  single.times.resize(1);
  single.positions.resize(12 * 3);
  CHECK_THROWS_WITH(stitch_clips(single, a, Options{}), Catch::Contains("1 frame(s)"));
  Options o;
  o.sample_step = 0;
  CHECK_THROWS_AS(stitch_clips(a, a, o), ConfigError);
  o = Options{};
  o.weights.beta = -1;
  CHECK_THROWS_WITH(stitch_clips(a, a, o), Catch::Contains("beta"));
  // Numbers in messages are written in their shortest exact form ("-10", not "-1e+01").
  o.weights.beta = -10;
  CHECK_THROWS_WITH(stitch_clips(a, a, o), Catch::Contains("beta -10:"));
  o = Options{};
  o.blend_window = -0.25;
  CHECK_THROWS_WITH(stitch_clips(a, a, o), Catch::Contains("blend_window -0.25:"));
}
