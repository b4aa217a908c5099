// throng timewarp DEFORMED.h5 --reference ORIGINAL.h5 -o OUT.h5: after a deformation made paths longer or
// shorter, one time warp shared by all agents brings their speeds back towards the original's (Kwon et al. 2008
// §6.2, Eq. 12), then every agent is resampled at the output frame rate through cubic splines
// (solver/timewarp/runner.h). The warp (old time → new time) is stored under /parameters/throng/timewarp.
// The job format is in io/timewarp/include/throng/io/timewarp_job.h; docs/commands/stitch.md is the README section.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/timewarp_job.h>

namespace throng::cli {

std::unique_ptr<Command> make_timewarp_command() {
  return std::make_unique<MethodCommand<timewarp::Job>>(MethodSpec{
      .name = "timewarp",
      .summary = "Retime a deformed crowd so its speeds match the original's (one shared time warp, spline resampling)",
      .job = JobArgument::optional,
      .job_help = "Time warp job (.yaml); the flags below override its keys",
      .inputs = {2, 2, "crowd", "Deformed crowd file (.h5), for example the output of throng edit", "--reference",
                 "The crowd before the deformation (.h5): the speeds to keep",
                 "timewarp takes two crowds, inputs: [deformed, reference] (the crowd before the deformation)"},
      .output_help = "Crowd file to write (.h5)"});
}

}  // namespace throng::cli
