// throng timewarp DEFORMED.h5 --reference ORIGINAL.h5 -o OUT.h5: after a deformation made paths longer or
// shorter, one time warp shared by all agents brings their speeds back towards the original's (Kwon et al. 2008
// §6.2, Eq. 12), then every agent is resampled at the output frame rate through cubic splines
// (solver/timewarp/timewarp.h). The warp (old time → new time) is stored under /parameters/throng/timewarp.
// The job format is in io/timewarp/include/throng/io/timewarp_job.h; docs/commands/stitch.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/command_job.h>
#include <throng/io/timewarp_job.h>

#include <algorithm>
#include <memory>

#include "factories.h"
#include "job_flags.h"

namespace throng::cli {
namespace {

struct Warped {
  CrowdFile crowd;
  ExtraWriter extra;
  Report report;
};

/// The work shared by `throng timewarp` and the `timewarp` step.
Warped warp_crowd(const CrowdFile& deformed, const CrowdFile& reference, const TimewarpJob& job, Context& context) {
  context.progress().update(0.0, "timewarp");
  auto result = std::make_shared<timewarp::Result>(timewarp::time_warp(deformed.motion, reference.motion, job.options));
  context.progress().update(1.0, "timewarp: done");
  const timewarp::Report& r = result->report;
  if (r.clamped_short + r.clamped_long > 0) {
    context.warn("timewarp: the clamp acts on " + std::to_string(r.clamped_short + r.clamped_long) + " of " +
                 std::to_string(r.frames_in > 0 ? r.frames_in - 1 : 0) + " frame intervals (" + std::to_string(r.clamped_short) +
                 " held at min_interval_ratio, " + std::to_string(r.clamped_long) + " at max_interval_ratio)");
  }
  Warped w;
  w.crowd.motion = result->crowd;
  w.crowd.scene = deformed.scene;
  w.crowd.provenance.credits = deformed.provenance.credits;
  for (const std::string& c : reference.provenance.credits) {
    if (std::find(w.crowd.provenance.credits.begin(), w.crowd.provenance.credits.end(), c) == w.crowd.provenance.credits.end()) {
      w.crowd.provenance.credits.push_back(c);
    }
  }
  w.extra = [result](const h5::Group& g) { write_timewarp_data(g, *result); };
  w.report["agents"] = r.agents;
  w.report["frames_in"] = r.frames_in;
  w.report["frames"] = r.frames_out;
  w.report["duration_in_s"] = r.duration_in_s;
  w.report["duration_s"] = r.duration_out_s;
  w.report["output_rate_hz"] = r.output_rate_hz;
  w.report["speed_deviation_before_mps"] = r.speed_deviation_before;
  w.report["speed_deviation_after_mps"] = r.speed_deviation_after;
  w.report["reference_speed_rms_mps"] = r.reference_speed_rms;
  w.report["clamped_short"] = r.clamped_short;
  w.report["clamped_long"] = r.clamped_long;
  w.report["still_intervals"] = r.still_intervals;
  return w;
}

class TimewarpCommand final : public Command {
 public:
  std::string name() const override { return "timewarp"; }
  std::string summary() const override {
    return "Retime a deformed crowd so its speeds match the original's (one shared time warp, spline resampling)";
  }

  void setup(CLI::App& app) override {
    app.add_option("crowd", input_, "Deformed crowd file (.h5), for example the output of throng edit")->required();
    app.add_option("--reference", reference_, "The crowd before the deformation (.h5): the speeds to keep")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
    app.add_option("--job", job_path_, "Time warp job (.yaml); the flags below override its keys");
    flags_.value(app, "--smoothing-time", "smoothing_time", "Seconds over which the warp's speed-up may change (0: Eq. 12's closed form)");
    flags_.value(app, "--min-interval-ratio", "min_interval_ratio", "Shortest a frame interval may become, as a fraction of its length");
    flags_.value(app, "--max-interval-ratio", "max_interval_ratio", "Longest a frame interval may become, as a multiple of its length");
    flags_.value(app, "--output-rate", "output_rate", "Frames per second of the output (0: the input's rate)");
    flags_.value(app, "--spline", "spline", "not_a_knot | natural: end condition of the resampling splines");
    flags_.value(app, "--time-tolerance", "time_tolerance", "Seconds: how close a reference frame's time must be to a deformed frame's");
  }

  void run(Context& context) override {
    const ConfigNode job = command_job(job_path_, flags_.yaml(), context.global.set, "timewarp");
    const TimewarpJob parsed = read_timewarp_job(job);
    const YAML::Node effective = effective_timewarp_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(input_, output_);
    check_distinct(reference_, output_);
    if (!job_path_.empty()) check_distinct(job_path_, output_);
    context.limit_threads();
    (void)AtomicOutput(output_);  // a missing or read-only output folder fails now (exit 4), not after the work

    const CrowdFile deformed = read_crowd_file(input_);
    const CrowdFile reference = read_crowd_file(reference_);
    Warped w = warp_crowd(deformed, reference, parsed, context);
    std::vector<std::string> inputs{input_.string(), reference_.string()};
    if (!job_path_.empty()) inputs.push_back(job_path_.string());
    w.crowd.provenance = context.provenance(effective, inputs, {&deformed.provenance, &reference.provenance});
    write_crowd_file(output_, w.crowd, w.extra);
    Report r;
    r["output"] = output_.string();
    r.update(w.report);
    context.print(r);
  }

  /// As a step: `inputs: [deformed, reference]`, the command line's order.
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>& inputs,
                                     Context& context) override {
    const TimewarpJob parsed = read_timewarp_job(step);
    if (inputs.size() != 2) {
      step.fail("timewarp takes two crowds, inputs: [deformed, reference] (the crowd before the deformation), found " +
                std::to_string(inputs.size()));
    }
    Warped w = warp_crowd(*inputs[0], *inputs[1], parsed, context);
    context.info("timewarp: " + w.report.dump());
    return StepResult{std::move(w.crowd), std::move(w.extra)};
  }

 private:
  std::filesystem::path input_, reference_, output_, job_path_;
  JobFlags flags_;
};

}  // namespace

std::unique_ptr<Command> make_timewarp_command() { return std::make_unique<TimewarpCommand>(); }

}  // namespace throng::cli
