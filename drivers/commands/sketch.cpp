// throng sketch JOB.yaml -o OUT.h5: a crowd from a few drawn strokes (stroke-driven crowds, solver/sketch).
// The job format is in io/sketch/include/throng/io/sketch_job.h; docs/commands/sketch.md is the README section.
#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>
#include <throng/io/sketch_job.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>

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

/// Refuses, before simulating, a run whose frames cannot fit in this machine's memory: all frames are held until
/// the file is written (positions, 24 B per agent and frame, then the file's per-frame ids, 8 B more), so a run
/// that does not fit would otherwise end in an allocation failure after the whole simulation. With duration 0
/// the bound is max_duration's frame count. ConfigError at `where` naming the keys to change.
void check_memory(const SketchJob& job, const std::string& where) {
  const sketch::Options& o = job.options;
  const bool fixed = o.duration_s > 0;
  const double seconds = fixed ? o.duration_s : o.max_duration_s;
  const double frames = std::floor(seconds * o.output_rate_hz) + 1;
  const double agents = static_cast<double>(o.agent_count);
  const double bytes = frames * agents * 32.0;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return;  // unknown: let the run try
  const double memory = static_cast<double>(pages) * static_cast<double>(page);
  if (bytes <= memory) return;
  std::ostringstream m;
  m << where << ": up to " << std::llround(std::min(frames, 1e18)) << " frames (" << (fixed ? "duration " : "max_duration ")
    << seconds << " s × output_rate " << o.output_rate_hz << " Hz) of " << o.agent_count << " agents need about ";
  m.precision(3);
  m << bytes / 1e9 << " GB of memory (32 bytes per agent and frame), more than this machine's " << memory / 1e9
    << " GB; lower output_rate, " << (fixed ? "duration" : "max_duration (or set a duration)") << " or agents.count";
  throw ConfigError(m.str());
}

/// The work shared by `throng sketch` and the `sketch` step of `throng run`; `where` names the job in messages.
Sketched sketch_crowd(SketchJob job, Context& context, const std::string& where) {
  check_memory(job, where);
  job.options.seed = context.global.seed;
  sketch::SimulationResult result = sketch::simulate(job.drawing, job.scene, job.options, context.progress());
  Sketched s;
  s.crowd.motion = std::move(result.motion);
  s.crowd.scene = job.scene;
  for (double t : result.arrival_time_s) s.arrived += std::isfinite(t) ? 1 : 0;
  const std::size_t n = result.arrival_time_s.size();
  if (job.options.duration_s == 0 && !result.finished) {
    std::ostringstream m;
    m << n - s.arrived << " of " << n << " agents had not reached the end of their path after max_duration = "
      << job.options.max_duration_s << " s (blocked by obstacles or each other?)";
    s.shortfall = m.str();
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

    Sketched s = sketch_crowd(std::move(parsed), context, job_path_.string());
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
    if (!s.shortfall.empty()) r["shortfall"] = s.shortfall;  // what the run missed (exit 5); absent on success
    context.print(r);
    if (!s.shortfall.empty())
      throw NumericalError("sketch: " + s.shortfall + "; the crowd was written to " + output_.string());
  }

  /// As a step: the step's keys are the job file's; it reads no crowd (it starts a new one).
  std::optional<StepResult> run_step(const ConfigNode& step, const std::vector<const CrowdFile*>&,
                                     Context& context) override {
    Sketched s = sketch_crowd(read_sketch_job(step), context, step.where());
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
