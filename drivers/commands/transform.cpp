// throng transform CROWD.h5 -o OUT.h5: place a clip in space and time — rotate, translate, retime, resample,
// renumber (solver/stitch/jobs.h); its scene moves with it. The job format is in
// io/stitch/include/throng/io/transform_job.h; every key also has a flag. docs/commands/stitch.md is the README section.
#include "../method_command.h"
#include "factories.h"

#include <throng/io/transform_job.h>

namespace throng::cli {

std::unique_ptr<Command> make_transform_command() {
  return std::make_unique<MethodCommand<stitch::TransformJob>>(MethodSpec{.name = "transform",
                                   .summary = "Place a clip in space and time: rotate, translate, retime, resample, renumber",
                                   .job = JobArgument::optional, .job_help = "Transform job (.yaml); the flags below override its keys",
                                   .inputs = {1, 1, "crowd", "Crowd file to transform (.h5)", nullptr, "", "transform takes one crowd"},
                                   .output_help = "Crowd file to write (.h5)"});
}

}  // namespace throng::cli
