// Properties of the deformation that a wrong implementation would break.
#include "../graph/synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/edit/edit.h>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <limits>

using namespace throng;
using namespace throng::edit;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 2>;

namespace {

// Keeps frames [first, last] of every agent where they are (a drag with no motion).
Drag hold(std::size_t first, std::size_t last) {
  Drag d;
  d.selection.first_frame = first;
  d.selection.last_frame = last;
  return d;
}

Drag move(std::size_t first, std::size_t last, Eigen::Vector2d offset, double rotation = 0.0,
          std::optional<Eigen::Vector2d> pivot = std::nullopt) {
  Drag d = hold(first, last);
  d.offset = offset;
  d.rotation = rotation;
  d.pivot = pivot;
  return d;
}

double max_gap(const CrowdMotion& a, const CrowdMotion& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  double gap = 0;
  for (std::size_t k = 0; k < a.positions.size(); ++k) gap = std::max(gap, std::abs(a.positions[k] - b.positions[k]));
  return gap;
}

// What rounding may leave in a result (metres). A backward-stable Cholesky solve of Q x = r leaves a forward
// error of about n · ε · cond(Q) · ‖x‖ (n unknowns); CHOLMOD's reciprocal condition estimate stands for
// 1/cond(Q). ‖x‖ is the scene's extent. The bound is loose (measured errors are ~10³ times smaller) but it is
// the problem's own: a wrong term or sign moves vertices by centimetres, far beyond it.
double rounding(const Report& report, const CrowdMotion& crowd) {
  REQUIRE(report.reciprocal_condition > 0);
  double extent = 1.0;
  for (double v : crowd.positions) extent = std::max(extent, std::abs(v));
  return static_cast<double>(report.unknowns) * std::numeric_limits<double>::epsilon() / report.reciprocal_condition * extent;
}

}  // namespace

TEST_CASE("unchanged handles give the input back, at every frame") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 41, 1.0, 1.2, 0.1, 0.4, 0.2);
  Options options;
  options.clip.sample_step = 3;
  Request request;
  request.drags = {hold(0, 1), hold(40, 40)};
  const Result result = edit_group_motion(crowd, options, request);
  REQUIRE(result.crowd.frame_count() == 41);
  REQUIRE(result.crowd.ids == crowd.ids);
  CHECK(result.crowd.times == crowd.times);
  const double tolerance = rounding(result.report, crowd);
  CAPTURE(tolerance, result.report.reciprocal_condition);
  CHECK(tolerance < 1e-6);  // the system is well conditioned: the bound means something
  CHECK(max_gap(result.crowd, crowd) < tolerance);
}

TEST_CASE("a rigid motion of every handle moves the whole result rigidly, at every frame") {
  // Every feature is invariant to rotations and translations, so the transformed input has zero energy in both
  // steps; between samples the output carries the original's detail with the agents' turn, so every output
  // frame, not only the samples, is the rigid image of the input.
  const CrowdMotion crowd = test::marching_grid(3, 4, 61, 1.0, 1.2, 0.1, 0.4, 0.2);
  const Eigen::Vector2d pivot(3, -2), offset(5, 7);
  for (double angle : {0.8, -1.57, 3.0}) {
    Request request;
    request.drags = {move(0, 0, offset, angle, pivot), move(24, 24, offset, angle, pivot), move(60, 60, offset, angle, pivot)};
    for (bool scale_compensation : {false, true}) {
      Options options;
      options.clip.sample_step = 12;
      options.scale_compensation = scale_compensation;
      const Result result = edit_group_motion(crowd, options, request);
      REQUIRE(result.sample_frames.size() == 6);  // 0, 12, ..., 60: most output frames lie between samples
      const Eigen::Rotation2Dd turn(angle);
      double gap = 0;
      for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
        for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
          const Eigen::Vector2d expected = pivot + turn * (crowd.position(f, a).head<2>() - pivot) + offset;
          gap = std::max(gap, (result.crowd.position(f, a).head<2>() - expected).norm());
        }
      }
      CAPTURE(angle, scale_compensation, gap);
      CHECK(gap < rounding(result.report, crowd));
      CHECK(result.report.max_output_residual < rounding(result.report, crowd));
    }
  }
}

