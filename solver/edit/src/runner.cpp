#include <throng/core/format.h>
#include <throng/edit/guard.h>
#include <throng/edit/output.h>
#include <throng/edit/runner.h>
#include <throng/edit/schema.h>
#include <throng/edit/session.h>
#include <throng/timewarp/schema.h>

#include <algorithm>
#include <unordered_map>

namespace throng::edit {
namespace {

// The pairs of clip agents among the input's formation edges, renumbered to the clip's agent indices.
std::vector<std::array<std::int32_t, 2>> clip_edges(const Crowd& input, const CrowdMotion& clip) {
  std::unordered_map<std::int64_t, std::int32_t> index_of_id;
  for (std::size_t j = 0; j < clip.agent_count(); ++j) index_of_id.emplace(clip.ids[j], static_cast<std::int32_t>(j));
  const std::size_t agents = input.motion.agent_count();
  std::vector<std::array<std::int32_t, 2>> out;
  for (const auto& [a, b] : input.formation_edges) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= agents || static_cast<std::size_t>(b) >= agents) continue;
    const auto ia = index_of_id.find(input.motion.ids[static_cast<std::size_t>(a)]);
    const auto ib = index_of_id.find(input.motion.ids[static_cast<std::size_t>(b)]);
    if (ia != index_of_id.end() && ib != index_of_id.end()) out.push_back({ia->second, ib->second});
  }
  return out;
}

}  // namespace

void describe(OptionBinder& b, Job& job) {
  describe(b, job.options);
  b.field({.key = "clip_only", .flag = "--clip-only",
           .help = "write only the clip (its frames and the agents it edited), not the whole crowd"},
          job.clip_only);
  b.section("guard", [&](OptionBinder& g) { timewarp::describe(g, job.guard); });
}

Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator) {
  const Crowd& input = *inputs.at(0);
  return finish_edit(input, job, edit_group_motion(input.motion, job.options, job.request, &progress), communicator.size());
}

Run finish_edit(const Crowd& input, const Job& job, Result result, int ranks) {
  Run out;
  out.clip_only = job.clip_only;
  out.backend = job.options.solver.backend;
  out.ranks = ranks;
  if (out.ranks > 1 && out.backend != "petsc") {
    out.warnings.push_back(std::to_string(out.ranks) + " ranks with the " + out.backend +
                           " backend: every rank solves the whole problem (--backend petsc shares it)");
  }
  out.result = std::move(result);
  const Result& r = out.result;
  const Report& report = r.report;
  out.clip_agents = r.crowd.agent_count();
  if (!report.left_out.empty()) {
    out.warnings.push_back(std::to_string(report.left_out.size()) + " agent(s) absent from part of the clip were not edited (" +
                           id_list(report.left_out) + ")" +
                           (job.clip_only ? " and are not in the clip-only output" : "; the output keeps them as they are"));
  }
  if (!report.fallback.empty()) out.warnings.push_back(report.fallback);
  if (r.boundary && r.boundary->is_jump()) {
    const BoundaryStep& e = *r.boundary;
    out.warnings.push_back("the local region's edge jumps: agent " + std::to_string(e.agent) + " after frame " +
                           std::to_string(e.frame) + " gets " + with_digits(e.added_m, 3) +
                           " m per frame added to one step (its fastest step in the input is " +
                           with_digits(e.agent_input_max_m, 3) + " m); widen local.halo (now " +
                           std::to_string(job.options.local.halo) + ") or use larger parts (local.vertices_per_part)");
  }
  out.seam_jump_m = seam_jump(input.motion, r.crowd, r.first_frame);
  const std::vector<std::int64_t> clip_ids = r.crowd.ids;
  const std::size_t first_frame = r.first_frame, last_frame = r.last_frame;
  out.crowd.scene = input.scene;
  if (job.clip_only) {
    out.crowd.formation_edges = clip_edges(input, r.crowd);
    out.crowd.motion = clip_with_velocities(input.motion, std::move(out.result.crowd), r.first_frame);
    out.result.crowd = CrowdMotion{};
  } else {
    out.crowd.motion = embed_clip(input.motion, r.crowd, r.first_frame);
    out.crowd.formation_edges = input.formation_edges;  // same agents, same indices
    if (out.seam_jump_m > 1e-6) {
      out.warnings.push_back("the edit moves agents by up to " + with_digits(out.seam_jump_m, 3) +
                             " m at a clip end that joins unedited frames (clip " + std::to_string(r.first_frame) + ".." +
                             std::to_string(r.last_frame) + " of 0.." + std::to_string(input.motion.frame_count() - 1) +
                             "): the output jumps there; hold the clip's ends or use --clip-only");
    }
  }
  // The guard on what is written (guard.h), then the request measured again on the written frames when their
  // times are still the input's; after a warp the measure before it stands (the request holds at warped times).
  const std::size_t written_first = job.clip_only ? first_frame : 0;
  timewarp::GuardResult guarded =
      guard_edit(out.crowd.motion, written_first, input.motion, job.request, first_frame, last_frame, job.guard);
  out.crowd.motion = std::move(guarded.crowd);
  out.guard = guarded.report;
  if (!out.guard.warped) {
    out.residual_after_guard = true;
    out.result.report.max_output_residual = max_request_residual(
        input.motion, clip_of(out.crowd.motion, written_first, first_frame, last_frame, clip_ids), first_frame, job.request);
  }
  return out;
}

