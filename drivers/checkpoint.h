// Checkpoints of `throng run` (docs/commands/run.md, "Interrupted runs"): after every step a pipeline records how far
// it got, and the crowds its later steps may still read, so that `throng run --resume` continues a killed run
// where it stopped instead of starting over, and ends with the same bits as a run that was never interrupted.
//
// One folder per job under the checkpoint folder (`.throng-resume` in the working folder unless --checkpoint-dir
// says otherwise), named after the job file and a hash of its absolute path:
//
//   .throng-resume/<job stem>-<16 hex digits>/
//     state.json    format, job, fingerprint, steps, done (steps finished), running (the step under way, 1-based,
//                   or null), rank, pid and host of the run that wrote it (rank 0's for a pipeline run by every
//                   rank), crowds ({step name: step index}), last (the index of the last crowd made, or null), files
//                   ({step index: {path, size, modified}}: the crowd file holding its crowd, with its size and
//                   modification time in ns), written (outputs counted so far), and once every step is done the
//                   pipeline's report
//     step-<i>.h5   the crowd step i made, while a later step may still read it (by its name or as the last crowd
//                   made) and the step wrote no crowd file of its own that stays as it wrote it (one it wrote holds
//                   the same crowd: the checkpoint names that file instead of copying it, unless a later step of
//                   the pipeline writes the same path). A crowd no later step reads is not kept.
//
// The run that checkpoints holds an exclusive lock (flock) on the folder from restore() to its end: a second run of
// the same job at the same time (same job file, same checkpoint folder) is not checkpointed (it warns) and leaves
// the first's checkpoint alone; resuming while another run holds it is refused (exit 2).
//
// The state is written when the run starts and after each step (naming the next step as under way). Every file is
// written atomically (AtomicOutput), after the step's own output: a run killed at any point leaves
// the previous state or the new one, and a step killed between its output and its record is simply run again
// (it writes the same bits). A checkpoint is emptied state first, so a state never names a crowd copy already
// removed; a state with every step done restores no crowd (nothing is left to run). A crowd round-trips a crowd
// file exactly, so a restored crowd is the crowd in memory.
//
// The fingerprint ties a checkpoint to what the run computes: the program version, the job as loaded (with
// --set), the seed, the number of MPI ranks of a pipeline run by every rank, and the bytes of every step's `job:`
// file. Resuming from a checkpoint with another fingerprint is refused (ConfigError, exit 2): it would mix two jobs.
// So is resuming when a crowd file the checkpoint keeps changed size or modification time since (exit 2). Data
// files a job reads are not in it (a step's input may be an earlier step's output): `--resume` trusts that they
// did not change.
//
// A pipeline run by every rank under mpiexec: rank 0 locks, writes and removes the checkpoint; on resume rank 0
// reads the state and gives it to every rank, every rank reads the crowds it keeps, and all agree on the outcome
// (one failing rank fails all with its error) before rank 0 writes anything.
//
// A pipeline run on its own removes its folder when it finishes; in a batch the folder keeps the finished job's
// report (so `--resume` skips the job) until the whole batch has succeeded. A run without --resume starts over
// and replaces any checkpoint of its job. Writing a checkpoint never fails a run: when the folder cannot be
// written the run says so once, removes what it had written, and goes on without.
#pragma once

#include "context.h"

#include <throng/io/crowd_file.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>

namespace throng::cli {

/// How `throng run` checkpoints: where, and whether this run continues from the checkpoint there.
struct CheckpointOptions {
  std::filesystem::path folder = ".throng-resume";
  bool resume = false;
};

/// What a resumed pipeline starts from.
struct RestoredPipeline {
  std::size_t done = 0;                       ///< steps finished (the run continues with step done + 1)
  std::map<std::string, CrowdFile> named;     ///< crowds of named steps
  std::optional<CrowdFile> last;              ///< the last crowd made
  std::size_t written = 0;                    ///< outputs counted so far
  std::optional<Report> report;               ///< the pipeline's report when every step was done
};

class PipelineCheckpoint {
 public:
  /// The checkpoint of `job_path` (a pipeline of `steps` steps whose fingerprint is `fingerprint`), run by `ranks`
  /// (every rank of a collective pipeline; Communicator::single() for a job of a batch): rank 0 of them alone
  /// locks, writes and removes files.
  PipelineCheckpoint(const CheckpointOptions& options, const std::filesystem::path& job_path, std::string fingerprint,
                     std::size_t steps, const Communicator& ranks, Context& context);
  ~PipelineCheckpoint();
  PipelineCheckpoint(const PipelineCheckpoint&) = delete;
  PipelineCheckpoint& operator=(const PipelineCheckpoint&) = delete;

