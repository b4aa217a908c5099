// throng run JOB.yaml [JOB2.yaml | FOLDER ...]: one pipeline of steps (drivers/pipeline.h), or several as a batch
// spread over the MPI ranks (drivers/batch.h).
//
// Batch: `throng run A.yaml B.yaml jobs/` runs every job (folders: their *.yaml, *.yml) spread over the MPI
// ranks; a failing job does not stop the others; a summary lists them. Before anything runs, two jobs naming the
// same output file are refused (exit 2). While the jobs run, whatever their steps print (an info step's report)
// goes to stderr, so stdout holds the summary alone (one JSON document with --json); the summary and the final
// "N of M jobs failed" come from rank 0 only.
//
// Interrupted runs: every pipeline is checkpointed after each step (drivers/checkpoint.h); `--resume` continues
// from there (a batch skips its finished jobs), `--checkpoint-dir` says where the checkpoints live.
#include "../batch.h"
#include "../pipeline.h"
#include "factories.h"

#include <throng/core/errors.h>
#include <throng/io/atomic_output.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <memory>
#include <fcntl.h>
#include <unistd.h>

namespace throng::cli {
namespace {

class RunCommand final : public Command {
 public:
  explicit RunCommand(std::vector<Command*> commands) : commands_(std::move(commands)) {}

  std::string name() const override { return "run"; }
  std::string summary() const override { return "Run a pipeline of steps (import, sketch, edit, ..., plot) from a YAML job"; }

  void setup(CLI::App& app) override {
    app.add_option("job", job_paths_, "Pipeline job (.yaml); several jobs or folders of them run as a batch over the MPI ranks")->required();
    app.add_flag("--resume", checkpoints_.resume,
                 "Continue an interrupted run from its checkpoint: finished steps and jobs are not run again");
    app.add_option("--checkpoint-dir", checkpoints_.folder, "Where runs keep their checkpoints")
        ->default_str(checkpoints_.folder.string());
  }

  void run(Context& context) override {
    if (job_paths_.size() == 1 && !std::filesystem::is_directory(job_paths_.front())) {
      // One pipeline: under mpiexec every rank runs it (collective solves), rank 0 writes and prints.
      std::optional<StdoutRedirect> silent;
      if (!context.writer()) silent.emplace(-1);
      if (auto report = run_pipeline(job_paths_.front(), commands_, context, true, checkpoints_)) context.print(*report);
      return;
    }
    // A batch: every rank sees the same jobs and the same errors; only rank 0 reports an error that ends it.
    context.process().use_ranks_independently();
    try {
      if (context.global.print_config) throw ConfigError("--print-config takes one job file, not a batch");
      const auto jobs = expand_jobs(job_paths_);
      refuse_shared_outputs(jobs, context);
      std::vector<JobOutcome> outcomes;
      {
        // stdout itself: the summary of a batch ended by a signal goes there (closed when the batch ends).
        const std::unique_ptr<int, void (*)(int*)> summary_fd(new int(::fcntl(1, F_DUPFD_CLOEXEC, 0)), [](int* fd) {
          set_interrupt_note(-1, "");  // no note may point at the descriptor once it is closed
          if (*fd >= 0) ::close(*fd);
          delete fd;
        });
        const StdoutRedirect to_stderr(2);
        outcomes = run_batch(
            jobs, [&](const std::filesystem::path& path) { return *run_pipeline(path, commands_, context, false, checkpoints_); },
            context, *summary_fd);
      }
      // A batch that succeeded has nothing left to resume; one with a failed job keeps every record, so that
      // --resume runs the failed jobs alone.
      const bool all_ok = std::all_of(outcomes.begin(), outcomes.end(), [](const JobOutcome& o) { return o.ok; });
      if (all_ok && context.writer()) remove_checkpoints(checkpoints_, jobs);
      finish_batch(outcomes, context);
    } catch (...) {
      if (!context.writer()) (void)std::freopen("/dev/null", "w", stderr);  // rank 0 says it once
      throw;
    }
  }

 private:
  /// Two jobs of a batch writing the same file would race (and the later would silently win): ConfigError
  /// naming both, before any job runs. A job that cannot be read is left to fail in its turn.
  static void refuse_shared_outputs(const std::vector<std::filesystem::path>& jobs, Context& context) {
    std::map<std::filesystem::path, std::filesystem::path> writer_of;
    for (const auto& job : jobs) {
      std::vector<std::filesystem::path> outputs;
      try {
        outputs = named_outputs(context.load_job(job));
      } catch (const std::exception&) {
        continue;
      }
      for (const auto& out : outputs) {
        const auto [it, fresh] = writer_of.emplace(out, job);
        if (!fresh && it->second != job) {
          throw ConfigError("run: the jobs " + it->second.string() + " and " + job.string() + " both write " +
                            out.string() + "; give each job its own output");
        }
      }
    }
  }

  std::vector<Command*> commands_;
  std::vector<std::filesystem::path> job_paths_;
  CheckpointOptions checkpoints_;
};

}  // namespace

std::unique_ptr<Command> make_run_command(std::vector<Command*> commands) {
  return std::make_unique<RunCommand>(std::move(commands));
}

}  // namespace throng::cli
