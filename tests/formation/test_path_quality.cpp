// Path quality: keyframes whose individuals keep their order round the formation are joined by direct paths
// (close to the straight ones, inside the keyframes' extent), and so are the example configs'. The loops of a
// formation made to become its mirror image (which the method, interpolating rotations, can only reach by
// turning round) are what these measures catch: before the configs were laid out in one order, the marching
// band's paths were 1.68 times the straight distance in its worst interval and left the keyframes' extent by
// 5.6 m; the airshow with the PCA adjustment (about its barycentre) leaves it by 63 m.
#include <throng/core/random.h>
#include <throng/formation/formation.h>
#include <throng/io/config.h>
#include <throng/io/formation_job.h>

#include "test_paths.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace throng;
using namespace throng::formation;

namespace {

struct Quality {
  double ratio = 0.0;      // Σ path lengths / Σ straight distances over the individuals, in one interval
  double excursion = 0.0;  // farthest any individual goes outside the bounding box of the two keyframes (m)
  double extent = 0.0;     // the larger side of that box (m)
};

// Frames first..last of `m` (d coordinates); `relative`: about the formation's barycentre at every frame.
Quality interval_quality(const CrowdMotion& m, std::size_t first, std::size_t last, int d, bool relative) {
  auto at = [&](std::size_t f) {
    Eigen::MatrixXd p = m.frame(f).leftCols(d);
    if (relative) p.rowwise() -= p.colwise().mean();
    return p;
  };
  const Eigen::MatrixXd a = at(first), b = at(last);
  const Eigen::RowVectorXd lo = a.colwise().minCoeff().cwiseMin(b.colwise().minCoeff());
  const Eigen::RowVectorXd hi = a.colwise().maxCoeff().cwiseMax(b.colwise().maxCoeff());
  Quality q;
  q.extent = (hi - lo).maxCoeff();
  double path = 0.0;
  Eigen::MatrixXd previous = a;
  for (std::size_t f = first; f <= last; ++f) {
    const Eigen::MatrixXd p = at(f);
    path += (p - previous).rowwise().norm().sum();
    previous = p;
    const Eigen::MatrixXd below = (p.rowwise() - lo).cwiseMin(0.0).cwiseAbs();
    const Eigen::MatrixXd above = (p.rowwise() - hi).cwiseMax(0.0);
    q.excursion = std::max({q.excursion, below.maxCoeff(), above.maxCoeff()});
  }
  q.ratio = path / (b - a).rowwise().norm().sum();
  return q;
}

Quality worst_interval(const Result& r, int d, bool relative) {
  Quality worst;
  for (std::size_t k = 0; k + 1 < r.keyframe_frames.size(); ++k) {
    const Quality q = interval_quality(r.motion, r.keyframe_frames[k], r.keyframe_frames[k + 1], d, relative);
    worst.ratio = std::max(worst.ratio, q.ratio);
    if (q.excursion / q.extent >= worst.excursion / std::max(worst.extent, 1e-300)) {
      worst.excursion = q.excursion;
      worst.extent = q.extent;
    }
  }
  return worst;
}

Eigen::MatrixXd ring(int n, double radius, double first_deg, double step_deg, Eigen::RowVector2d centre = {0, 0}) {
  Eigen::MatrixXd p(n, 2);
  for (int i = 0; i < n; ++i) {
    const double a = (first_deg + step_deg * i) * std::numbers::pi / 180.0;
    p.row(i) = centre + radius * Eigen::RowVector2d(std::cos(a), std::sin(a));
  }
  return p;
}

Result two_keyframes(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, from, {}});
  p.keyframes.push_back(Keyframe{8.0, to, {}});
  return animate_formation(p, Options{});
}

}  // namespace

