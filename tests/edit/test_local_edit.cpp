// Local edits (throng/edit/local_edit.h): what a wrong region, boundary or cache would break.
#include "../graph/synthetic_crowd.h"

#include <throng/core/errors.h>
#include <throng/edit/edit.h>
#include <throng/edit/local_edit.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>

using namespace throng;
using namespace throng::edit;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 2>;
using Catch::Matchers::Contains;

namespace {

constexpr std::size_t frames = 61;

Drag hold(Frame first, Frame last) {
  Drag d;
  d.selection.first_frame = first;
  d.selection.last_frame = last;
  return d;
}

// 48 agents marching for 61 frames, sampled every second frame: 31 samples, 1,488 vertices.
CrowdMotion scene() { return test::marching_grid(6, 8, frames, 1.0, 1.2, 0.1, 0.3, 0.2); }

Options local_options(int parts, int halo) {
  Options o;
  o.clip.sample_step = 2;
  o.local.parts = parts;
  o.local.halo = halo;
  return o;
}

// Everyone held at the first and last frame; agents 100..103 (a corner of the grid) dragged at frame 30.
Request corner_drag(Eigen::Vector2d offset, std::vector<std::int64_t> agents = {100, 101, 102, 103}) {
  Request r;
  r.drags = {hold(0, 0), hold(-1, -1)};
  Drag d = hold(30, 30);
  d.selection.agents = std::move(agents);
  d.offset = offset;
  r.drags.push_back(d);
  return r;
}

bool same_bits(const Eigen::RowVector2d& a, const Eigen::RowVector2d& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 2) == 0; }

// The step-1 systems are ~3·10³ unknowns over ~20 m; Cholesky round-off is ~1e-13 m (see test_properties.cpp).
// Assembling a subproblem sums AᵀWA in another order, so local and global differ by round-off only.
constexpr double rounding = 1e-9;

}  // namespace

TEST_CASE("a local edit whose halo covers the graph equals the global edit") {
  const CrowdMotion crowd = scene();
  const Request request = corner_drag({1.5, -0.8});
  for (bool scale_compensation : {true, false}) {
    Options global = local_options(0, 0);
    global.scale_compensation = scale_compensation;
    Editor editor(crowd, global, request);
    editor.precompute();
    const Positions expected = editor.deform(request);
    for (auto [parts, halo] : {std::pair{1, 0}, std::pair{6, -1}, std::pair{6, 100}}) {
      INFO("parts " << parts << ", halo " << halo << ", scale compensation " << scale_compensation);
      Options options = local_options(parts, halo);
      options.scale_compensation = scale_compensation;
      LocalEditor local(crowd, options, request);
      const Positions got = local.deform(request);
      CHECK(local.region().size() == editor.graph().vertex_count());
      CHECK(local.report().region_boundary == 0);
      CHECK((got - expected).cwiseAbs().maxCoeff() < rounding);
      // And the edit really moved things (so the comparison is not between two copies of the input).
      CHECK((got - editor.graph().clip.positions).cwiseAbs().maxCoeff() > 0.1);
    }
  }
}

TEST_CASE("vertices outside the local region keep their input positions bit for bit") {
  const CrowdMotion crowd = scene();
  const Request request = corner_drag({1.5, -0.8});
  LocalEditor local(crowd, local_options(12, 0), request);
  const Positions got = local.deform(request);
  const Positions& input = local.graph().clip.positions;
  const auto& region = local.region();
  REQUIRE_FALSE(region.empty());
  CHECK(region.size() < static_cast<std::size_t>(input.rows()) / 2);  // one part of twelve (the drag sits in one or two)
  CHECK(local.report().region_boundary > 0);
  std::vector<char> inside(static_cast<std::size_t>(input.rows()), 0);
  for (int v : region) inside[static_cast<std::size_t>(v)] = 1;
  std::size_t outside = 0, moved_inside = 0;
  for (Eigen::Index v = 0; v < input.rows(); ++v) {
    if (inside[static_cast<std::size_t>(v)]) {
      moved_inside += (got.row(v) - input.row(v)).norm() > 1e-6;
    } else {
      ++outside;
      if (!same_bits(got.row(v), input.row(v))) FAIL("vertex " << v << " outside the region moved");
    }
  }
  CHECK(outside > 0);
  CHECK(moved_inside > 4);  // more than the dragged vertices: the region deforms around them
  // The drag is met exactly, the held frames stay.
  const Clip& clip = local.graph().clip;
  const auto s30 = static_cast<std::size_t>(clip.sample_of_frame(30));
  for (std::size_t j = 0; j < 4; ++j) {
    const Eigen::Index v = clip.vertex(s30, j);
    CHECK((got.row(v) - input.row(v) - Eigen::RowVector2d(1.5, -0.8)).norm() < rounding);
  }
}

