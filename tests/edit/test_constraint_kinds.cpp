// The general constraints beyond relative position, velocity and on-a-line (issue 16): an acceleration at a
// frame, a weighted sum over agents (a centroid held on a path) and a user's own row. Each holds at every frame
// it covers while a drag pulls against it, changes the motion where it should, and agrees with the same
// constraint written another way; bad entries are ConfigErrors naming them, contradictions NumericalErrors.
#include "../graph/synthetic_crowd.h"

#include <throng/core/communicator.h>
#include <throng/core/errors.h>
#include <throng/core/progress.h>
#include <throng/edit/edit.h>
#include <throng/edit/guard.h>
#include <throng/edit/local_edit.h>
#include <throng/edit/runner.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace throng;
using namespace throng::edit;
using Catch::Matchers::Contains;

namespace {

constexpr double held = 1e-9;  // metres: what "holds" means for a constraint through the Schur complement

Drag move(Frame first, Frame last, Eigen::Vector2d offset) {
  Drag d;
  d.selection.first_frame = first;
  d.selection.last_frame = last;
  d.offset = offset;
  return d;
}

// The first frames held, the last ones dragged 2 m left and 3 m up: every constraint below is pulled on.
Request pulled() {
  Request r;
  r.drags = {move(0, 1, {0, 0}), move(29, 30, {2.0, 3.0})};
  return r;
}

Eigen::Vector2d xy(const CrowdMotion& c, std::size_t frame, std::int64_t id) {
  return c.position(frame, static_cast<std::size_t>(id - 100)).head<2>();
}

// The three-point second difference over unequal spacing at frames f0 < f1 < f2 (m/s²).
Eigen::Vector2d acceleration(const CrowdMotion& c, std::size_t f0, std::size_t f1, std::size_t f2, std::int64_t id) {
  const double h0 = c.times[f1] - c.times[f0], h1 = c.times[f2] - c.times[f1];
  return 2.0 * ((xy(c, f2, id) - xy(c, f1, id)) / h1 - (xy(c, f1, id) - xy(c, f0, id)) / h0) / (h0 + h1);
}

Eigen::Vector2d centroid(const CrowdMotion& c, std::size_t frame, const std::vector<std::int64_t>& ids) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::int64_t id : ids) sum += xy(c, frame, id);
  return sum / static_cast<double>(ids.size());
}

double max_gap(const CrowdMotion& a, const CrowdMotion& b) {
  REQUIRE(a.positions.size() == b.positions.size());
  double gap = 0;
  for (std::size_t k = 0; k < a.positions.size(); ++k) gap = std::max(gap, std::abs(a.positions[k] - b.positions[k]));
  return gap;
}

RowTerm term(std::int64_t agent, Frame frame, int axis, double coefficient) { return {agent, frame, axis, coefficient}; }

Options sampled(std::size_t step) {
  Options o;
  o.clip.sample_step = step;
  return o;
}

}  // namespace

TEST_CASE("acceleration, sum and row constraints hold at every output frame while a drag pulls against them") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 31, 1.0, 1.2, 0.1, 0.3, 0.2);
  Request request = pulled();
  const std::vector<std::int64_t> group{100, 101, 102};
  const Eigen::Vector2d centre(4.0, 0.5);
  request.constraints.push_back(Acceleration{103, 14, Eigen::Vector2d(0.5, -0.3)});
  request.constraints.push_back(Sum{group, {}, 10, 16, centre});
  request.constraints.push_back(Row{{term(104, 21, 0, 2.0), term(105, 22, 1, -1.0)}, 3.5});
  request.constraints.push_back(Sum{{106, 107}, {0.25, 0.75}, 3, 5, std::nullopt});  // the original's weighted sum
  const Result result = edit_group_motion(crowd, sampled(4), request);
  const CrowdMotion& out = result.crowd;
  CHECK((acceleration(out, 13, 14, 15, 103) - Eigen::Vector2d(0.5, -0.3)).norm() < held / 0.01);
  for (std::size_t f = 10; f <= 16; ++f) CHECK((centroid(out, f, group) - centre).norm() < held);
  CHECK(std::abs(2.0 * xy(out, 21, 104).x() - xy(out, 22, 105).y() - 3.5) < held);
  for (std::size_t f = 3; f <= 5; ++f) {
    const Eigen::Vector2d original = 0.25 * xy(crowd, f, 106) + 0.75 * xy(crowd, f, 107);
    CHECK((0.25 * xy(out, f, 106) + 0.75 * xy(out, f, 107) - original).norm() < held);
  }
  CHECK(result.report.max_output_residual < held);
  CHECK(result.report.max_constraint_residual < held);
  CHECK(result.report.constraint_rows == 2 + 2 * 7 + 1 + 2 * 3);
  // The drag did pull: without the constraints the centroid is elsewhere.
  Request free = pulled();
  const Result unconstrained = edit_group_motion(crowd, sampled(4), free);
  CHECK((centroid(unconstrained.crowd, 13, group) - centre).norm() > 0.5);
  // The output residual reads the output: the input itself misses the centroid by its distance from `centre`.
  CHECK_THAT(max_request_residual(crowd, crowd, 0, Request{{}, {}, {Sum{group, {}, 10, 10, centre}}}),
             Catch::Matchers::WithinAbs((centroid(crowd, 10, group) - centre).norm(), 1e-12));
}