TEST_CASE("keyframes in one order round the formation are joined by direct paths and a mirror image loops") {
  SECTION("a block translating and turning by 90°: the rigid path, about its barycentre an arc of 90°") {
    Eigen::MatrixXd block(12, 2);
    for (int i = 0; i < 12; ++i) block.row(i) = Eigen::RowVector2d(1.5 * (i % 4) - 2.25, 1.5 * (i / 4) - 1.5);
    Eigen::MatrixXd turned(12, 2);
    turned.col(0) = -block.col(1).array() + 10.0;
    turned.col(1) = block.col(0).array() + 4.0;
    const Quality q = worst_interval(two_keyframes(block, turned), 2, true);
    CHECK(q.ratio == Catch::Detail::Approx(std::numbers::pi / 4 / std::sin(std::numbers::pi / 4)).epsilon(1e-3));
    // A corner, √(2.25² + 1.5²) m from the barycentre, swings past the box's side at 2.25 m: no farther.
    CHECK(q.excursion <= std::hypot(2.25, 1.5) - 2.25 + 1e-6);
  }
  // A line of 9 curling into a circle: its middle at the bottom, its ends meeting at the top.
  const Eigen::MatrixXd line = [] {
    Eigen::MatrixXd p = Eigen::MatrixXd::Zero(9, 2);
    for (int i = 0; i < 9; ++i) p(i, 0) = 1.5 * (i - 4);
    return p;
  }();
  SECTION("a line curling into a circle in its own order") {
    const Quality q = worst_interval(two_keyframes(line, ring(9, 3.0, 270.0 - 4 * 40.0, 40.0)), 2, true);
    CHECK(q.ratio <= 1.1);  // measured 1.04
    CHECK(q.excursion <= 0.05 * q.extent);
  }
  SECTION("a circle opening into an arc of a larger circle, pointing the way the arc goes") {
    const Eigen::MatrixXd arc = ring(5, 7.0, 30.0, 14.4, {0, -7});
    const Quality q = worst_interval(two_keyframes(ring(5, 1.4, 58.8 - 144.0, 72.0), arc), 2, true);
    // Measured 1.252, before Eq. 5's cumulative form (46f5216) as after: for two keyframes both forms are
    // M(t) = M_0 G^{s(t)}, and the ratio is the same for every tension, orientation and reordering option (1.254
    // unordered). The ends, 74% of the straight distance, go nearly straight (1.08 and 1.10); the middle three,
    // 0.46-0.97 m from their targets, bow out ~0.3 m while the circle opens (1.46-2.35). An earlier comment's 1.20
    // was never a run (the test was not registered). Bound: 1.3, 4% over the measure, far below the mirror's 1.91.
    CHECK(q.ratio <= 1.3);
    CHECK(q.excursion <= 0.05 * q.extent);
  }
  SECTION("the same keyframes, the circle going round the other way: the paths loop") {
    const Eigen::MatrixXd arc = ring(5, 7.0, 30.0, 14.4, {0, -7});
    const Quality q = worst_interval(two_keyframes(ring(5, 1.4, 58.8 + 144.0, -72.0), arc), 2, true);
    CHECK(q.ratio >= 1.5);  // measured 1.91
  }
}

TEST_CASE("the example configs' paths are direct: the marching band and the airshow") {
  auto run = [](const char* name) {
    const FormationJob job = read_job<FormationJob>(ConfigNode::load_file(test::source_dir() / "configs" / name));
    return animate_formation(job.problem, job.options);
  };
  {
    INFO("marching band, in the field");
    const Quality q = worst_interval(run("formation-marching-band.yaml"), 2, false);
    CHECK(q.ratio <= 1.15);     // measured 1.078 (1.68 with the earlier layout)
    CHECK(q.excursion <= 1.5);  // measured 0.785 m (5.6 m)
  }
  {
    INFO("airshow, about the formation's barycentre");
    const Quality q = worst_interval(run("formation-airshow.yaml"), 3, true);
    CHECK(q.ratio <= 2.0);                 // measured 1.81 (with the PCA adjustment 1.60, but see below)
    CHECK(q.excursion <= 0.2 * q.extent);  // measured 16.0 m of 123 m (with the PCA adjustment 63 m of 120 m)
  }
}

TEST_CASE("the 1,260-individual hierarchy: the groups' paths are direct but for the spline's bulge") {
  // Measured on the 35 top-level groups' centres (Σ path / Σ straight per interval): 1.51, 1.20, 1.36 at the
  // config's tension 0.5 (worst groups 5.3, 2.9 and 4.1 times their own straight distance), 1.05, 1.18, 1.31 at
  // tension 0. The spectral paths are direct; what tension adds in the circle → star interval is Catmull-Rom's:
  // the tangent at the star, τ(p_runner − p_circle), carries the star → runner move (44 m on average per group)
  // into an interval whose own move is 9 m, so the groups bulge out and back (worst 1.49 at τ = 0, 5.3 at 0.5).
  // Bounds 5-10% over the measures.
  const FormationJob job =
      read_job<FormationJob>(ConfigNode::load_file(test::source_dir() / "configs" / "formation-hierarchy-1260.yaml"));
  auto group_ratios = [](const Result& r) {
    std::vector<std::vector<int>> groups;
    for (const Group& g : r.hierarchy.subgroups) {
      std::vector<int> all;
      std::vector<const Group*> stack{&g};
      while (!stack.empty()) {
        const Group* top = stack.back();
        stack.pop_back();
        all.insert(all.end(), top->members.begin(), top->members.end());
        for (const Group& child : top->subgroups) stack.push_back(&child);
      }
      groups.push_back(std::move(all));
    }
    auto centres = [&](std::size_t f) {
      Eigen::MatrixXd c(static_cast<Eigen::Index>(groups.size()), 2);
      for (std::size_t g = 0; g < groups.size(); ++g) {
        Eigen::RowVector2d sum(0, 0);
        for (int i : groups[g]) sum += r.motion.position(f, static_cast<std::size_t>(i)).head<2>().transpose();
        c.row(static_cast<Eigen::Index>(g)) = sum / static_cast<double>(groups[g].size());
      }
      return c;
    };
    std::vector<double> ratios;
    for (std::size_t k = 0; k + 1 < r.keyframe_frames.size(); ++k) {
      const std::size_t a = r.keyframe_frames[k], b = r.keyframe_frames[k + 1];
      double path = 0.0;
      Eigen::MatrixXd previous = centres(a);
      for (std::size_t f = a + 1; f <= b; ++f) {
        const Eigen::MatrixXd c = centres(f);
        path += (c - previous).rowwise().norm().sum();
        previous = c;
      }
      ratios.push_back(path / (centres(b) - centres(a)).rowwise().norm().sum());
    }
    return ratios;
  };
  REQUIRE(job.problem.keyframes.size() == 4);
  REQUIRE(job.options.tension == 0.5);
  const std::vector<double> eased = group_ratios(animate_formation(job.problem, job.options));
  REQUIRE(eased.size() == 3);
  CHECK(eased[0] <= 1.6);   // measured 1.51
  CHECK(eased[1] <= 1.3);   // measured 1.20
  CHECK(eased[2] <= 1.45);  // measured 1.36
  Options stopping = job.options;
  stopping.tension = 0.0;
  const std::vector<double> direct = group_ratios(animate_formation(job.problem, stopping));
  CHECK(direct[0] <= 1.1);   // measured 1.05
  CHECK(direct[1] <= 1.25);  // measured 1.18
  CHECK(direct[2] <= 1.4);   // measured 1.31
}

