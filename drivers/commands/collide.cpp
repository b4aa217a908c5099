// throng collide CROWD.h5 [--job COLLIDE.yaml] [flags] -o OUT.h5: push colliding trajectories apart, and out of
// obstacles, until every clearance holds (collision repair, solver/collide/runner.h). Options come from the job
// file (io/collide/include/throng/io/collide_job.h), overridden by the flags, overridden by --set.
// docs/commands/collide.md is the README section.
//
// Collisions left at the end (iteration cap, or pinned frames that collide): the output and the report are
// written, then the command exits 5 (NumericalError) unless allow_remaining. As a `throng run` step the step
// fails (exit 5, the step writes nothing) unless allow_remaining, which turns it into a warning.
//
// Under mpiexec every rank runs the repair (the trajectories' solves are spread over the ranks and gathered),
// so every rank holds the result; rank 0 alone writes the output and prints the report.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/collide_job.h>

namespace throng::cli {

std::unique_ptr<Command> make_collide_command() {
  using Method = MethodCommand<collide::Job>;
  return std::make_unique<Method>(
      MethodSpec{
          .name = "collide", .summary = "Repair collisions: push trajectories apart and out of obstacles, keeping pinned frames",
          .job = JobArgument::optional, .job_help = "Collide job (.yaml); the flags below override its keys",
          .inputs = {.min = 1, .max = 1, .help = "Crowd file to repair (.h5)", .count_text = "collide takes one crowd"},
          .output_help = "Crowd file to write (.h5): the repaired crowd"},
      Method::Hooks{.fails = [](const collide::Job& job, bool) { return !job.allow_remaining; }});
}

}  // namespace throng::cli
