// Group motion editing as a job: what `throng edit`, the `edit` step of `throng run` and library users run. The
// job file's format is in throng/io/edit_job.h.
#pragma once

#include <throng/core/communicator.h>
#include <throng/core/crowd.h>
#include <throng/core/progress.h>
#include <throng/core/report.h>
#include <throng/core/schema.h>
#include <throng/edit/edit.h>

#include <string>
#include <vector>

namespace throng::edit {

struct Job {
  Options options;
  Request request;
  bool clip_only = false;  ///< the output is the clip alone, not the whole crowd with the clip put back (output.h)
};

/// The job's options: Options (schema.h) and clip_only.
void describe(OptionBinder& b, Job& job);

/// A finished edit.
struct Run {
  Crowd crowd;                        ///< the whole input with the clip edited, or the clip alone
  Result result;                      ///< the edit (its clip moved into `crowd` when clip_only)
  std::size_t clip_agents = 0;        ///< agents the edit covered
  double seam_jump_m = 0;             ///< output.h seam_jump
  bool clip_only = false;
  std::string backend;
  int ranks = 1;
  std::vector<std::string> warnings;  ///< agents left out, a backend fallback, a jump at a local region's edge, a seam
  std::string shortfall;              ///< always empty: an edit meets its request or throws
};

/// Edits the one crowd of `inputs` (edit_group_motion), puts the clip back into the whole crowd (or keeps the clip
/// alone, its formation edges renumbered) and measures the request on the written frames. The ranks: the petsc
/// backend shares its solves over them; with another backend every rank solves the whole problem (a warning says
/// so).
[[nodiscard]] Run run(const Crowds& inputs, const Job& job, Progress& progress, const Communicator& communicator);

/// The report: the same fields on stdout and in /parameters/throng/edit.
void describe(ReportWriter& w, const Run& run);

}  // namespace throng::edit