void describe(ReportWriter& w, const Run& run) {
  const Result& result = run.result;
  const Report& r = result.report;
  w.count("agents", run.crowd.motion.agent_count());
  w.count("frames", run.crowd.motion.frame_count());
  w.flag("clip_only", run.clip_only);
  w.count("clip_agents", run.clip_agents);
  w.counts("clip_frames", {result.first_frame, result.last_frame});
  w.number("seam_jump_m", run.seam_jump_m);
  w.count("samples", r.samples);
  w.count("unknowns", r.unknowns);
  w.count("features", r.spatial_features + r.temporal_features + r.spatiotemporal_features);
  w.count("handles", r.handles);
  w.count("constraint_rows", r.constraint_rows);
  w.count("left_out", r.left_out.size());
  w.text("backend", run.backend);
  w.ranks("ranks", run.ranks);
  w.text("factorization", r.factorization);
  w.seconds("graph_s", r.graph_seconds);
  w.seconds("precompute_s", r.precompute_seconds);
  w.seconds("solve_s", r.solve_seconds);
  // Pins, drags and constraints on every written frame they cover (velocity: |Δp − v Δt|).
  w.number("max_constraint_residual_m", std::max(r.max_constraint_residual, r.max_output_residual));
  // How the global systems were solved (SolverOptions::method, "auto" resolved); the iterative method's work and
  // the error it estimates it left; with solver.compare_direct, the distance to the direct solve (−1: not compared).
  w.text("method", r.method);
  w.count("iterations", static_cast<std::size_t>(r.iterations));
  w.count("precompute_iterations", static_cast<std::size_t>(r.precompute_iterations));
  w.number("solver_error_m", r.solver_error_m);
  w.count("coarse_size", r.coarse_size);
  w.number("direct_difference_m", r.direct_difference_m);
  // The plausibility guard on the written crowd (guard.h), as stitch reports it; whether max_constraint_residual_m
  // was measured after it (false: the guard warped, the residual is the edit's before it).
  timewarp::describe(w, run.guard);
  w.flag("residual_after_guard", run.residual_after_guard);
  if (!result.boundary) return;
  w.count("parts", static_cast<std::size_t>(r.parts));
  w.count("region_parts", static_cast<std::size_t>(r.region_parts));
  w.count("region_vertices", r.region_vertices);
  w.count("region_boundary", r.region_boundary);
  w.seconds("partition_s", r.partition_seconds);
  // The region's edge in time (BoundaryStep): what the edit added to a step there, metres per frame, the
  // agent's own fastest step it is judged against (0 when no agent crosses the edge), and whether that is a jump.
  const BoundaryStep& e = *result.boundary;
  w.number("region_edge_step_m", e.added_m);
  w.number("region_edge_reference_m", e.agent >= 0 ? e.reference_m() : 0.0);
  w.flag("region_edge_jump", e.is_jump());
}

}  // namespace throng::edit
