// The default for commands that cannot be a step of `throng run`.
#include "../command.h"

#include <throng/core/errors.h>

namespace throng::cli {

std::optional<StepResult> Command::run_step(const ConfigNode& step, const std::vector<const CrowdFile*>&, Context&) {
  step.fail("'" + name() + "' cannot be a step of throng run");
}

}  // namespace throng::cli
