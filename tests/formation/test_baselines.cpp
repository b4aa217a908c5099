// The paper's baselines (Interpolation::linear and ::polar; its Figures 3, 5 and 9): what each interpolates,
// checked against the definitions written out here.
#include <throng/formation/formation.h>

#include "fixtures.h"
#include "spline_reference.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

using namespace throng::formation;
using throng::test::eps;

namespace {

Problem scattered_keyframes(int n, int count, int dimension = 2) {
  Problem p;
  for (int k = 0; k < count; ++k) {
    Keyframe key;
    key.time_s = 2.0 * k + 0.5 * k * k;  // uneven intervals
    key.positions = throng::test::scattered(n, 3.0 + k, 70 + static_cast<std::uint64_t>(k), 0.5, dimension);
    key.positions.col(0).array() += 4.0 * k;
    p.keyframes.push_back(key);
  }
  return p;
}

// The interval and local parameter of each output frame (every keyframe time is a frame; the last frame ends
// the last interval).
struct FramePlace {
  int segment;
  double t;
};
std::vector<FramePlace> places(const Result& r) {
  std::vector<FramePlace> out;
  const auto& kf = r.keyframe_frames;
  for (std::size_t f = 0; f < r.motion.frame_count(); ++f) {
    int s = 0;
    while (s + 2 < static_cast<int>(kf.size()) && f >= kf[static_cast<std::size_t>(s) + 1]) ++s;
    const double t = static_cast<double>(f - kf[static_cast<std::size_t>(s)]) /
                     static_cast<double>(kf[static_cast<std::size_t>(s) + 1] - kf[static_cast<std::size_t>(s)]);
    out.push_back({s, t});
  }
  return out;
}

double wrap(double a) { return std::remainder(a, 2 * std::numbers::pi); }

}  // namespace

TEST_CASE("linear baseline: every individual on the Catmull-Rom spline of its own keyframe positions") {
  for (int dimension : {2, 3}) {
    const Problem p = scattered_keyframes(30, 4, dimension);
    for (double tension : {0.0, 0.5, 1.0}) {
      INFO("dimension " << dimension << " tension " << tension);
      Options o;
      o.interpolation = Interpolation::linear;
      o.tension = tension;
      o.frame_rate_hz = 8;
      const Result r = animate_formation(p, o);
      double worst = 0.0;
      const std::vector<FramePlace> at = places(r);
      for (std::size_t f = 0; f < at.size(); ++f) {
        const auto w = throng::test::eq5_weights(at[f].t, tension);
        const auto keys = throng::test::eq5_keys(at[f].segment, 4);
        Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(30, dimension);
        for (int i = 0; i < 4; ++i) expected += w[static_cast<std::size_t>(i)] * p.keyframes[static_cast<std::size_t>(keys[static_cast<std::size_t>(i)])].positions;
        worst = std::max(worst, (r.motion.frame(f).leftCols(dimension) - expected).cwiseAbs().maxCoeff());
      }
      CHECK(worst <= 64 * eps * 20.0);  // a few roundings of coordinates up to 20 m
    }
  }
}

TEST_CASE("linear baseline: two keyframes give straight paths, uniform in time at tension 1, and a turned "
          "formation shrinks through the middle (the paper's Figure 3(a))") {
  const Eigen::MatrixXd source = throng::test::scattered(25, 4.0, 31);
  const double angle = 150.0 * std::numbers::pi / 180.0;
  Problem p;
  p.keyframes.push_back(Keyframe{0.0, source, {}});
  p.keyframes.push_back(Keyframe{4.0, throng::test::rigid_2d(source, angle, {3.0, 1.0}), {}});
  Options o;
  o.interpolation = Interpolation::linear;
  o.tension = 1.0;
  o.frame_rate_hz = 10;
  const Result r = animate_formation(p, o);
  REQUIRE(r.motion.frame_count() == 41);
  for (std::size_t f = 0; f <= 40; ++f) {
    const double s = static_cast<double>(f) / 40.0;
    const Eigen::MatrixXd expected = (1 - s) * p.keyframes[0].positions + s * p.keyframes[1].positions;
    CHECK((r.motion.frame(f).leftCols(2) - expected).cwiseAbs().maxCoeff() <= 64 * eps * 10.0);
  }
  // Halfway every pairwise offset d is (d + R d)/2: its length is |cos(angle/2)| |d|.
  const Eigen::MatrixXd middle = r.motion.frame(20).leftCols(2);
  for (Eigen::Index i = 0; i < 25; ++i)
    for (Eigen::Index j = i + 1; j < 25; ++j)
      CHECK((middle.row(i) - middle.row(j)).norm() ==
            Catch::Detail::Approx(std::abs(std::cos(angle / 2)) * (source.row(i) - source.row(j)).norm()).margin(1e-12));
}