TEST_CASE("agents a one-off local edit never reaches come back bit for bit at every frame") {
  // A wide, short crowd (128 agents, 11 frames): METIS cuts it across the agents, so some agents lie wholly
  // outside the region (in the long scene above it cuts across time and every agent is touched somewhere).
  const CrowdMotion crowd = test::marching_grid(8, 16, 11, 1.0, 1.2, 0.1, 0.3, 0.2);
  Request request;
  request.drags = {hold(0, 0), hold(-1, -1)};
  Drag d = hold(6, 6);
  d.selection.agents = {100, 101, 102};
  d.offset = {0.8, 0.4};
  request.drags.push_back(d);
  const Options options = local_options(8, 0);
  const Result result = edit_group_motion(crowd, options, request);
  LocalEditor local(crowd, options, request);
  (void)local.deform(request);
  const Clip& clip = local.graph().clip;
  std::vector<char> touched(clip.agent_count(), 0);
  for (int v : local.region()) touched[static_cast<std::size_t>(v) % clip.agent_count()] = 1;
  CHECK(result.report.region_vertices == local.region().size());
  std::size_t untouched_agents = 0;
  for (std::size_t j = 0; j < clip.agent_count(); ++j) {
    if (touched[j]) continue;
    ++untouched_agents;
    for (std::size_t f = 0; f < crowd.frame_count(); ++f) {
      CHECK(std::memcmp(result.crowd.position(f, j).data(), crowd.position(f, clip.agents[j]).data(), 3 * sizeof(double)) == 0);
    }
  }
  CHECK(untouched_agents > clip.agent_count() / 2);
  // The dragged agents did move.
  const Eigen::Vector3d moved = result.crowd.position(6, 0) - crowd.position(6, 0);
  CHECK((moved.head<2>() - Eigen::Vector2d(0.8, 0.4)).norm() < rounding);
}

TEST_CASE("a wider halo solves more parts and comes closer to the global edit") {
  const CrowdMotion crowd = scene();
  const Request request = corner_drag({1.5, -0.8});
  Editor editor(crowd, local_options(0, 0), request);
  const Positions global = editor.deform(request);
  std::size_t last_size = 0;
  double last_gap = 1e9;
  for (int halo : {0, 1, 2}) {
    LocalEditor local(crowd, local_options(16, halo), request);
    const Positions got = local.deform(request);
    const double gap = (got - global).cwiseAbs().maxCoeff();
    INFO("halo " << halo << ": " << local.region().size() << " vertices, gap " << gap);
    CHECK(local.region().size() > last_size);
    CHECK(gap < last_gap);  // strictly: each ring of parts frees vertices the global edit moves
    last_size = local.region().size();
    last_gap = gap;
  }
}

