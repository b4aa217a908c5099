// The plausibility guard after an edit (throng/edit/guard.h, issue 14): a drag that makes a clip too fast is
// slowed to 1.25 × the input's fastest speed, kinks at a drag's edge are smoothed with the request's frames held,
// and guard.enabled = false writes the paper's edit bit for bit.
#include "../graph/synthetic_crowd.h"

#include <throng/core/communicator.h>
#include <throng/core/progress.h>
#include <throng/edit/guard.h>
#include <throng/edit/output.h>
#include <throng/edit/runner.h>

#include <catch2/catch.hpp>

#include <numbers>

#include "facing_angles.h"

using namespace throng;
using namespace throng::edit;

namespace {

Drag drag(Frame first, Frame last, Eigen::Vector2d offset) {
  Drag d;
  d.selection.first_frame = first;
  d.selection.last_frame = last;
  d.offset = offset;
  return d;
}

// 3 × 4 agents walking east at 1.2 m/s for 9.6 s (97 frames of 0.1 s), facing their path.
Crowd walking_group() {
  Crowd c;
  c.motion = test::marching_grid(3, 4, 97, 1.0, 1.2, 0.1, 0.0, 0.1);
  test::face_at_angle_to_path(c.motion, 0.0);
  return c;
}

Run edit_with(const Crowd& input, const Job& job) {
  NoProgress progress;
  return run({&input}, job, progress, Communicator::single());
}

}  // namespace

TEST_CASE("guard: a drag that makes the clip too fast is slowed to 1.25 x the input's fastest speed") {
  const Crowd input = walking_group();
  const double input_fastest = timewarp::fastest_speed(input.motion);
  REQUIRE(input_fastest > 1.1);
  Job job;
  job.options.clip.sample_step = 6;
  // The head held, the tail 8 m further east: the 5.5 s between walk 8 m more, about 2.6 m/s.
  job.request.drags = {drag(0, 5, {0, 0}), drag(60, -1, {8, 0})};
  Job unguarded = job;
  unguarded.guard.enabled = false;
  const Run before = edit_with(input, unguarded);
  REQUIRE(timewarp::fastest_speed(before.crowd.motion) > 2 * input_fastest);  // the edit alone is too fast

  const Run after = edit_with(input, job);
  const CrowdMotion& out = after.crowd.motion;
  CHECK(after.guard.warped);
  CHECK(after.guard.largest_stretch > 1.5);
  CHECK_FALSE(after.residual_after_guard);  // warped: the residual is the edit's, before the guard
  CHECK(timewarp::fastest_speed(out) <= 1.25 * input_fastest * (1 + 1e-9));
  CHECK(after.guard.max_speed_after == timewarp::fastest_speed(out));
  // Slower over the same path: longer, at the same frame rate, every agent still there.
  CHECK(out.frame_count() > input.motion.frame_count() * 3 / 2);
  CHECK(std::abs(out.times[1] - out.times[0] - 0.1) < 1e-9);
  REQUIRE(out.agent_count() == input.motion.agent_count());
  CHECK(out.ids == input.motion.ids);
  // The path's ends: where the drags put them. The first frame is pinned; each pass of the guard (at most 3)
  // resamples at the frame rate up to the last whole frame of its warped time, so the last written frame is
  // within a frame's walk per pass of the tail drag's end.
  const std::size_t last = input.motion.frame_count() - 1;
  for (std::size_t a = 0; a < out.agent_count(); ++a) {
    CHECK((out.position(0, a) - input.motion.position(0, a)).norm() < 1e-9);
    CHECK((out.position(out.frame_count() - 1, a).head<2>() - input.motion.position(last, a).head<2>() -
           Eigen::Vector2d(8, 0)).norm() <= 3 * 1.25 * input_fastest * 0.1);
  }
  // The facings survive the warp: one per frame and agent, turned no further from east than the edit's own.
  REQUIRE(out.orientations.size() == out.frame_count() * out.agent_count() * 4);
  out.validate("guarded");
  auto widest_yaw = [](const CrowdMotion& m) {
    double worst = 0;
    for (std::size_t f = 0; f < m.frame_count(); ++f)
      for (std::size_t a = 0; a < m.agent_count(); ++a) worst = std::max(worst, std::abs(test::facing_yaw(m, f, a)));
    return worst;
  };
  const double edited_yaw = widest_yaw(before.crowd.motion);
  CHECK(edited_yaw > 0.1);  // the edit turned them (the check below is not trivial)
  CHECK(widest_yaw(out) <= edited_yaw + 1e-3);
}

