// throng stitch A.h5 B.h5 [C.h5 ...] -o OUT.h5: clips with the same agents played one after the other become one
// clip of t + t′ − 1 frames whose formation morphs across each joint (Kwon et al. 2008 §5; solver/stitch/stitch.h).
// The job format is in io/stitch/include/throng/io/stitch_job.h; docs/commands/stitch.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/command_job.h>
#include <throng/io/stitch_job.h>
#include <throng/linalg/mpi.h>

#include <iomanip>
#include <memory>
#include <numbers>
#include <sstream>

#include "factories.h"
#include "input_crowds.h"
#include "job_flags.h"

namespace throng::cli {
namespace {

struct Stitched {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
};

std::string id_list(const std::vector<std::int64_t>& ids) {
  std::ostringstream s;
  for (std::size_t k = 0; k < ids.size() && k < 10; ++k) s << (k ? ", " : "") << ids[k];
  if (ids.size() > 10) s << ", ...";
  return s.str();
}

std::string short_number(double value) {
  std::ostringstream s;
  s << std::setprecision(4) << value;
  return s.str();
}

/// The work shared by `throng stitch` and the `stitch` step; `speak` false keeps its warnings quiet (the ranks
/// other than 0 of one stitch under mpiexec).
Stitched stitch_all(const std::vector<const CrowdFile*>& inputs, const StitchJob& job, Context& context, bool speak = true) {
  auto stitched = std::make_shared<StitchedCrowds>(stitch_crowds(inputs, job, context.progress()));
  Stitched s;
  s.crowd = stitched->crowd;
  s.extra = [stitched](const h5::Group& g) { write_stitch_data(g, *stitched); };
  Report joints = Report::array();
  for (std::size_t k = 0; k < stitched->joints.size(); ++k) {
    const stitch::Report& r = stitched->joints[k].report;
    const std::string which = "stitch: joint " + std::to_string(k + 1) + ": ";
    if (speak && !r.left_out_first.empty()) {
      context.warn(which + std::to_string(r.left_out_first.size()) + " agent(s) of the clip so far absent from part of it were left out (" +
                   id_list(r.left_out_first) + ")");
    }
    if (speak && !r.left_out_second.empty()) {
      context.warn(which + std::to_string(r.left_out_second.size()) + " agent(s) of input " + std::to_string(k + 2) +
                   " absent from part of it were left out (" + id_list(r.left_out_second) + ")");
    }
    if (speak && r.window_limited) {
      context.warn(which + "blending the whole clips would solve " + std::to_string(r.whole_clip_vertices) +
                   " vertices (agents × samples), over max_blend_vertices " + std::to_string(job.options.max_blend_vertices) +
                   ": the window is shortened to " + short_number(r.window_first_s) + " s / " + short_number(r.window_second_s) +
                   " s per side (set blend_window, raise sample_step or max_blend_vertices)");
    }
    Report j;
    j["frame"] = stitched->joint_frames[k];
    j["agents"] = r.agents;
    j["matched_same_id"] = r.matched_same_id;
    j["matching_distance_m"] = r.matching_distance;
    j["rotation_deg"] = r.rotation * 180.0 / std::numbers::pi;
    j["translation_m"] = {r.translation.x(), r.translation.y()};
    j["gap_rms_m"] = r.gap_rms;
    j["gap_max_m"] = r.gap_max;
    j["window"] = {r.window_first, r.window_second};
    j["window_s"] = {r.window_first_s, r.window_second_s};
    j["window_limited"] = r.window_limited;
    j["fit_starts"] = r.fit_starts;
    j["fit_rounds"] = r.fit_rounds;
    j["solved_samples"] = r.solved_samples;
    j["unknowns"] = r.unknowns;
    j["max_change_m"] = r.max_change;
    j["solve_s"] = r.matching_seconds + r.graph_seconds + r.precompute_seconds + r.solve_seconds;
    joints.push_back(j);
  }
  const CrowdMotion& m = s.crowd.motion;
  s.report["inputs"] = inputs.size();
  s.report["agents"] = m.agent_count();
  s.report["frames"] = m.frame_count();
  s.report["times_s"] = {m.times.empty() ? 0.0 : m.times.front(), m.times.empty() ? 0.0 : m.times.back()};
  s.report["joints"] = joints;
  return s;
}

class StitchCommand final : public Command {
 public:
  std::string name() const override { return "stitch"; }
  std::string summary() const override {
    return "Play clips of the same agents one after the other, morphing the formation across each joint";
  }

  void setup(CLI::App& app) override {
    app.add_option("clips", inputs_, "Crowd files to stitch (.h5), two or more, in order")->required()->expected(2, -1);
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
    app.add_option("--job", job_path_, "Stitch job (.yaml): weights, solver ...; the flags below override its keys");
    flags_.value(app, "--blend-window", "blend_window",
                 "Seconds from each joint over which formations blend, per side (default 0: the whole clips, within --max-blend-vertices)");
    flags_.value(app, "--max-blend-vertices", "max_blend_vertices", "Budget of the automatic window: agents × solved samples (default 60000; 0: none)");
    flags_.value(app, "--matching", "matching", "world | centred: how agents are matched across the joint");
    flags_.value(app, "--alignment", "alignment", "rigid | translation | none: how the next clip is moved onto the joint");
    flags_.value(app, "--sample-step", "sample_step", "Frames between graph samples");
  }

  void run(Context& context) override {
    const ConfigNode job = command_job(job_path_, flags_.yaml(), context.global.set, "stitch");
    const StitchJob parsed = read_stitch_job(job);
    const YAML::Node effective = effective_stitch_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    for (const auto& in : inputs_) check_distinct(in, output_);
    if (!job_path_.empty()) check_distinct(job_path_, output_);
    context.limit_threads();
    (void)AtomicOutput(output_);  // a missing or read-only output folder fails now (exit 4), not after the work

    const InputCrowds in = read_input_crowds(inputs_, job_path_);
    const bool writer = mpi::rank() == 0;  // starts MPI when launched by mpiexec
    if (writer && mpi::size() > 1 && parsed.options.solver.backend != "petsc") {
      context.warn("stitch: " + std::to_string(mpi::size()) + " ranks with the " + parsed.options.solver.backend +
                   " backend: every rank solves the whole problem (solver.backend petsc shares it)");
    }
    Stitched s = stitch_all(in.crowds, parsed, context, writer);
    s.crowd.provenance = context.provenance(effective, in.names, in.sources);
    if (!writer) return;  // one file and one report, from rank 0
    write_crowd_file(output_, s.crowd, s.extra);
    Report r;
    r["output"] = output_.string();
    r.update(s.report);
    context.print(r);
  }

  /// As a step: stitches the clips it reads (`inputs: [a, b, ...]`), in order.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    const StitchJob parsed = read_stitch_job(step);
    if (inputs.size() < 2) step.fail("stitch takes two or more clips (inputs: [a, b, ...]), found " + std::to_string(inputs.size()));
    Stitched s = stitch_all(inputs, parsed, context);
    context.info("stitch: " + s.report.dump());
    return StepResult{std::move(s.crowd), std::move(s.extra)};
  }

 private:
  std::vector<std::filesystem::path> inputs_;
  std::filesystem::path output_, job_path_;
  JobFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_stitch_command() { return std::make_unique<StitchCommand>(); }

}  // namespace throng::cli
