// throng edit CROWD.h5 --job EDIT.yaml -o OUT.h5 [--backend eigen|petsc]: deform a group motion by pinning and
// dragging agents while keeping its formations and trajectories (group motion editing, solver/edit).
// The job format is in io/edit/include/throng/io/edit_job.h; docs/commands/edit.md is the README section.
// Output: the whole input crowd with the edited clip put back (solver/edit output.h), or only the clip with
// --clip-only (job key clip_only).
// With local.parts > 0 or auto (or --local-parts) the edit is local (solver/edit local_edit.h): only the parts it
// reaches are solved; the report gives the step across the region's edge in time and a warning says when it
// is a jump (edit::BoundaryStep); docs/commands/scale.md describes it.
//
// Under mpiexec every rank reads the input and builds the problem; the petsc backend shares the solves between
// the ranks; rank 0 writes the output and prints the report.
#include <throng/core/errors.h>
#include <throng/edit/local_edit.h>
#include <throng/edit/output.h>
#include <throng/io/atomic_output.h>
#include <throng/io/edit_job.h>
#include <throng/linalg/mpi.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <sstream>

#include "factories.h"

namespace throng::cli {
namespace {

/// A finished edit: the crowd to write, its method data and the report.
struct Edited {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
};

/// The work shared by `throng edit` and the `edit` step of `throng run`.
Edited edit_crowd(const CrowdFile& input, const EditJob& job, Context& context) {
  Progress& progress = context.progress();
  auto result = std::make_shared<edit::Result>();
  std::optional<edit::BoundaryStep> edge;  // local edits: the region's edge in time
  // Fills the result from either editor (they share the request language and the report).
  auto finish = [&](const auto& editor, const Eigen::Matrix<double, Eigen::Dynamic, 2>& samples) {
    progress.update(0.95, "edit: resample");
    result->crowd = editor.resample(samples);
    result->report = editor.report();
    result->first_frame = editor.graph().clip.first_frame;
    result->last_frame = editor.graph().clip.last_frame;
    result->sample_frames = editor.graph().clip.frames;
  };
  if (job.options.local.parts > 0) {
    progress.update(0.0, "edit: graph and partition");
    edit::LocalEditor editor(input.motion, job.options, job.request);
    progress.update(0.3, "edit: local solve");
    finish(editor, editor.deform(job.request));
    edge = editor.boundary_step();
  } else {
    progress.update(0.0, "edit: graph");
    edit::Editor editor(input.motion, job.options, job.request);
    progress.update(0.2, "edit: factorise");
    editor.precompute();
    progress.update(0.8, "edit: solve");
    finish(editor, editor.deform(job.request));
  }
  progress.update(1.0, "edit: done");

  const edit::Report& r = result->report;
  if (!r.left_out.empty()) {
    std::ostringstream ids;
    for (std::size_t k = 0; k < r.left_out.size() && k < 10; ++k) ids << (k ? ", " : "") << r.left_out[k];
    context.warn("edit: " + std::to_string(r.left_out.size()) + " agent(s) absent from part of the clip were not edited (" +
                 ids.str() + (r.left_out.size() > 10 ? ", ..." : "") + ")" +
                 (job.clip_only ? " and are not in the clip-only output" : "; the output keeps them as they are"));
  }
  if (!r.fallback.empty()) context.warn("edit: " + r.fallback);
  if (edge && edge->is_jump()) {
    std::ostringstream text;
    text.precision(3);
    text << "edit: the local region's edge jumps: agent " << edge->agent << " after frame " << edge->frame << " gets "
         << edge->added_m << " m per frame added to one step (its fastest step in the input is " << edge->agent_input_max_m
         << " m); widen local.halo (now " << job.options.local.halo << ") or use larger parts (local.vertices_per_part)";
    context.warn(text.str());
  }
  // The request measured on the output frames (the solver's own check sees the samples only).
  result->report.max_output_residual = edit::max_request_residual(input.motion, result->crowd, result->first_frame, job.request);

  Edited e;
  e.crowd.scene = input.scene;
  const double seam = edit::seam_jump(input.motion, result->crowd, result->first_frame);
  if (job.clip_only) {
    e.crowd.motion = edit::clip_with_velocities(input.motion, result->crowd);
    // Formation edges name agent indices: keep the pairs of clip agents, renumbered.
    std::vector<std::int32_t> clip_index(input.motion.agent_count(), -1);
    for (std::size_t j = 0; j < result->crowd.agent_count(); ++j) {
      for (std::size_t a = 0; a < input.motion.agent_count(); ++a) {
        if (input.motion.ids[a] == result->crowd.ids[j]) clip_index[a] = static_cast<std::int32_t>(j);
      }
    }
    for (const auto& [a, b] : input.formation_edges) {
      if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= clip_index.size() || static_cast<std::size_t>(b) >= clip_index.size()) continue;
      if (clip_index[a] >= 0 && clip_index[b] >= 0) e.crowd.formation_edges.push_back({clip_index[a], clip_index[b]});
    }
  } else {
    e.crowd.motion = edit::embed_clip(input.motion, result->crowd, result->first_frame);
    e.crowd.formation_edges = input.formation_edges;  // same agents, same indices
    if (seam > 1e-6) {
      std::ostringstream text;
      text.precision(3);
      text << "edit: the edit moves agents by up to " << seam << " m at a clip end that joins unedited frames (clip "
           << result->first_frame << ".." << result->last_frame << " of 0.." << input.motion.frame_count() - 1
           << "): the output jumps there; hold the clip's ends or use --clip-only";
      context.warn(text.str());
    }
  }
  const bool clip_only = job.clip_only;
  e.extra = [result, clip_only, seam](const h5::Group& g) { write_edit_data(g, *result, clip_only, seam); };
  e.report["agents"] = e.crowd.motion.agent_count();
  e.report["frames"] = e.crowd.motion.frame_count();
  e.report["clip_only"] = job.clip_only;
  e.report["clip_agents"] = result->crowd.agent_count();
  e.report["clip_frames"] = {result->first_frame, result->last_frame};
  e.report["seam_jump_m"] = seam;
  e.report["samples"] = r.samples;
  e.report["unknowns"] = r.unknowns;
  e.report["features"] = r.spatial_features + r.temporal_features + r.spatiotemporal_features;
  e.report["handles"] = r.handles;
  e.report["constraint_rows"] = r.constraint_rows;
  e.report["left_out"] = r.left_out.size();
  e.report["backend"] = job.options.solver.backend;
  e.report["ranks"] = mpi::size();
  e.report["factorization"] = r.factorization;
  e.report["graph_s"] = r.graph_seconds;
  e.report["precompute_s"] = r.precompute_seconds;
  e.report["solve_s"] = r.solve_seconds;
  // Pins, drags and constraints on every written frame they cover (velocity: |Δp − v Δt|).
  e.report["max_constraint_residual_m"] = std::max(r.max_constraint_residual, result->report.max_output_residual);
  if (job.options.local.parts > 0) {
    e.report["parts"] = r.parts;
    e.report["region_parts"] = r.region_parts;
    e.report["region_vertices"] = r.region_vertices;
    e.report["region_boundary"] = r.region_boundary;
    e.report["partition_s"] = r.partition_seconds;
    // The region's edge in time (edit::BoundaryStep): what the edit added to a step there, metres per frame,
    // the agent's own fastest step it is judged against (0 when no agent crosses the edge), and whether that
    // is a jump.
    e.report["region_edge_step_m"] = edge->added_m;
    e.report["region_edge_reference_m"] = edge->agent >= 0 ? edge->reference_m() : 0.0;
    e.report["region_edge_jump"] = edge->is_jump();
  }
  return e;
}

class EditCommand final : public Command {
 public:
  std::string name() const override { return "edit"; }
  std::string summary() const override {
    return "Deform a group motion by pinning and dragging agents, keeping formations and trajectories";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file to edit (.h5)")->required();
    app.add_option("--job", job_path_, "Edit job (.yaml): clip, pins, drags, constraints, weights, solver")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5): the input crowd with the clip edited")->required();
    app.add_flag("--clip-only", clip_only_, "Write only the clip (its frames and the agents it edited), not the whole crowd "
                                            "(sets the job's clip_only)");
    app.add_option("--backend", backend_, "Solver backend, overriding the job's solver.backend")
        ->check(CLI::IsMember({"eigen", "petsc"}));
    app.add_option("--local-parts", local_parts_,
                   "Local edit: split the graph into this many METIS parts (auto: parts of local.vertices_per_part "
                   "vertices) and solve only those the edit reaches (overrides the job's local.parts; 0 = global)")
        ->check(CLI::Validator(
            [](const std::string& text) -> std::string {
              if (text == "auto") return {};
              if (!text.empty() && text.size() <= 10 && text.find_first_not_of("0123456789") == std::string::npos &&
                  std::stoll(text) <= 1000000000) {
                return {};
              }
              return "expected a part count (0 to 1e9, 0 = global) or auto, found '" + text + "'";
            },
            "N|auto"));
    app.add_option("--halo", halo_, "Local edit: parts within this many hops of the reached ones are solved too "
                                    "(overrides local.halo; -1 = every connected part)")
        ->check(CLI::Range(-1, 1000000));
  }