TEST_CASE("a zero acceleration straightens a curving path at that frame, unequal frame times included") {
  CrowdMotion crowd = test::marching_grid(3, 3, 31, 1.0, 1.2, 0.1, 0.8, 0.1);
  // Unequal spacing: frame times 0.1 s apart, stretched by up to ±30 % (the positions stay: a faster and slower walk).
  for (std::size_t f = 1; f < crowd.frame_count(); ++f) {
    crowd.times[f] = crowd.times[f - 1] + 0.1 * (1.0 + 0.3 * std::sin(1.7 * static_cast<double>(f)));
  }
  for (Frame frame : {Frame{15}, Frame{0}, Frame{-1}}) {
    Request request;
    request.drags = {move(0, 0, {0, 0}), move(-1, -1, {0.5, -1.0})};
    request.constraints.push_back(Acceleration{104, frame, Eigen::Vector2d::Zero()});
    const Result result = edit_group_motion(crowd, {}, request);
    // The three frames the editor fits: f − 1, f, f + 1 inside, the three nearest at the clip's ends.
    const std::size_t mid = frame == 0 ? 1 : frame == -1 ? 29 : 15;
    CAPTURE(frame);
    CHECK(acceleration(crowd, mid - 1, mid, mid + 1, 104).norm() > 0.5);  // the input curves there
    CHECK(acceleration(result.crowd, mid - 1, mid, mid + 1, 104).norm() < held / 0.01);
    CHECK(result.report.max_output_residual < held);
  }
  // A non-zero acceleration is met by the unequal-spacing formula (not by (p0 − 2 p1 + p2)/Δt²).
  Request request;
  request.drags = {move(0, 0, {0, 0}), move(-1, -1, {0, 0})};
  request.constraints.push_back(Acceleration{104, 9, Eigen::Vector2d(1.0, 2.0)});
  const Result result = edit_group_motion(crowd, {}, request);
  CHECK((acceleration(result.crowd, 8, 9, 10, 104) - Eigen::Vector2d(1.0, 2.0)).norm() < held / 0.01);
  const double h = crowd.times[9] - crowd.times[8];
  const Eigen::Vector2d uniform = (xy(result.crowd, 10, 104) - 2 * xy(result.crowd, 9, 104) + xy(result.crowd, 8, 104)) / (h * h);
  CHECK((uniform - Eigen::Vector2d(1.0, 2.0)).norm() > 0.1);  // the spacing is unequal there: the formulas differ
}