TEST_CASE("drags of the same handles reuse the region's factorisations") {
  const CrowdMotion crowd = scene();
  LocalEditor local(crowd, local_options(12, 1), corner_drag({0.5, 0}));
  (void)local.deform(corner_drag({0.5, 0}));
  const int factorizations = local.report().factorizations;
  CHECK(factorizations == 2);  // step 1 and step 2
  CHECK(local.report().regions_built == 1);
  const Positions second = local.deform(corner_drag({2.0, 1.0}));
  CHECK(local.report().factorizations == factorizations);
  CHECK(local.report().regions_built == 1);
  // The reused factorisation gives what a fresh editor gives.
  LocalEditor fresh(crowd, local_options(12, 1), corner_drag({2.0, 1.0}));
  CHECK((fresh.deform(corner_drag({2.0, 1.0})) - second).cwiseAbs().maxCoeff() == 0.0);
  // Another group: a new region; back to the first: the cache still holds it.
  const Request other = corner_drag({0, 1}, {144, 145, 146, 147});
  (void)local.deform(other);
  CHECK(local.report().regions_built == 2);
  (void)local.deform(corner_drag({1.0, 1.0}));
  CHECK(local.report().regions_built == 2);
  CHECK(local.report().factorizations == 4);
  // With room for one region only, the first is dropped and rebuilt.
  Options one = local_options(12, 1);
  one.local.max_cached_regions = 1;
  LocalEditor small(crowd, one, corner_drag({0.5, 0}));
  (void)small.deform(corner_drag({0.5, 0}));
  (void)small.deform(other);
  (void)small.deform(corner_drag({0.5, 0}));
  CHECK(small.report().regions_built == 3);
  CHECK(small.report().factorizations == 6);
}

TEST_CASE("an edit that moves nothing solves nothing, and commit makes the result current") {
  const CrowdMotion crowd = scene();
  LocalEditor local(crowd, local_options(12, 0), corner_drag({0, 0}));
  const Positions same = local.deform(corner_drag({0, 0}));
  CHECK(local.region().empty());
  CHECK(local.report().regions_built == 0);
  CHECK(same == local.graph().clip.positions);

  const Positions first = local.deform(corner_drag({1.0, 0.5}));
  local.commit();
  CHECK(local.current() == first);
  // A second edit elsewhere: the first edit's vertices outside the new region stay as committed.
  const Request far = corner_drag({0, 1}, {144, 145, 146, 147});
  const Positions second = local.deform(far);
  std::vector<char> inside(static_cast<std::size_t>(second.rows()), 0);
  for (int v : local.region()) inside[static_cast<std::size_t>(v)] = 1;
  for (Eigen::Index v = 0; v < second.rows(); ++v) {
    if (!inside[static_cast<std::size_t>(v)] && !same_bits(second.row(v), first.row(v))) FAIL("vertex " << v << " moved");
  }
  // The second request holds agents 100..103 at their input positions at frame 30 only if they are in it: they
  // are not, so the corner keeps its committed drag.
  const Clip& clip = local.graph().clip;
  const Eigen::Index v = clip.vertex(static_cast<std::size_t>(clip.sample_of_frame(30)), 0);
  CHECK((second.row(v) - clip.positions.row(v) - Eigen::RowVector2d(1.0, 0.5)).norm() < rounding);
}

TEST_CASE("a general constraint reaches its part and is met") {
  const CrowdMotion crowd = scene();
  Request request = corner_drag({0, 0});
  request.constraints.push_back(Velocity{.agent = 140, .frame = 20, .velocity = {0.5, 1.0}});
  LocalEditor local(crowd, local_options(12, 0), request);
  const Positions got = local.deform(request);
  REQUIRE_FALSE(local.region().empty());
  const Clip& clip = local.graph().clip;
  const std::size_t j = static_cast<std::size_t>(clip.agent_of_id(140));
  const auto s0 = static_cast<std::size_t>(clip.sample_of_frame(20)), s1 = static_cast<std::size_t>(clip.sample_of_frame(21));
  const Eigen::RowVector2d velocity = (got.row(clip.vertex(s1, j)) - got.row(clip.vertex(s0, j))) / (clip.times[s1] - clip.times[s0]);
  CHECK((velocity - Eigen::RowVector2d(0.5, 1.0)).norm() < 1e-6);
  CHECK(local.report().max_constraint_residual < 1e-8);
}

