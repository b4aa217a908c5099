// throng sketch JOB.yaml -o OUT.h5: a crowd from a few drawn strokes (stroke-driven crowds, solver/sketch).
// The job format is in io/sketch/include/throng/io/sketch_job.h; docs/commands/sketch.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/sketch_job.h>

#include <cmath>
#include <memory>

#include "factories.h"

namespace throng::cli {
namespace {

/// A finished run: the crowd to write and the method data stored with it.
struct Sketched {
  CrowdFile crowd;
  ExtraWriter extra;
  std::size_t arrived = 0;
  std::string shortfall;  ///< empty when the run met its goal, else what it missed
};

/// The work shared by `throng sketch` and the `sketch` step of `throng run`.
Sketched sketch_crowd(SketchJob job, Context& context) {
  job.options.seed = context.global.seed;
  sketch::SimulationResult result = sketch::simulate(job.drawing, job.scene, job.options, context.progress());
  Sketched s;
  s.crowd.motion = std::move(result.motion);
  s.crowd.scene = job.scene;
  for (double t : result.arrival_time_s) s.arrived += std::isfinite(t) ? 1 : 0;
  const std::size_t n = result.arrival_time_s.size();
  if (job.options.duration_s == 0 && !result.finished) {
    s.shortfall = std::to_string(n - s.arrived) + " of " + std::to_string(n) +
                  " agents had not reached the end of their path after max_duration = " +
                  std::to_string(job.options.max_duration_s) + " s (blocked by obstacles or each other?)";
  }
  if (result.unresolved_obstacle_contacts > 0) {
    if (!s.shortfall.empty()) s.shortfall += "; ";
    s.shortfall += std::to_string(result.unresolved_obstacle_contacts) +
                   " agent-steps ended overlapping an obstacle (obstacles closer together than an agent's width)";
  }
  auto data = std::make_shared<const std::pair<SketchJob, sketch::SimulationResult>>(std::move(job), std::move(result));
  s.extra = [data](const h5::Group& g) { write_sketch_data(g, data->first, data->second); };
  return s;
}

class SketchCommand final : public Command {
 public:
  std::string name() const override { return "sketch"; }
  std::string summary() const override {
    return "Make a crowd from drawn strokes: a timed main line (path, speed) and auxiliary lines (spread, "
           "irregularity)";
  }

  void setup(CLI::App& app) override {
    app.add_option("job", job_path_, "Sketch job (.yaml): strokes, agents, options, obstacles")->required();
    app.add_option("-o,--output", output_, "Crowd file to write (.h5)")->required();
  }

  void run(Context& context) override {
    const ConfigNode job = context.load_job(job_path_);
    SketchJob parsed = read_sketch_job(job);
    const YAML::Node effective = effective_sketch_job(parsed);
    if (context.print_config_if_asked(effective)) return;
    check_distinct(job_path_, output_);
    context.limit_threads();

    Sketched s = sketch_crowd(std::move(parsed), context);
    s.crowd.provenance = context.provenance(effective, {job_path_.string()});
    write_crowd_file(output_, s.crowd, s.extra);

    const CrowdMotion& m = s.crowd.motion;
    Report r;
    r["output"] = output_.string();
    r["agents"] = m.agent_count();
    r["frames"] = m.frame_count();
    r["duration_s"] = m.frame_count() ? m.times.back() : 0.0;
    r["arrived"] = s.arrived;
    r["obstacles"] = s.crowd.scene.obstacles.size();
    r["seed"] = context.global.seed;
    context.print(r);
    if (!s.shortfall.empty())
      throw NumericalError("sketch: " + s.shortfall + "; the crowd was written to " + output_.string());
  }

  /// As a step: the step's keys are the job file's; it reads no crowd (it starts a new one).
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>&,
                                     Context& context) override {
    Sketched s = sketch_crowd(read_sketch_job(step), context);
    if (!s.shortfall.empty()) context.warn("sketch: " + s.shortfall);
    return StepResult{std::move(s.crowd), std::move(s.extra)};
  }

 private:
  std::filesystem::path job_path_;
  std::filesystem::path output_;
};

}  // namespace

std::unique_ptr<Command> make_sketch_command() { return std::make_unique<SketchCommand>(); }

}  // namespace throng::cli