TEST_CASE("rows written for x and y give the same edit as the relative-position constraint") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 31, 1.0, 1.2, 0.1, 0.3, 0.2);
  const Eigen::Vector2d offset(0.3, -1.7);
  Request as_kind = pulled();
  as_kind.constraints.push_back(RelativePosition{100, 105, 12, 12, offset});
  Request as_rows = pulled();
  as_rows.constraints.push_back(Row{{term(100, 12, 0, 1.0), term(105, 12, 0, -1.0)}, offset.x()});
  as_rows.constraints.push_back(Row{{term(105, 12, 1, -1.0), term(100, 12, 1, 1.0)}, offset.y()});
  const Result a = edit_group_motion(crowd, sampled(4), as_kind);
  const Result b = edit_group_motion(crowd, sampled(4), as_rows);
  CHECK(b.report.constraint_rows == 2);
  CHECK(max_gap(a.crowd, b.crowd) < held);
  CHECK((xy(b.crowd, 12, 100) - xy(b.crowd, 12, 105) - offset).norm() < held);
  // A velocity written as two rows of its own (Δp = v Δt), scaled: the same edit again.
  Request velocity = pulled();
  velocity.constraints.push_back(Velocity{103, 20, Eigen::Vector2d(1.5, 0.2)});
  Request velocity_rows = pulled();
  const double dt = crowd.times[21] - crowd.times[20];
  velocity_rows.constraints.push_back(Row{{term(103, 21, 0, 3.0), term(103, 20, 0, -3.0)}, 3.0 * 1.5 * dt});
  velocity_rows.constraints.push_back(Row{{term(103, 21, 1, 1.0), term(103, 20, 1, -1.0)}, 0.2 * dt});
  CHECK(max_gap(edit_group_motion(crowd, sampled(4), velocity).crowd, edit_group_motion(crowd, sampled(4), velocity_rows).crowd) < held);
}

TEST_CASE("a sum with weights 1/n holds the centroid: the same edit as explicit weights or per-axis rows") {
  const CrowdMotion crowd = test::marching_grid(3, 4, 31, 1.0, 1.2, 0.1, 0.3, 0.2);
  const std::vector<std::int64_t> group{104, 105, 106, 107};
  // The centroid on a straight line across the drag: (1 + 0.1 f, 0.5) at frames 8..12.
  Request by_default = pulled(), by_weights = pulled(), by_rows = pulled();
  for (std::size_t f = 8; f <= 12; ++f) {
    const Eigen::Vector2d at(1.0 + 0.1 * static_cast<double>(f), 0.5);
    by_default.constraints.push_back(Sum{group, {}, static_cast<Frame>(f), static_cast<Frame>(f), at});
    by_weights.constraints.push_back(Sum{group, {0.25, 0.25, 0.25, 0.25}, static_cast<Frame>(f), static_cast<Frame>(f), at});
    for (int axis = 0; axis < 2; ++axis) {
      Row row{{}, at[axis]};
      for (std::int64_t id : group) row.terms.push_back(term(id, static_cast<Frame>(f), axis, 0.25));
      by_rows.constraints.push_back(row);
    }
  }
  const Result a = edit_group_motion(crowd, sampled(4), by_default);
  const Result b = edit_group_motion(crowd, sampled(4), by_weights);
  const Result c = edit_group_motion(crowd, sampled(4), by_rows);
  for (std::size_t f = 8; f <= 12; ++f) {
    CHECK((centroid(a.crowd, f, group) - Eigen::Vector2d(1.0 + 0.1 * static_cast<double>(f), 0.5)).norm() < held);
  }
  CHECK(max_gap(a.crowd, b.crowd) < held);
  CHECK(max_gap(a.crowd, c.crowd) < held);
  // The agents are free around their centroid: they do not all sit on it.
  CHECK((xy(a.crowd, 10, 104) - xy(a.crowd, 10, 107)).norm() > 0.5);
}

TEST_CASE("the new kinds hold in a local edit too") {
  const CrowdMotion crowd = test::marching_grid(4, 5, 41, 1.0, 1.2, 0.1, 0.2, 0.2);
  Options options = sampled(2);
  options.local.parts = 8;
  options.local.halo = 1;
  Request request;
  request.drags = {move(0, 1, {0, 0}), move(39, 40, {0, 0}), move(20, 20, {0.0, 1.0})};
  request.drags[2].selection.agents = {100, 101};
  request.constraints.push_back(Sum{{102, 103}, {}, 19, 21, std::nullopt});
  request.constraints.push_back(Acceleration{104, 18, Eigen::Vector2d::Zero()});
  request.constraints.push_back(Row{{term(105, 22, 0, 1.0)}, xy(crowd, 22, 105).x() + 0.2});
  const Result result = edit_locally(crowd, options, request);
  CHECK(max_request_residual(crowd, result.crowd, result.first_frame, request) < held);
  CHECK(result.report.constraint_rows == 2 * 3 + 2 + 1);
}

