// Atomic, safe output files: every file throng writes (crowd files, CSV, SVG/PNG pictures) goes through this.
//
// - The data goes to a temporary file created in the target's folder with O_CREAT | O_EXCL | O_NOFOLLOW under an
//   unpredictable name (`.NAME.tmp-` and 16 random hex digits): a symbolic link or file planted in a shared
//   output folder is never followed or reused. Writers write through its descriptor (write(), or
//   descriptor_path() for a library that opens files by name), never by the temporary's name.
// - Only a regular file (or nothing) is ever replaced: a folder, device node (`-o /dev/null` as root), symbolic
//   link, pipe or socket at the target is refused before any work.
// - commit() flushes the file to disk (fsync), renames it onto the target (atomic on one file system) and flushes
//   the folder, so a crash leaves the old file or the new one, never a mix.
// - A failed or interrupted run leaves no partial output: the temporary file is removed when an AtomicOutput is
//   destroyed without commit(), and on every catchable termination signal by the handler that
//   install_interrupt_cleanup() sets up (the program calls it once). An input is never opened for writing.
#pragma once

#include <cstddef>
#include <filesystem>
#include <future>
#include <string>
#include <string_view>

namespace throng {

/// The checks AtomicOutput makes of its target before it writes anything, for a command that wants to fail before
/// long work (reading a large crowd): ConfigError (exit 2) for an empty name; IoError (exit 4) naming the target
/// when it names a folder, its folder is missing or not writable, or something other than a regular file is there.
void check_output_target(const std::filesystem::path& target);

class AtomicOutput {
 public:
  /// Checks `target` and creates the temporary file. ConfigError (exit 2) for an empty name; IoError (exit 4)
  /// naming the target when its folder is missing or not writable, when something other than a regular file is
  /// there, or when the temporary cannot be created.
  explicit AtomicOutput(std::filesystem::path target);
  ~AtomicOutput();
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  /// The temporary file's name (for messages and tests; write through descriptor() or descriptor_path()).
  [[nodiscard]] const std::filesystem::path& temporary() const noexcept { return temporary_; }
  [[nodiscard]] const std::filesystem::path& target() const noexcept { return target_; }
  /// The temporary file's descriptor (open for writing).
  [[nodiscard]] int descriptor() const noexcept { return fd_; }
  /// A name that opens exactly the temporary file created here, whatever happens to names in its folder
  /// (`/proc/self/fd/N`; the temporary's name where /proc is not mounted). For libraries that open by name (HDF5).
  [[nodiscard]] std::filesystem::path descriptor_path() const;

  /// Appends `bytes` to the temporary file. IoError naming the target on failure (a full disk included).
  void write(std::string_view bytes);

  /// Starts flushing what the temporary holds so far to disk (fdatasync) on a thread of its own and returns at
  /// once; does nothing while an earlier one still runs. A writer that makes its file over a long run calls it
  /// after each large write, so the disk works while the program computes and commit() waits only for the rest
  /// (`throng sketch` with `--compression none` at 10,000 agents: 106–109 → 89–94 ms, bench_sketch_command; the
  /// final flush had taken 21–23 ms of it, the disk's time more than the CPU's). commit() and the destructor wait
  /// for it.
  void flush_in_background();

  /// Flushes the temporary file to disk, renames it onto the target and flushes the folder. Throws IoError if any
  /// step fails (the temporary is then removed and the target left as it was), a background flush included:
  /// Linux reports a failed writeback to one flush of a descriptor only, so commit's own might not see it.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path temporary_;
  int folder_fd_ = -1;
  int fd_ = -1;
  int slot_ = -1;
  bool committed_ = false;
  std::future<int> flushing_;  // the background flush: 0, or the errno it failed with
  int flush_error_ = 0;        // the errno of a background flush that failed
};

/// Flushes the regular file `path` to disk (fsync): what a resume record names is on disk before the record.
/// IoError naming the file on failure.
void sync_file(const std::filesystem::path& path);

/// Makes the finished file `from` (written in the target's folder, by a writer that keeps it across runs: a
/// resumable stream's partial file) the file `target`: flushes it to disk, renames it onto the target (which must be
/// a regular file or nothing: check_output_target) and flushes the folder. IoError naming the target on failure.
void move_into_place(const std::filesystem::path& from, const std::filesystem::path& target);

/// Installs handlers for every catchable signal whose default is to end the process (SIGHUP, SIGINT, SIGQUIT,
/// SIGTERM, SIGPIPE, SIGALRM, SIGUSR1, SIGUSR2, SIGXCPU, SIGXFSZ, SIGVTALRM, SIGPROF, SIGABRT) that remove every
/// pending temporary output and exit with 128 + signal (130 for Ctrl-C). A signal ignored when the program
/// started (`nohup` ignores SIGHUP) stays ignored. Faults (SIGSEGV, SIGBUS, SIGFPE, SIGILL) are left to
/// install_input_crash_report (input_crash.h), the sanitizers and the system. Safe to call more than once.
void install_interrupt_cleanup();

namespace detail {
/// Unlinks every pending temporary output (async-signal-safe: for signal handlers, input_crash.h's too).
void remove_pending_outputs() noexcept;
/// Writes `size` bytes to `fd` through partial writes and EINTR, giving up on an error (async-signal-safe).
void write_from_handler(int fd, const char* data, std::size_t size) noexcept;
}  // namespace detail

/// While one lives, the handlers of install_interrupt_cleanup() only note a terminating signal; when the last one
/// ends, a noted signal is acted on as it would have been (pending temporaries removed, the note written, exit
/// 128 + signal). For a record that must reach the disk whole or not at all: a resumable stream's window (data,
/// flush, state), so that Ctrl-C or SIGTERM never stops it half-way. Nests; not for long work.
class DeferredInterrupts {
 public:
  DeferredInterrupts() noexcept;
  ~DeferredInterrupts();
  DeferredInterrupts(const DeferredInterrupts&) = delete;
  DeferredInterrupts& operator=(const DeferredInterrupts&) = delete;
};

/// What the handlers of install_interrupt_cleanup() write to descriptor `fd` after removing the pending outputs and
/// before exiting (a batch's summary so far); an empty text writes nothing. Replaces the previous note. The text
/// is prepared here, ahead of any signal: the handler only calls write(), which is async-signal-safe.
void set_interrupt_note(int fd, std::string text);

/// Throws ConfigError when `output` names the same file as `input` (an input is never overwritten).
void check_distinct(const std::filesystem::path& input, const std::filesystem::path& output);

}  // namespace throng
