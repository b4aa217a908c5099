// redrag (solver/edit/src/request.h): a request that moves the same handles again, resolved from the last
// resolution, must give resolve()'s bits, and must refuse whatever it cannot bring up to date.
#include "../graph/synthetic_crowd.h"
#include "request.h"

#include <throng/core/errors.h>
#include <throng/core/random.h>
#include <throng/graph/clip.h>

#include <catch2/catch.hpp>

#include <cfloat>
#include <cstring>
#include <numbers>

using namespace throng;
using namespace throng::edit;
using Catch::Matchers::Contains;

namespace {


Drag drag_of(Frame first, Frame last, std::vector<std::int64_t> agents = {}) {
  Drag d;
  d.selection = {.agents = std::move(agents), .first_frame = first, .last_frame = last};
  return d;
}

// Pins with and without a position, everyone's first and last frame held, a turned group with its default pivot,
// a group with a pivot of its own, and a velocity constraint.
Request request_of() {
  Request r;
  r.pins = {{.agent = 110, .frame = 12, .position = std::nullopt}, {.agent = 111, .frame = 12, .position = Eigen::Vector2d(4.0, 1.5)}};
  r.drags = {drag_of(0, 0), drag_of(-1, -1), drag_of(14, 18, {100, 101, 102, 103}), drag_of(20, 22, {140, 141})};
  r.drags[2].offset = {0.5, -0.25};
  r.drags[2].rotation = 0.3;
  r.drags[3].pivot = Eigen::Vector2d(1.0, 2.0);
  r.constraints.push_back(Velocity{.agent = 120, .frame = 8, .velocity = {0.5, 0.2}});
  return r;
}

// 48 agents (ids 100..147) marching for 31 frames, every frame a sample, and a request with its resolution.
struct Setup {
  explicit Setup(Request request = request_of())
      : before(std::move(request)), original(resolve(before, clip, crowd.ids)) {}
  CrowdMotion crowd = test::marching_grid(6, 8, 31, 1.0, 1.2, 0.1, 0.3, 0.2);
  Clip clip = make_clip(crowd, ClipOptions{});
  Request before;
  ResolvedRequest original;
};

template <typename T>
bool same_bytes(const T* a, const T* b, std::size_t n) { return n == 0 || std::memcmp(a, b, n * sizeof(T)) == 0; }

bool same_matrix(linalg::SparseMatrix a, linalg::SparseMatrix b) {
  a.makeCompressed();
  b.makeCompressed();
  const auto nnz = static_cast<std::size_t>(a.nonZeros());
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() &&
         same_bytes(a.outerIndexPtr(), b.outerIndexPtr(), static_cast<std::size_t>(a.outerSize()) + 1) &&
         same_bytes(a.innerIndexPtr(), b.innerIndexPtr(), nnz) && same_bytes(a.valuePtr(), b.valuePtr(), nnz);
}

// Every field, bit for bit.
void check_same(const ResolvedRequest& got, const ResolvedRequest& want) {
  CHECK(got.handle_vertices == want.handle_vertices);
  REQUIRE(got.handle_targets.rows() == want.handle_targets.rows());
  CHECK(same_bytes(got.handle_targets.data(), want.handle_targets.data(), static_cast<std::size_t>(want.handle_targets.size())));
  REQUIRE(got.handle_coordinates.size() == want.handle_coordinates.size());
  CHECK(same_bytes(got.handle_coordinates.data(), want.handle_coordinates.data(), static_cast<std::size_t>(want.handle_coordinates.size())));
  CHECK(same_matrix(got.handle_basis, want.handle_basis));
  CHECK(same_matrix(got.C, want.C));
  REQUIRE(got.d.size() == want.d.size());
  CHECK(same_bytes(got.d.data(), want.d.data(), static_cast<std::size_t>(want.d.size())));
  CHECK(got.row_source == want.row_source);
  REQUIRE(got.drags.size() == want.drags.size());
  for (std::size_t k = 0; k < want.drags.size(); ++k) {
    CHECK(got.drags[k].rows == want.drags[k].rows);
    CHECK(got.drags[k].alone == want.drags[k].alone);
    CHECK(got.drags[k].column == want.drags[k].column);
    CHECK(same_bytes(got.drags[k].centroid.data(), want.drags[k].centroid.data(), 2));
  }
}

}  // namespace

TEST_CASE("redrag gives resolve's bits for new offsets, rotations and pivots of the same drags") {
  const Setup setup;
  const auto& [crowd, clip, first, original] = setup;
  Request before = first;
  ResolvedRequest resolved = original;
  REQUIRE(resolved.drags.size() == 4);
  // The first and last frames of all 48 agents, 5 × 4 and 3 × 2 group handles: each placed by its drag alone.
  CHECK(resolved.drags[0].rows.size() == 48);
  CHECK(resolved.drags[2].rows.size() == 20);
  CHECK(resolved.drags[3].rows.size() == 6);
  for (const auto& d : resolved.drags) CHECK(d.alone);
  Rng random(7);
  for (int step = 0; step < 40; ++step) {
    Request now = before;
    // One or two drags change, in any of their motion's values (a rotation back to 0 included).
    for (int change = 0; change < 1 + step % 2; ++change) {
      Drag& d = now.drags[random.below(4)];
      d.offset = {random.uniform(-3, 3), random.uniform(-3, 3)};
      d.rotation = step % 5 == 0 ? 0.0 : random.uniform(-std::numbers::pi, std::numbers::pi);
      if (step % 3 == 0) d.pivot = Eigen::Vector2d(random.uniform(-5, 5), random.uniform(-5, 5));
      if (step % 7 == 0) d.pivot.reset();
    }
    INFO("step " << step);
    REQUIRE(redrag(resolved, before, now, clip));
    check_same(resolved, resolve(now, clip, crowd.ids));
    before = now;
  }
  // Nothing changed: nothing to do, and still the same.
  REQUIRE(redrag(resolved, before, before, clip));
  check_same(resolved, resolve(before, clip, crowd.ids));
}