  void run(Context& context) override {
    const ConfigNode job = context.load_job(job_path_);
    EditJob parsed = read_edit_job(job);
    if (!backend_.empty()) parsed.options.solver.backend = backend_;
    if (local_parts_) parsed.options.local.parts = *local_parts_ == "auto" ? edit::LocalOptions::by_size : std::stoi(*local_parts_);
    if (halo_) parsed.options.local.halo = *halo_;
    if (clip_only_) parsed.clip_only = true;
    const YAML::Node effective = effective_edit_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);
    check_distinct(job_path_, output_);
    context.limit_threads();

    const bool writer = mpi::rank() == 0;  // starts MPI when launched by mpiexec
    if (writer && mpi::size() > 1 && parsed.options.solver.backend != "petsc") {
      context.warn("edit: " + std::to_string(mpi::size()) + " ranks with the " + parsed.options.solver.backend +
                   " backend: every rank solves the whole problem (--backend petsc shares it)");
    }
    const CrowdFile input = read_crowd_file(input_);
    Edited e = edit_crowd(input, parsed, context);
    e.crowd.provenance = context.provenance(effective, {input_.string(), job_path_.string()}, {&input.provenance});
    if (!writer) return;
    write_crowd_file(output_, e.crowd, e.extra);
    Report r;
    r["output"] = output_.string();
    r.update(e.report);
    context.print(r);
  }

  /// As a step: edits the one crowd it reads; the step's keys are the job file's.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    const EditJob parsed = read_edit_job(step);
    if (inputs.size() != 1) step.fail("edit takes one crowd, found " + std::to_string(inputs.size()));
    Edited e = edit_crowd(*inputs.front(), parsed, context);
    e.crowd.provenance.credits = inputs.front()->provenance.credits;
    context.info("edit: " + e.report.dump());
    return StepResult{std::move(e.crowd), std::move(e.extra)};
  }

 private:
  std::filesystem::path input_;
  std::filesystem::path job_path_;
  std::filesystem::path output_;
  std::string backend_;
  std::optional<std::string> local_parts_;
  std::optional<int> halo_;
  bool clip_only_ = false;
};

}  // namespace

std::unique_ptr<Command> make_edit_command() { return std::make_unique<EditCommand>(); }

}  // namespace throng::cli
