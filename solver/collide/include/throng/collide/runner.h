// The collide method as a job: what `throng collide`, the `collide` step of `throng run` and library users run.
// The job file's format is in throng/io/collide_job.h.
#pragma once

#include <throng/collide/collide.h>
#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>

#include <string>
#include <vector>

namespace throng::collide {

struct Job {
  Options options;
  bool allow_remaining = false;  ///< collisions left at the end are a warning, not a failure
  Scene scene;                   ///< the job's own obstacles (added to the crowd's) and region
};

/// The job's options: Options (schema.h) and allow_remaining.
void describe(OptionBinder& b, Job& job);

/// A finished repair.
struct Run {
  Crowd crowd;      ///< the repaired crowd; its scene is the input's obstacles then the job's; the input's edges
  Report report;
  std::vector<std::string> warnings;
  std::string shortfall;  ///< what is left (summary()), empty when converged
};

/// Repairs the one crowd of `inputs` among its obstacles and the job's (the job's region replaces the crowd's),
/// spreading the solves over `communicator`'s ranks. ConfigError for a bad option or an unknown fixed agent, as
/// resolve_collisions.
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator);

/// The report: the same fields on stdout and in /parameters/throng/collide.
void describe(ReportWriter& w, const Run& run);

}  // namespace throng::collide
