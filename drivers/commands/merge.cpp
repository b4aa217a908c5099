// throng merge A.h5 B.h5 [C.h5 ...] -o OUT.h5: several groups in a shared time span become one crowd (one graph
// for editing and stitching: formation edges join the groups where they are neighbours; solver/stitch/jobs.h).
// The job format is in io/stitch/include/throng/io/merge_job.h; docs/commands/stitch.md is the README section.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/merge_job.h>

namespace throng::cli {

std::unique_ptr<Command> make_merge_command() {
  return std::make_unique<MethodCommand<stitch::MergeJob>>(MethodSpec{
      .name = "merge", .summary = "Merge groups sharing a time span into one crowd (one formation graph across the groups)",
      .job = JobArgument::optional,
      .job_help = "Merge job (.yaml): options and obstacles to add; the flags below override its keys",
      .inputs = {.min = 2, .max = any_number, .name = "crowds", .help = "Crowd files to merge (.h5), two or more, in order",
                 .count_text = "merge takes two or more crowds (inputs: [a, b, ...])"},
      .output_help = "Crowd file to write (.h5)"});
}

}  // namespace throng::cli
