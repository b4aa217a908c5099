// throng stitch A.h5 B.h5 [C.h5 ...] -o OUT.h5: clips with the same agents played one after the other become one
// clip of t + t′ − 1 frames whose formation morphs across each joint (Kwon et al. 2008 §5; solver/stitch/jobs.h).
// The job format is in io/stitch/include/throng/io/stitch_job.h; docs/commands/stitch.md is the README section.
// Under mpiexec every rank stitches (the petsc backend shares the solves); rank 0 writes and reports.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/stitch_job.h>

namespace throng::cli {

std::unique_ptr<Command> make_stitch_command() {
  return std::make_unique<MethodCommand<stitch::StitchJob>>(MethodSpec{.name = "stitch",
                                                          .summary = "Play clips of the same agents one after the other, morphing "
                                                                     "the formation across each joint",
                                                          .job = JobArgument::optional,
                                                          .job_help = "Stitch job (.yaml): weights, solver ...; the flags below "
                                                                      "override its keys",
                                                          .inputs = {.min = 2, .max = any_number, .name = "clips",
                                                                     .help = "Crowd files to stitch (.h5), two or more, in order",
                                                                     .count_text = "stitch takes two or more clips (inputs: [a, b, ...])"},
                                                          .output_help = "Crowd file to write (.h5)"});
}

}  // namespace throng::cli