  /// Collective over `ranks`. Takes the folder's lock (another run holding it: this run is not checkpointed, or
  /// with --resume ConfigError). With --resume: the state the checkpoint holds (nullopt when there is none: the
  /// run starts from the first step, and says so); logs where the run being resumed stopped (its step, rank, pid
  /// and host). ConfigError when the checkpoint was made for another fingerprint or a crowd file it keeps changed;
  /// InputError when its files are damaged. Without --resume: empties the folder and returns nullopt.
  [[nodiscard]] std::optional<RestoredPipeline> restore();

  /// Records that step `index` (0-based), the first this run runs, is under way (later calls do nothing: each
  /// step's record from finished() names the next step as under way).
  void starting(std::size_t index);
  /// Records that step `index` is done: `crowd` is what it made (null for picture and table steps), `name` its
  /// name ("" when unnamed); `written` counts the outputs so far. A crowd a later step reads (`read_later`) is
  /// kept: as the crowd file `output` the step wrote (the same crowd, already on disk) unless a later step writes
  /// that path again (`output_rewritten`), else as a copy.
  void finished(std::size_t index, const CrowdFile* crowd, const std::string& name, std::size_t written,
                const std::filesystem::path& output, bool read_later, bool output_rewritten);
  /// The pipeline ended with `report`: removes the folder, or (`keep`, in a batch) keeps the report alone.
  void completed(const Report& report, bool keep);

  /// This job's checkpoint folder.
  [[nodiscard]] const std::filesystem::path& folder() const noexcept { return folder_; }

  /// A crowd file the checkpoint keeps, as it was when kept.
  struct KeptFile {
    std::filesystem::path path;
    std::uintmax_t size = 0;
    std::int64_t modified = 0;  ///< modification time, ns since the file clock's epoch
  };

 private:
  [[nodiscard]] std::string take_folder();
  [[nodiscard]] std::optional<RestoredPipeline> parse_state(const std::string& text);
  void write_state(std::optional<std::size_t> running, const Report* report);
  void disable(const std::string& why);
  void remove_folder();
  [[nodiscard]] std::filesystem::path crowd_path(std::size_t index) const;

  std::filesystem::path folder_;
  std::string job_;
  std::string fingerprint_;
  std::size_t steps_;
  bool resume_;
  const Communicator& ranks_;
  bool owner_;    // holds (or will take) the folder's lock: may remove it
  bool writing_;  // still writes the checkpoint (false on ranks other than 0, and after disable())
  int lock_fd_ = -1;
  Context& context_;
  std::size_t done_ = 0;
  std::size_t written_ = 0;
  bool started_ = false;
  std::map<std::string, std::size_t> crowds_;  // step name → the step whose crowd it names
  std::optional<std::size_t> last_;
  std::map<std::size_t, KeptFile> files_;  // step → the crowd file that holds its crowd
};

/// The checkpoint folder of `job_path` under `options.folder`.
[[nodiscard]] std::filesystem::path checkpoint_folder(const CheckpointOptions& options, const std::filesystem::path& job_path);

/// Removes the checkpoint folder of each of `jobs` (but one another run holds), then `options.folder` itself if nothing else is left in it.
void remove_checkpoints(const CheckpointOptions& options, const std::vector<std::filesystem::path>& jobs);

/// A stable 64-bit FNV-1a hash of `text` as 16 hex digits (the same on every machine and build).
[[nodiscard]] std::string stable_hash(const std::string& text);

}  // namespace throng::cli