TEST_CASE("local options out of range are ConfigErrors naming the key") {
  const CrowdMotion crowd = scene();
  const Request request = corner_drag({1, 0});
  CHECK_THROWS_WITH(LocalEditor(crowd, local_options(0, 0), request), Contains("local.parts 0"));
  CHECK_THROWS_WITH(LocalEditor(crowd, local_options(-1, 0), request), Contains("local.parts -1"));
  CHECK_THROWS_WITH(LocalEditor(crowd, local_options(100000, 0), request), Contains("local.parts 100000"));
  CHECK_THROWS_WITH(LocalEditor(crowd, local_options(4, -2), request), Contains("local.halo -2"));
  Options o = local_options(4, 0);
  o.local.max_cached_regions = 0;
  CHECK_THROWS_WITH(LocalEditor(crowd, o, request), Contains("local.max_cached_regions"));
}

TEST_CASE("a local edit equals the global edit with every vertex outside the region pinned where it is") {
  const CrowdMotion crowd = scene();
  const Request request = corner_drag({1.5, -0.8});
  for (int halo : {0, 1}) {
    LocalEditor local(crowd, local_options(12, halo), request);
    const Positions got = local.deform(request);
    REQUIRE(local.report().region_boundary > 0);  // a real boundary, not the whole graph
    // The same request, plus a pin at its current (input) position for every vertex outside the region: one
    // drag per sample holding the agents outside there.
    const Clip& clip = local.graph().clip;
    std::vector<char> inside(static_cast<std::size_t>(clip.positions.rows()), 0);
    for (int v : local.region()) inside[static_cast<std::size_t>(v)] = 1;
    Request pinned = request;
    for (std::size_t i = 0; i < clip.frames.size(); ++i) {
      Drag d = hold(static_cast<Frame>(clip.frames[i]), static_cast<Frame>(clip.frames[i]));
      for (std::size_t j = 0; j < clip.agent_count(); ++j) {
        if (!inside[static_cast<std::size_t>(clip.vertex(i, j))]) d.selection.agents.push_back(clip.ids[j]);
      }
      if (!d.selection.agents.empty()) pinned.drags.push_back(d);
    }
    Editor global(crowd, local_options(0, 0), pinned);
    const Positions expected = global.deform(pinned);
    INFO("halo " << halo);
    CHECK((got - expected).cwiseAbs().maxCoeff() < rounding);
    CHECK((got - clip.positions).cwiseAbs().maxCoeff() > 0.1);  // it moved
  }
}

