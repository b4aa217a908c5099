// Group motion editing as a job: what `throng edit`, the `edit` step of `throng run` and library users run. The
// job file's format is in throng/io/edit_job.h.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/progress.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>
#include <throng/edit/edit.h>
#include <throng/timewarp/guard.h>

#include <string>
#include <vector>

namespace throng::edit {

struct Job {
  Options options;
  Request request;
  bool clip_only = false;  ///< the output is the clip alone, not the whole crowd with the clip put back (output.h)
  /// After the edit (issue 14; throng/edit/guard.h): speed held to guard.max_speed_ratio × the input's fastest and
  /// kinks beyond max(guard.max_acceleration, the input's own acceleration there) smoothed, the request's frames
  /// pinned. guard.enabled = false: the paper's edit alone.
  timewarp::GuardOptions guard;
};

/// The job's options: Options (schema.h), clip_only and the `guard` section (timewarp/schema.h).
void describe(OptionBinder& b, Job& job);

/// A finished edit.
struct Run {
  Crowd crowd;                        ///< the whole input with the clip edited, or the clip alone
  Result result;                      ///< the edit (its clip moved into `crowd` when clip_only)
  std::size_t clip_agents = 0;        ///< agents the edit covered
  double seam_jump_m = 0;             ///< output.h seam_jump
  timewarp::GuardReport guard;        ///< what the guard did to the written crowd
  /// result.report.max_output_residual was measured on the written crowd after the guard (true), or on the edit
  /// before it (false: the guard warped, so the request holds at the warped times of its frames; guard.h)
  bool residual_after_guard = false;
  bool clip_only = false;
  std::string backend;
  int ranks = 1;
  std::vector<std::string> warnings;  ///< agents left out, a backend fallback, a jump at a local region's edge, a seam
  std::string shortfall;              ///< always empty: an edit meets its request or throws
};

/// Edits the one crowd of `inputs` (edit_group_motion), puts the clip back into the whole crowd (or keeps the clip
/// alone, its formation edges renumbered), guards it (Job::guard) and measures the request on the written frames. The ranks: the petsc
/// backend shares its solves over them; with another backend every rank solves the whole problem (a warning says
/// so).
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator);

/// The report: the same fields on stdout and in /parameters/throng/edit.
void describe(ReportWriter& w, const Run& run);

}  // namespace throng::edit
