// Sharp keyframes (Keyframe::sharp, §4.1: "a point at which the curve is set to be nonsmooth ... is
// duplicated"): the spline of every method duplicates them, the paths turn there, and nothing else changes.
#include <throng/formation/formation.h>

#include "fixtures.h"
#include "spline_reference.h"

#include <catch2/catch.hpp>

#include <numbers>

using namespace throng::formation;
using throng::test::eps;

namespace {

// A square march: the group (a scatter) goes east 12 m, then north 12 m, then east again; keyframe 1 is the
// corner. Its shape changes a little at each keyframe, so the spectral method has something to do.
Problem square_march(int n) {
  const Eigen::RowVector2d corners[4] = {{0, 0}, {12, 0}, {12, 12}, {24, 12}};
  Problem p;
  for (int k = 0; k < 4; ++k) {
    const Eigen::MatrixXd shape = throng::test::scattered(n, 2.5, 90 + static_cast<std::uint64_t>(k), 0.6);
    p.keyframes.push_back(Keyframe{10.0 * k, shape.rowwise() + corners[k], {}});
  }
  return p;
}

double angle_between(const Eigen::RowVector2d& a, const Eigen::RowVector2d& b) {
  return std::atan2(a(0) * b(1) - a(1) * b(0), a.dot(b));
}

}  // namespace

TEST_CASE("sharp keyframe, linear baseline: the spline with that keyframe duplicated, exactly") {
  Problem p = square_march(12);
  p.keyframes[1].sharp = true;
  const std::vector<bool> sharp{false, true, false, false};
  Options o;
  o.interpolation = Interpolation::linear;
  o.frame_rate_hz = 4;
  const Result r = animate_formation(p, o);
  double worst = 0.0, unlike_smooth = 0.0;
  for (int segment = 0; segment < 3; ++segment) {
    const std::size_t first = r.keyframe_frames[static_cast<std::size_t>(segment)];
    const std::size_t last = r.keyframe_frames[static_cast<std::size_t>(segment) + 1];
    for (std::size_t f = first; f <= last; ++f) {
      const double t = static_cast<double>(f - first) / static_cast<double>(last - first);
      const auto w = throng::test::eq5_weights(t, o.tension);
      Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(12, 2), smooth = Eigen::MatrixXd::Zero(12, 2);
      const auto keys = throng::test::eq5_keys(segment, 4, sharp);
      const auto smooth_keys = throng::test::eq5_keys(segment, 4);
      for (int i = 0; i < 4; ++i) {
        expected += w[static_cast<std::size_t>(i)] * p.keyframes[static_cast<std::size_t>(keys[static_cast<std::size_t>(i)])].positions;
        smooth += w[static_cast<std::size_t>(i)] * p.keyframes[static_cast<std::size_t>(smooth_keys[static_cast<std::size_t>(i)])].positions;
      }
      worst = std::max(worst, (r.motion.frame(f).leftCols(2) - expected).cwiseAbs().maxCoeff());
      unlike_smooth = std::max(unlike_smooth, (r.motion.frame(f).leftCols(2) - smooth).cwiseAbs().maxCoeff());
    }
  }
  CHECK(worst <= 64 * eps * 30.0);
  CHECK(unlike_smooth >= 0.1);  // the duplication matters here (metres)
}

TEST_CASE("sharp keyframe: every method's group turns there along its two chords instead of rounding the corner") {
  for (Interpolation method : {Interpolation::spectral, Interpolation::linear, Interpolation::polar}) {
    for (bool sharp : {false, true}) {
      INFO("method " << static_cast<int>(method) << " sharp " << sharp);
      Problem p = square_march(12);
      p.keyframes[1].sharp = sharp;
      Options o;
      o.interpolation = method;
      o.frame_rate_hz = 200;  // one-frame differences close to the tangents
      const Result r = animate_formation(p, o);
      const std::size_t corner = r.keyframe_frames[1];
      const Eigen::RowVector2d before = r.motion.frame(corner).leftCols(2).colwise().mean() - r.motion.frame(corner - 1).leftCols(2).colwise().mean();
      const Eigen::RowVector2d after = r.motion.frame(corner + 1).leftCols(2).colwise().mean() - r.motion.frame(corner).leftCols(2).colwise().mean();
      const double turn = angle_between(before, after);
      // The barycentres' chords: east then north, a quarter turn. Rounded, the tangent at the keyframe is along
      // the chord from keyframe 0 to 2 on both sides (no turn); sharp, along each interval's own chord.
      const Eigen::RowVector2d in = p.keyframes[1].positions.colwise().mean() - p.keyframes[0].positions.colwise().mean();
      const Eigen::RowVector2d out = p.keyframes[2].positions.colwise().mean() - p.keyframes[1].positions.colwise().mean();
      if (sharp) {
        CHECK(std::abs(angle_between(in, before)) <= 0.02);
        CHECK(std::abs(angle_between(out, after)) <= 0.02);
        CHECK(turn == Catch::Detail::Approx(angle_between(in, out)).margin(0.03));
      } else {
        CHECK(std::abs(turn) <= 0.02);
      }
    }
  }
}

TEST_CASE("sharp keyframe: only the two intervals that meet there change, for every method and product") {
  Problem p = square_march(16);
  const double times[5] = {0, 10, 20, 30, 40};
  const Eigen::MatrixXd fifth = throng::test::scattered(16, 2.5, 99, 0.6).rowwise() + Eigen::RowVector2d(36, 12);
  p.keyframes.push_back(Keyframe{times[4], fifth, {}});
  for (Interpolation method : {Interpolation::spectral, Interpolation::linear, Interpolation::polar}) {
    for (KeyframeProduct product : {KeyframeProduct::cumulative, KeyframeProduct::paper}) {
      INFO("method " << static_cast<int>(method) << " product " << static_cast<int>(product));
      Options o;
      o.interpolation = method;
      o.keyframe_product = product;
      o.frame_rate_hz = 3;
      const Result smooth = animate_formation(p, o);
      Problem cornered = p;
      cornered.keyframes[2].sharp = true;
      const Result sharp = animate_formation(cornered, o);
      const auto& kf = smooth.keyframe_frames;
      for (std::size_t segment = 0; segment < 4; ++segment) {
        // The interval's frames: a keyframe's frame is the first of the interval it starts (the last frame
        // belongs to the last interval).
        const std::size_t end = segment == 3 ? kf[segment + 1] + 1 : kf[segment + 1];
        double change = 0.0;
        for (std::size_t f = kf[segment]; f < end; ++f)
          change = std::max(change, (sharp.motion.frame(f) - smooth.motion.frame(f)).cwiseAbs().maxCoeff());
        INFO("interval " << segment);
        if (segment == 1 || segment == 2) CHECK(change >= 0.01);
        else CHECK(change == 0.0);  // the same computation: the same bits
      }
    }
  }
}

TEST_CASE("sharp first and last keyframes change nothing (they are duplicated already)") {
  Problem p = square_march(10);
  const Result plain = animate_formation(p, Options{});
  p.keyframes.front().sharp = true;
  p.keyframes.back().sharp = true;
  CHECK(animate_formation(p, Options{}).motion.positions == plain.motion.positions);
}
