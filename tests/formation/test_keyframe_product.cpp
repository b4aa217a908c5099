// Eq. 5 for the eigenbases through several keyframes (Options::keyframe_product): the paper's powers of products
// and the cumulative form, each against its formula evaluated here with Eigen's matrix powers, both through the
// keyframes, and where they differ.
#include <throng/formation/formation.h>

#include "fixtures.h"
#include "spectral_group.h"
#include "spline_reference.h"

#include <unsupported/Eigen/MatrixFunctions>

#include <catch2/catch.hpp>

using namespace throng::formation;

namespace {

constexpr int individuals = 10;

std::vector<Eigen::MatrixXd> three_formations() {
  std::vector<Eigen::MatrixXd> out;
  for (int k = 0; k < 3; ++k) out.push_back(throng::test::scattered(individuals, 2.0 + 0.5 * k, 300 + static_cast<std::uint64_t>(k), 0.6));
  return out;
}

SpectralGroup group_of(const std::vector<Eigen::MatrixXd>& formations, const Options& options) {
  GroupKeyframes g;
  for (const Eigen::MatrixXd& x : formations) {
    g.positions.push_back(x);
    g.anchors.push_back(x.colwise().mean().transpose());
    g.edits.emplace_back();
  }
  g.what = "test";
  for (int i = 0; i < individuals; ++i) g.item_names.push_back("individual " + std::to_string(i));
  return SpectralGroup(g, options);
}

Eigen::MatrixXd power(const Eigen::MatrixXd& r, double c) { return Eigen::MatrixPower<Eigen::MatrixXd>(Eigen::MatrixXd(r))(c); }

}  // namespace

TEST_CASE("Eq. 5 through three keyframes: each product is its formula, both pass through every keyframe's basis, "
          "and they differ between keyframes") {
  const std::vector<Eigen::MatrixXd> formations = three_formations();
  Options paper_options;
  paper_options.keyframe_product = KeyframeProduct::paper;
  const SpectralGroup paper = group_of(formations, paper_options);
  const SpectralGroup cumulative = group_of(formations, Options{});
  const double tol = 1e-9;
  double largest_difference = 0.0;
  for (int segment = 0; segment < 2; ++segment) {
    const auto keys = throng::test::eq5_keys(segment, 3);
    auto m = [&](int i) -> const Eigen::MatrixXd& { return paper.aligned_basis(keys[static_cast<std::size_t>(i)]); };
    // R0: n−1 → n, R1: n → n+1, R2: n+1 → n+2 (the identity where a keyframe is duplicated).
    const Eigen::MatrixXd r0 = m(1) * m(0).transpose(), r1 = m(2) * m(1).transpose(), r2 = m(3) * m(2).transpose();
    for (double t : {0.0, 0.2, 0.5, 0.9, 1.0}) {
      INFO("segment " << segment << " t " << t);
      const auto c = throng::test::eq5_weights(t, 0.5);
      const Eigen::MatrixXd printed = power(r2 * r1 * r0, c[3]) * power(r1 * r0, c[2]) * power(r0, c[1]) * m(0);
      const Eigen::MatrixXd cumulated = power(r2, c[3]) * power(r1, c[2] + c[3]) * power(r0, c[1] + c[2] + c[3]) * m(0);
      CHECK((paper.eigenbasis_at(segment, t) - printed).cwiseAbs().maxCoeff() <= tol);
      CHECK((cumulative.eigenbasis_at(segment, t) - cumulated).cwiseAbs().maxCoeff() <= tol);
      largest_difference = std::max(largest_difference, (printed - cumulated).cwiseAbs().maxCoeff());
    }
    for (const SpectralGroup* g : {&paper, &cumulative}) {
      CHECK((g->eigenbasis_at(segment, 0.0) - g->aligned_basis(segment)).cwiseAbs().maxCoeff() <= tol);
      CHECK((g->eigenbasis_at(segment, 1.0) - g->aligned_basis(segment + 1)).cwiseAbs().maxCoeff() <= tol);
    }
  }
  // The three keyframes' rotations do not commute: the two readings of Eq. 5 are different paths.
  CHECK(largest_difference >= 0.01);
  // The aligned bases are the same whichever product (the product only changes the path between them).
  for (int k = 0; k < 3; ++k) CHECK(paper.aligned_basis(k) == cumulative.aligned_basis(k));
}

TEST_CASE("Eq. 5 at tension 0: the cumulative form keeps each interval on its two keyframes' path, the paper's "
          "product does not, and with two keyframes they agree") {
  const std::vector<Eigen::MatrixXd> formations = three_formations();
  Problem three, last_two;
  for (int k = 0; k < 3; ++k) three.keyframes.push_back(Keyframe{2.0 * k, formations[static_cast<std::size_t>(k)], {}});
  last_two.keyframes = {Keyframe{0.0, formations[1], {}}, Keyframe{2.0, formations[2], {}}};
  Options o;
  o.tension = 0.0;
  o.frame_rate_hz = 10;
  const Result two = animate_formation(last_two, o);
  double cumulative_off = 0.0, paper_off = 0.0;
  for (KeyframeProduct product : {KeyframeProduct::cumulative, KeyframeProduct::paper}) {
    o.keyframe_product = product;
    const Result r = animate_formation(three, o);
    for (std::size_t k = 0; k < 3; ++k)
      CHECK((r.motion.frame(r.keyframe_frames[k]).leftCols(2) - formations[k]).cwiseAbs().maxCoeff() <= 1e-10);
    double off = 0.0;  // interval 1 (keyframes 1 → 2) against the two-keyframe run, frame by frame
    for (std::size_t f = 0; f <= 20; ++f)
      off = std::max(off, (r.motion.frame(20 + f) - two.motion.frame(f)).cwiseAbs().maxCoeff());
    (product == KeyframeProduct::cumulative ? cumulative_off : paper_off) = off;
    // Two keyframes: one rotation, the same path either way.
    const Result pair = animate_formation(last_two, o);
    double apart = 0.0;
    for (std::size_t f = 0; f < pair.motion.frame_count(); ++f)
      apart = std::max(apart, (pair.motion.frame(f) - two.motion.frame(f)).cwiseAbs().maxCoeff());
    CHECK(apart <= 1e-10);
  }
  CHECK(cumulative_off <= 1e-10);
  CHECK(paper_off >= 0.01);  // metres: keyframe 0 pulls the paper's interval 1 off the direct path
}