TEST_CASE("the guard holds the frames the new kinds cover") {
  Request r;
  r.constraints = {Acceleration{100, 15, {0, 0}}, Acceleration{100, 10, {0, 0}}, Acceleration{100, -1, {0, 0}},
                   Sum{{100, 101}, {}, 12, 13, std::nullopt}, Row{{term(100, 17, 0, 1.0), term(101, -2, 1, 1.0)}, 0.0}};
  // Clip [10, 20]: 14..16, 10..12 (one-sided at the first frame), 18..20 (at the last), 12..13, 17 and 19.
  CHECK(constrained_frames(r, 10, 20) == std::vector<std::size_t>{10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20});
  r.constraints = {Acceleration{100, 15, {0, 0}}, Row{{term(100, 18, 0, 1.0)}, 0.0}};
  CHECK(constrained_frames(r, 10, 20) == std::vector<std::size_t>{14, 15, 16, 18});
}

TEST_CASE("contradictory rows are a numerical error naming them") {
  const CrowdMotion crowd = test::marching_grid(3, 3, 21, 1.0, 1.2, 0.1, 0.2, 0.2);
  Request r;
  r.drags = {move(0, 0, {0, 0}), move(-1, -1, {0, 0})};
  r.constraints.push_back(Row{{term(101, 10, 0, 1.0)}, 5.0});
  r.constraints.push_back(Row{{term(101, 10, 0, 2.0)}, 12.0});  // x = 6
  CHECK_THROWS_WITH(edit_group_motion(crowd, {}, r),
                    Contains("contradictory constraints: constraints[0] (row of 1 term from agent 101 at frame 10) and constraints[1]"));
  CHECK_THROWS_AS(edit_group_motion(crowd, {}, r), NumericalError);
  // A centroid of one agent against a row on the same agent.
  r.constraints = {Sum{{102}, {}, 7, 7, Eigen::Vector2d(1, 1)}, Row{{term(102, 7, 1, 1.0)}, 3.0}};
  CHECK_THROWS_WITH(edit_group_motion(crowd, {}, r), Contains("constraints[0] (sum over agent 102) and constraints[1]"));
  // An acceleration at frames the drags decide otherwise.
  r.drags = {move(0, 2, {0, 0}), move(-1, -1, {0, 0})};
  r.constraints = {Acceleration{101, 1, Eigen::Vector2d(3, 0)}};
  CHECK_THROWS_WITH(edit_group_motion(crowd, {}, r),
                    Contains("constraints[0] (acceleration of agent 101 at frame 1) cannot be met together with the pins and drags"));
}