TEST_CASE("guard: disabled, the output is the paper's edit bit for bit") {
  const Crowd input = walking_group();
  Job job;
  job.options.clip.sample_step = 6;
  job.request.drags = {drag(0, 5, {0, 0}), drag(60, -1, {8, 0})};
  job.guard.enabled = false;
  const Run run = edit_with(input, job);
  const Result paper = edit_group_motion(input.motion, job.options, job.request);
  const CrowdMotion expected = embed_clip(input.motion, paper.crowd, paper.first_frame);
  const CrowdMotion& out = run.crowd.motion;
  CHECK_FALSE(run.guard.warped);
  CHECK(run.guard.kinks_before == 0);  // nothing counted: the guard did not look
  CHECK(out.times == expected.times);
  CHECK(out.positions == expected.positions);
  CHECK(out.velocities == expected.velocities);
  CHECK(out.orientations == expected.orientations);
}

TEST_CASE("guard: kinks at a drag's edge are smoothed, the request still held on every frame it covers") {
  const Crowd input = walking_group();
  Job job;
  job.options.clip.sample_step = 6;
  // Held to frame 40, 0.5 m to the left from frame 60: the edit bends the paths between, sharpest at the drags'
  // edges; beyond 0.7 m/s² (the least a bridge of the 2 s between needs is 6 · 0.5 / 2² = 0.75 m/s²) are kinks.
  job.request.drags = {drag(0, 40, {0, 0}), drag(60, -1, {0, 0.5})};
  job.guard.max_speed_ratio = 10;  // the speed limit out of the way: smoothing alone, no warp
  job.guard.max_acceleration = 1.0;
  Job unguarded = job;
  unguarded.guard.enabled = false;
  const Run before = edit_with(input, unguarded);
  const Run after = edit_with(input, job);
  REQUIRE_FALSE(after.guard.warped);
  INFO(after.guard.kinks_before << " " << after.guard.kinks_after << " " << after.guard.max_acceleration_before << " " << after.guard.max_acceleration_after);
  REQUIRE(after.guard.kinks_before > 0);
  CHECK(after.guard.max_acceleration_before > 5);  // the edit alone: 7.8 m/s² at the drags' edges
  CHECK(after.guard.kinks_after == 0);
  CHECK(after.guard.max_acceleration_after <= 1.0);
  CHECK(after.guard.largest_shift > 1e-3);  // the guard moved something
  // Measured on the written frames after the guard: the drags hold exactly.
  CHECK(after.residual_after_guard);
  CHECK(after.result.report.max_output_residual < 1e-9);
  // Constrained frames untouched, only the frames between the drags moved.
  const CrowdMotion &b = before.crowd.motion, &g = after.crowd.motion;
  REQUIRE(g.frame_count() == b.frame_count());
  const std::vector<std::size_t> held = constrained_frames(job.request, 0, 96);
  CHECK(held.size() == 41 + 37);
  for (std::size_t f : held)
    for (std::size_t a = 0; a < g.agent_count(); ++a) CHECK((g.position(f, a) - b.position(f, a)).norm() < 1e-9);
}

TEST_CASE("guard: the frames a request constrains, as the editor reads them") {
  Request r;
  Pin p;
  p.frame = -1;  // the clip's last frame
  r.pins = {p};
  r.drags = {drag(-3, -2, {1, 0}), drag(0, 11, {0, 0})};  // clamped to the clip [10, 20]
  Velocity v;
  v.frame = 15;
  r.constraints = {v};
  CHECK(constrained_frames(r, 10, 20) == std::vector<std::size_t>{10, 11, 15, 16, 18, 19, 20});
}