TEST_CASE("with tension 0 each interval of several keyframes is the two-keyframe transition between its ends") {
  // τ = 0 gives the neighbours no weight (c−1 = c2 = 0), so the interval n → n+1 must not depend on them: the
  // eigenbasis follows the rotation between M_n and M_{n+1} only. The paper's product (R1 R0)^{c1} R0^{c0} M_{n−1}
  // leaves that path when R0 and R1 do not commute (for these 2-D keyframes by 1.1 and 1.2 m in intervals 1
  // and 2); Eq. 5 in cumulative form, R1^{c1} R0 M_{n−1} = R1^{c1} M_n, does not. The same holds in 3-D for the
  // coefficient directions and the orientation (there the product form did not even reduce to the slerp).
  // The pairing of eigenvectors must not depend on the earlier keyframes either: greedy reordering visits the
  // source keyframe's vectors in its own eigenvalue order. When it visited them in the column order the chain
  // inherited from keyframe 0, the random keyframes' intervals 1 and 2 left their two-keyframe paths by 6.5 and
  // 4.8 m. What is left is rounding: the chain's bases differ from the pair's by signs, ~1e-14 m measured.
  auto constructed = [](int d) {
    Problem four;
    for (int k = 0; k < 4; ++k) {
      Eigen::MatrixXd p(10, d);
      for (int i = 0; i < 10; ++i) {
        const double a = 0.7 * i + 1.3 * k * k + 0.4 * k;
        p(i, 0) = (2.0 + 0.3 * i) * std::cos(a) + 3.0 * k;
        p(i, 1) = (1.0 + 0.2 * ((i * (k + 3)) % 7)) * std::sin(a);
        if (d == 3) p(i, 2) = 0.5 * ((i * (k + 2)) % 5) + 0.3 * k * std::cos(1.1 * i);
      }
      four.keyframes.push_back(Keyframe{2.0 * k, p, {}});
    }
    return four;
  };
  const Problem random = [] {  // 20 individuals scattered in a 10 m square, a new scatter at each keyframe
    Rng rng(7);
    Problem four;
    for (int k = 0; k < 4; ++k) {
      Eigen::MatrixXd p(20, 2);
      for (int i = 0; i < 20; ++i) p.row(i) << rng.uniform(-5, 5), rng.uniform(-5, 5);
      four.keyframes.push_back(Keyframe{2.0 * k, p, {}});
    }
    return four;
  }();
  struct Case {
    const char* name;
    Problem four;
  };
  for (const Case& c : {Case{"constructed 2-D", constructed(2)}, Case{"constructed 3-D", constructed(3)}, Case{"random 2-D", random}}) {
    for (Reordering reordering : {Reordering::none, Reordering::greedy, Reordering::max_min}) {
      Options o;
      o.tension = 0.0;
      o.reordering = reordering;
      const Result all = animate_formation(c.four, o);
      for (std::size_t n = 0; n < 3; ++n) {
        INFO(c.name << ", reordering " << static_cast<int>(reordering) << ", interval " << n);
        Problem two;
        two.keyframes = {c.four.keyframes[n], c.four.keyframes[n + 1]};
        const Result alone = animate_formation(two, o);
        const std::size_t first = all.keyframe_frames[n];
        double worst = 0.0;
        for (std::size_t f = 0; f < alone.motion.frame_count(); ++f)
          worst = std::max(worst, (all.motion.frame(first + f) - alone.motion.frame(f)).cwiseAbs().maxCoeff());
        CHECK(worst <= 1e-9);
      }
    }
  }
}