TEST_CASE("a drag over a frame range holds its rigid map at every output frame of the range") {
  // The tail drag of the battlefield edit, shrunk: a turn and a move of the last frames with a coarse sampling.
  const CrowdMotion crowd = test::marching_grid(3, 4, 97, 1.0, 1.2, 0.1, 0.3, 0.2);
  Options options;
  options.clip.sample_step = 12;
  Request request;
  request.drags = {hold(0, 5), move(60, 96, {6.0, -4.0}, -1.57)};
  const Result result = edit_group_motion(crowd, options, request);
  // The pivot: the centroid of the selected original positions (every frame of the range, every agent).
  Eigen::Vector2d pivot = Eigen::Vector2d::Zero();
  for (std::size_t f = 60; f <= 96; ++f)
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) pivot += crowd.position(f, a).head<2>();
  pivot /= 37.0 * static_cast<double>(crowd.agent_count());
  const Eigen::Rotation2Dd turn(-1.57);
  double gap = 0;
  for (std::size_t f = 60; f <= 96; ++f) {
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
      const Eigen::Vector2d p = crowd.position(f, a).head<2>();
      gap = std::max(gap, (result.crowd.position(f, a).head<2>() - (pivot + turn * (p - pivot) + Eigen::Vector2d(6.0, -4.0))).norm());
    }
  }
  for (std::size_t f = 0; f <= 5; ++f) {
    for (std::size_t a = 0; a < crowd.agent_count(); ++a) gap = std::max(gap, (result.crowd.position(f, a) - crowd.position(f, a)).norm());
  }
  const double tolerance = rounding(result.report, crowd);
  CAPTURE(gap, tolerance);
  CHECK(gap < tolerance);
  CHECK(result.report.max_output_residual < tolerance);
  // Between the ranges the edit deforms: the check above is not vacuous.
  CHECK((result.crowd.position(40, 0) - crowd.position(40, 0)).norm() > 0.5);
}

TEST_CASE("pins, drags and every general constraint are met at every output frame") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 31, 1.0, 1.2, 0.1, 0.3, 0.2);
  Options options;
  options.clip.sample_step = 4;
  Request request;
  request.drags = {hold(0, 1), move(29, 30, {2.0, 3.0})};
  request.pins = {{105, 13, Eigen::Vector2d(9.0, 1.5)}};
  request.constraints.push_back(RelativePosition{100, 101, 15, 21, Eigen::Vector2d(0.0, -1.5)});
  request.constraints.push_back(Velocity{103, 22, Eigen::Vector2d(1.5, 0.2)});
  request.constraints.push_back(OnLine{110, 5, 11, Eigen::Vector2d(6.0, -1.0), Eigen::Vector2d(1.0, 0.5)});
  const Result result = edit_group_motion(crowd, options, request);
  const CrowdMotion& out = result.crowd;
  auto xy = [&](std::size_t frame, std::int64_t id) -> Eigen::Vector2d {
    return out.position(frame, static_cast<std::size_t>(id - 100)).head<2>();
  };
  const double tolerance = rounding(result.report, crowd);
  CAPTURE(tolerance);
  // Handles are eliminated unknowns: exact.
  CHECK(xy(13, 105) == Eigen::Vector2d(9.0, 1.5));
  for (std::int64_t id = 100; id < 112; ++id) {
    for (std::size_t f : {0, 1}) CHECK(xy(f, id) == crowd.position(f, static_cast<std::size_t>(id - 100)).head<2>());
    for (std::size_t f : {29, 30}) {
      CHECK(xy(f, id) == crowd.position(f, static_cast<std::size_t>(id - 100)).head<2>() + Eigen::Vector2d(2.0, 3.0));
    }
  }
  // Constraints through the Schur complement: to rounding, at every output frame of their ranges (frames 15..21
  // and 5..11 are not on the 4-frame sampling, they become samples).
  for (std::size_t f = 15; f <= 21; ++f) CHECK((xy(f, 100) - xy(f, 101) - Eigen::Vector2d(0.0, -1.5)).norm() < tolerance);
  const double dt = out.times[23] - out.times[22];
  CHECK(((xy(23, 103) - xy(22, 103)) / dt - Eigen::Vector2d(1.5, 0.2)).norm() < tolerance / dt);
  const Eigen::Vector2d normal = Eigen::Vector2d(-0.5, 1.0).normalized();
  for (std::size_t f = 5; f <= 11; ++f) CHECK(std::abs(normal.dot(xy(f, 110) - Eigen::Vector2d(6.0, -1.0))) < tolerance);
  CHECK(result.report.max_constraint_residual < tolerance);
  CHECK(result.report.max_output_residual < tolerance);
  CHECK(result.report.constraint_rows == 2 * 7 + 2 + 7);
}