TEST_CASE("the step across the region's edge is measured against the input, and a wider halo softens it") {
  const CrowdMotion crowd = scene();
  const Request request = corner_drag({4.0, -3.0});  // a drag large against the parts: the edge takes it
  // Each agent's fastest input step and the clip's, straight from the clip.
  LocalEditor whole(crowd, local_options(12, -1), request);
  (void)whole.deform(request);
  const Clip& clip = whole.graph().clip;
  auto gap = [&](std::size_t i) { return static_cast<double>(clip.frames[i + 1] - clip.frames[i]); };
  std::vector<double> fastest(clip.agent_count(), 0.0);
  for (std::size_t i = 0; i + 1 < clip.frames.size(); ++i) {
    for (std::size_t j = 0; j < clip.agent_count(); ++j) {
      fastest[j] = std::max(fastest[j], (clip.positions.row(clip.vertex(i + 1, j)) - clip.positions.row(clip.vertex(i, j))).norm() / gap(i));
    }
  }
  const double input_max = *std::max_element(fastest.begin(), fastest.end());
  // A region covering the graph has no edge.
  const BoundaryStep none = whole.boundary_step();
  CHECK(none.added_m == 0);
  CHECK(none.agent == -1);
  CHECK_FALSE(none.is_jump());
  CHECK(none.input_max_m == input_max);
  double last = 1e9;
  for (int halo : {0, 2}) {
    LocalEditor local(crowd, local_options(12, halo), request);
    const Positions got = local.deform(request);
    const BoundaryStep b = local.boundary_step();
    INFO("halo " << halo << ": " << b.added_m << " m/frame added at agent " << b.agent << ", frame " << b.frame << " (agent's fastest "
                 << b.agent_input_max_m << ", clip's " << b.input_max_m << ")");
    CHECK(b.input_max_m == input_max);
    REQUIRE(b.agent >= 0);
    // The reported pair is the edge pair with the largest added step against its agent's reference, by brute force.
    std::vector<char> inside(static_cast<std::size_t>(got.rows()), 0);
    for (int v : local.region()) inside[static_cast<std::size_t>(v)] = 1;
    double worst = -1, worst_added = 0;
    std::int64_t worst_agent = -1;
    std::size_t worst_frame = 0;
    for (std::size_t i = 0; i + 1 < clip.frames.size(); ++i) {
      for (std::size_t j = 0; j < clip.agent_count(); ++j) {
        const Eigen::Index v0 = clip.vertex(i, j), v1 = clip.vertex(i + 1, j);
        if (inside[static_cast<std::size_t>(v0)] == inside[static_cast<std::size_t>(v1)]) continue;
        const double added = ((got.row(v1) - got.row(v0)) - (clip.positions.row(v1) - clip.positions.row(v0))).norm() / gap(i);
        const double ratio = added / std::max(fastest[j], BoundaryStep::reference_floor * input_max);
        if (ratio > worst) worst = ratio, worst_added = added, worst_agent = clip.ids[j], worst_frame = clip.frames[i];
      }
    }
    CHECK(b.agent == worst_agent);
    CHECK(b.frame == worst_frame);
    CHECK(b.added_m == worst_added);
    const auto j = static_cast<std::size_t>(std::find(clip.ids.begin(), clip.ids.end(), b.agent) - clip.ids.begin());
    const auto i = static_cast<std::size_t>(std::find(clip.frames.begin(), clip.frames.end(), b.frame) - clip.frames.begin());
    REQUIRE(i + 1 < clip.frames.size());
    CHECK(b.agent_input_max_m == fastest[j]);
    CHECK(b.edited_m == (got.row(clip.vertex(i + 1, j)) - got.row(clip.vertex(i, j))).norm() / gap(i));
    CHECK(b.input_m == (clip.positions.row(clip.vertex(i + 1, j)) - clip.positions.row(clip.vertex(i, j))).norm() / gap(i));
    CHECK(b.is_jump() == (b.added_m > BoundaryStep::jump_factor * b.reference_m()));
    CHECK(b.added_m < last);
    last = b.added_m;
  }
  // A 5 m drag stopped by a halo of 0 is a jump at the edge; a 2 cm nudge is not (it adds at most 2 cm over
  // the two frames of a sample interval, a tenth of these agents' ~0.12 m per frame).
  LocalEditor big(crowd, local_options(12, 0), request);
  (void)big.deform(request);
  CHECK(big.boundary_step().is_jump());
  LocalEditor small(crowd, local_options(12, 0), corner_drag({0.02, 0.0}));
  (void)small.deform(corner_drag({0.02, 0.0}));
  const BoundaryStep nudge = small.boundary_step();
  REQUIRE(nudge.agent >= 0);
  CHECK(nudge.added_m > 0);
  CHECK(nudge.added_m < 0.02);
  CHECK_FALSE(nudge.is_jump());
}

