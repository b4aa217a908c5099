// throng transform CROWD.h5 -o OUT.h5: place a clip in space and time — rotate, translate, retime, resample,
// renumber (solver/stitch/transform.h); its scene moves with it. The job format is in
// io/stitch/include/throng/io/transform_job.h; every key also has a flag. docs/commands/stitch.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/command_job.h>
#include <throng/io/transform_job.h>

#include <numbers>

#include "factories.h"
#include "job_flags.h"

namespace throng::cli {
namespace {

struct Transformed {
  CrowdFile crowd;
  Report report;
};

/// The work shared by `throng transform` and the `transform` step.
Transformed transform_crowd(const CrowdFile& input, const TransformJob& job) {
  Transformed t;
  t.crowd.motion = input.motion;
  t.crowd.scene = input.scene;
  t.crowd.formation_edges = input.formation_edges;
  t.crowd.provenance.credits = input.provenance.credits;
  const stitch::TransformOptions options = resolve_transform(job, input.motion);
  stitch::transform(t.crowd.motion, t.crowd.scene, options);
  const CrowdMotion& m = t.crowd.motion;
  t.report["agents"] = m.agent_count();
  t.report["frames"] = m.frame_count();
  t.report["times_s"] = {m.times.empty() ? 0.0 : m.times.front(), m.times.empty() ? 0.0 : m.times.back()};
  t.report["rotation_deg"] = options.rotation * 180.0 / std::numbers::pi;
  t.report["translation_m"] = {options.translation.x(), options.translation.y()};
  t.report["time_shift_s"] = options.time_shift;
  return t;
}

class TransformCommand final : public Command {
 public:
  std::string name() const override { return "transform"; }
  std::string summary() const override {
    return "Place a clip in space and time: rotate, translate, retime, resample, renumber";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Crowd file to transform (.h5)")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
    app.add_option("--job", job_path_, "Transform job (.yaml); the flags below override its keys");
    flags_.value(app, "--rotate", "rotate", "Degrees, counter-clockwise, about the pivot");
    flags_.list(app, "--pivot", "pivot", "X,Y of the rotation's fixed point (default: the first frame's centroid)");
    flags_.list(app, "--translate", "translate", "X,Y metres, after the rotation");
    flags_.list(app, "--place-at", "place_at", "X,Y: move the first frame's centroid here (instead of --translate)");
    flags_.value(app, "--time-scale", "time_scale", "Durations multiply by this (2: half as fast)");
    flags_.value(app, "--time-shift", "time_shift", "Seconds added to every time");
    flags_.value(app, "--start-time", "start_time", "The first frame's new time in seconds (instead of --time-shift)");
    flags_.value(app, "--frame-rate", "frame_rate", "Resample at this many frames per second (0: keep the frames)");
    flags_.value(app, "--id-offset", "id_offset", "Added to every agent id");
    flags_.value(app, "--species", "species", "Every agent's species becomes this");
  }

  void run(Context& context) override {
    const ConfigNode job = command_job(job_path_, flags_.yaml(), context.global.set, "transform");
    const TransformJob parsed = read_transform_job(job);
    const YAML::Node effective = effective_transform_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);
    if (!job_path_.empty()) check_distinct(job_path_, output_);
    context.limit_threads();
    (void)AtomicOutput(output_);  // a missing or read-only output folder fails now (exit 4), not after the work

    const CrowdFile input = read_crowd_file(input_);
    Transformed t = transform_crowd(input, parsed);
    std::vector<std::string> inputs{input_.string()};
    if (!job_path_.empty()) inputs.push_back(job_path_.string());
    t.crowd.provenance = context.provenance(effective, inputs, {&input.provenance});
    write_crowd_file(output_, t.crowd);
    Report r;
    r["output"] = output_.string();
    r.update(t.report);
    context.print(r);
  }

  /// As a step: transforms the one crowd it reads.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    const TransformJob parsed = read_transform_job(step);
    if (inputs.size() != 1) step.fail("transform takes one crowd, found " + std::to_string(inputs.size()));
    Transformed t = transform_crowd(*inputs.front(), parsed);
    context.info("transform: " + t.report.dump());
    return StepResult{std::move(t.crowd), {}};
  }

 private:
  std::filesystem::path input_, output_, job_path_;
  JobFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_transform_command() { return std::make_unique<TransformCommand>(); }

}  // namespace throng::cli
