// The time warp as a job: what `throng timewarp`, the `timewarp` step of `throng run` and library users run. The
// job file's format is in throng/io/timewarp_job.h.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/progress.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>
#include <throng/timewarp/guard.h>
#include <throng/timewarp/timewarp.h>

#include <string>
#include <vector>

namespace throng::timewarp {

struct Job {
  Options options;
  /// After the warp (issue 14): speed held to guard.max_speed_ratio × the reference's fastest and kinks beyond
  /// guard.max_acceleration (or the reference agent's own largest acceleration, if larger) smoothed (guard.h).
  /// The warp of Eq. 12 restores speeds in least squares; where the clamp or the fit leaves an agent faster, or a
  /// resampled seam jerks, the guard finishes the job. guard.enabled = false: the paper's warp alone.
  GuardOptions guard;
};

void describe(OptionBinder& b, Job& job);

/// A finished warp: the warped crowd (the deformed crowd's scene), the warp and the report.
struct Run {
  Crowd crowd;
  Warp warp;
  Report report;
  GuardReport guard;                  ///< what the guard did after the warp
  std::vector<std::string> warnings;  ///< when the clamp acts
  std::string shortfall;              ///< always empty: a warp meets its goal or throws
};

/// Warps inputs [deformed, reference]: the deformed crowd's speeds are brought back to the reference's
/// (time_warp), keeping the deformed crowd's scene. One process: the warp is one small solve.
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator);

/// The report: the same fields on stdout and in /parameters/throng/timewarp.
void describe(ReportWriter& w, const Run& run);

}  // namespace throng::timewarp