TEST_CASE("linear baseline: a hierarchy changes nothing (barycentres interpolate linearly too)") {
  Problem p = scattered_keyframes(24, 3);
  Options o;
  o.interpolation = Interpolation::linear;
  const Result flat = animate_formation(p, o);
  Group root;
  for (int g = 0; g < 4; ++g) {
    Group sub;
    for (int i = 0; i < 6; ++i) sub.members.push_back(g * 6 + i);
    root.subgroups.push_back(sub);
  }
  p.hierarchy = root;
  const Result tree = animate_formation(p, o);
  REQUIRE(tree.hierarchy.subgroups.size() == 4);
  double worst = 0.0;
  for (std::size_t f = 0; f < flat.motion.frame_count(); ++f)
    worst = std::max(worst, (flat.motion.frame(f) - tree.motion.frame(f)).cwiseAbs().maxCoeff());
  CHECK(worst <= 64 * eps * 20.0);
}

TEST_CASE("polar baseline without orientation alignment: each individual's distance to the barycentre and its "
          "angle are Eq. 4 with positions for coefficients") {
  const Problem p = scattered_keyframes(30, 2);
  for (double tension : {1.0, 0.5}) {
    INFO("tension " << tension);
    Options o;
    o.interpolation = Interpolation::polar;
    o.orientation = OrientationAlignment::none;
    o.tension = tension;
    o.frame_rate_hz = 10;
    const Result r = animate_formation(p, o);
    const Eigen::MatrixXd& x0 = p.keyframes[0].positions;
    const Eigen::MatrixXd& x1 = p.keyframes[1].positions;
    const Eigen::RowVector2d b0 = x0.colwise().mean(), b1 = x1.colwise().mean();
    const std::vector<FramePlace> at = places(r);
    double worst = 0.0;
    for (std::size_t f = 0; f < at.size(); ++f) {
      const auto w = throng::test::eq5_weights(at[f].t, tension);
      const double s = w[2] + w[3];  // endpoints duplicated: (1 − s) keyframe 0 + s keyframe 1
      const Eigen::RowVector2d b = (1 - s) * b0 + s * b1;
      const Eigen::MatrixXd got = r.motion.frame(f).leftCols(2);
      for (Eigen::Index i = 0; i < 30; ++i) {
        const Eigen::RowVector2d u0 = x0.row(i) - b0, u1 = x1.row(i) - b1;
        const double r_expected = (1 - s) * u0.norm() + s * u1.norm();
        const double a0 = std::atan2(u0(1), u0(0));
        const double a_expected = a0 + s * wrap(std::atan2(u1(1), u1(0)) - a0);
        const Eigen::RowVector2d expected = b + r_expected * Eigen::RowVector2d(std::cos(a_expected), std::sin(a_expected));
        worst = std::max(worst, (got.row(i) - expected).norm());
      }
    }
    CHECK(worst <= 1e-12 * 20.0);
  }
}

