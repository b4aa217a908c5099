// throng sketch JOB.yaml -o OUT.h5: a crowd from a few drawn strokes (stroke-driven crowds, solver/sketch/runner.h).
// The job format is in io/sketch/include/throng/io/sketch_job.h; docs/commands/sketch.md is the README section.
// Agents that do not arrive within max_duration (or steps that end inside an obstacle): the crowd and the report
// (with a `shortfall` field) are written, then exit 5; as a step of `throng run`, a warning.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/sketch_job.h>

namespace throng::cli {

std::unique_ptr<Command> make_sketch_command() {
  using Method = MethodCommand<sketch::Job>;
  return std::make_unique<Method>(
      MethodSpec{
          .name = "sketch",
          .summary = "Make a crowd from drawn strokes: a timed main line (path, speed) and auxiliary lines (spread, irregularity)",
          .job = JobArgument::positional, .job_help = "Sketch job (.yaml): strokes, agents, options, obstacles",
          .inputs = {.count_text = "sketch reads no crowd"}, .output_help = "Crowd file to write (.h5)"},
      Method::Hooks{.run = [](const Crowds& in, sketch::Job& job, MethodRun& r) {
        try {
          return sketch::run(in, job, r.progress(), r.communicator());
        } catch (const ConfigError& e) {
          throw ConfigError(r.where + ": " + e.what());  // the memory check before the simulation names the job
        }
      }});
}

}  // namespace throng::cli
