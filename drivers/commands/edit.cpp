// throng edit CROWD.h5 --job EDIT.yaml -o OUT.h5 [--backend eigen|petsc]: deform a group motion by pinning and
// dragging agents while keeping its formations and trajectories (group motion editing, solver/edit/runner.h).
// The job format is in io/edit/include/throng/io/edit_job.h; docs/commands/edit.md is the README section.
// Output: the whole input crowd with the edited clip put back (solver/edit output.h), or only the clip with
// --clip-only (job key clip_only).
// With local.parts > 0 or auto (or --local-parts) the edit is local (solver/edit local_edit.h): only the parts it
// reaches are solved; the report gives the step across the region's edge in time and a warning says when it
// is a jump (edit::BoundaryStep); docs/commands/scale.md describes it.
//
// Under mpiexec every rank reads the input and builds the problem; the petsc backend shares the solves between
// the ranks; rank 0 writes the output and prints the report.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/edit_job.h>

namespace throng::cli {

std::unique_ptr<Command> make_edit_command() {
  return std::make_unique<MethodCommand<edit::Job>>(MethodSpec{
      .name = "edit",
      .summary = "Deform a group motion by pinning and dragging agents, keeping formations and trajectories",
      .job = JobArgument::required, .job_help = "Edit job (.yaml): clip, pins, drags, constraints, weights, solver",
      .inputs = {.min = 1, .max = 1, .help = "Crowd file to edit (.h5)", .count_text = "edit takes one crowd"},
      .output_help = "Crowd file to write (.h5): the input crowd with the clip edited"});
}

}  // namespace throng::cli