TEST_CASE("polar baseline in 3-D: distance to the barycentre linear in s, direction along the great circle (slerp)") {
  const Problem p = scattered_keyframes(20, 2, 3);
  Options o;
  o.interpolation = Interpolation::polar;
  o.orientation = OrientationAlignment::none;
  o.frame_rate_hz = 10;
  const Result r = animate_formation(p, o);
  const Eigen::MatrixXd& x0 = p.keyframes[0].positions;
  const Eigen::MatrixXd& x1 = p.keyframes[1].positions;
  const Eigen::RowVector3d b0 = x0.colwise().mean(), b1 = x1.colwise().mean();
  const std::vector<FramePlace> at = places(r);
  double worst_length = 0.0, worst_angle = 0.0, worst_plane = 0.0;
  for (std::size_t f = 0; f < at.size(); ++f) {
    const auto w = throng::test::eq5_weights(at[f].t, o.tension);
    const double s = w[2] + w[3];
    const Eigen::RowVector3d b = (1 - s) * b0 + s * b1;
    for (Eigen::Index i = 0; i < 20; ++i) {
      const Eigen::Vector3d u0 = (x0.row(i) - b0).transpose(), u1 = (x1.row(i) - b1).transpose();
      const Eigen::Vector3d u = (r.motion.frame(f).row(i) - b).transpose();
      worst_length = std::max(worst_length, std::abs(u.norm() - ((1 - s) * u0.norm() + s * u1.norm())));
      const double total = std::atan2(u0.cross(u1).norm(), u0.dot(u1));
      worst_angle = std::max(worst_angle, std::abs(std::atan2(u0.cross(u).norm(), u0.dot(u)) - s * total));
      worst_plane = std::max(worst_plane, std::abs(u.dot(u0.cross(u1).normalized())) / std::max(u.norm(), 1e-9));
    }
  }
  CHECK(worst_length <= 1e-12 * 20.0);
  CHECK(worst_angle <= 1e-10);
  CHECK(worst_plane <= 1e-10);
}

TEST_CASE("polar baseline with the PCA adjustment: a turned copy of the formation moves rigidly (the paper's "
          "Figure 3(b)), also when it turns past a half turn") {
  const Eigen::MatrixXd source = throng::test::scattered(25, 4.0, 31);
  for (double degrees : {40.0, 150.0, 200.0}) {
    INFO("turn " << degrees);
    Problem p;
    p.keyframes.push_back(Keyframe{0.0, source, {}});
    p.keyframes.push_back(Keyframe{4.0, throng::test::rigid_2d(source, degrees * std::numbers::pi / 180.0, {3.0, 1.0}), {}});
    Options o;
    o.interpolation = Interpolation::polar;
    const Result r = animate_formation(p, o);
    CHECK(throng::test::largest_distance_change(r.motion) <= 1e-9);
  }
}

TEST_CASE("every method hits every keyframe exactly: 2-D and 3-D, both Eq. 5 products, sharp keyframes, a hierarchy") {
  for (int dimension : {2, 3}) {
    Problem p = scattered_keyframes(24, 4, dimension);
    p.keyframes[1].sharp = true;
    for (bool tree : {false, true}) {
      if (tree) {
        Group root;
        root.members = {0, 1, 2};
        for (int g = 0; g < 3; ++g) {
          Group sub;
          for (int i = 3 + 7 * g; i < 10 + 7 * g; ++i) sub.members.push_back(i);
          root.subgroups.push_back(sub);
        }
        p.hierarchy = root;
      }
      for (Interpolation method : {Interpolation::spectral, Interpolation::linear, Interpolation::polar}) {
        for (KeyframeProduct product : {KeyframeProduct::cumulative, KeyframeProduct::paper}) {
          INFO("dimension " << dimension << " tree " << tree << " method " << static_cast<int>(method) << " product "
                            << static_cast<int>(product));
          Options o;
          o.interpolation = method;
          o.keyframe_product = product;
          o.frame_rate_hz = 6;
          const Result r = animate_formation(p, o);
          for (std::size_t k = 0; k < 4; ++k)
            CHECK((r.motion.frame(r.keyframe_frames[k]).leftCols(dimension) - p.keyframes[k].positions).cwiseAbs().maxCoeff() <=
                  1000 * 24 * eps * 20.0);
          r.motion.validate("formation output");
          CHECK(r.keyframe_edges.size() == 4);
          CHECK(!r.keyframe_edges[0].empty());  // the baselines build the same graphs (for the output and checks)
        }
      }
    }
  }
}
