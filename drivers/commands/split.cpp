// throng split CROWD.h5 -o PART.h5 [--other REST.h5]: cut a crowd by time (at a frame, or a range of frames) or by
// agents (ids, species), keeping the data exactly (solver/stitch/split.h). The job format is in
// io/stitch/include/throng/io/split_job.h; every key also has a flag. docs/commands/stitch.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/command_job.h>
#include <throng/io/split_job.h>

#include <memory>

#include "factories.h"
#include "job_flags.h"

namespace throng::cli {
namespace {

/// One part as a crowd file with its method data and report.
struct Part {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
};

/// The work shared by `throng split` and the `split` step: the part the job keeps (or the other one).
Part split_part(const CrowdFile& input, const SplitJob& job, bool other) {
  auto part = std::make_shared<SplitPart>(split_crowd(input.motion, job, other));
  Part p;
  p.crowd.motion = part->crowd;
  p.crowd.scene = input.scene;
  p.crowd.provenance.credits = input.provenance.credits;
  p.extra = [part](const h5::Group& g) { write_split_data(g, *part); };
  const CrowdMotion& m = part->crowd;
  p.report["part"] = part->part;
  p.report["agents"] = m.agent_count();
  p.report["frames"] = m.frame_count();
  p.report["input_frames"] = {part->first_frame, part->last_frame};
  p.report["times_s"] = {m.times.front(), m.times.back()};
  return p;
}

class SplitCommand final : public Command {
 public:
  std::string name() const override { return "split"; }
  std::string summary() const override {
    return "Cut a crowd by time (at a frame, or a range) or by agents (ids, species) into clips";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file to split (.h5)")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5): the part the job keeps")->required();
    app.add_option("--other", other_, "Also write the other part here: the other half of a split by time, or the rest of a split by agents");
    app.add_option("--job", job_path_, "Split job (.yaml); the flags below override its keys");
    flags_.value(app, "--at-frame", "at_frame", "Split at this frame (both parts hold it)");
    flags_.value(app, "--at-time", "at_time", "Split at the frame nearest this time (s)");
    flags_.list(app, "--frames", "frames", "Keep frames FIRST,LAST");
    flags_.list(app, "--times", "times", "Keep the frames nearest times FIRST,LAST (s)");
    flags_.value(app, "--keep", "keep", "first | second: the part of a split by time written to --output");
    flags_.list(app, "--agents", "agents", "Select these agent ids");
    flags_.list(app, "--species", "species", "Select every agent of these species");
    flags_.value(app, "--keep-agents", "keep_agents", "selected | rest: the part of a split by agents written to --output");
    flags_.flag(app, "--present-throughout", "present_throughout", "Keep only agents present at every frame of the part");
  }

  void run(Context& context) override {
    const ConfigNode job = command_job(job_path_, flags_.yaml(), context.global.set, "split");
    const SplitJob parsed = read_split_job(job);
    const YAML::Node effective = effective_split_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);
    if (!job_path_.empty()) check_distinct(job_path_, output_);
    if (!other_.empty()) {
      check_distinct(input_, other_);
      check_distinct(output_, other_);
    }
    context.limit_threads();
    (void)AtomicOutput(output_);  // a missing or read-only output folder fails now (exit 4), not after the work
    if (!other_.empty()) (void)AtomicOutput(other_);

    const CrowdFile input = read_crowd_file(input_);
    Part part = split_part(input, parsed, false);
    std::optional<Part> other;
    if (!other_.empty()) other = split_part(input, parsed, true);  // both parts exist before anything is written
    std::vector<std::string> inputs{input_.string()};
    if (!job_path_.empty()) inputs.push_back(job_path_.string());
    part.crowd.provenance = context.provenance(effective, inputs, {&input.provenance});
    write_crowd_file(output_, part.crowd, part.extra);
    if (other) {
      other->crowd.provenance = context.provenance(effective, inputs, {&input.provenance});
      try {
        write_crowd_file(other_, other->crowd, other->extra);
      } catch (...) {
        std::error_code ec;
        std::filesystem::remove(output_, ec);  // no half-done split: both parts or neither
        throw;
      }
    }
    Report r;
    r["output"] = output_.string();
    r.update(part.report);
    if (other) {
      Report o;
      o["output"] = other_.string();
      o.update(other->report);
      r["other"] = o;
    }
    context.print(r);
  }

  /// As a step: the part the step's keys choose of the one crowd it reads (a second split step with `keep: second`
  /// or `keep_agents: rest` makes the other part).
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    const SplitJob parsed = read_split_job(step);
    if (inputs.size() != 1) step.fail("split takes one crowd, found " + std::to_string(inputs.size()));
    Part p = split_part(*inputs.front(), parsed, false);
    context.info("split: " + p.report.dump());
    return StepResult{std::move(p.crowd), std::move(p.extra)};
  }

 private:
  std::filesystem::path input_, output_, other_, job_path_;
  JobFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_split_command() { return std::make_unique<SplitCommand>(); }

}  // namespace throng::cli
