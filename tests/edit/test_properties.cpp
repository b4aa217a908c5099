// Properties of the deformation that a wrong implementation would break.
#include "../graph/synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/edit/edit.h>

#include <catch2/catch.hpp>

#include <Eigen/Geometry>

#include <cmath>

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

// Scenes here span ~30 m with ~10³ unknowns; a backward-stable Cholesky leaves errors near cond·ε·|x|, measured
// ≈ 3e-14 m (cond ≈ 10²..10³). 1e-9 m leaves four orders of margin for other machines and BLAS kernels, while
// any wrong term or sign moves vertices by centimetres.
constexpr double rounding = 1e-9;

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
  CHECK(max_gap(result.crowd, crowd) < rounding);
}

TEST_CASE("a rigid motion of every handle moves the whole result rigidly") {
  // Every feature is invariant to rotations and translations, so the transformed input has zero energy in both
  // steps. (Checked at the samples: between them the output interpolates the displacement, which a rotation
  // makes depend on the path's curvature.)
  const CrowdMotion crowd = test::marching_grid(3, 4, 31, 1.0, 1.2, 0.1, 0.4, 0.2);
  const Eigen::Vector2d pivot(3, -2), offset(5, 7);
  const double angle = 0.8;
  Request request;
  request.drags = {move(0, 0, offset, angle, pivot), move(15, 15, offset, angle, pivot), move(30, 30, offset, angle, pivot)};
  for (bool scale_compensation : {false, true}) {
    Options options;
    options.clip.sample_step = 2;
    options.scale_compensation = scale_compensation;
    const Result result = edit_group_motion(crowd, options, request);
    const Eigen::Rotation2Dd turn(angle);
    double gap = 0;
    for (std::size_t f = 0; f < crowd.frame_count(); f += 2) {
      for (std::size_t a = 0; a < crowd.agent_count(); ++a) {
        const Eigen::Vector2d expected = pivot + turn * (crowd.position(f, a).head<2>() - pivot) + offset;
        gap = std::max(gap, (result.crowd.position(f, a).head<2>() - expected).norm());
      }
    }
    CAPTURE(scale_compensation);
    CHECK(gap < rounding);
  }
}

TEST_CASE("pins, drags and every general constraint are met in the output") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 31, 1.0, 1.2, 0.1, 0.3, 0.2);
  Options options;
  options.clip.sample_step = 4;
  Request request;
  request.drags = {hold(0, 1), move(29, 30, {2.0, 3.0})};
  request.pins = {{105, 12, Eigen::Vector2d(9.0, 1.5)}};
  request.constraints.push_back(RelativePosition{100, 101, 16, 20, Eigen::Vector2d(0.0, -1.5)});
  request.constraints.push_back(Velocity{103, 22, Eigen::Vector2d(1.5, 0.2)});
  request.constraints.push_back(OnLine{110, 6, 10, Eigen::Vector2d(6.0, -1.0), Eigen::Vector2d(1.0, 0.5)});
  const Result result = edit_group_motion(crowd, options, request);
  const CrowdMotion& out = result.crowd;
  auto xy = [&](std::size_t frame, std::int64_t id) -> Eigen::Vector2d {
    return out.position(frame, static_cast<std::size_t>(id - 100)).head<2>();
  };
  // Handles are eliminated unknowns: exact.
  CHECK(xy(12, 105) == Eigen::Vector2d(9.0, 1.5));
  for (std::int64_t id = 100; id < 112; ++id) {
    CHECK(xy(0, id) == crowd.position(0, static_cast<std::size_t>(id - 100)).head<2>());
    CHECK(xy(30, id) == crowd.position(30, static_cast<std::size_t>(id - 100)).head<2>() + Eigen::Vector2d(2.0, 3.0));
  }
  // Constraints through the Schur complement: to rounding, at every sample they cover (here every frame named
  // in the request is a sample; the relative position acts on samples 16 and 20).
  CHECK((xy(16, 100) - xy(16, 101) - Eigen::Vector2d(0.0, -1.5)).norm() < rounding);
  CHECK((xy(20, 100) - xy(20, 101) - Eigen::Vector2d(0.0, -1.5)).norm() < rounding);
  const double dt = out.times[23] - out.times[22];
  CHECK(((xy(23, 103) - xy(22, 103)) / dt - Eigen::Vector2d(1.5, 0.2)).norm() < rounding / dt);
  const Eigen::Vector2d normal = Eigen::Vector2d(-0.5, 1.0).normalized();
  for (std::size_t f : {6, 8, 10}) CHECK(std::abs(normal.dot(xy(f, 110) - Eigen::Vector2d(6.0, -1.0))) < rounding);
  CHECK(result.report.max_constraint_residual < rounding);
  CHECK(result.report.constraint_rows == 4 + 2 + 3);
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
  for (double dy : {1.0, 2.5, -3.0}) {
    request.drags[1].offset = Eigen::Vector2d(0.5, dy);
    std::get<Velocity>(request.constraints[0]).velocity.y() = 0.1 * dy;
    const CrowdMotion dragged = editor.resample(editor.deform(request));
    CHECK(editor.report().factorizations == factorizations);
    CHECK(editor.report().schur_columns == schur);
    const Result fresh = edit_group_motion(crowd, options, request);
    CHECK(dragged.positions == fresh.crowd.positions);
  }
  // A different handle set refactorises.
  request.drags[1].selection.agents = {100, 101};
  (void)editor.deform(request);
  CHECK(editor.report().factorizations == factorizations + 2);
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