TEST_CASE("the output residual measures the request on the output frames") {
  // Fed the unedited input, max_request_residual reports how far each request is from it: the drag's offset, the
  // pin's move, the constraint's violation. It reads the output, so it can fail where the solver's check cannot.
  const CrowdMotion crowd = test::marching_grid(2, 3, 21, 1.0, 1.2, 0.1, 0.0, 0.0);
  Request request;
  request.drags = {move(18, 20, {0.0, 0.5})};
  CHECK_THAT(max_request_residual(crowd, crowd, 0, request), Catch::Matchers::WithinAbs(0.5, 1e-12));
  request.drags.clear();
  request.pins = {{101, 7, Eigen::Vector2d(crowd.position(7, 1).x() + 0.25, crowd.position(7, 1).y())}};
  CHECK_THAT(max_request_residual(crowd, crowd, 0, request), Catch::Matchers::WithinAbs(0.25, 1e-12));
  request.pins.clear();
  // The grid marches along +x: a line along +y through agent 100's start is missed by 1.2 m/s · 1 s at frame 10.
  request.constraints.push_back(OnLine{100, 0, 10, crowd.position(0, 0).head<2>(), Eigen::Vector2d(0.0, 1.0)});
  CHECK_THAT(max_request_residual(crowd, crowd, 0, request), Catch::Matchers::WithinAbs(1.2, 1e-9));
  // A clip that starts later: frames are input frames, the clip's rows start at first_frame.
  CrowdMotion late = crowd;
  late.times.erase(late.times.begin(), late.times.begin() + 5);
  late.positions.erase(late.positions.begin(), late.positions.begin() + static_cast<long>(5 * crowd.agent_count() * 3));
  request.constraints = {OnLine{100, 5, 10, crowd.position(5, 0).head<2>(), Eigen::Vector2d(0.0, 1.0)}};
  CHECK_THAT(max_request_residual(crowd, late, 5, request), Catch::Matchers::WithinAbs(0.6, 1e-9));
}

TEST_CASE("a drag after precompute reuses the factorisation and equals a fresh edit") {
  const CrowdMotion crowd = test::marching_grid(3, 3, 25, 1.0, 1.2, 0.1, 0.2, 0.2);
  Options options;
  options.clip.sample_step = 2;
  Request request;
  request.drags = {hold(0, 0), move(24, 24, {0, 0})};
  request.constraints.push_back(Velocity{101, 10, Eigen::Vector2d(1.2, 0.0)});
  Editor editor(crowd, options, request);
  editor.precompute();
  const int factorizations = editor.report().factorizations;
  const int schur = editor.report().schur_columns;
  CHECK(factorizations == 2);  // step 1 and step 2
  CHECK(editor.report().analyses == 1);  // step 2 reuses step 1's symbolic analysis (one pattern)
  for (double dy : {1.0, 2.5, -3.0}) {
    request.drags[1].offset = Eigen::Vector2d(0.5, dy);
    std::get<Velocity>(request.constraints[0]).velocity.y() = 0.1 * dy;
    const CrowdMotion dragged = editor.resample(editor.deform(request));
    CHECK(editor.report().factorizations == factorizations);
    CHECK(editor.report().schur_columns == schur);
    const Result fresh = edit_group_motion(crowd, options, request);
    CHECK(dragged.positions == fresh.crowd.positions);
  }
  // A different handle set refactorises (and analyses once more, shared again).
  request.drags[1].selection.agents = {100, 101};
  const CrowdMotion regrabbed = editor.resample(editor.deform(request));
  CHECK(editor.report().factorizations == factorizations + 2);
  CHECK(editor.report().analyses == 2);
  CHECK(regrabbed.positions == edit_group_motion(crowd, options, request).crowd.positions);
}

TEST_CASE("one thread and two threads give the same bits") {
  const CrowdMotion crowd = test::marching_grid(5, 6, 40, 1.0, 1.2, 0.1, 0.3, 0.3);
  Options options;
  options.clip.sample_step = 2;
  Request request;
  request.drags = {hold(0, 1), move(38, 39, {4, -6}, 0.5)};
  Result one, two;
  {
    ThreadLimit limit(1);
    one = edit_group_motion(crowd, options, request);
  }
  {
    ThreadLimit limit(2);
    two = edit_group_motion(crowd, options, request);
  }
  CHECK(one.crowd.positions == two.crowd.positions);
}