TEST_CASE("bad acceleration, sum and row entries are configuration errors naming the entry") {
  const CrowdMotion crowd = test::marching_grid(3, 3, 21, 1.0, 1.2, 0.1, 0.2, 0.2);
  auto expect = [&](const Constraint& c, const std::string& text, const CrowdMotion* other = nullptr) {
    Request r;
    r.drags = {move(0, 0, {0, 0}), move(-1, -1, {0, 0})};
    r.constraints = {Acceleration{100, 5, {0, 0}}, c};
    CAPTURE(text);
    CHECK_THROWS_AS(edit_group_motion(other ? *other : crowd, {}, r), ConfigError);
    CHECK_THROWS_WITH(edit_group_motion(other ? *other : crowd, {}, r), Contains(text));
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expect(Acceleration{999, 5, {0, 0}}, "constraints[1].agent: no agent with id 999 in the crowd");
  expect(Acceleration{101, 21, {0, 0}}, "constraints[1].frame 21 is outside the clip [0, 20]");
  expect(Acceleration{101, 5, {nan, 0}}, "constraints[1].acceleration (nan, 0) is not finite");
  const CrowdMotion two_frames = test::marching_grid(2, 2, 2);
  {
    Request r;
    r.drags = {move(0, 0, {0, 0}), move(1, 1, {0, 0})};
    r.constraints = {Acceleration{100, 0, {0, 0}}};
    CHECK_THROWS_WITH(edit_group_motion(two_frames, {}, r),
                      Contains("constraints[0]: an acceleration needs three frames, and the clip [0, 1] has 2"));
  }
  expect(Sum{{}, {}, 0, -1, std::nullopt}, "constraints[1].agents: no agent given");
  expect(Sum{{100, 999}, {}, 0, -1, std::nullopt}, "constraints[1].agents[1]: no agent with id 999 in the crowd");
  expect(Sum{{100, 101, 100}, {}, 0, -1, std::nullopt}, "constraints[1].agents[2]: agent 100 is named twice");
  expect(Sum{{100, 101}, {1.0}, 0, -1, std::nullopt}, "constraints[1].weights: 1 weights for 2 agents");
  expect(Sum{{100, 101}, {0.0, 0.0}, 0, -1, std::nullopt}, "constraints[1].weights: every weight is 0");
  expect(Sum{{100, 101}, {0.5, nan}, 0, -1, std::nullopt}, "constraints[1].weights[1] is not finite");
  expect(Sum{{100, 101}, {}, 0, -1, Eigen::Vector2d(nan, 0)}, "constraints[1].value (nan, 0) is not finite");
  expect(Sum{{100, 101}, {}, 30, 40, std::nullopt}, "constraints[1]: frames [30, 40] are outside the clip [0, 20]");
  expect(Row{{}, 0.0}, "constraints[1].terms: no term given");
  expect(Row{{term(100, 3, 0, 1.0), term(999, 3, 0, 1.0)}, 0.0}, "constraints[1].terms[1].agent: no agent with id 999 in the crowd");
  expect(Row{{term(100, 40, 0, 1.0)}, 0.0}, "constraints[1].terms[0].frame 40 is outside the clip [0, 20]");
  expect(Row{{term(100, 3, 2, 1.0)}, 0.0}, "constraints[1].terms[0].axis 2: expected x (0) or y (1)");
  expect(Row{{term(100, 3, 0, nan)}, 0.0}, "constraints[1].terms[0].coefficient is not finite");
  expect(Row{{term(100, 3, 0, 1.0)}, nan}, "constraints[1].value is not finite");
  expect(Row{{term(100, 3, 0, 0.0), term(101, 3, 0, 0.0)}, 1.0}, "constraints[1].terms: every coefficient is 0");
  // The same coordinate twice, also when one frame counts back from the end (20 is −1 in a 21-frame clip).
  expect(Row{{term(100, 20, 1, 1.0), term(101, 3, 0, 1.0), term(100, -1, 1, 2.0)}, 0.0},
         "constraints[1].terms[2]: the same coordinate as constraints[1].terms[0] (agent 100, frame 20, y)");
}

TEST_CASE("acceleration, sum and row constraints still hold after the guard smooths the edit") {
  // As tests/edit/test_guard.cpp's kink case: held to frame 40, 0.5 m to the side from frame 60; the guard smooths
  // the bend between (no warp), and the frames the new kinds name inside the bend are held.
  Crowd input;
  input.motion = test::marching_grid(3, 4, 97, 1.0, 1.2, 0.1, 0.0, 0.1);
  Job job;
  job.options.clip.sample_step = 6;
  job.request.drags = {move(0, 40, {0, 0}), move(60, -1, {0, 0.5})};
  job.request.constraints = {Acceleration{104, 50, Eigen::Vector2d(0.0, 0.4)}, Sum{{100, 101, 102}, {}, 44, 46, std::nullopt},
                             Row{{term(105, 55, 1, 1.0), term(106, 53, 1, -1.0)}, -0.8}};
  job.guard.max_speed_ratio = 10;  // smoothing alone
  job.guard.max_acceleration = 1.0;
  NoProgress progress;
  const Run after = run({&input}, job, progress, Communicator::single());
  REQUIRE_FALSE(after.guard.warped);
  CHECK(after.guard.kinks_before > 0);
  CHECK(after.guard.largest_shift > 1e-3);  // the guard moved frames
  CHECK(after.residual_after_guard);
  CHECK(after.result.report.max_output_residual < held);  // measured on the guarded frames
}
