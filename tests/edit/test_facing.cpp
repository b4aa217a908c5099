// Facing and actions through an edit (throng/edit/output.h): each edited agent keeps its facing at the same
// angle to its path as in the input.
#include "../graph/synthetic_crowd.h"

#include <throng/edit/edit.h>
#include <throng/edit/output.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "facing_angles.h"

using namespace throng;
using namespace throng::edit;
using Catch::Matchers::WithinAbs;

namespace {

constexpr double pi = std::numbers::pi;

Drag hold(std::size_t first, std::size_t last) {
  Drag d;
  d.selection.first_frame = first;
  d.selection.last_frame = last;
  return d;
}

// A turning group, edited so that its tail is moved and turned by −90°: the paths bend.
struct Edited {
  CrowdMotion input;
  Result result;
};

Edited sideways_group_edited(double facing_angle) {
  Edited e;
  e.input = test::marching_grid(3, 4, 97, 1.0, 1.2, 0.1, 0.3, 0.0);
  test::face_at_angle_to_path(e.input, facing_angle);
  Options options;
  options.clip.sample_step = 12;
  Request request;
  Drag tail = hold(60, 96);
  tail.offset = Eigen::Vector2d(6.0, -4.0);
  tail.rotation = -1.57;
  request.drags = {hold(0, 5), tail};
  e.result = edit_group_motion(e.input, options, request);
  return e;
}

}  // namespace

TEST_CASE("an edit of a group walking sideways keeps the angle between facing and path") {
  const Edited e = sideways_group_edited(pi / 2);  // facing left of the path: a sideways walk
  const CrowdMotion out = embed_clip(e.input, e.result.crowd, e.result.first_frame);
  REQUIRE(out.orientations.size() == e.input.orientations.size());
  out.validate("edited");
  std::size_t compared = 0;
  double largest_bend = 0;
  for (std::size_t f = 0; f < out.frame_count(); ++f) {
    for (std::size_t a = 0; a < out.agent_count(); ++a) {
      const auto before = test::facing_to_path(e.input, f, a), after = test::facing_to_path(out, f, a);
      REQUIRE(before);
      REQUIRE(after);
      REQUIRE_THAT(*after, WithinAbs(pi / 2, 1e-9));
      // How much the edit turned the path here (the property is not trivial).
      const Eigen::Vector3d vb = *path_velocity(e.input, f, a), va = *path_velocity(out, f, a);
      largest_bend = std::max(largest_bend, std::abs(yaw_change(vb, va)));
      ++compared;
    }
  }
  CHECK(compared == 97 * 12);
  CHECK(largest_bend > pi / 4);
  // The facing itself turned with the path: not the input's facing copied.
  double largest_turn = 0;
  for (std::size_t f = 0; f < out.frame_count(); ++f) {
    for (std::size_t a = 0; a < out.agent_count(); ++a) {
      largest_turn = std::max(largest_turn, std::abs(test::wrapped(test::facing_yaw(out, f, a) - test::facing_yaw(e.input, f, a))));
    }
  }
  CHECK(largest_turn > pi / 4);
  // The input walks at 1.2 m/s throughout. The drag stretches the middle of the paths (the tail is moved 7 m
  // further in the same time): where that makes an agent faster than 2 m/s it runs, elsewhere it still walks.
  std::size_t runs = 0, mismatches = 0;
  for (std::size_t f = 0; f < out.frame_count(); ++f) {
    for (std::size_t a = 0; a < out.agent_count(); ++a) {
      REQUIRE(e.input.action(f, a) == action_walk);
      mismatches += out.action(f, a) != path_action(out, f, a);
      runs += out.action(f, a) == action_run;
    }
  }
  CHECK(mismatches == 0);
  CHECK(runs > 0);
  CHECK(runs < out.actions.size() / 2);
}

TEST_CASE("the clip alone carries the facing too, and an input without facing gives an output without") {
  const Edited e = sideways_group_edited(-pi / 3);
  const CrowdMotion clip = clip_with_velocities(e.input, e.result.crowd, e.result.first_frame);
  REQUIRE(clip.orientations.size() == clip.frame_count() * clip.agent_count() * 4);
  clip.validate("clip");
  for (std::size_t f = 0; f < clip.frame_count(); ++f) {
    for (std::size_t a = 0; a < clip.agent_count(); ++a) {
      const auto after = test::facing_to_path(clip, f, a);
      REQUIRE(after);
      REQUIRE_THAT(*after, WithinAbs(-pi / 3, 1e-9));
    }
  }
  CrowdMotion plain = e.input;
  plain.orientations.clear();
  plain.actions.clear();
  plain.action_table.clear();
  const CrowdMotion out = embed_clip(plain, e.result.crowd, e.result.first_frame);
  CHECK(out.orientations.empty());
  CHECK(out.actions.empty());
  CHECK(clip_with_velocities(plain, e.result.crowd, e.result.first_frame).orientations.empty());
}
