// `throng run JOB.yaml`: a pipeline of steps, each one of the subcommands, passing crowds in memory and writing
// files only where a step asks (docs/commands/run.md).
//
//   steps:
//     - step: import                      # the command; its keys follow, as in its job file
//       dataset: ../data/real/eth         # paths in a job are relative to the job file's folder
//       name: eth                         # optional: later steps can take this result by name
//     - step: sketch
//       job: sketch-paper.yaml            # optional: a job file for the step's keys (inline keys override it)
//       output: out/paper.h5              # optional: write this step's crowd here (relative to the working folder)
//     - step: edit
//       input: paper                      # optional: a step name or a crowd file; default: the last crowd made
//       job: edit-battlefield.yaml
//       output: out/edited.h5
//     - step: stitch
//       inputs: [eth, out/edited.h5]      # steps that read several crowds
//     - step: plot                        # steps that make pictures or tables use `output` for their file
//       overlay: paper
//       output: out/edited.png
//
// Pipeline keys: step, name, input, inputs, job, output. Paths: `input`, `inputs` and `job`, and the paths inside
// a step's keys (an import's dataset, a formation's from_crowd.file, a tiling's library.real.dataset), resolve
// against the folder of the file that names them (the pipeline's, or the step's job file); `output` against the
// working directory. A failing step stops the run; files already written by earlier steps stay (each is
// complete: files are written atomically), the failing step leaves nothing; `throng run --resume` continues after
// the last step done (drivers/checkpoint.h).
//
// A step input that is neither an earlier step's name nor an existing file is an I/O error (exit 4, as for
// `throng edit missing.h5`); every error of a step, reading its inputs and job file included, is labelled
// "step i/n <command>".
//
// One pipeline under mpiexec: every rank runs every step that makes a crowd (the petsc backend shares the
// solves between the ranks), rank 0 alone writes the crowd files and prints (the other ranks' stdout goes to
// /dev/null). Steps that make a picture or a table (plot, export, info) write their own files: rank 0 alone
// runs them and tells the others how they ended, so a file is written once and a failing step stops every
// rank with the same exit code.
#pragma once

#include "checkpoint.h"
#include "command.h"

#include <filesystem>
#include <optional>
#include <vector>

namespace throng::cli {

/// Runs the pipeline `job_path` with `commands` as its steps and returns its report (nullopt after
/// --print-config). `collective`: every rank runs this pipeline (one job under mpiexec), so crowd files are
/// written by rank 0 only and the steps that write their own files run on rank 0 only; otherwise (a batch: each
/// rank its own jobs) this rank writes everything. Checkpointed after every step (drivers/checkpoint.h): with
/// `checkpoints.resume` it continues from its checkpoint; one that every step of was done returns its report.
[[nodiscard]] std::optional<Report> run_pipeline(const std::filesystem::path& job_path, const std::vector<Command*>& commands,
                                                 Context& context, bool collective, const CheckpointOptions& checkpoints);

/// The outputs a job's steps name (crowd files and pictures), as absolute normal paths.
[[nodiscard]] std::vector<std::filesystem::path> named_outputs(const ConfigNode& job);

/// While alive, file descriptor 1 (stdout) points at `target` (another descriptor, or /dev/null when -1);
/// restored afterwards. C++ and C streams are flushed on both edges so nothing lands on the wrong side.
class StdoutRedirect {
 public:
  explicit StdoutRedirect(int target);
  ~StdoutRedirect();
  StdoutRedirect(const StdoutRedirect&) = delete;
  StdoutRedirect& operator=(const StdoutRedirect&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace throng::cli
