// The iterative method of the Editor (solver.method iterative): within its stated tolerance of the direct
// (exact) method, handles exactly and constraints to rounding, the same for repeated drags as for fresh
// solves, and the same bits for any thread count. Tolerances come from the method's contract: positions within
// SolverOptions::position_tolerance of the exact solve.
#include "../graph/synthetic_crowd.h"
#include "shipped_scenes.h"
#include "test_paths.h"

#include <throng/core/errors.h>
#include <throng/core/parallel.h>
#include <throng/edit/edit.h>
#include <throng/linalg/spd_solver.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>

using namespace throng;
using namespace throng::edit;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 2>;
using Catch::Matchers::Contains;

namespace {

Drag hold(Frame first, Frame last) {
  Drag d;
  d.selection.first_frame = first;
  d.selection.last_frame = last;
  return d;
}

Drag move(Frame first, Frame last, Eigen::Vector2d offset, double rotation = 0.0, std::vector<std::int64_t> agents = {}) {
  Drag d = hold(first, last);
  d.offset = offset;
  d.rotation = rotation;
  d.selection.agents = std::move(agents);
  return d;
}

// 48 agents marching and turning for 121 frames, sampled every second frame (61 samples, 2,928 vertices).
CrowdMotion scene() { return test::marching_grid(6, 8, 121, 1.0, 1.2, 0.1, 0.3, 0.2); }

Options with_method(const std::string& method, double tolerance = 1e-4) {
  Options o;
  o.clip.sample_step = 2;
  o.solver.method = method;
  o.solver.position_tolerance = tolerance;
  return o;
}

// The head held, the tail turned and moved, a group in the middle pulled aside.
Request head_and_tail(Eigen::Vector2d tail_offset) {
  Request r;
  r.drags = {hold(0, 1), move(-6, -1, tail_offset, 0.3), move(58, 62, {0.0, 1.5}, 0.0, {119, 120, 121})};
  return r;
}

double max_distance(const Positions& a, const Positions& b) {
  REQUIRE(a.rows() == b.rows());
  return (a - b).rowwise().norm().maxCoeff();
}

Positions direct_solution(const CrowdMotion& crowd, Options options, const Request& request) {
  options.solver.method = "direct";
  Editor editor(crowd, options, request);
  editor.precompute();
  return editor.deform(request);
}

bool same_bits(const Positions& a, const Positions& b) {
  return a.rows() == b.rows() && std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

}  // namespace

TEST_CASE("the iterative method is within its tolerance of the direct one, handles met exactly") {
  const CrowdMotion crowd = scene();
  const Request request = head_and_tail({3.0, 4.0});
  const Options options = with_method("iterative");
  Editor editor(crowd, options, request);
  editor.precompute();
  const Positions x = editor.deform(request);
  const Report& r = editor.report();
  CHECK(r.method == "iterative");
  CHECK(r.coarse_size > 0);
  CHECK(r.solver_error_m <= options.solver.position_tolerance);
  const Positions exact = direct_solution(crowd, options, request);
  const double difference = max_distance(x, exact);
  CAPTURE(difference, r.iterations, r.precompute_iterations);
  CHECK(difference <= options.solver.position_tolerance);
  // The edit moves vertices by metres: the comparison is not vacuous.
  CHECK(max_distance(exact, editor.graph().clip.positions) > 2.0);
  // Handles sit exactly at their targets: the same bits as the direct method puts there (both place them from
  // the resolved request), which are the drag's formula (rotation about the selection's centroid, the offset
  // added) to rounding: pivot + (p − pivot) + offset rounds differently from p + offset.
  const Clip& clip = editor.graph().clip;
  const long frame58 = clip.sample_of_frame(58);  // a dragged frame of the middle group (frames 1, 59, 61 are samples too)
  REQUIRE(frame58 >= 0);
  const Eigen::Index head = clip.vertex(0, 5), middle = clip.vertex(static_cast<std::size_t>(frame58), static_cast<std::size_t>(clip.agent_of_id(120)));
  for (const Eigen::Index handle : {head, middle}) CHECK(same_bits(Positions(x.row(handle)), Positions(exact.row(handle))));
  CHECK(same_bits(Positions(x.row(head)), Positions(clip.positions.row(head))));
  const double rounding = 1e-13 * (1.0 + clip.positions.cwiseAbs().maxCoeff());
  CHECK((x.row(middle) - clip.positions.row(middle) - Eigen::RowVector2d(0.0, 1.5)).norm() <= rounding);
  // Step 1 alone is also within the tolerance of the direct step 1.
  Options direct_options = options;
  direct_options.solver.method = "direct";
  Editor direct(crowd, direct_options, request);
  (void)direct.deform(request);
  CHECK(max_distance(editor.step1(), direct.step1()) <= options.solver.position_tolerance);
}

TEST_CASE("the shipped battlefield edit: the iterative method against the direct one") {
  const test::ShippedEdit shipped = test::battlefield(test::source_dir());
  Options options = shipped.job.options;
  options.solver.method = "iterative";
  options.solver.compare_direct = true;
  const Result result = edit_group_motion(shipped.crowd, options, shipped.job.request);
  const Report& r = result.report;
  CAPTURE(r.direct_difference_m, r.iterations, r.precompute_iterations, r.solver_error_m);
  CHECK(r.method == "iterative");
  REQUIRE(r.direct_difference_m >= 0);
  // The default tolerance (1 mm), and so well within the 1 cm.
  CHECK(r.direct_difference_m <= options.solver.position_tolerance);
  // Every pin and drag holds on the written frames to rounding, as with the direct method.
  CHECK(r.max_output_residual < 1e-6);
}

TEST_CASE("general constraints are met to rounding and contradictions are named, as with the direct method") {
  const CrowdMotion crowd = test::marching_grid(5, 6, 61, 1.0, 1.2, 0.1, 0.3, 0.2);
  Options options = with_method("iterative");
  options.clip.sample_step = 4;
  Request request;
  request.drags = {hold(0, 1), move(59, 60, {2.0, 3.0})};
  request.pins = {{105, 13, Eigen::Vector2d(9.0, 1.5)}};
  request.constraints.push_back(RelativePosition{100, 101, 15, 21, Eigen::Vector2d(0.0, -1.5)});
  request.constraints.push_back(Velocity{103, 22, Eigen::Vector2d(1.5, 0.2)});
  request.constraints.push_back(OnLine{110, 5, 11, Eigen::Vector2d(6.0, -1.0), Eigen::Vector2d(1.0, 0.5)});
  Editor editor(crowd, options, request);
  const Positions x = editor.deform(request);
  const Report& r = editor.report();
  double extent = 1.0;
  for (double v : crowd.positions) extent = std::max(extent, std::abs(v));
  CAPTURE(r.max_constraint_residual);
  CHECK(r.max_constraint_residual <= options.solver.constraint_tolerance * (1.0 + extent));
  CHECK(max_distance(x, direct_solution(crowd, options, request)) <= options.solver.position_tolerance);
  // Two offsets for one pair over the same frames cannot both hold.
  Request contradiction = request;
  contradiction.constraints.push_back(RelativePosition{100, 101, 15, 21, Eigen::Vector2d(0.5, -1.5)});
  Editor bad(crowd, options, contradiction);
  try {
    (void)bad.deform(contradiction);
    FAIL("contradictory constraints were accepted");
  } catch (const NumericalError& e) {
    CHECK_THAT(e.what(), Contains("contradictory") && Contains("constraints[0]") && Contains("constraints[3]"));
  }
}

TEST_CASE("repeated drags of one editor equal a fresh editor's solve, within twice the tolerance") {
  const CrowdMotion crowd = scene();
  const Options options = with_method("iterative");
  Editor editor(crowd, options, head_and_tail({3.0, 4.0}));
  editor.precompute();
  Positions last;
  for (int k = 0; k < 6; ++k) last = editor.deform(head_and_tail({3.0 + 0.3 * k, 4.0 - 0.2 * k}));
  CHECK(editor.report().factorizations == 2);  // both steps set up once: drags add none
  const Request final_request = head_and_tail({4.5, 3.0});
  Editor fresh(crowd, options, final_request);
  const Positions once = fresh.deform(final_request);
  // Each is within the tolerance of the exact solution, so within twice of each other.
  CHECK(max_distance(last, once) <= 2 * options.solver.position_tolerance);
  CHECK(max_distance(last, direct_solution(crowd, options, final_request)) <= options.solver.position_tolerance);
  // Every drag starts from a span (the precompute's probes, then the drags before it): a few iterations at most.
  CAPTURE(editor.report().iterations, fresh.report().iterations);
  CHECK(editor.report().iterations <= 6);
  CHECK(fresh.report().iterations <= 6);
}

TEST_CASE("the precompute probes the moved drag, so the first drags of a gesture start as close as later ones") {
  // Without the probes the first drag after the precompute started from step 1's result alone and took the most
  // iterations of the gesture (here, to 0.1 mm: 14, 9 and 5 for the three drags below and 8 for the still request;
  // 116 and 24 for the first two at 10,000 agents, bench_edit), the second the next most. With them: 4, 3, 1 and 4.
  const CrowdMotion crowd = scene();
  const Options options = with_method("iterative");
  Editor editor(crowd, options, head_and_tail({3.0, 4.0}));
  editor.precompute();
  for (int k = 0; k < 3; ++k) {
    const Request request = head_and_tail({3.0 + 0.4 * k, 4.0 - 0.3 * k});
    const Positions x = editor.deform(request);
    CAPTURE(k, editor.report().iterations);
    CHECK(editor.report().iterations <= 6);
    CHECK(max_distance(x, direct_solution(crowd, options, request)) <= options.solver.position_tolerance);
  }
  // A request that moves no drag yet (a selection just made): the last drag is probed, and dragging it is as quick.
  Request still = head_and_tail({0.0, 0.0});
  still.drags[1].rotation = 0.0;
  still.drags[2].offset = {0.0, 0.0};
  std::swap(still.drags[1], still.drags[2]);  // the tail last
  Editor fresh(crowd, options, still);
  fresh.precompute();
  Request dragged = still;
  dragged.drags[2].offset = {0.6, -0.4};
  const Positions x = fresh.deform(dragged);
  CAPTURE(fresh.report().iterations);
  CHECK(fresh.report().iterations <= 6);
  CHECK(max_distance(x, direct_solution(crowd, options, dragged)) <= options.solver.position_tolerance);
}

TEST_CASE("a selection added to an editor's request is the drag its new precompute probes") {
  // The tail dragged first; then the middle group is added as a new drag (a session's next selection). The new
  // handle set is precomputed again, and the probes go to the new drag, not to the tail that was moved before.
  const CrowdMotion crowd = scene();
  const Options options = with_method("iterative");
  Request request;
  request.drags = {hold(0, 1), move(-6, -1, {3.0, 4.0}, 0.3)};
  const Request first = request;
  Editor editor(crowd, options, first);
  (void)editor.deform(request);
  request.drags.push_back(move(58, 62, {0.0, 1.5}, 0.0, {119, 120, 121}));
  (void)editor.deform(request);  // the new handles: a precompute, then this solve
  request.drags[2].offset = {0.4, 1.1};
  const Positions x = editor.deform(request);
  CAPTURE(editor.report().iterations);
  CHECK(editor.report().iterations <= 6);
  // Against the direct method on the same clip (the first request's samples).
  Options direct_options = options;
  direct_options.solver.method = "direct";
  Editor direct(crowd, direct_options, first);
  CHECK(max_distance(x, direct.deform(request)) <= options.solver.position_tolerance);
}

TEST_CASE("the iterative method gives the same bits for any thread count") {
  const CrowdMotion crowd = scene();
  const Options options = with_method("iterative");
  Positions results[2];
  for (std::size_t threads : {std::size_t{1}, std::size_t{2}}) {
    const ThreadLimit limit(threads);
    Editor editor(crowd, options, head_and_tail({3.0, 4.0}));
    (void)editor.deform(head_and_tail({3.0, 4.0}));
    results[threads - 1] = editor.deform(head_and_tail({3.5, 3.5}));
  }
  CHECK(same_bits(results[0], results[1]));
}

TEST_CASE("more individually placed pins than the handle basis holds are solved per drag, within the tolerance") {
  const CrowdMotion crowd = scene();
  const Options options = with_method("iterative");
  Request request;
  request.drags = {hold(0, 1)};
  // 40 pins with their own positions: 80 coordinates, beyond ConstrainedLeastSquares::max_basis_columns.
  for (int k = 0; k < 40; ++k) {
    const auto agent = static_cast<std::int64_t>(100 + k);
    const Eigen::Vector2d at = crowd.position(120, static_cast<std::size_t>(k)).head<2>() + Eigen::Vector2d(2.0, 0.5 * (k % 3));
    request.pins.push_back({agent, 120, at});
  }
  Editor editor(crowd, options, request);
  const Positions x = editor.deform(request);
  CHECK(editor.report().iterations > 0);  // step 1 is a solve per drag here
  CHECK(max_distance(x, direct_solution(crowd, options, request)) <= options.solver.position_tolerance);
}

TEST_CASE("without scale compensation the iterative result is step 1's") {
  const CrowdMotion crowd = scene();
  Options options = with_method("iterative");
  options.scale_compensation = false;
  const Request request = head_and_tail({3.0, 4.0});
  Editor editor(crowd, options, request);
  const Positions x = editor.deform(request);
  CHECK(same_bits(x, editor.step1()));
  CHECK(max_distance(x, direct_solution(crowd, options, request)) <= options.solver.position_tolerance);
}

TEST_CASE("auto solves small systems directly and large ones iteratively") {
  const CrowdMotion crowd = scene();
  const Request request = head_and_tail({3.0, 4.0});
  Options options = with_method("auto");
  Editor small(crowd, options, request);
  CHECK(small.report().method == "direct");
  options.solver.auto_direct_vertices = 1000;  // this scene has 2,928 vertices, 2,640 of them free
  Editor large(crowd, options, request);
  CHECK(large.report().method == "iterative");
  options.solver.backend = "petsc";  // auto never picks the iterative method for another backend
  const auto backends = linalg::available_backends();
  if (std::find(backends.begin(), backends.end(), "petsc") != backends.end()) {
    Editor distributed(crowd, options, request);
    CHECK(distributed.report().method == "direct");
  }
}

TEST_CASE("bad method options are configuration errors naming the key") {
  const CrowdMotion crowd = scene();
  const Request request = head_and_tail({3.0, 4.0});
  auto fails = [&](const Options& options, const std::string& key) {
    try {
      Editor editor(crowd, options, request);
      FAIL("accepted: " + key);
    } catch (const ConfigError& e) {
      CHECK_THAT(e.what(), Contains(key));
    }
  };
  Options o = with_method("cholesky");
  fails(o, "solver.method");
  o = with_method("iterative");
  o.solver.backend = "petsc";
  fails(o, "solver.backend");
  o = with_method("iterative", 0.0);
  fails(o, "solver.position_tolerance");
  o = with_method("iterative");
  o.solver.coarse_agents = 0;
  fails(o, "solver.coarse_agents");
  o = with_method("iterative");
  o.solver.coarse_samples = 0;
  fails(o, "solver.coarse_samples");
  o = with_method("iterative");
  o.solver.coarse_functions = 3;
  fails(o, "solver.coarse_functions");
}
