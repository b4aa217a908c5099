// Batch and farm use of `throng run`: several job files (or folders of them) run one after another on each
// rank, spread over the MPI ranks round-robin by job index (job k on rank k mod #ranks), each failure caught and
// recorded so the other jobs still run, and one summary at the end.
//
// Contract:
//  * Each job is a whole `throng run` pipeline; its files are written atomically by the pipeline (a failed job
//    leaves no partial file of the step that failed; files its earlier steps finished stay, as for one job).
//  * With several ranks every rank solves alone (PETSc on MPI_COMM_SELF, see throng/linalg/mpi.h
//    use_ranks_independently): ranks never wait for each other until the summary is gathered.
//  * Summary (rank 0, stdout; JSON with --json): jobs, succeeded, failed, ranks, and per job its path, rank,
//    status (ok | failed), exit code, error message, seconds and the pipeline's report.
//  * Interrupted (killed, or ended by a signal): `throng run --resume` with the same jobs skips the jobs that
//    finished and resumes the others after their last step done (drivers/checkpoint.h).
//  * Exit: 0 when every job succeeded; otherwise the exit code of the first failed job in job order (2 config,
//    3 input, 4 I/O, 5 numerical, 70 internal), on every rank.
#pragma once

#include "context.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace throng::cli {

/// The job files named on the command line: files as given, folders expanded to the *.yaml and *.yml files
/// directly in them (sorted by name). Throws IoError naming a path that does not exist, ConfigError for a
/// folder without a job file or an empty list.
[[nodiscard]] std::vector<std::filesystem::path> expand_jobs(const std::vector<std::filesystem::path>& paths);

/// What became of one job.
struct JobOutcome {
  std::string job;         ///< the job file
  int rank = 0;            ///< the rank that ran it
  bool ok = false;
  int exit_code = 0;       ///< 0, or the code its error maps to
  std::string error;       ///< the error message ("" when ok)
  double seconds = 0;      ///< wall time of the job
  Report report;           ///< the pipeline's report (null when it failed)
};

/// Runs this rank's share of `jobs` through `run_job` (which runs one pipeline and returns its report, or
/// throws), then gathers every rank's outcomes: returns all jobs' outcomes in job order, on every rank.
/// While a job runs, a terminating signal (SIGTERM from a scheduler, Ctrl-C) ends the program with this rank's
/// summary so far (its finished jobs, the one interrupted, those not run) on `summary_fd` (rank 0) or stderr (the
/// other ranks) and exit code 128 + the signal; each job logs the rank and pid running it.
[[nodiscard]] std::vector<JobOutcome> run_batch(const std::vector<std::filesystem::path>& jobs,
                                                const std::function<Report(const std::filesystem::path&)>& run_job,
                                                Context& context, int summary_fd);

/// Prints the summary on rank 0 and, when a job failed, throws the first failed job's error type with a message
/// listing the failed jobs and why (on every rank, so every rank exits with the same code).
void finish_batch(const std::vector<JobOutcome>& outcomes, Context& context);

}  // namespace throng::cli
