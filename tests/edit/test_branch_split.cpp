// The battlefield's branch split (Kwon et al. 2008, Figure 1/12; issue 16): with formation.splits cutting the
// edges between two sets of agents from a frame on, a drag of one branch moves it away without dragging the
// other along, and two drags pull the branches apart.
#include "../graph/synthetic_crowd.h"

#include <throng/core/parallel.h>
#include <throng/edit/edit.h>

#include <catch2/catch.hpp>

#include <limits>

using namespace throng;
using namespace throng::edit;

namespace {

// 4 × 4 agents marching along +x for 4 s (41 frames of 0.1 s); agent 100 + 4 r + c is in row r, column c (y across).
// Branch "left": columns 0 and 1; branch "right": columns 2 and 3.
std::vector<std::int64_t> columns(int first, int last) {
  std::vector<std::int64_t> ids;
  for (int r = 0; r < 4; ++r)
    for (int c = first; c <= last; ++c) ids.push_back(100 + 4 * r + c);
  return ids;
}

Drag move(const std::vector<std::int64_t>& agents, Frame first, Frame last, Eigen::Vector2d offset) {
  Drag d;
  d.selection.agents = agents;
  d.selection.first_frame = first;
  d.selection.last_frame = last;
  d.offset = offset;
  return d;
}

Eigen::Vector2d centroid(const CrowdMotion& c, std::size_t frame, const std::vector<std::int64_t>& ids) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::int64_t id : ids) sum += c.position(frame, static_cast<std::size_t>(id - 100)).head<2>();
  return sum / static_cast<double>(ids.size());
}

// The largest displacement of `ids` from the input over frames [first, last].
double displacement(const CrowdMotion& input, const CrowdMotion& out, const std::vector<std::int64_t>& ids,
                    std::size_t first, std::size_t last) {
  double worst = 0;
  for (std::size_t f = first; f <= last; ++f) {
    for (std::int64_t id : ids) {
      const auto a = static_cast<std::size_t>(id - 100);
      worst = std::max(worst, (out.position(f, a) - input.position(f, a)).head<2>().norm());
    }
  }
  return worst;
}

Options split_from(std::size_t frame) {
  Options o;
  o.clip.sample_step = 2;
  o.formation.splits.push_back({columns(0, 1), frame, std::numeric_limits<std::size_t>::max()});
  return o;
}

}  // namespace

TEST_CASE("branch split: dragging one branch away leaves the other where it was") {
  const CrowdMotion crowd = test::marching_grid(4, 4, 41, 1.0, 1.2, 0.1, 0.0, 0.1);
  const auto left = columns(0, 1), right = columns(2, 3);
  // The group held at the start and where the branches part (frame 16), the left branch 3 m further left at
  // the end: the paper's battlefield holds its head the same way.
  Request request;
  request.drags = {move({}, 0, 1, {0, 0}), move({}, 16, 16, {0, 0}), move(left, 39, 40, {0.0, -3.0})};
  Options whole;
  whole.clip.sample_step = 2;
  const Result together = edit_group_motion(crowd, whole, request);
  const Result split = edit_group_motion(crowd, split_from(16), request);
  const double dragged_along = displacement(crowd, together.crowd, right, 30, 40);
  const double left_behind = displacement(crowd, split.crowd, right, 30, 40);
  INFO("right branch moved " << dragged_along << " m with the formation whole, " << left_behind << " m split");
  CHECK(dragged_along > 1.0);                // one formation: the right branch follows the left one
  CHECK(left_behind < 0.1 * dragged_along);  // split: it keeps its own way
  // The left branch went where it was dragged, and before the split nothing moved much (held at 0 and 16).
  CHECK((centroid(split.crowd, 40, left) - centroid(crowd, 40, left) - Eigen::Vector2d(0.0, -3.0)).norm() < 1e-9);
  CHECK(displacement(crowd, split.crowd, right, 0, 16) < 0.1);
  CHECK(split.report.max_output_residual < 1e-9);
}

TEST_CASE("branch split: two drags in different directions pull the branches apart") {
  const CrowdMotion crowd = test::marching_grid(4, 4, 41, 1.0, 1.2, 0.1, 0.0, 0.1);
  const auto left = columns(0, 1), right = columns(2, 3);
  Request request;
  request.drags = {move({}, 0, 1, {0, 0}), move({}, 16, 16, {0, 0}), move(left, 39, 40, {1.0, -3.0}),
                   move(right, 39, 40, {1.0, 3.0})};
  const Result split = edit_group_motion(crowd, split_from(16), request);
  const double gap_before = (centroid(crowd, 40, left) - centroid(crowd, 40, right)).norm();
  const double gap_after = (centroid(split.crowd, 40, left) - centroid(split.crowd, 40, right)).norm();
  CHECK(gap_after > gap_before + 5.0);  // the drags' 6 m apart, met exactly at the dragged frames
  // Within each branch the formation holds: the branch keeps its shape (its agents' spacing) half-way there.
  for (const auto& branch : {left, right}) {
    const auto a = static_cast<std::size_t>(branch[0] - 100), b = static_cast<std::size_t>(branch[1] - 100);
    const double spacing_in = (crowd.position(28, a) - crowd.position(28, b)).head<2>().norm();
    const double spacing_out = (split.crowd.position(28, a) - split.crowd.position(28, b)).head<2>().norm();
    CHECK(std::abs(spacing_out - spacing_in) < 0.1 * spacing_in);
  }
}

TEST_CASE("branch split with acceleration, sum and row constraints: one thread and two threads give the same bits") {
  const CrowdMotion crowd = test::marching_grid(4, 4, 41, 1.0, 1.2, 0.1, 0.3, 0.1);
  const auto left = columns(0, 1), right = columns(2, 3);
  Request request;
  request.drags = {move({}, 0, 1, {0, 0}), move({}, 16, 16, {0, 0}), move(left, 39, 40, {1.0, -3.0}),
                   move(right, 39, 40, {1.0, 3.0})};
  request.constraints.emplace_back(Acceleration{105, 25, Eigen::Vector2d::Zero()});
  request.constraints.emplace_back(Sum{right, {}, 30, 32, std::nullopt});
  request.constraints.emplace_back(Row{{{100, 20, 0, 1.0}, {101, 22, 1, 0.5}}, 3.0});
  Result one, two;
  {
    ThreadLimit limit(1);
    one = edit_group_motion(crowd, split_from(16), request);
  }
  {
    ThreadLimit limit(2);
    two = edit_group_motion(crowd, split_from(16), request);
  }
  CHECK(one.crowd.positions == two.crowd.positions);
  CHECK(one.report.max_output_residual < 1e-9);
}