TEST_CASE("parts by size: blocks of samples times groups of agents, and a size out of range is a ConfigError") {
  const CrowdMotion crowd = scene();
  const Request request = corner_drag({1.5, -0.8});
  Options o = local_options(LocalOptions::by_size, 0);
  o.local.vertices_per_part = 300;  // 1,488 vertices: about 5 parts
  LocalEditor local(crowd, o, request);
  // The parts of partition_time_blocks (tested in tests/graph/test_block_partition.cpp), not of METIS on the
  // whole graph as a count asks.
  const Partition blocks = partition_time_blocks(local.graph(), 300, {.seed = o.local.seed});
  CHECK(local.partition().part_of == blocks.part_of);
  CHECK(local.report().parts == blocks.part_count());
  CHECK(blocks.part_count() >= 3);
  CHECK(blocks.part_count() <= 8);
  // Those parts, given to the region solve, edit as any partition does: held vertices stay bit for bit.
  const auto& edited = local.deform(request);
  const std::vector<int>& region = local.region();
  REQUIRE_FALSE(region.empty());
  REQUIRE(region.size() < local.graph().vertex_count());
  for (std::size_t v = 0; v < local.graph().vertex_count(); ++v) {
    if (std::binary_search(region.begin(), region.end(), static_cast<int>(v))) continue;
    REQUIRE(edited.row(static_cast<Eigen::Index>(v)) == local.graph().clip.positions.row(static_cast<Eigen::Index>(v)));
  }
  // Larger than the graph: one part, the global edit.
  o.local.vertices_per_part = 1000000;
  LocalEditor one(crowd, o, request);
  CHECK(one.partition().part_count() == 1);
  Editor editor(crowd, local_options(0, 0), request);
  CHECK((one.deform(request) - editor.deform(request)).cwiseAbs().maxCoeff() < rounding);
  o.local.vertices_per_part = 0;
  CHECK_THROWS_WITH(LocalEditor(crowd, o, request), Contains("local.vertices_per_part 0"));
  o.local.vertices_per_part = -3;
  CHECK_THROWS_AS(LocalEditor(crowd, o, request), ConfigError);
}

TEST_CASE("a cached region takes new constraint values and rows in place and gives what a fresh editor gives") {
  const CrowdMotion crowd = scene();
  Request request = corner_drag({0.5, 0});
  request.constraints.push_back(Velocity{.agent = 100, .frame = 20, .velocity = {0.5, 0.2}});
  LocalEditor local(crowd, local_options(12, 1), request);
  (void)local.deform(request);
  const int factorizations = local.report().factorizations;
  REQUIRE(local.report().regions_built == 1);
  // New values of the same rows, then one more row on a neighbour of the dragged corner.
  request.constraints[0] = Velocity{.agent = 100, .frame = 20, .velocity = {0.8, -0.1}};
  (void)local.deform(request);
  request.constraints.push_back(Velocity{.agent = 101, .frame = 20, .velocity = {0.4, 0.3}});
  const Positions got = local.deform(request);
  CHECK(local.report().regions_built == 1);
  CHECK(local.report().factorizations == factorizations);
  CHECK(local.report().max_constraint_residual < 1e-8);
  LocalEditor fresh(crowd, local_options(12, 1), request);
  CHECK((fresh.deform(request) - got).cwiseAbs().maxCoeff() < rounding);
}

TEST_CASE("a deform that fails leaves no half-built region: the same request fails the same way, a good one works") {
  const CrowdMotion crowd = scene();
  // A row whose norm overflows: the region's solvers refuse it while the region is being built.
  Request bad = corner_drag({0.5, 0});
  Row row;
  row.terms = {{.agent = 100, .frame = 30, .axis = 0, .coefficient = 1e200}, {.agent = 101, .frame = 30, .axis = 0, .coefficient = -1e200}};
  bad.constraints.push_back(row);
  LocalEditor local(crowd, local_options(12, 1), bad);
  std::string first;
  try {
    (void)local.deform(bad);
  } catch (const std::exception& e) {
    first = e.what();
  }
  REQUIRE_FALSE(first.empty());
  CHECK_THROWS_WITH(local.deform(bad), first);
  CHECK(local.report().regions_built == 0);
  const Request good = corner_drag({0.5, 0});
  LocalEditor fresh(crowd, local_options(12, 1), good);
  CHECK((local.deform(good) - fresh.deform(good)).cwiseAbs().maxCoeff() == 0.0);
}