TEST_CASE("redrag refuses requests that differ in more than their drags' motion, and leaves the resolution alone") {
  const Setup setup;
  const auto& [crowd, clip, before, original] = setup;
  ResolvedRequest resolved = original;
  auto refused = [&](const Request& now) {
    const bool done = redrag(resolved, before, now, clip);
    check_same(resolved, original);
    return !done;
  };
  Request now = before;
  now.drags[2].selection.agents.push_back(104);
  CHECK(refused(now));
  now = before;
  now.drags[3].selection.last_frame = 23;
  CHECK(refused(now));
  now = before;
  now.pins[1].position = Eigen::Vector2d(4.0, 1.75);
  CHECK(refused(now));
  now = before;
  now.pins[0].position = Eigen::Vector2d(0, 0);
  CHECK(refused(now));
  now = before;
  now.constraints[0] = Velocity{.agent = 120, .frame = 8, .velocity = {0.5, 0.25}};
  CHECK(refused(now));
  now = before;
  now.constraints.clear();
  CHECK(refused(now));
  // Equal constraint values whose zeros differ in sign: resolve()'s d would differ in bits.
  now = before;
  now.constraints[0] = Velocity{.agent = 120, .frame = 8, .velocity = {0.5, 0.2}};
  CHECK_FALSE(refused(now));  // the same bits: taken (nothing to change)
  Request zero_velocity = before;
  zero_velocity.constraints[0] = Velocity{.agent = 120, .frame = 8, .velocity = {0.0, 0.2}};
  ResolvedRequest at_zero_velocity = resolve(zero_velocity, clip, crowd.ids);
  now = zero_velocity;
  std::get<Velocity>(now.constraints[0]).velocity.x() = -0.0;
  CHECK_FALSE(redrag(at_zero_velocity, zero_velocity, now, clip));
  now = before;
  now.drags.pop_back();
  CHECK(refused(now));
  // Equal pins whose zeros differ in sign: resolve()'s coordinates would differ in bits.
  Request zero = before;
  zero.pins[1].position = Eigen::Vector2d(0.0, 1.5);
  ResolvedRequest at_zero = resolve(zero, clip, crowd.ids);
  now = zero;
  now.pins[1].position = Eigen::Vector2d(-0.0, 1.5);
  CHECK_FALSE(redrag(at_zero, zero, now, clip));
  // A resolution made elsewhere (no drag placements) is not brought up to date.
  ResolvedRequest bare = original;
  bare.drags.clear();
  now = before;
  now.drags[2].offset = {1, 1};
  CHECK_FALSE(redrag(bare, before, now, clip));
}

TEST_CASE("redrag refuses a changed drag that shares a vertex with another entry: resolve() must check them") {
  Request overlapping = request_of();
  overlapping.pins.push_back({.agent = 101, .frame = 15, .position = std::nullopt});  // inside drags[2]'s group
  overlapping.drags[2].offset = {0, 0};
  overlapping.drags[2].rotation = 0;  // so the pin and the drag agree
  const Setup setup(overlapping);
  const auto& [crowd, clip, before, original] = setup;
  CHECK_FALSE(original.drags[2].alone);
  CHECK(original.drags[3].alone);
  ResolvedRequest resolved = original;
  Request now = before;
  now.drags[2].offset = {1, 0};  // now they disagree at agent 101, frame 15
  CHECK_FALSE(redrag(resolved, before, now, clip));
  check_same(resolved, original);
  CHECK_THROWS_AS(resolve(now, clip, crowd.ids), NumericalError);
  // The drag that placed its own vertices alone still takes the fast way.
  now = before;
  now.drags[3].offset = {0.5, 0.5};
  REQUIRE(redrag(resolved, before, now, clip));
  check_same(resolved, resolve(now, clip, crowd.ids));
  // A selection that names an agent twice places its vertices twice: not alone.
  Request twice = request_of();
  twice.drags[3].selection.agents = {141, 140, 141};
  ResolvedRequest twice_resolved = resolve(twice, clip, crowd.ids);
  CHECK_FALSE(twice_resolved.drags[3].alone);
  now = twice;
  now.drags[3].offset = {0.25, 0};
  CHECK_FALSE(redrag(twice_resolved, twice, now, clip));
}

TEST_CASE("redrag leaves a motion that is not finite to resolve(), which names it, and leaves the resolution alone") {
  const Setup setup;
  const auto& [crowd, clip, before, original] = setup;
  ResolvedRequest resolved = original;
  Request now = before;
  now.drags[1].offset = {1, 1};  // a change that would be written, were the next one finite
  now.drags[2].offset.x() = std::numeric_limits<double>::quiet_NaN();
  CHECK_FALSE(redrag(resolved, before, now, clip));
  check_same(resolved, original);
  CHECK_THROWS_WITH(resolve(now, clip, crowd.ids), Contains("drags[2]: offset, rotation and pivot must be finite"));
  // A finite motion whose targets overflow: turned by π about a pivot at the largest double.
  now = before;
  now.drags[1].offset = {1, 1};
  now.drags[3].rotation = std::numbers::pi;
  now.drags[3].pivot = Eigen::Vector2d(DBL_MAX, 0);
  CHECK_FALSE(redrag(resolved, before, now, clip));
  check_same(resolved, original);
  CHECK_THROWS_WITH(resolve(now, clip, crowd.ids), Contains("drags[3]: target position") && Contains("is not finite"));
}
